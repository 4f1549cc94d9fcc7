#include "Observables.h"

#include <algorithm>
#include <cmath>

#include "ContactTimes.h"
#include "NearPairs.h"

namespace mixflow::dem {

Energies energies(const ParticleView& p, double gravity, MPI_Comm comm) {
  double local[3] = {0, 0, 0};
  for (int i = 0; i < p.n; ++i) {
    const double m = p.mass[i], r = p.radius[i];
    const double* v = p.v[i];
    const double* w = p.omega[i];
    local[0] += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    local[1] += 0.5 * (0.4 * m * r * r) * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    local[2] += m * gravity * p.x[i][1];
  }
  double total[3];
  MPI_Allreduce(local, total, 3, MPI_DOUBLE, MPI_SUM, comm);
  long n = p.n, nTotal = 0;
  MPI_Allreduce(&n, &nTotal, 1, MPI_LONG, MPI_SUM, comm);
  return {total[0], total[1], total[2], nTotal};
}

std::vector<double> gatherOnRoot(const std::vector<double>& local, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int n = static_cast<int>(local.size());
  std::vector<int> counts(size), offsets(size);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      offsets[r] = total;
      total += counts[r];
    }
    all.resize(total);
  }
  MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
              comm);
  return all;
}

namespace {
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(n) {
    for (int i = 0; i < n; ++i) parent[i] = i;
  }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};
}  // namespace

double granularFront(const std::vector<std::array<double, 3>>& c, double radius, double maxGap,
                     double periodicWidth) {
  const int n = static_cast<int>(c.size());
  if (n == 0) return 0.0;
  const double reach = 2 * radius + maxGap;  // centre distance that still connects two particles
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const auto& p : c)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  const bool periodic = periodicWidth > 0;
  if (periodic) lo[2] = 0.0, hi[2] = periodicWidth;
  DisjointSets sets(n);
  const bool axes[3] = {false, false, periodic};
  forEachPairWithin(c, lo, hi, axes, reach, [&](int p, int q, double) { sets.unite(p, q); });
  std::vector<int> size(n, 0);
  int biggest = 0;
  for (int p = 0; p < n; ++p) {
    const int r = sets.find(p);
    if (++size[r] > size[biggest]) biggest = r;
  }
  double front = -1e300;
  for (int p = 0; p < n; ++p)
    if (sets.find(p) == biggest) front = std::max(front, c[p][0]);
  return front + radius;
}

Profile depositProfile(const std::vector<std::array<double, 3>>& centres, double radius,
                       double width, double dx, double dz, double xmax, double packingFraction) {
  const int nx = static_cast<int>(std::ceil(xmax / dx));
  const int nz = std::max(1, static_cast<int>(std::round(width / dz)));
  const double dzUsed = width / nz;
  std::vector<double> top(static_cast<size_t>(nx) * nz, 0.0), volume(nx, 0.0);
  const double vp = 4.0 / 3.0 * kPi * radius * radius * radius;
  for (const auto& c : centres) {
    const int i = static_cast<int>(std::floor(c[0] / dx));
    if (i < 0 || i >= nx) continue;
    const int k = std::clamp(static_cast<int>(std::floor(c[2] / dzUsed)), 0, nz - 1);
    double& t = top[static_cast<size_t>(i) * nz + k];
    t = std::max(t, c[1] + radius);
    volume[i] += vp;
  }
  Profile p;
  for (int i = 0; i < nx; ++i) {
    double sum = 0;
    for (int k = 0; k < nz; ++k) sum += top[static_cast<size_t>(i) * nz + k];
    p.x.push_back((i + 0.5) * dx);
    p.hTop.push_back(sum / nz);
    p.hVolume.push_back(volume[i] / (packingFraction * width * dx));
  }
  return p;
}

double thicknessFront(const Profile& p, double dx, double xStart, double minHeight) {
  for (size_t i = 0; i < p.x.size(); ++i)
    if (p.x[i] > xStart && p.hTop[i] < minHeight) return std::max(xStart, p.x[i] - 0.5 * dx);
  return p.x.empty() ? xStart : p.x.back() + 0.5 * dx;
}

VelocityProfile velocityProfile(const ParticleView& p, double x0, double halfWidth, double dy,
                                double ymax, MPI_Comm comm) {
  const int ny = static_cast<int>(std::ceil(ymax / dy));
  std::vector<double> sum(ny, 0.0), sumAll(ny);
  std::vector<long> cnt(ny, 0), cntAll(ny);
  for (int i = 0; i < p.n; ++i) {
    if (std::abs(p.x[i][0] - x0) > halfWidth) continue;
    const int j = static_cast<int>(std::floor(p.x[i][1] / dy));
    if (j < 0 || j >= ny) continue;
    sum[j] += p.v[i][0];
    ++cnt[j];
  }
  MPI_Allreduce(sum.data(), sumAll.data(), ny, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(cnt.data(), cntAll.data(), ny, MPI_LONG, MPI_SUM, comm);
  VelocityProfile out;
  for (int j = 0; j < ny; ++j) {
    if (cntAll[j] == 0) continue;
    out.y.push_back((j + 0.5) * dy);
    out.u.push_back(sumAll[j] / cntAll[j]);
    out.count.push_back(cntAll[j]);
  }
  return out;
}

TopShear topLayerShear(const VelocityProfile& vp, double dy, int layers, long minCount) {
  TopShear out;
  int top = -1;
  for (int j = static_cast<int>(vp.y.size()) - 1; j >= 0 && top < 0; --j)
    if (vp.count[j] >= minCount) top = j;
  if (top < 0) return out;
  out.surface = vp.y[top] + 0.5 * dy;
  // Bins below the top, contiguous (a gap in y ends the layer), `layers` in all.
  double sy = 0, su = 0, syy = 0, syu = 0;
  int n = 0;
  for (int j = top; j >= 0 && n < layers; --j) {
    if (j < top && vp.y[j + 1] - vp.y[j] > 1.5 * dy) break;
    sy += vp.y[j], su += vp.u[j], syy += vp.y[j] * vp.y[j], syu += vp.y[j] * vp.u[j];
    ++n;
  }
  const double den = n * syy - sy * sy;
  if (n < 2 || den <= 0) return out;
  out.rate = (n * syu - sy * su) / den;
  out.valid = true;
  return out;
}

double savagePaper(double d, double rhoS, double rhoF, double rate, double g, double tanPhi) {
  return d * rhoS * rate * rate / (g * tanPhi * (rhoS - rhoF));
}

double savageIverson(double d, double h, double rhoS, double rhoF, double rate, double g,
                     double tanPhi) {
  return h > 0 ? rhoS * d * d * rate * rate / ((rhoS - rhoF) * g * h * tanPhi) : 0.0;
}

double sphereSlabVolume(double yc, double r, double a, double b) {
  const double lo = std::max(a, yc - r) - yc, hi = std::min(b, yc + r) - yc;
  if (hi <= lo) return 0.0;
  // Integral of pi (r^2 - s^2) ds from lo to hi.
  return kPi * (r * r * (hi - lo) - (hi * hi * hi - lo * lo * lo) / 3.0);
}

}  // namespace mixflow::dem
