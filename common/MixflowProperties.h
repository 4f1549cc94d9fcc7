// constant/mixflowProperties (optional): the formulation switches of the fluid solvers
// (mixflowFoam, mixflowCoupled, mixflowBulkFoam) and the eps_f floor the coupling clips to.
// One declaration table (MixflowProperties.cpp) gives every entry; the defaults are the
// initializers below. Unknown entries are refused naming the file, the entry and the allowed ones.
#pragma once

#include <string>

#include "Schema.h"

namespace mixflow {

struct MixflowProperties {
  std::string formulation = "B";           // only B is implemented (docs/model.md §3)
  std::string viscousStress = "full";      // full: div(tau); voidfractionWeighted: div(eps_f tau)
  bool continuityVoidfractionRate = true;  // d(eps_f)/dt in the pressure equation's continuity
  double voidfractionMin = 0.05;           // eps_f below it is a fatal error
  bool particleRamp = false;  // present: OpenFOAM's Function1 reads it (verification mode)

  static const Schema& schema();
  // An empty path or a missing file: the defaults.
  static MixflowProperties read(const std::string& file);
};

}  // namespace mixflow
