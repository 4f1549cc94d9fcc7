// The DEM half's load per MPI rank over a collapse: particles held and LIGGGHTS compute and
// communication seconds so far, one row per rank at each sample, so the imbalance of a
// decomposition (max over mean) reads off a spreadsheet. Output:
// <case>/postProcessing/dem/rankLoad.csv.
#pragma once

#include <mpi.h>

#include <fstream>
#include <string>

#include "LiggghtsSession.h"

namespace mixflow::dem {

class RankLoad {
 public:
  // append: continue an existing rankLoad.csv (a resumed run).
  RankLoad(const std::string& outDir, MPI_Comm comm, bool append);
  // Gathers this sample's counts and times on rank 0 and writes its rows.
  void sample(double time, const LiggghtsSession& lig);

 private:
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  std::ofstream csv_;
};

}  // namespace mixflow::dem
