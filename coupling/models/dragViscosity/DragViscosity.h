// How a drag law sees a non-Newtonian pore liquid: the viscosity mu_f it is evaluated with,
// selected at run time by `dragViscosity` in the drag's Coeffs sub-dictionary (DiFeliceDrag,
// GidaspowDrag), one small class per closure (docs/parameters.md lists them with defaults;
// `auto`, the default, is resolved for a Newtonian liquid and slip otherwise):
//   resolved  the mixture's apparent viscosity at the resolved (cell) shear rate, as the fluid
//             solver has it (capped at rest); optionally bounded by viscosityMax
//   slip      the liquid's law at a particle-scale rate sqrt(rate_resolved^2 + rate_slip^2),
//             rate_slip = |U - v| / d max(shearRateFactor, 12 (1 - eps_f) / eps_f): Christopher &
//             Middleman's pore-wall rate of a packed bed, blending to the single sphere's
//             shearRateFactor |U - v| / d when dilute. Its power-law part carries the published
//             shape factor (powerLawShape): X(n) of a lone sphere, C&M's ((3n + 1) / 4n)^n
//             in a bed. Its yield part tau_y / rate gives the drag a plastic force that the
//             implicit drag integrates as a regularised sign of the slip.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Dictionary.h"

namespace mixflow::coupling {

struct ParticleState;
struct FluidAtParticle;

// The pore liquid's generalised-Newtonian law (SI, dynamic), as the fluid solver has it:
// mu(rate) = min(cap, (tau_y + K rate^n) / rate); a Newtonian liquid has tau_y = 0, n = 1, K = mu.
struct LiquidLaw {
  double density = 1000;
  double yieldStress = 0;     // tau_y [Pa]
  double consistency = 1e-3;  // K [Pa s^n]
  double flowIndex = 1;       // n
  double viscosityCap = 0;    // [Pa s]; 0: none (Newtonian)
  double airDensity = 1;
  double airViscosity = 1.48e-5;  // [Pa s]
  bool newtonian() const { return yieldStress == 0 && flowIndex == 1 && viscosityCap == 0; }
  // The liquid's apparent viscosity at this shear rate, its power-law part K rate^(n-1) times
  // shape (the drag's correction for the flow around grains; 1: the liquid's own law).
  double viscosity(double rate, double shape = 1.0) const;
  // The liquid fraction of a liquid/air mixture of density rho (clamped to [0, 1]).
  double liquidFraction(double rho) const;
};

class DragViscosity {
 public:
  virtual ~DragViscosity() = default;
  // mu_f [Pa s] for particle p in fluid f at slip |U - v|.
  virtual double viscosity(const ParticleState& p, const FluidAtParticle& f, double slip) const = 0;
  virtual unsigned needs() const = 0;  // FluidNeeds bits
  virtual std::string describe() const = 0;

  // Reads `dragViscosity` (default auto) and its settings from the drag's Coeffs dictionary.
  static std::unique_ptr<DragViscosity> New(const Dictionary& dragCoeffs, const LiquidLaw& liquid);
  static std::vector<std::string> available();
  // The Coeffs entries the closures read (for the drag laws' allowOnly).
  static std::vector<std::string> entries();
};

std::unique_ptr<DragViscosity> makeResolvedDragViscosity(const Dictionary& d, const LiquidLaw& l);
std::unique_ptr<DragViscosity> makeSlipDragViscosity(const Dictionary& d, const LiquidLaw& l);

// The slip closure's shear rate, exposed for tests.
double slipShearRate(double slip, double diameter, double voidfraction, double shearRateFactor);
// X(n): creeping drag on a sphere in a power-law liquid over 3 pi K V^n d^(2-n) (tabulated
// numerical solutions, tests/reference/powerlaw_sphere_drag_correction.csv; 1 for n >= 1).
double powerLawSphereFactor(double n);
// The slip closure's power-law shape factor: X(n)^(1-w) ((3n + 1) / 4n)^(n w), w = pore /
// (pore + shearRateFactor), pore = 12 (1 - eps_f) / eps_f (the bed's share of the slip rate).
double powerLawShapeFactor(double n, double voidfraction, double shearRateFactor);

}  // namespace mixflow::coupling
