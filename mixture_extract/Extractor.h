// mixflowExtract's driver: reads a case (finished or still running), decides which time windows
// are new and complete, bins them and appends them to the case's HDF5 file, then rewrites the
// XDMF index and the regions CSV.
#pragma once

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>

#include "FluidSource.h"

namespace mixflow::mx {

struct ExtractOptions {
  std::string caseDir = ".";
  std::string dictFile;    // default <case>/system/extractDict
  std::string output;      // file base (no extension); default from extractDict `output`
  bool overwrite = false;  // start the output again instead of appending
  bool checkOnly = false;  // validate and list the windows, write nothing
  int threads = 1;         // snapshot files parsed concurrently
};

struct ExtractReport {
  // skipped: generated windows after the last snapshot of a finished case; unpaired: generated
  // windows whose snapshots have no solved fluid time within pairTolerance.
  int written = 0, present = 0, deferred = 0, skipped = 0, unpaired = 0;
  long snapshotsRead = 0;
  std::string h5, xdmf, csv;
};

// The HDF5 file was updated but its XDMF index or regions CSV could not be rewritten.
struct IndexWriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Extractor {
 public:
  Extractor(ExtractOptions options, std::ostream& log);
  // Replaces the fluid source chosen by extractDict (tests: a SyntheticFluidSource).
  void setFluidSource(std::shared_ptr<FluidSource> fluid) { fluid_ = std::move(fluid); }
  ExtractReport run();

 private:
  ExtractOptions opt_;
  std::ostream& log_;
  std::shared_ptr<FluidSource> fluid_;
};

// Whether the dumped c_pstress holds the kinetic term, from the `compute <id> all stress/atom`
// line of <case>/dem/in.liggghts (no keywords or `ke`: included). Throws InputError when the line
// cannot be found (then set particles.stressKineticTerm in extractDict).
bool stressHasKineticTerm(const std::string& caseDir, const std::string& setting);

}  // namespace mixflow::mx
