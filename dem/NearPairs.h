// The pairs of points closer than a reach, found through a cell list: the grains' clustering for
// the granular front (Observables.h) and the slab balance's neighbour counts (SlabBalance.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mixflow::dem {

// Calls f(p, q, d2) once for every pair p < q of points c inside the box [lo, hi] whose squared
// distance d2 is at most reach^2, the minimum image along the axes where periodic[k] (period
// hi[k] - lo[k]). Points outside the box count in its edge cells.
template <class F>
void forEachPairWithin(const std::vector<std::array<double, 3>>& c, const double lo[3],
                       const double hi[3], const bool periodic[3], double reach, F&& f) {
  const int n = static_cast<int>(c.size());
  int dims[3];
  for (int k = 0; k < 3; ++k) dims[k] = std::max(1, static_cast<int>((hi[k] - lo[k]) / reach));
  auto cellOf = [&](const std::array<double, 3>& p, int k) {
    return std::clamp(static_cast<int>((p[k] - lo[k]) / (hi[k] - lo[k] + 1e-300) * dims[k]), 0,
                      dims[k] - 1);
  };
  // Dense cell list: head/next linked lists.
  std::vector<int> head(static_cast<size_t>(dims[0]) * dims[1] * dims[2], -1), next(n, -1);
  auto index = [&](int i, int j, int k) {
    return (static_cast<size_t>(k) * dims[1] + j) * dims[0] + i;
  };
  for (int p = 0; p < n; ++p) {
    const size_t id = index(cellOf(c[p], 0), cellOf(c[p], 1), cellOf(c[p], 2));
    next[p] = head[id];
    head[id] = p;
  }
  const double reach2 = reach * reach;
  std::vector<size_t> near;
  for (int p = 0; p < n; ++p) {
    const int cell[3] = {cellOf(c[p], 0), cellOf(c[p], 1), cellOf(c[p], 2)};
    // The neighbouring cells, each once (a periodic side of fewer than 3 cells wraps onto itself).
    near.clear();
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          int m[3] = {cell[0] + di, cell[1] + dj, cell[2] + dk};
          bool inside = true;
          for (int k = 0; k < 3; ++k) {
            if (periodic[k]) m[k] = (m[k] + dims[k]) % dims[k];
            inside = inside && m[k] >= 0 && m[k] < dims[k];
          }
          const size_t id = index(m[0], m[1], m[2]);
          if (inside && std::find(near.begin(), near.end(), id) == near.end()) near.push_back(id);
        }
    for (const size_t id : near)
      for (int q = head[id]; q >= 0; q = next[q]) {
        if (q <= p) continue;
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
          double d = c[p][k] - c[q][k];
          if (periodic[k]) d -= (hi[k] - lo[k]) * std::round(d / (hi[k] - lo[k]));
          d2 += d * d;
        }
        if (d2 <= reach2) f(p, q, d2);
      }
  }
}

}  // namespace mixflow::dem
