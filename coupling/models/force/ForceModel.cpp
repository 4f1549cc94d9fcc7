#include "ForceModel.h"

#include <map>
#include <stdexcept>

namespace mixflow::coupling {

namespace {
using Factory = std::unique_ptr<ForceModel> (*)(const Dictionary&, const ForceContext&);

// The run-time selection table: name in couplingProperties -> factory. A new law is one source
// file with its factory and one line here.
const std::map<std::string, Factory>& table() {
  static const std::map<std::string, Factory> t = {
      {"DiFeliceDrag", &makeDiFeliceDrag},
      {"GidaspowDrag", &makeGidaspowDrag},
      {"buoyancy", &makeBuoyancy},
      {"viscousForce", &makeViscousForce},
  };
  // A case lists each model once: the table bounds the models per case (ModelForces).
  if (t.size() > kMaxForceModels)
    throw std::logic_error("ForceModel: more laws than kMaxForceModels; raise it");
  return t;
}
}  // namespace

std::vector<std::string> ForceModel::available() {
  std::vector<std::string> names;
  for (const auto& kv : table()) names.push_back(kv.first);
  return names;
}

std::unique_ptr<ForceModel> ForceModel::New(const std::string& name, const Dictionary& properties,
                                            const ForceContext& context) {
  const auto it = table().find(name);
  if (it == table().end()) {
    std::string list;
    for (const auto& n : available()) list += (list.empty() ? "" : " ") + n;
    properties.fail("forceModels", "unknown force model '" + name + "'; available: " + list);
  }
  return it->second(properties.subDictOrEmpty(name + "Coeffs"), context);
}

}  // namespace mixflow::coupling
