// Text companions of the HDF5 file, both regenerated from the file after every update and written
// through a temporary file + rename:
//   <base>.xdmf         ParaView/VisIt index: a temporal collection of 3-D rectilinear grids (the
//                       bins, one cell across the width), cell data read from the HDF5 hyperslabs;
//   <base>_regions.csv  tidy time series of region averages: one row per region, window, quantity.
#pragma once

#include <string>

#include "H5WindowReader.h"

namespace mixflow::mx {

void writeXdmf(const std::string& xdmfPath, const std::string& h5Path, const StoredOutput& s);
void writeRegionsCsv(const std::string& csvPath, const StoredOutput& s);

// Writes text to path + ".tmp" and renames it over path.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace mixflow::mx
