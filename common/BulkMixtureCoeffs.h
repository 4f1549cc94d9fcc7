// bulkMixtureCoeffs: the mixture phase's sub-dictionary of constant/transportProperties for
// mixflowBulkFoam's bulkMixture viscosity model (cfd/bulkMixture/bulkMixtureViscosity.H),
// written by mixflowPrepare from constant/bulkProperties in kinematic units. Declared once here:
// the writer (prepare/FoamCaseWriter.cpp) writes these entries, the solver refuses any other and
// any value outside its range before the first step, and docs/parameters.md shows the table.
#pragma once

#include <string>

#include "Schema.h"

namespace mixflow {

struct BulkMixtureCoeffs {
  static const Schema& schema();
  // Validates the sub-dictionary bulkMixtureCoeffs of the phase PHASE in the transportProperties
  // FILE (InputError naming file, entry and allowed range).
  static void check(const std::string& file, const std::string& phase);
};

}  // namespace mixflow
