#include "SlabBalance.h"

// LIGGGHTS headers
#include <atom.h>
#include <comm.h>
#include <domain.h>
#include <irregular.h>
#include <lammps.h>
#include <neighbor.h>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "CollapseRecorder.h"
#include "NearPairs.h"
#include "Observables.h"

namespace mixflow::dem {

BalanceWeight balanceWeight(const std::string& word) {
  if (word == "pairs") return BalanceWeight::pairs;
  if (word == "contacts") return BalanceWeight::contacts;
  return BalanceWeight::particles;  // demDict has checked the word
}

namespace {

// Each grain's weight: 1, plus half the grains whose centre lies within r_i + r_j + skin (pairs)
// or r_i + r_j (contacts) of its own, the minimum image across periodic sides. Half: a pair's
// work is done once, by one of its two grains. Counted from the positions on one rank, not from
// LIGGGHTS' neighbour lists, whose content depends on when they were last built: so the same
// grains give the same slabs whatever the decomposition and whether the run was resumed.
std::vector<double> grainWeights(const std::vector<std::array<double, 3>>& x,
                                 const std::vector<double>& r, const LAMMPS_NS::Domain& box,
                                 BalanceWeight weight, double skin) {
  std::vector<double> w(x.size(), 1.0);
  if (weight == BalanceWeight::particles || x.empty()) return w;
  const double gap = weight == BalanceWeight::pairs ? skin : 0.0;
  const double rmax = *std::max_element(r.begin(), r.end());
  const bool periodic[3] = {box.periodicity[0] != 0, box.periodicity[1] != 0,
                            box.periodicity[2] != 0};
  forEachPairWithin(x, box.boxlo, box.boxhi, periodic, 2 * rmax + gap,
                    [&](int p, int q, double d2) {
                      const double reach = r[p] + r[q] + gap;
                      if (d2 < reach * reach) w[p] += 0.5, w[q] += 0.5;
                    });
  return w;
}

}  // namespace

bool balanceSlabs(LiggghtsSession& lig, MPI_Comm comm, BalanceWeight weight) {
  LAMMPS_NS::LAMMPS* lmp = lig.lammps();
  LAMMPS_NS::Comm* c = lmp->comm;
  const int slabs = c->procgrid[0];
  if (slabs <= 1 || c->procgrid[1] != 1 || c->procgrid[2] != 1) return false;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<double> split(slabs + 1, 0.0);
  const LAMMPS_NS::Atom* a = lmp->atom;
  std::vector<double> local;  // x, y, z, radius per particle
  local.reserve(4 * a->nlocal);
  for (int i = 0; i < a->nlocal; ++i)
    local.insert(local.end(), {a->x[i][0], a->x[i][1], a->x[i][2], a->radius[i]});
  const std::vector<double> all = gatherOnRoot(local, comm);
  if (rank == 0) {
    std::vector<std::array<double, 3>> x(all.size() / 4);
    std::vector<double> r(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
      x[i] = {all[4 * i], all[4 * i + 1], all[4 * i + 2]};
      r[i] = all[4 * i + 3];
    }
    const std::vector<double> w = grainWeights(x, r, *lmp->domain, weight, lmp->neighbor->skin);
    std::vector<std::pair<double, double>> xw(x.size());
    for (size_t i = 0; i < x.size(); ++i) xw[i] = {x[i][0], w[i]};
    std::sort(xw.begin(), xw.end());
    std::vector<double> prefix(xw.size() + 1, 0.0);  // weight of the first k particles
    for (size_t i = 0; i < xw.size(); ++i) prefix[i + 1] = prefix[i] + xw[i].second;
    const double lo = lmp->domain->boxlo[0], prd = lmp->domain->prd[0];
    split[slabs] = 1.0;
    for (int i = 1; i < slabs; ++i) {
      // The i-th weighted quantile: the most particles whose weight is at most i / slabs of
      // the total (with unit weights, n i / slabs rounded down); the boundary lies halfway
      // between that last particle and the next.
      const double target = prefix.back() * i / slabs;
      const size_t k = static_cast<size_t>(std::upper_bound(prefix.begin(), prefix.end(), target) -
                                           prefix.begin() - 1);
      const double b =
          xw.empty() ? lo + prd * i / slabs
                     : (k == 0 ? xw[0].first
                               : 0.5 * (xw[k - 1].first + xw[std::min(k, xw.size() - 1)].first));
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
