// Unit tests of the DEM closed forms and observables on configurations with known answers.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <functional>
#include <string>

#include "ContactTimes.h"
#include "LiggghtsCommands.h"
#include "Observables.h"
#include "PackingSearch.h"

using namespace mixflow::dem;

TEST(ContactTimes, RayleighTimeOfPaperParticle) {
  // docs/model.md §2: T_R ~ 1.2e-5 s for 70 GPa; LIGGGHTS' check/timestep/gran reports 1.2412e-5 s.
  EXPECT_NEAR(rayleighTime(0.012, 2500, 70e9, 0.3), 1.2412e-5, 1e-8);
}

TEST(ContactTimes, HertzImpactMatchesReferenceTable) {
  // tests/reference/hertz_impact_analytic.csv, Chung & Ooi test 1 glass: E*=2.5e10, R*=0.005,
  // m*=0.0058643, v=20: delta_max 274.1127 um, F_max 10.6969 kN, t_c 40.3357 us.
  const double e = effectiveModulus(48e9, 0.2, 48e9, 0.2);
  EXPECT_NEAR(e, 2.5e10, 1e6);
  EXPECT_NEAR(hertzMaxOverlap(e, 0.005, 0.0058643, 20) * 1e6, 274.1127, 0.01);
  EXPECT_NEAR(hertzPeakForce(e, 0.005, 0.0058643, 20) / 1e3, 10.6969, 0.001);
  EXPECT_NEAR(hertzContactTime(e, 0.005, 0.0058643, 20) * 1e6, 40.3357, 0.005);
  // A rigid wall adds no compliance.
  EXPECT_NEAR(effectiveModulus(70e9, 0.3, INFINITY, 0.3), 70e9 / (1 - 0.09), 1.0);
}

TEST(Observables, SphereSlabVolumeIsExact) {
  const double r = 0.5, v = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(sphereSlabVolume(0, r, -1, 1), v, 1e-15);
  EXPECT_NEAR(sphereSlabVolume(0, r, 0, 1), 0.5 * v, 1e-15);
  EXPECT_NEAR(sphereSlabVolume(0, r, -1, 0) + sphereSlabVolume(0, r, 0, 0.2) +
                  sphereSlabVolume(0, r, 0.2, 3),
              v, 1e-15);
  EXPECT_EQ(sphereSlabVolume(2, r, -1, 1), 0.0);
}

TEST(Observables, FrontIgnoresDetachedParticles) {
  // A touching row of 10 particles from x = 0.5 to 9.5 (d = 1), one grain 0.3 d ahead (attached),
  // and a detached one 3 d further: the front is the attached grain's edge.
  std::vector<std::array<double, 3>> c;
  for (int i = 0; i < 10; ++i) c.push_back({0.5 + i, 0.5, 0.5});
  c.push_back({10.8, 0.5, 0.5});
  c.push_back({15.0, 0.5, 0.5});
  EXPECT_NEAR(granularFront(c, 0.5, 0.5, 0.0), 11.3, 1e-12);
  // With a zero gap tolerance the 0.3 d gap detaches it.
  EXPECT_NEAR(granularFront(c, 0.5, 0.0, 0.0), 10.0, 1e-12);
}

TEST(Observables, FrontConnectsAcrossPeriodicBoundary) {
  // Two clusters that only touch through the periodic z boundary (width 4) form one mass.
  std::vector<std::array<double, 3>> c = {{0.5, 0.5, 0.5}, {1.5, 0.5, 0.5}, {2.0, 0.5, 3.6}};
  EXPECT_NEAR(granularFront(c, 0.5, 0.1, 4.0), 2.5, 1e-12);
  EXPECT_NEAR(granularFront(c, 0.5, 0.1, 0.0), 2.0, 1e-12);  // not periodic: (2, z=3.6) is alone
}

TEST(Observables, DepositProfileOfAFullLayer) {
  // One full layer of particles (d = 1) on a 4 x 2 floor: hTop = 1 everywhere.
  std::vector<std::array<double, 3>> c;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 2; ++k) c.push_back({0.5 + i, 0.5, 0.5 + k});
  const Profile p = depositProfile(c, 0.5, 2.0, 1.0, 1.0, 4.0, 0.5);
  ASSERT_EQ(p.x.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(p.hTop[i], 1.0);
    EXPECT_NEAR(p.hVolume[i], 2 * kPi / 6.0 / (0.5 * 2.0 * 1.0), 1e-12);
  }
}

TEST(Observables, ThicknessFrontEndsWhereTheDepositThins) {
  Profile p;
  p.x = {0.5, 1.5, 2.5, 3.5, 4.5};
  p.hTop = {3.0, 2.0, 1.2, 0.6, 1.0};  // the grain at 4.5 is beyond the thin bin: not counted
  EXPECT_DOUBLE_EQ(thicknessFront(p, 1.0, 1.0, 1.0), 3.0);
  EXPECT_DOUBLE_EQ(thicknessFront(p, 1.0, 1.0, 0.5), 5.0);  // never thinner: end of the profile
}

TEST(Observables, EnergiesOfKnownParticles) {
  double x0[3] = {0, 2, 0}, v0[3] = {3, 0, 4}, w0[3] = {0, 0, 10};
  double* x[1] = {x0};
  double* v[1] = {v0};
  double* w[1] = {w0};
  double r[1] = {0.1}, m[1] = {2.0};
  ParticleView p;
  p.n = 1, p.x = x, p.v = v, p.omega = w, p.radius = r, p.mass = m;
  const Energies e = energies(p, 9.81, MPI_COMM_WORLD);
  EXPECT_DOUBLE_EQ(e.kineticTranslational, 25.0);
  EXPECT_DOUBLE_EQ(e.kineticRotational, 0.5 * 0.4 * 2.0 * 0.01 * 100);
  EXPECT_DOUBLE_EQ(e.potential, 2.0 * 9.81 * 2);
  EXPECT_EQ(e.count, 1);
}

// demDict settle.gravity buoyant (the default): a mixture's grains settle under g (1 - rho_f /
// rho_s); a dry scene, and `full`, keep LIGGGHTS' g (no command, so older samples keep their
// fingerprint).
TEST(SettleGravity, BuoyantWeightOfAMixtureOnly) {
  Scene s;
  s.particles.density = 2500;
  s.fluidDensity = 1000;
  s.settle.gravity = "full";
  EXPECT_TRUE(settleGravityCommands(s).empty());
  s.settle.gravity = Scene().settle.gravity;  // the default
  EXPECT_EQ(s.settle.gravity, "buoyant");
  const auto c = settleGravityCommands(s);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], "unfix gravi");
  const double g = std::stod(c[1].substr(std::string("fix gravi all gravity ").size()));
  EXPECT_NEAR(g, 9.81 * 0.6, 1e-6);
  s.fluidDensity = 0;  // dry
  EXPECT_TRUE(settleGravityCommands(s).empty());
}

// The packing control's search (demDict settle.packingControl friction) on known monotone φ(μ)
// curves with a ±0.001 ripple standing for the packing's trial-to-trial noise.
namespace {
// Runs the search on phi(mu) with at most `settles` trials; returns it for inspection.
template <class F>
PackingSearch searchOn(F phi, double first, int settles, double minF = 0, double maxF = 1) {
  PackingSearch s(0.6056, 0.003, minF, maxF, first);
  for (int k = 0; k < settles && !s.landed(); ++k) {
    const auto f = s.next();
    if (!f) break;
    EXPECT_GE(*f, minF);
    EXPECT_LE(*f, maxF);
    s.add(*f, phi(*f));
  }
  return s;
}
double ripple(double mu) { return 0.001 * std::sin(97.0 * mu); }
}  // namespace

// The reference tier's measured points (0.63, 0.61, 0.569 at μ 0, 0.1, 0.7) and a softer tier's
// curve, denser by 0.02 and flatter at high friction: both land within the tolerance in the
// default 6 settles from the default first friction 0.1 (each settle is a whole settle's cost).
TEST(PackingSearch, LandsOnMonotoneCurves) {
  const auto reference = [](double mu) {
    return 0.63 - 0.0215 * std::log(1 + mu / 0.05) + ripple(mu);
  };
  const auto soft = [](double mu) { return 0.65 - 0.05 * std::sqrt(mu) + ripple(mu); };
  for (const auto& phi :
       {std::function<double(double)>(reference), std::function<double(double)>(soft)}) {
    const PackingSearch s = searchOn(phi, 0.1, 6);
    ASSERT_TRUE(s.landed()) << "after " << s.trials().size() << " settles";
    EXPECT_NEAR(s.trials().back().fraction, 0.6056, 0.003);
    EXPECT_LE(s.trials().size(), 4u);
  }
}

// A target no friction in range reaches: the search ends at the bound, and says so.
TEST(PackingSearch, StopsAtAnUnreachableTarget) {
  const PackingSearch s = searchOn([](double mu) { return 0.64 - 0.01 * mu; }, 0.1, 10);
  EXPECT_FALSE(s.landed());
  EXPECT_FALSE(s.next().has_value());
  EXPECT_DOUBLE_EQ(s.trials().back().friction, 1.0);
  EXPECT_NE(s.whyNot().find("maxFriction"), std::string::npos) << s.whyNot();
  const PackingSearch t = searchOn([](double mu) { return 0.58 - 0.01 * mu; }, 0.1, 10);
  EXPECT_FALSE(t.next().has_value());
  EXPECT_DOUBLE_EQ(t.trials().back().friction, 0.0);
  EXPECT_NE(t.whyNot().find("minFriction"), std::string::npos) << t.whyNot();
}

// Noise larger than the tolerance (a looser sample at less friction) is reported, not chased.
TEST(PackingSearch, ReportsNoiseAboveTheTolerance) {
  PackingSearch s(0.6056, 0.003, 0, 1, 0.1);
  s.add(0.1, 0.600);
  s.add(0.2, 0.612);
  EXPECT_FALSE(s.next().has_value());
  EXPECT_NE(s.whyNot().find("noise"), std::string::npos) << s.whyNot();
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
