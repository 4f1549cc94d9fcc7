#include "RankLoad.h"

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "Dictionary.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

RankLoad::RankLoad(const std::string& outDir, MPI_Comm comm, bool append) : comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  if (rank_ != 0) return;
  const fs::path file = fs::path(outDir) / "rankLoad.csv";
  const bool header = !append || !fs::exists(file);
  csv_.open(file, append ? std::ios::app : std::ios::trunc);
  if (!csv_) throw std::runtime_error("cannot write " + file.string());
  if (header) csv_ << "time_s,rank,particles,dem_compute_s,dem_comm_s\n";
}

void RankLoad::sample(double time, const LiggghtsSession& lig) {
  const double local[3] = {static_cast<double>(lig.particles().n), lig.computeSeconds(),
                           lig.commSeconds()};
  std::vector<double> all(rank_ == 0 ? 3 * ranks_ : 0);
  MPI_Gather(local, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, 0, comm_);
  if (rank_ != 0) return;
  for (int r = 0; r < ranks_; ++r)
    csv_ << formatNumber(time) << ',' << r << ',' << static_cast<long>(all[3 * r]) << ','
         << formatNumber(all[3 * r + 1]) << ',' << formatNumber(all[3 * r + 2]) << '\n';
  csv_ << std::flush;
}

}  // namespace mixflow::dem
