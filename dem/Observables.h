// Granular observables of a dam break (docs/model.md §8), computed from the particles each rank
// owns and reduced over MPI. Functions on plain arrays so tests can feed them known configurations.
#pragma once

#include <mpi.h>

#include <array>
#include <vector>

namespace mixflow::dem {

// Read-only view of the particles a rank owns (LIGGGHTS per-atom arrays).
struct ParticleView {
  int n = 0;
  double** x = nullptr;
  double** v = nullptr;
  double** omega = nullptr;
  double* radius = nullptr;
  double* mass = nullptr;
};

struct Energies {
  double kineticTranslational = 0;
  double kineticRotational = 0;
  double potential = 0;  // m g y, datum at the floor y = 0
  long count = 0;
  double kinetic() const { return kineticTranslational + kineticRotational; }
};

Energies energies(const ParticleView& p, double gravity, MPI_Comm comm);

// Values from every rank gathered on rank 0 (empty elsewhere).
std::vector<double> gatherOnRoot(const std::vector<double>& local, MPI_Comm comm);

// Front of the main mass (docs/model.md §8): particles are connected when their surface gap is at
// most maxGap; the main mass is the largest connected cluster, and the front is its largest x plus
// r. Detached particles (saltating or scattered ahead) never move the front. periodicWidth > 0
// wraps z.
double granularFront(const std::vector<std::array<double, 3>>& centres, double radius,
                     double maxGap, double periodicWidth);

// Deposit profile on x bins of width dx over [0, xmax): hTop = mean over z columns (width dz) of
// the highest particle top in the column (0 for an empty column); hVolume = particle volume in the
// bin divided by (packingFraction * W * dx).
struct Profile {
  std::vector<double> x, hTop, hVolume;
};
Profile depositProfile(const std::vector<std::array<double, 3>>& centres, double radius,
                       double width, double dx, double dz, double xmax, double packingFraction);

// Front of the deposit by thickness: the first bin beyond xStart whose hTop is below minHeight ends
// the deposit; returns that bin's left edge (xStart if the first bin is already thin).
double thicknessFront(const Profile& p, double dx, double xStart, double minHeight);

// Mean u_x of particles whose centre lies within |x - x0| <= halfWidth, on y bins of width dy.
struct VelocityProfile {
  std::vector<double> y, u;
  std::vector<long> count;
};
VelocityProfile velocityProfile(const ParticleView& p, double x0, double halfWidth, double dy,
                                double ymax, MPI_Comm comm);

// Shear rate at the top of the granular flow from a u(y) profile on bins of height dy: the top is
// the highest bin holding at least minCount particles; the rate is the least-squares slope du/dy
// over that bin and the populated bins below it, `layers` bins in all. valid = false when fewer
// than two bins qualify. surface = upper edge of the top bin (the flow depth at the section).
struct TopShear {
  bool valid = false;
  double surface = 0;
  double rate = 0;
};
TopShear topLayerShear(const VelocityProfile& vp, double dy, int layers, long minCount);
// Savage number, Li & Zhao Eq. 16 as printed: d rho_s rate^2 / (g tanPhi (rho_s - rho_f)), and
// Iverson's form with d^2 / h in place of d.
double savagePaper(double d, double rhoS, double rhoF, double rate, double g, double tanPhi);
double savageIverson(double d, double h, double rhoS, double rhoF, double rate, double g,
                     double tanPhi);

// Exact volume of a sphere (centre yc, radius r) between the planes y = a and y = b.
double sphereSlabVolume(double yc, double r, double a, double b);

}  // namespace mixflow::dem
