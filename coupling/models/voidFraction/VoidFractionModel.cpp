#include "VoidFractionModel.h"

#include <map>

namespace mixflow::coupling {

namespace {
using Factory = std::unique_ptr<VoidFractionModel> (*)(const Dictionary&);

// Run-time selection table: name in couplingProperties -> factory.
const std::map<std::string, Factory>& table() {
  static const std::map<std::string, Factory> t = {
      {"centre", &makeCentreVoidFraction},
      {"divided", &makeDividedVoidFraction},
  };
  return t;
}
}  // namespace

std::vector<std::string> VoidFractionModel::available() {
  std::vector<std::string> names;
  for (const auto& kv : table()) names.push_back(kv.first);
  return names;
}

std::unique_ptr<VoidFractionModel> VoidFractionModel::New(const std::string& name,
                                                          const Dictionary& properties) {
  const auto it = table().find(name);
  if (it == table().end()) {
    std::string list;
    for (const auto& n : available()) list += (list.empty() ? "" : " ") + n;
    properties.fail("voidFractionModel",
                    "unknown void-fraction model '" + name + "'; available: " + list);
  }
  return it->second(properties.subDictOrEmpty(name + "Coeffs"));
}

}  // namespace mixflow::coupling
