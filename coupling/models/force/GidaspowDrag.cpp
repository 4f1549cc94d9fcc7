// GidaspowDrag: Gidaspow (1994) drag -- Ergun (1952) for dense beds (eps_f < switchVoidfraction,
// default 0.8) and Wen & Yu (1966) above. Written per particle, with u_r = |U - v| the
// interstitial slip, V_p the particle volume, d its diameter:
//   eps_f < 0.8:  beta_A = V_p [150 (1 - eps_f) mu / (eps_f d^2) + 1.75 rho u_r / d]
//                 (= Ergun's momentum-exchange coefficient K V_p / (1 - eps_f)),
//   eps_f >= 0.8: beta_A = (3/4) Cd rho u_r V_p eps_f^-1.65 / d,
//                 Cd = 24 / Re (1 + 0.15 Re^0.687) for Re = eps_f rho d u_r / mu < 1000, else 0.44.
// beta_A is formulation A's drag; formulation B divides by eps_f as for DiFeliceDrag. A fixed bed
// then has the Ergun pressure gradient exactly: -dp/dx - rho g = n beta_B u_r with n = (1 - eps_f)
// / V_p and u_r = U_superficial / eps_f gives Ergun's 150 (1 - eps)^2 mu U / (eps^3 d^2)
// + 1.75 (1 - eps) rho U^2 / (eps^3 d). Not in Li & Zhao (who use Di Felice); it is here as the
// drag law whose bed limit is Ergun, for the fixed-bed verification and comparisons.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "DragLaw.h"
#include "ForceModel.h"

namespace mixflow::coupling {

double gidaspowBeta(double diameter, double rho, double mu, double voidfraction, double slip,
                    double switchVoidfraction, bool divideByVoidfraction) {
  if (!(diameter > 0 && rho > 0 && mu > 0 && voidfraction > 0 && slip >= 0))
    throw std::runtime_error("GidaspowDrag: needs d, rho_f, mu_f, eps_f > 0 and |U - v| >= 0");
  const double vp = 0.52359877559829887 * diameter * diameter * diameter;  // pi d^3 / 6
  const double eps = voidfraction;
  double beta;
  if (eps < switchVoidfraction) {
    beta = vp *
           (150.0 * (1.0 - eps) * mu / (eps * diameter * diameter) + 1.75 * rho * slip / diameter);
  } else {
    const double re = eps * rho * diameter * slip / mu;
    // Cd u_r, finite as u_r -> 0: 24 mu / (eps rho d) (1 + 0.15 Re^0.687)
    const double cdSlip =
        re < 1000 ? 24.0 * mu / (eps * rho * diameter) * (1.0 + 0.15 * std::pow(re, 0.687))
                  : 0.44 * slip;
    beta = 0.75 * cdSlip * rho * vp * std::pow(eps, -1.65) / diameter;
  }
  return divideByVoidfraction ? beta / eps : beta;
}

namespace {

class GidaspowDrag final : public DragLaw {
 public:
  GidaspowDrag(const Dictionary& coeffs, const ForceContext& c)
      : DragLaw(coeffs, c, {"switchVoidfraction"}) {
    switch_ = coeffs.scalarOr("switchVoidfraction", 0.8, Range::closed(0.0, 1.0));
  }
  const std::string& name() const override {
    static const std::string n = "GidaspowDrag";
    return n;
  }
  std::string describe() const override {
    std::ostringstream s;
    s << "GidaspowDrag: Ergun below eps_f = " << switch_
      << ", Wen-Yu above; implicit in the fluid (Ksl, Us); "
      << (divide_ ? "divided by eps_f (formulation B drag)" : "formulation A drag") << "; "
      << viscosityDescription();
    return s.str();
  }

 private:
  double beta(double d, double rho, double mu, double voidfraction, double slip) const override {
    return gidaspowBeta(d, rho, mu, voidfraction, slip, switch_, divide_);
  }
  double switch_ = 0.8;
};

}  // namespace

std::unique_ptr<ForceModel> makeGidaspowDrag(const Dictionary& coeffs, const ForceContext& c) {
  return std::make_unique<GidaspowDrag>(coeffs, c);
}

}  // namespace mixflow::coupling
