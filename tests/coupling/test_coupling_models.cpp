// Unit tests of the coupling's OpenFOAM-free parts: force laws against the tables in
// tests/reference, sphere points, void-fraction models and the per-cell source assembly on a
// synthetic uniform grid (exact volume and action-reaction balances), and the consistency refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Dictionary.h"
#include "ForceModel.h"
#include "ParticleRouting.h"
#include "SourceAssembly.h"
#include "SpherePoints.h"
#include "VoidFractionModel.h"

using namespace mixflow;
using namespace mixflow::coupling;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

// Rows of a tests/reference CSV ('#' comments, header, "..." quoting) as column -> text.
std::vector<std::map<std::string, std::string>> readCsv(const std::string& name) {
  std::ifstream in(std::string(MIXFLOW_REFERENCE_DIR) + "/" + name);
  EXPECT_TRUE(in.good()) << "cannot open " << name;
  auto split = [](const std::string& line) {
    std::vector<std::string> out(1);
    bool q = false;
    for (char c : line) {
      if (c == '"')
        q = !q;
      else if (c == ',' && !q)
        out.emplace_back();
      else if (c != '\r')
        out.back() += c;
    }
    return out;
  };
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = split(line);
      continue;
    }
    const auto cells = split(line);
    std::map<std::string, std::string> r;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) r[header[i]] = cells[i];
    rows.push_back(r);
  }
  return rows;
}

Dictionary dict(const std::string& text) { return Dictionary::parse(text, "test"); }

// Uniform grid [0, L]^3, n cells per direction: the mesh as the models see it.
class GridLocator final : public CellLocator {
 public:
  GridLocator(double L, int n) : L_(L), n_(n), h_(L / n) {}
  long findCell(const Vec3& p, long) const override {
    if (p.x < 0 || p.y < 0 || p.z < 0 || p.x >= L_ || p.y >= L_ || p.z >= L_) return -1;
    const long i = static_cast<long>(p.x / h_), j = static_cast<long>(p.y / h_),
               k = static_cast<long>(p.z / h_);
    return i + n_ * (j + n_ * k);
  }
  bool sphereInsideCell(const Vec3& c, double r, long cell) const override {
    const long i = cell % n_, j = (cell / n_) % n_, k = cell / (n_ * n_);
    const double lo[3] = {i * h_, j * h_, k * h_};
    for (int a = 0; a < 3; ++a)
      if (c[a] - r < lo[a] || c[a] + r > lo[a] + h_) return false;
    return true;
  }
  void facesNear(const Vec3& p, long cell, double band, std::vector<NearFace>& out) const override {
    out.clear();
    const long idx[3] = {cell % n_, (cell / n_) % n_, cell / (n_ * n_)};
    const long stride[3] = {1, n_, static_cast<long>(n_) * n_};
    for (int a = 0; a < 3; ++a) {
      const Vec3 n(a == 0 ? 1 : 0, a == 1 ? 1 : 0, a == 2 ? 1 : 0);
      const double lo = p[a] - idx[a] * h_, hi = (idx[a] + 1) * h_ - p[a];
      if (idx[a] > 0 && lo < band) out.push_back({cell - stride[a], std::max(0.0, lo), -1.0 * n});
      if (idx[a] < n_ - 1 && hi < band) out.push_back({cell + stride[a], std::max(0.0, hi), n});
    }
  }
  long cells() const { return static_cast<long>(n_) * n_ * n_; }
  double cellVolume() const { return h_ * h_ * h_; }

 private:
  double L_;
  int n_;
  double h_;
};

// Terminal velocity of a sphere under the Di Felice drag at eps_f = 1 (bisection on
// beta(u) u = (rho_p - rho_f) g V_p).
double terminalVelocity(double d, double rhoP, double rhoF, double mu) {
  const double weight = (rhoP - rhoF) * kG * kPi * d * d * d / 6;
  double lo = 0, hi = 100;
  for (int it = 0; it < 200; ++it) {
    const double u = 0.5 * (lo + hi);
    (diFelice(d, rhoF, mu, 1.0, u, true).beta * u < weight ? lo : hi) = u;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(DiFeliceDrag, TerminalVelocitiesMatchReferenceTable) {
  // terminal_velocity_single_sphere.csv, column u_DallaValle (5 significant digits).
  const auto rows = readCsv("terminal_velocity_single_sphere.csv");
  ASSERT_GE(rows.size(), 5u);
  for (const auto& r : rows) {
    const double u = terminalVelocity(std::stod(r.at("d_m")), std::stod(r.at("rho_p")),
                                      std::stod(r.at("rho_f")), std::stod(r.at("mu_Pa_s")));
    EXPECT_NEAR(u / std::stod(r.at("u_DallaValle")), 1.0, 1e-4) << r.at("case");
  }
}

TEST(DiFeliceDrag, ChiMatchesReferenceTable) {
  // difelice_chi.csv: chi(Re) and eps^-chi at eps = 0.6 and 0.45 (4 decimals).
  const double d = 1e-3, rho = 1000, mu = 1e-3, eps = 0.6;
  for (const auto& r : readCsv("difelice_chi.csv")) {
    const double re = std::stod(r.at("Re"));
    const double slip = re * mu / (rho * d * eps);
    const DiFeliceTerms t = diFelice(d, rho, mu, eps, slip, false);
    EXPECT_NEAR(t.reynolds, re, 1e-9 * re);
    EXPECT_NEAR(t.chi, std::stod(r.at("chi")), 6e-5) << "Re " << re;
    EXPECT_NEAR(std::pow(0.6, -t.chi), std::stod(r.at("eps0.6^-chi")), 6e-4) << "Re " << re;
    EXPECT_NEAR(std::pow(0.45, -t.chi), std::stod(r.at("eps0.45^-chi")), 6e-4) << "Re " << re;
  }
}

TEST(DiFeliceDrag, ForceFormulaAndFormulationB) {
  // F = (1/8) Cd rho pi d^2 eps^(2 - chi) |u| u with Cd = (0.63 + 4.8/sqrt(Re))^2, Re = rho d eps
  // |u| / mu; formulation B divides by eps.
  const double d = 2e-3, rho = 1208, mu = 0.06, eps = 0.7, u = 0.03;
  const double re = rho * d * eps * u / mu;
  const double cd = std::pow(0.63 + 4.8 / std::sqrt(re), 2);
  const double chi = 3.7 - 0.65 * std::exp(-std::pow(1.5 - std::log10(re), 2) / 2);
  const double fA = 0.125 * cd * rho * kPi * d * d * std::pow(eps, 2 - chi) * u * u;
  EXPECT_NEAR(diFelice(d, rho, mu, eps, u, false).beta * u, fA, 1e-12 * fA);
  EXPECT_NEAR(diFelice(d, rho, mu, eps, u, true).beta * u, fA / eps, 1e-12 * fA);
  // Zero slip: beta finite, the creeping-flow limit (1/8) 4.8^2 pi mu d eps^-1.7 (A).
  EXPECT_NEAR(diFelice(d, rho, mu, eps, 0, false).beta,
              0.125 * 4.8 * 4.8 * kPi * mu * d * std::pow(eps, 1 - 3.7), 1e-12);
  EXPECT_THROW(diFelice(d, rho, 0.0, eps, u, true), std::runtime_error);
}

TEST(ForceModels, SelectionAndCoefficients) {
  ForceContext c;
  c.g = Vec3(0, -kG, 0);
  const Dictionary props = dict("DiFeliceDragCoeffs { divideByVoidfraction no; }");
  const auto drag = ForceModel::New("DiFeliceDrag", props, c);
  ParticleState p;
  p.radius = 1e-3;
  p.v = Vec3(0, -0.01, 0);
  FluidAtParticle f;
  f.rho = 1000;
  f.mu = 1e-3;
  f.voidfraction = 0.5;
  const ParticleForce fd = drag->force(p, f);
  EXPECT_NEAR(fd.beta, diFelice(2e-3, 1000, 1e-3, 0.5, 0.01, false).beta, 1e-15);
  EXPECT_GT(fd.total(f.U, p.v).y, 0);  // drag opposes the fall
  EXPECT_THROW(ForceModel::New("Drag", props, c), InputError);
  EXPECT_THROW(ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { typo 1; }"), c),
               InputError);
}

TEST(DiFeliceDrag, ViscosityMaxBoundsOnlyTheDragsViscosity) {
  // A capped Herschel-Bulkley liquid near rest (mu 1e4 Pa s) seen by the drag at viscosityMax
  // 1 Pa s: beta is the one at 1 Pa s; a liquid below the bound is untouched.
  ForceContext c;
  const auto drag = ForceModel::New(
      "DiFeliceDrag", dict("DiFeliceDragCoeffs { divideByVoidfraction no; viscosityMax 1; }"), c);
  ParticleState p;
  p.radius = 0.012;
  FluidAtParticle f;
  f.rho = 1000;
  f.voidfraction = 0.4;
  f.U = Vec3(0, 1e-3, 0);
  f.mu = 1e4;
  EXPECT_NEAR(drag->force(p, f).beta, diFelice(0.024, 1000, 1.0, 0.4, 1e-3, false).beta, 1e-9);
  f.mu = 0.5;
  EXPECT_NEAR(drag->force(p, f).beta, diFelice(0.024, 1000, 0.5, 0.4, 1e-3, false).beta, 1e-9);
  EXPECT_THROW(ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { viscosityMax 0; }"), c),
               InputError);
}

TEST(DragViscosity, LiquidLawAndSlipRate) {
  LiquidLaw b;  // the paper's Bingham liquid
  b.density = 1400;
  b.yieldStress = 2.1;
  b.consistency = 4;
  b.viscosityCap = 1e4;
  EXPECT_NEAR(b.viscosity(1.0), 6.1, 1e-12);  // (tau_y + mu_p rate) / rate
  EXPECT_NEAR(b.viscosity(1e-6), 1e4, 1e-9);  // capped at rest
  EXPECT_NEAR(b.liquidFraction(1400), 1.0, 1e-15);
  EXPECT_NEAR(b.liquidFraction(700.5), 0.5, 1e-15);
  EXPECT_NEAR(b.liquidFraction(0.5), 0.0, 1e-15);
  // Dilute: the single sphere's |U - v| / d; packed (eps 0.4): 12 (1 - eps) / eps = 18 times it.
  EXPECT_NEAR(slipShearRate(0.024, 0.024, 0.999, 1.0), 1.0, 1e-12);
  EXPECT_NEAR(slipShearRate(0.024, 0.024, 0.4, 1.0), 18.0, 1e-12);
  EXPECT_NEAR(slipShearRate(0.024, 0.024, 0.999, 1.5), 1.5, 1e-12);
}

TEST(DragViscosity, PowerLawShapeFactorHasTheSphereAndBedLimits) {
  // Lone sphere (eps_f 1): X(n) of the tabulated numerical solutions; 1 for a Newtonian or
  // Bingham law (n = 1) in any packing.
  EXPECT_DOUBLE_EQ(powerLawSphereFactor(1.0), 1.0);
  EXPECT_NEAR(powerLawSphereFactor(0.5), 1.420, 1e-12);
  EXPECT_NEAR(powerLawSphereFactor(0.45), 1.431, 1e-12);
  EXPECT_DOUBLE_EQ(powerLawShapeFactor(1.0, 0.4, 1.0), 1.0);
  EXPECT_NEAR(powerLawShapeFactor(0.5, 1.0, 1.0), 1.420, 1e-12);
  // Packed: the pore rate 12 (1 - eps) / eps = 18 at eps 0.4 takes weight 18/19 for Christopher &
  // Middleman's ((3n + 1) / 4n)^n = 1.25^0.5 at n 0.5.
  const double bed = std::sqrt(1.25);
  EXPECT_NEAR(powerLawShapeFactor(0.5, 0.4, 1.0),
              std::pow(1.420, 1.0 / 19) * std::pow(bed, 18.0 / 19), 1e-12);
  // The liquid's law takes the factor on its power-law part only.
  LiquidLaw hb;
  hb.yieldStress = 30;
  hb.consistency = 4.279;
  hb.flowIndex = 0.479;
  hb.viscosityCap = 1e4;
  EXPECT_NEAR(hb.viscosity(2.0, 1.5), 30 / 2.0 + 1.5 * 4.279 * std::pow(2.0, 0.479 - 1), 1e-12);
}

TEST(DragViscosity, SlipClosureGivesTheBinghamPlasticDrag) {
  // A lone grain at slip s in a Bingham liquid: mu = tau_y d / s + mu_p, so the drag tends to the
  // plastic force Cd Re / 24 x 3 pi tau_y d^2 as s -> 0 (before the cap), and the resolved
  // closure keeps the cell's (capped) viscosity.
  ForceContext c;
  c.liquid.density = 1400;
  c.liquid.yieldStress = 2.1;
  c.liquid.consistency = 4;
  c.liquid.viscosityCap = 1e4;
  const auto slip =
      ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { dragViscosity slip; }"), c);
  const auto resolved =
      ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { dragViscosity resolved; }"), c);
  // auto: slip for this liquid, resolved for a Newtonian one.
  const auto autoBingham = ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { }"), c);
  EXPECT_TRUE(autoBingham->needs() & kNeedsShearRate);
  EXPECT_FALSE(
      ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { }"), ForceContext())->needs() &
      kNeedsShearRate);
  EXPECT_TRUE(slip->needs() & kNeedsShearRate);
  EXPECT_FALSE(resolved->needs() & kNeedsShearRate);
  ParticleState p;
  p.radius = 0.012;
  FluidAtParticle f;
  f.rho = 1400;
  f.voidfraction = 1.0;
  f.mu = 1e4;  // the cell at its cap
  const double s = 0.05;
  f.U = Vec3(0, s, 0);
  const double mu = 2.1 * 0.024 / s + 4;
  EXPECT_NEAR(slip->force(p, f).beta, diFelice(0.024, 1400, mu, 1.0, s, true).beta, 1e-12);
  EXPECT_NEAR(resolved->force(p, f).beta, diFelice(0.024, 1400, 1e4, 1.0, s, true).beta, 1e-9);
  // A resolved shear rate adds in quadrature: at rate r and zero slip mu = mu(r).
  f.U = Vec3(0, 0, 0);
  f.shearRate = 2.0;
  EXPECT_NEAR(slip->force(p, f).beta, diFelice(0.024, 1400, 2.1 / 2.0 + 4, 1.0, 0, true).beta,
              1e-12);
  // Plastic limit: F / (3 pi tau_y d^2) -> Cd Re / 24 = 4.8^2 / 24 = 0.96 at small slip.
  f.shearRate = 0;
  const double small = 1e-4;
  f.U = Vec3(0, small, 0);
  const double F = slip->force(p, f).beta * small;
  EXPECT_NEAR(F / (3 * 3.14159265358979 * 2.1 * 0.024 * 0.024), 0.96, 0.01);
  // Entries of the other closure are refused.
  EXPECT_THROW(
      ForceModel::New("DiFeliceDrag",
                      dict("DiFeliceDragCoeffs { dragViscosity slip; viscosityMax 1; }"), c),
      InputError);
  EXPECT_THROW(ForceModel::New("DiFeliceDrag",
                               dict("DiFeliceDragCoeffs { dragViscosity resolved; "
                                    "slipCoeffs { shearRateFactor 2; } }"),
                               c),
               InputError);
  EXPECT_THROW(
      ForceModel::New("DiFeliceDrag", dict("DiFeliceDragCoeffs { dragViscosity pore; }"), c),
      InputError);
}

TEST(DragViscosity, ResolvedClosureAtZeroShearTakesTheLiquidsLimit) {
  // OpenFOAM's HerschelBulkley gives nu = 0 in a cell at rest when tau_y = 0 and n = 1; the
  // resolved closure then takes the law's limit K, the same drag as the Newtonian liquid K.
  ForceContext hb;
  hb.liquid.density = 1000;
  hb.liquid.yieldStress = 0;
  hb.liquid.consistency = 1e-3;
  hb.liquid.flowIndex = 1;
  hb.liquid.viscosityCap = 1e4;
  ForceContext water;
  water.liquid.density = 1000;
  const auto coeffs = dict("DiFeliceDragCoeffs { dragViscosity resolved; }");
  const auto inHb = ForceModel::New("DiFeliceDrag", coeffs, hb);
  const auto inWater = ForceModel::New("DiFeliceDrag", coeffs, water);
  ParticleState p;
  p.radius = 0.012;
  FluidAtParticle f;
  f.rho = 1000;
  f.voidfraction = 0.4;
  f.U = Vec3(0, 0.01, 0);
  f.mu = 0;  // the solver's HB value at zero shear
  const double beta = diFelice(0.024, 1000, 1e-3, 0.4, 0.01, true).beta;
  EXPECT_NEAR(inHb->force(p, f).beta, beta, 1e-12 * beta);
  f.mu = 1e-3;  // the Newtonian solver's value
  EXPECT_NEAR(inWater->force(p, f).beta, beta, 1e-12 * beta);
  // A yield-stress liquid at rest: its cap.
  hb.liquid.yieldStress = 3;
  f.mu = 0;
  EXPECT_NEAR(ForceModel::New("DiFeliceDrag", coeffs, hb)->force(p, f).beta,
              diFelice(0.024, 1000, 1e4, 0.4, 0.01, true).beta, 1e-9);
}

TEST(ForceModels, BuoyancyIsMinusDisplacedFluidWeight) {
  ForceContext c;
  c.g = Vec3(0, -kG, 0);
  const auto b = ForceModel::New("buoyancy", dict(""), c);
  ParticleState p;
  p.radius = 0.012;
  FluidAtParticle f;
  f.rho = 1400;
  const Vec3 F = b->force(p, f).explicitForce;
  EXPECT_NEAR(F.y, 1400 * kG * 4.0 / 3.0 * kPi * std::pow(0.012, 3), 1e-15);
  EXPECT_EQ(F.x, 0);
  EXPECT_EQ(b->force(p, f).beta, 0);
  c.formulation = "A";  // buoyancy + formulation A counts buoyancy twice: refused
  EXPECT_THROW(ForceModel::New("buoyancy", dict(""), c), InputError);
}

TEST(ForceModels, ViscousForceIsPlusVolumeTimesDivTau) {
  ForceContext c;
  const auto v = ForceModel::New("viscousForce", dict(""), c);
  ParticleState p;
  p.radius = 0.01;
  FluidAtParticle f;
  f.divTau = Vec3(3, -2, 1);  // N/m3 pushing the fluid parcel towards +x
  const Vec3 F = v->force(p, f).explicitForce;
  const double vp = 4.0 / 3.0 * kPi * 1e-6;
  EXPECT_NEAR(F.x, 3 * vp, 1e-18);
  EXPECT_NEAR(F.y, -2 * vp, 1e-18);
  c.viscousStress = "voidfractionWeighted";  // fluid has div(eps tau): would double count
  EXPECT_THROW(ForceModel::New("viscousForce", dict(""), c), InputError);
}

TEST(SpherePoints, WeightsSumToOneAndSplitLikeTheBall) {
  const SpherePoints s = SpherePoints::make(3, 16);
  ASSERT_EQ(s.offsets.size(), 48u);
  double sum = 0, cx = 0, cy = 0, cz = 0;
  for (size_t i = 0; i < s.weights.size(); ++i) {
    sum += s.weights[i];
    cx += s.weights[i] * s.offsets[i].x;
    cy += s.weights[i] * s.offsets[i].y;
    cz += s.weights[i] * s.offsets[i].z;
    EXPECT_LT(mag(s.offsets[i]), 1.0);
  }
  EXPECT_EQ(sum, 1.0);  // exactly, in the order the coupling adds them
  EXPECT_NEAR(cx, 0, 0.03);
  EXPECT_NEAR(cy, 0, 0.03);
  EXPECT_NEAR(cz, 0, 0.03);
  // A plane cutting the ball: the points' split within 0.07 of the exact cap volume (one point
  // is 1/48 = 0.021 of the volume).
  double worst = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double a = -0.95; a <= 0.95; a += 0.05)
      worst = std::max(worst, std::abs(s.fractionAbove(axis, a) - exactCapFraction(a)));
  EXPECT_LT(worst, 0.07);
  std::cout << "  worst cap-fraction error of the 48-point sphere: " << worst << std::endl;
}

TEST(VoidFraction, DividedConservesVolumeAndReportsOutside) {
  const GridLocator grid(0.1, 5);                                    // 2 cm cells
  const auto divided = VoidFractionModel::New("divided", dict(""));  // default: no smoothing
  const auto smoothed = VoidFractionModel::New("divided", dict("dividedCoeffs { smoothing 0.5; }"));
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> pos(-0.005, 0.105), rad(0.002, 0.008);
  ParticleCells cells;
  for (int n = 0; n < 2000; ++n) {
    ParticleState p;
    p.x = Vec3(pos(rng), pos(rng), pos(rng));
    p.radius = rad(rng);
    for (const auto* model : {divided.get(), smoothed.get()}) {
      model->locate(p, -1, grid, cells);
      const double vp = p.volume();
      EXPECT_NEAR(cells.insideVolume() + cells.outsideVolume, vp, 1e-14 * vp);
      EXPECT_GE(cells.outsideVolume, 0);
      for (const auto& cv : cells.volumes) EXPECT_GE(cv.second, 0);
      EXPECT_EQ(cells.centreCell, grid.findCell(p.x, -1));
    }
  }
  // Centre on the wall plane x = 0: about half outside.
  ParticleState p;
  p.x = Vec3(0.0, 0.05, 0.05);
  p.radius = 0.005;
  divided->locate(p, -1, grid, cells);
  EXPECT_NEAR(cells.outsideVolume / p.volume(), 0.5, 0.05);
  // Centre on an inner face plane x = 0.04: about half in each cell.
  p.x = Vec3(0.04, 0.05, 0.05);
  divided->locate(p, -1, grid, cells);
  ASSERT_EQ(cells.volumes.size(), 2u);
  EXPECT_NEAR(cells.volumes[0].second / p.volume(), 0.5, 0.05);
  // The centre model puts everything in one cell.
  const auto centre = VoidFractionModel::New("centre", dict(""));
  centre->locate(p, -1, grid, cells);
  ASSERT_EQ(cells.volumes.size(), 1u);
  EXPECT_EQ(cells.volumes[0].second, p.volume());
  EXPECT_THROW(VoidFractionModel::New("bigCell", dict("")), InputError);
}

TEST(VoidFraction, FaceSmoothingMakesVoidFractionContinuous) {
  // A sphere moved in steps of 1e-6 m across a face (x = 0.04) and across an edge (x = y =
  // 0.04): without smoothing a cell's share jumps by a whole point (1/48 of V_p) as a point
  // crosses; with smoothing 0.5 it changes by at most ~ V_p dx / b per step (b = 0.5 r).
  const GridLocator grid(0.1, 5);  // 2 cm cells
  const double r = 0.004, dx = 1e-6;
  for (const bool edge : {false, true})
    for (const double smoothing : {0.0, 0.5}) {
      std::ostringstream coeffs;
      coeffs << "dividedCoeffs { smoothing " << smoothing << "; }";
      const auto model = VoidFractionModel::New("divided", dict(coeffs.str()));
      std::vector<double> last(grid.cells(), 0.0), now(grid.cells());
      double worst = 0;
      ParticleCells cells;
      ParticleState p;
      p.radius = r;
      for (int k = 0; k <= 20000; ++k) {
        const double t = 0.03 + k * dx;
        p.x = Vec3(t, edge ? t : 0.05, 0.05);
        model->locate(p, -1, grid, cells);
        std::fill(now.begin(), now.end(), 0.0);
        for (const auto& cv : cells.volumes) now[cv.first] += cv.second;
        ASSERT_NEAR(cells.insideVolume(), p.volume(), 1e-15);
        if (k > 0)
          for (long c = 0; c < grid.cells(); ++c)
            worst = std::max(worst, std::abs(now[c] - last[c]) / p.volume());
        last.swap(now);
      }
      std::cout << "  " << (edge ? "edge" : "face") << " crossing, smoothing " << smoothing
                << ": largest change of a cell's share in one 1e-6 m step " << worst << std::endl;
      if (smoothing > 0)
        EXPECT_LT(worst, 2 * dx / (smoothing * r));  // Lipschitz: no jump
      else
        EXPECT_GT(worst, 0.02);  // a whole point (1/48 = 0.0208)
    }
}

namespace {

// Random particles in a dense grid: volumes, clipping, sources; returns the assembly.
struct Balance {
  double volumeError, actionReaction, clipped, outside, scale;
};

Balance randomBalance(
    const std::string& vfModel, SourceAssembly::Distribution dist, bool interpolatedU,
    unsigned seed,
    SourceAssembly::ReactionVelocity rv = SourceAssembly::ReactionVelocity::particleMean) {
  const GridLocator grid(0.1, 5);
  const auto model = VoidFractionModel::New(vfModel, dict(""));
  std::vector<double> volumes(grid.cells(), grid.cellVolume());
  SourceAssembly a(volumes, 0.4, dist, rv);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-0.004, 0.104), unit(-1, 1), rad(0.004, 0.006);
  std::vector<Vec3> Ucell(grid.cells());
  for (auto& u : Ucell) u = Vec3(unit(rng), unit(rng), unit(rng));
  const int n = 3000;  // ~ solid fraction 0.6 on average: many cells clipped at eps_f = 0.4
  std::vector<ParticleState> ps(n);
  std::vector<ParticleCells> cs(n);
  for (int i = 0; i < n; ++i) {
    ps[i].x = Vec3(pos(rng), pos(rng) * 0.5, pos(rng));  // packed into the lower half
    ps[i].v = Vec3(unit(rng), unit(rng), unit(rng));
    ps[i].radius = rad(rng);
    model->locate(ps[i], -1, grid, cs[i]);
    a.addVolume(ps[i], cs[i]);
  }
  a.finishVoidfraction();
  for (int i = 0; i < n; ++i) {
    if (cs[i].centreCell < 0) continue;
    ParticleForce f;
    f.beta = 1e-3 * (1 + unit(rng));
    f.explicitForce = Vec3(unit(rng), unit(rng), unit(rng));
    const Vec3 Ui = interpolatedU ? Ucell[cs[i].centreCell] + 0.3 * Vec3(unit(rng), 0, unit(rng))
                                  : Ucell[cs[i].centreCell];
    a.addSource(ps[i], cs[i], f, Ui, Ucell);
  }
  a.finishSources(Ucell);
  const ExchangeTotals& t = a.totals();
  Balance b;
  b.volumeError = (t.fluidSeenVolume - (t.particleVolume - t.outsideVolume - t.clippedVolume)) /
                  t.particleVolume;
  b.actionReaction = mag(t.forceOnParticles + t.forceOnFluid) / t.forceScale;
  b.clipped = t.clippedVolume / t.particleVolume;
  b.outside = t.outsideVolume / t.particleVolume;
  b.scale = t.forceScale;
  for (double e : a.voidfraction()) EXPECT_GE(e, 0.4);
  return b;
}

}  // namespace

TEST(SourceAssembly, ExactVolumeAndActionReaction) {
  struct Case {
    const char* model;
    SourceAssembly::Distribution dist;
    bool interpolated;
  };
  using RV = SourceAssembly::ReactionVelocity;
  for (const Case& c : {Case{"divided", SourceAssembly::Distribution::volume, true},
                        Case{"divided", SourceAssembly::Distribution::centre, true},
                        Case{"divided", SourceAssembly::Distribution::volume, false},
                        Case{"centre", SourceAssembly::Distribution::volume, false}})
    for (const RV rv : {RV::particleMean, RV::cell}) {
      const Balance b = randomBalance(c.model, c.dist, c.interpolated, 2024, rv);
      std::cout << "  " << c.model
                << (c.dist == SourceAssembly::Distribution::volume ? " / volume" : " / centre")
                << (c.interpolated ? " / interpolated U" : " / cell U")
                << (rv == RV::cell ? " / reaction at U_c" : " / reaction at particle mean")
                << ": volume error " << b.volumeError << ", action-reaction " << b.actionReaction
                << ", clipped " << b.clipped << ", outside " << b.outside << std::endl;
      EXPECT_LT(std::abs(b.volumeError), 1e-12);
      EXPECT_LT(b.actionReaction, 1e-12);
      EXPECT_GT(b.clipped, 0.01);   // the floor was exercised
      EXPECT_GT(b.outside, 0.001);  // so was the outside accounting
    }
}

TEST(SourceAssembly, SliverCellDragActsOnItsOwnVelocity) {
  // One particle centred in cell A with a sliver in cell B, which moves at 3 m/s while A is at
  // rest; the particle's drag used U_A. The fluid's force on B, Ksl_B (Us_B - U_B) + fSource_B,
  // must depend on U_B through the implicit term: with particleMean the explicit part per unit
  // Ksl is the same in A and B (so dF_B/dU_B = -Ksl_B V_B), with `cell` it cancels the implicit
  // term in B (the fluid in B feels no drag on its own velocity). Both give the exact total.
  const GridLocator grid(0.1, 5);
  const auto model = VoidFractionModel::New("divided", dict(""));
  ParticleState p;
  p.x = Vec3(0.057, 0.05, 0.05);  // 3 mm from the face x = 0.06 between A and B
  p.v = Vec3(0, -0.2, 0);
  p.radius = 0.005;
  ParticleCells cells;
  model->locate(p, -1, grid, cells);
  ASSERT_EQ(cells.volumes.size(), 2u);
  const long A = cells.centreCell;
  const long B = cells.volumes[0].first == A ? cells.volumes[1].first : cells.volumes[0].first;
  std::vector<Vec3> Ucell(grid.cells());
  Ucell[B] = Vec3(0, -3, 0);
  ParticleForce f;
  f.beta = 0.5;
  using RV = SourceAssembly::ReactionVelocity;
  for (const RV rv : {RV::particleMean, RV::cell}) {
    SourceAssembly a(std::vector<double>(grid.cells(), grid.cellVolume()), 0.05,
                     SourceAssembly::Distribution::volume, rv);
    a.addVolume(p, cells);
    a.finishVoidfraction();
    a.addSource(p, cells, f, Ucell[A], Ucell);
    a.finishSources(Ucell);
    // Total: exactly minus the particle's drag beta (U_A - v).
    EXPECT_NEAR(a.totals().forceOnFluid.y, -f.beta * (Ucell[A].y - p.v.y), 1e-14);
    const double perKslA = a.fSource()[A].y / a.Ksl()[A];
    const double perKslB = a.fSource()[B].y / a.Ksl()[B];
    if (rv == RV::particleMean) {
      EXPECT_NEAR(perKslA, perKslB, 1e-12);  // the same explicit velocity in both cells
    } else {
      EXPECT_NEAR(perKslB, Ucell[B].y - Ucell[A].y, 1e-12);  // cancels -Ksl_B U_B
    }
  }
}

TEST(SourceAssembly, DragOnlyWithCellValuesNeedsNoExplicitPart) {
  // Drag only, U_i = U of the centre cell, reaction in the centre cell: fSource stays zero and
  // Ksl (Us - U_c) V_c is exactly the drag reaction.
  const GridLocator grid(0.1, 5);
  const auto model = VoidFractionModel::New("centre", dict(""));
  SourceAssembly a(std::vector<double>(grid.cells(), grid.cellVolume()), 0.05,
                   SourceAssembly::Distribution::centre);
  std::vector<Vec3> Ucell(grid.cells(), Vec3(0.1, 0, 0));
  ParticleState p;
  p.x = Vec3(0.05, 0.05, 0.05);
  p.v = Vec3(0, -0.2, 0);
  p.radius = 0.003;
  ParticleCells cells;
  model->locate(p, -1, grid, cells);
  a.addVolume(p, cells);
  a.finishVoidfraction();
  ParticleForce f;
  f.beta = 0.5;
  a.addSource(p, cells, f, Ucell[cells.centreCell], Ucell);
  a.finishSources(Ucell);
  const long c = cells.centreCell;
  EXPECT_EQ(mag(a.fSource()[c]), 0.0);
  EXPECT_NEAR(a.Ksl()[c] * grid.cellVolume(), 0.5, 1e-15);
  EXPECT_NEAR(a.Us()[c].y, -0.2, 1e-15);
  EXPECT_NEAR(a.voidfraction()[c], 1 - p.volume() / grid.cellVolume(), 1e-15);
}

TEST(GidaspowDrag, FixedBedGivesErgunPressureDrop) {
  // ergun_cfdem_ErgunTestMPI.csv: d 1 mm, eps 0.451335, L 0.0156 m, rho_f 10, nu 1.5e-4.
  // Formulation B, bed at rest: -dp/dx - rho g = n beta_B U / eps, n = (1 - eps) / V_p.
  const double d = 1e-3, eps = 0.451335, L = 0.0156, rho = 10, mu = 1.5e-3;
  const double n = (1 - eps) / (kPi * d * d * d / 6);
  int rows = 0;
  for (const auto& r : readCsv("ergun_cfdem_ErgunTestMPI.csv")) {
    const double U = std::stod(r.at("U_superficial_m_s"));
    const double ergun = std::stod(r.at("dP_Ergun_Pa"));
    const double ur = U / eps;
    const double dpG = n * gidaspowBeta(d, rho, mu, eps, ur, 0.8, true) * ur * L;
    EXPECT_NEAR(dpG / ergun, 1.0, 2e-5) << "U " << U;
    // Di Felice's bed drop is ~20 % lower than Ergun's at this porosity (a property of the
    // correlation, reported by the coupled fixed-bed test).
    const double dpD = n * diFelice(d, rho, mu, eps, ur, true).beta * ur * L;
    if (rows++ == 0)
      std::cout << "  U " << U << ": Ergun " << ergun << " Pa, Gidaspow " << dpG
                << " Pa, Di Felice " << dpD << " Pa (" << 100 * (dpD / ergun - 1) << " %)"
                << std::endl;
  }
  EXPECT_GE(rows, 10);
  // Single particle (eps -> 1, Wen-Yu branch): the standard drag (pi d^2 / 8) Cd rho u^2.
  const double u = 0.05, re = rho * d * u / mu;
  const double cd = 24 / re * (1 + 0.15 * std::pow(re, 0.687));
  EXPECT_NEAR(gidaspowBeta(d, rho, mu, 1.0, u, 0.8, true) * u, kPi * d * d / 8 * cd * rho * u * u,
              1e-15);
}

// The force laws at the extremes: Re_p -> 0, very large Re_p, eps_f at the floor
// and at 1, a capped yield-stress liquid at rest. Every coefficient must be finite and positive
// and reach the law's own limits; inputs outside the law's support throw with a message.
TEST(ForceModels, DiFeliceExtremes) {
  const double d = 0.024, rho = 1000;
  // Re_p -> 0 (zero slip): the Stokes-like limit 0.125 * 4.8^2 * pi mu d eps^(1 - 3.7) (formulation
  // A), 0.96 x Stokes' 3 pi mu d at eps_f = 1; continuous as the slip goes to zero.
  for (double mu : {1e-3, 4.0, 1e4}) {
    const double b0 = diFelice(d, rho, mu, 1.0, 0.0, false).beta;
    EXPECT_NEAR(b0, 0.125 * 4.8 * 4.8 * kPi * mu * d, 1e-12 * b0) << "mu " << mu;
    EXPECT_NEAR(diFelice(d, rho, mu, 1.0, 1e-14, false).beta, b0, 1e-5 * b0);
    EXPECT_TRUE(std::isfinite(diFelice(d, rho, mu, 0.36, 0.0, true).beta));
  }
  // Re_p -> infinity (slip 1e3 m/s in water, Re_p = 2.4e7): Newton's regime, beta / slip ->
  // 0.125 * 0.63^2 rho pi d^2 eps^(2 - 3.7).
  const double slip = 1e3;
  const DiFeliceTerms hi = diFelice(d, rho, 1e-3, 0.5, slip, false);
  const double newton = 0.125 * 0.63 * 0.63 * rho * kPi * d * d * std::pow(0.5, 2 - 3.7);
  EXPECT_GT(hi.reynolds, 1e7);
  EXPECT_NEAR(hi.beta / slip, newton, 0.02 * newton);
  // eps_f at the solver's floor (0.05) and at 1: finite, and larger at the floor.
  const double bFloor = diFelice(d, rho, 1e-3, 0.05, 0.1, true).beta;
  const double bOne = diFelice(d, rho, 1e-3, 1.0, 0.1, true).beta;
  EXPECT_TRUE(std::isfinite(bFloor) && std::isfinite(bOne));
  EXPECT_GT(bFloor, bOne);
  // Outside the support: eps_f = 0, mu = 0, negative slip -> a message naming the values.
  EXPECT_THROW(diFelice(d, rho, 1e-3, 0.0, 0.1, true), std::runtime_error);
  EXPECT_THROW(diFelice(d, rho, 0.0, 0.5, 0.1, true), std::runtime_error);
  try {
    diFelice(d, rho, 1e-3, 0.0, 0.1, true);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("eps_f 0"), std::string::npos) << e.what();
  }
}

// The exchange's records go between ranks as runs of doubles: each unpacks to what was packed,
// and packs to exactly its declared width.
TEST(ParticleRouting, RecordsRoundTrip) {
  std::vector<double> b;
  ParticleRecord r1{7, 123456789, ParticleState{Vec3(1, 2, 3), Vec3(-4, 5e-3, 6), 1e-3, 2.5e-6}};
  r1.pack(b);
  ASSERT_EQ(b.size(), ParticleRecord::kWidth);
  const ParticleRecord u1 = ParticleRecord::unpack(b.data(), b.size());
  EXPECT_EQ(u1.ownerIndex, 7);
  EXPECT_EQ(u1.tag, 123456789);
  EXPECT_EQ(u1.p.x.z, 3);
  EXPECT_EQ(u1.p.v.y, 5e-3);
  EXPECT_EQ(u1.p.radius, 1e-3);
  EXPECT_EQ(u1.p.mass, 2.5e-6);

  PartRecord r2;
  r2.ownerIndex = 3;
  r2.workIndex = 11;
  r2.inside = 0.25;
  r2.centre = true;
  r2.drag = CentreForce{ParticleForce{0.5, Vec3(1, 2, 3)}, Vec3(4, 5, 6), 7, Vec3(8, 9, 10), 11};
  r2.drag.sample = DragFluidSample{1000, 2.5, 0.125, 0.4};
  r2.nModels = 2;
  r2.modelForces[0] = Vec3(12, 13, 14);
  r2.modelForces[1] = Vec3(15, 16, 17);
  b.clear();
  r2.pack(b);
  ASSERT_EQ(b.size(), PartRecord::width(2));
  const PartRecord u2 = PartRecord::unpack(b.data(), b.size());
  EXPECT_EQ(u2.workIndex, 11);
  EXPECT_TRUE(u2.centre);
  EXPECT_EQ(u2.drag.force.explicitForce.z, 3);
  EXPECT_EQ(u2.drag.U.x, 4);
  EXPECT_EQ(u2.drag.invFluidMass, 7);
  EXPECT_EQ(u2.drag.fluidAcceleration.y, 9);
  EXPECT_EQ(u2.drag.counterflow, 11);
  EXPECT_EQ(u2.drag.sample.rho, 1000);
  EXPECT_EQ(u2.drag.sample.voidfraction, 0.4);
  ASSERT_EQ(u2.nModels, 2u);
  EXPECT_EQ(u2.modelForces[1].z, 17);

  ReactionRecord r3{5,
                    FluidReaction{ParticleForce{2, Vec3(1, 1, 1)}, Vec3(3, 3, 3), Vec3(4, 4, 4),
                                  Vec3(0.5, 0.5, 0.5)},
                    1e-6, true, 0.75};
  b.clear();
  r3.pack(b);
  ASSERT_EQ(b.size(), ReactionRecord::kWidth);
  const ReactionRecord u3 = ReactionRecord::unpack(b.data(), b.size());
  EXPECT_EQ(u3.workIndex, 5);
  EXPECT_EQ(u3.reaction.force.beta, 2);
  EXPECT_EQ(u3.reaction.U.y, 3);
  EXPECT_EQ(u3.reaction.v.z, 4);
  EXPECT_EQ(u3.reaction.explicitDrag.x, 0.5);
  EXPECT_EQ(u3.insideTotal, 1e-6);
  EXPECT_TRUE(u3.holdsCentre);
  EXPECT_EQ(u3.sigma, 0.75);

  b.clear();
  VelocityRecord{9, Vec3(1, 2, 3)}.pack(b);
  ASSERT_EQ(b.size(), VelocityRecord::kWidth);
  EXPECT_EQ(VelocityRecord::unpack(b.data(), b.size()).U.y, 2);
}
