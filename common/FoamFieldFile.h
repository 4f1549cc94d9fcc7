// The internalField of an OpenFOAM ASCII vol field file: the one reader of field files.
#pragma once

#include <string>
#include <vector>

namespace mixflow {

// n x ncomp values (ncomp 1 scalar, 3 vector); n = -1 for a uniform field (one value). Throws
// InputError naming FILE for a binary, truncated or mistyped field.
std::vector<double> readInternalField(const std::string& file, int ncomp, long& n);

}  // namespace mixflow
