// Fluid-particle force models (docs/model.md §6), selected at run time by name from the
// `forceModels (...)` list of constant/couplingProperties; only the listed ones run.
//
// A model sees one particle and the fluid sampled at it, and returns its force split as
//   F = beta (U - v) + F_explicit,
// beta >= 0 being an implicit drag coefficient [kg/s] (only drag laws set it). The coupling turns
// beta into the fluid's implicit Ksl (Us - U) and F_explicit into the explicit fSource, so that
// the fluid receives exactly -sum F (cfd/README.md, "What the coupling provides").
//
// Models are plain C++ (no OpenFOAM): the fluid values come already interpolated.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "Dictionary.h"
#include "DragViscosity.h"
#include "Vec3.h"

namespace mixflow::coupling {

// One particle as the coupling sees it.
struct ParticleState {
  Vec3 x;             // centre [m]
  Vec3 v;             // velocity [m/s]
  double radius = 0;  // [m]
  double mass = 0;    // [kg] (for the drag relaxation limit)
  double volume() const { return 4.18879020478639098 * radius * radius * radius; }  // 4/3 pi r^3
};

// The fluid at a particle (cell value or interpolated, see FoamCoupling).
struct FluidAtParticle {
  Vec3 U;                   // interstitial fluid velocity [m/s]
  double rho = 0;           // fluid density: the VOF liquid/air mixture's [kg/m3]
  double mu = 0;            // apparent dynamic viscosity rho * nu of the mixture [Pa s]
  double shearRate = 0;     // resolved shear rate sqrt(2) |symm(grad U)| [1/s]
  double voidfraction = 1;  // eps_f of the particle's cell (after the eps_f floor)
  Vec3 divTau;              // div(tau): viscous force per unit volume on the fluid [N/m3]
  Vec3 gradP;               // grad(p) [Pa/m] (no formulation-B model uses it)
};

// The scalars of an exchange's fluid sample that the drag laws read besides U: with
// dragCoefficientUpdate slip the implicit drag evaluates the laws with them at every DEM step
// (DemLink.h). voidfraction 0: no such sample (beta held over the interval).
struct DragFluidSample {
  double rho = 0, mu = 0, shearRate = 0, voidfraction = 0;
  static DragFluidSample of(const FluidAtParticle& f) {
    return {f.rho, f.mu, f.shearRate, f.voidfraction};
  }
  FluidAtParticle at(const Vec3& U) const {
    FluidAtParticle f;
    f.U = U;
    f.rho = rho;
    f.mu = mu;
    f.shearRate = shearRate;
    f.voidfraction = voidfraction;
    return f;
  }
};

// Which fluid quantities a model reads (the coupling samples only what the active models need).
enum FluidNeeds : unsigned {
  kNeedsU = 1u << 0,
  kNeedsRho = 1u << 1,
  kNeedsMu = 1u << 2,
  kNeedsVoidfraction = 1u << 3,
  kNeedsDivTau = 1u << 4,
  kNeedsGradP = 1u << 5,
  kNeedsShearRate = 1u << 6,
};

// Settings every model may check its consistency against.
struct ForceContext {
  Vec3 g;                              // gravitational acceleration [m/s2]
  std::string formulation = "B";       // volume-averaged equations (docs/model.md §3)
  std::string viscousStress = "full";  // fluid viscous term: full div(tau) or div(eps_f tau)
  LiquidLaw liquid;                    // the pore liquid's law (drag viscosity closures)
};

struct ParticleForce {
  double beta = 0;     // implicit drag coefficient [kg/s]: drag = beta (U - v)
  Vec3 explicitForce;  // every other force on the particle [N]
  Vec3 total(const Vec3& U, const Vec3& v) const { return beta * (U - v) + explicitForce; }
};

// Each force model's force on one particle, in forceModels order: a fixed array, so the exchange's
// per-particle records need no heap storage. A case lists each model once, so the run-time
// selection table's size (checked against this bound, ForceModel.cpp) bounds the count.
constexpr size_t kMaxForceModels = 4;
using ModelForces = std::array<Vec3, kMaxForceModels>;

class ForceModel {
 public:
  virtual ~ForceModel() = default;
  virtual const std::string& name() const = 0;
  virtual unsigned needs() const = 0;
  // The model's force on particle p (a fresh ParticleForce: the caller sums the models).
  virtual ParticleForce force(const ParticleState& p, const FluidAtParticle& f) const = 0;
  // One line describing the settings (logged at start-up).
  virtual std::string describe() const = 0;

  // Builds the model `name`; its settings come from the sub-dictionary `<name>Coeffs` (absent:
  // defaults). Throws InputError naming the file and the allowed models on an unknown name.
  static std::unique_ptr<ForceModel> New(const std::string& name, const Dictionary& properties,
                                         const ForceContext& context);
  static std::vector<std::string> available();
};

// Factories of the built-in models (one source file each).
std::unique_ptr<ForceModel> makeDiFeliceDrag(const Dictionary& coeffs, const ForceContext& c);
std::unique_ptr<ForceModel> makeBuoyancy(const Dictionary& coeffs, const ForceContext& c);
std::unique_ptr<ForceModel> makeViscousForce(const Dictionary& coeffs, const ForceContext& c);
std::unique_ptr<ForceModel> makeGidaspowDrag(const Dictionary& coeffs, const ForceContext& c);

// Di Felice (1994) drag coefficient pieces, exposed for tests.
struct DiFeliceTerms {
  double reynolds;  // Re_p = rho d eps_f |U - v| / mu
  double chi;       // 3.7 - 0.65 exp(-(1.5 - log10 Re_p)^2 / 2)
  double beta;      // F_d = beta (U - v)
};
// `divideByVoidfraction` turns the drag of Li & Zhao's Eq. 10 (formulation A's drag) into the
// formulation-B drag F_d / eps_f (Zhou et al. 2010; see DiFeliceDrag.cpp).
DiFeliceTerms diFelice(double diameter, double rho, double mu, double voidfraction, double slip,
                       bool divideByVoidfraction);

// Gidaspow (Ergun / Wen-Yu) implicit drag coefficient [kg/s] (GidaspowDrag.cpp).
double gidaspowBeta(double diameter, double rho, double mu, double voidfraction, double slip,
                    double switchVoidfraction, bool divideByVoidfraction);

}  // namespace mixflow::coupling
