#include "SlabBalance.h"

// LIGGGHTS headers
#include <comm.h>
#include <domain.h>
#include <irregular.h>
#include <lammps.h>

#include <algorithm>
#include <vector>

#include "CollapseRecorder.h"

namespace mixflow::dem {

bool balanceSlabs(LiggghtsSession& lig, MPI_Comm comm) {
  LAMMPS_NS::LAMMPS* lmp = lig.lammps();
  LAMMPS_NS::Comm* c = lmp->comm;
  const int slabs = c->procgrid[0];
  if (slabs <= 1 || c->procgrid[1] != 1 || c->procgrid[2] != 1) return false;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<double> split(slabs + 1, 0.0);
  const auto centres = gatherCentres(lig.particles(), comm);
  if (rank == 0) {
    std::vector<double> x;
    x.reserve(centres.size());
    for (const auto& p : centres) x.push_back(p[0]);
    std::sort(x.begin(), x.end());
    const double lo = lmp->domain->boxlo[0], prd = lmp->domain->prd[0];
    split[slabs] = 1.0;
    for (int i = 1; i < slabs; ++i) {
      // Boundary halfway between the neighbouring particles of the i-th quantile.
      const size_t k = x.size() * i / slabs;
      const double b = x.empty()
                           ? lo + prd * i / slabs
                           : (k == 0 ? x[0] : 0.5 * (x[k - 1] + x[std::min(k, x.size() - 1)]));
      split[i] = std::clamp((b - lo) / prd, split[i - 1], 1.0);
    }
  }
  MPI_Bcast(split.data(), slabs + 1, MPI_DOUBLE, 0, comm);
  return setSlabSplits(lig, split);
}

std::vector<double> slabSplits(LiggghtsSession& lig) {
  const LAMMPS_NS::Comm* c = lig.lammps()->comm;
  const int slabs = c->procgrid[0];
  if (c->procgrid[1] != 1 || c->procgrid[2] != 1) return {};
  return std::vector<double>(c->xsplit, c->xsplit + slabs + 1);
}

bool setSlabSplits(LiggghtsSession& lig, const std::vector<double>& splits) {
  LAMMPS_NS::LAMMPS* lmp = lig.lammps();
  LAMMPS_NS::Comm* c = lmp->comm;
  const int slabs = c->procgrid[0];
  if (slabs <= 1 || c->procgrid[1] != 1 || c->procgrid[2] != 1 ||
      splits.size() != static_cast<size_t>(slabs + 1))
    return false;
  lig.storeContactHistory();
  c->uniform = 0;
  for (int i = 0; i <= slabs; ++i) c->xsplit[i] = splits[i];
  lmp->domain->set_local_box();
  LAMMPS_NS::Irregular irregular(lmp);
  irregular.migrate_atoms();
  lig.invalidateSetup();
  return true;
}

}  // namespace mixflow::dem
