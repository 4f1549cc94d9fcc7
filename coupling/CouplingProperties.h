// constant/couplingProperties: what a coupled case asks of the coupling (OpenFOAM dictionary
// syntax, read with mixflow's validating reader: unknown entries, unknown model names and
// inconsistent combinations stop the run before it starts). Every top-level entry is declared
// once in schema() (CouplingProperties.cpp), whose table docs/parameters.md shows; the models'
// Coeffs blocks are read by the models.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Dictionary.h"
#include "Schema.h"

namespace mixflow::coupling {

struct CouplingProperties {
  Dictionary dict;  // the file (for the models' Coeffs sub-dictionaries)
  std::string demScript;
  long exchangeEvery = 100;
  std::vector<std::string> forceModels;
  std::string voidFractionModel = "divided";
  std::string interpolation = "cell";
  std::string sourceDistribution = "volume";
  std::string dragReactionVelocity = "particleMean";
  // eps_f floor of the coupling; absent: mixflowProperties' voidfractionMin (MixflowProperties.h),
  // which it may only raise.
  std::optional<double> voidfractionMin;
  long logEvery = 1;
  // implicit: beta, U and the explicit forces are held over the interval and the drag is updated
  // with the particle's velocity at every DEM step (backward Euler, stable for any beta; see
  // DemLink.h); held: the whole force of the exchange is held over the interval.
  std::string dragIntegration = "implicit";
  // implicit only. none: the drag sees the fluid velocity U of the exchange over the whole
  // interval, and the fluid step has the semi-implicit coefficient beta / (1 + beta T / m).
  // share (experimental): the drag acts on the particle's share of its cell's fluid, m_f = rho_f
  // V_p eps_f / (1 - eps_f), whose velocity U + a tau - J / m_f follows the fluid's own
  // acceleration a (last step's, the particles' drag removed) and responds to the drag impulse J
  // given so far (backward Euler for the pair); the fluid step receives exactly -J / T,
  // explicitly. Meant for liquids whose relaxation time m_f / beta is shorter than T (viscous
  // liquids); coupling/README.md, "Drag integration", has what it changes and what it does not.
  // continuity: the drag sees U - c (v - v_ref), c = (1 - eps_f) / eps_f: the cell's mixture volume
  // flux is held over the interval instead of U, so the pore fluid counterflows a compacting bed
  // within the interval as the fluid step's continuity will make it (DemLink.h).
  std::string dragFluidResponse = "none";
  // implicit only. slip: the drag coefficient follows the grain's slip speed at every DEM step
  // (the drag laws evaluated with the exchange's fluid sample, DemLink.h); exchange: beta of the
  // exchange's slip is held over the interval, which freezes a plastic (yield-stress) drag at
  // the slip the last interval ended with.
  std::string dragCoefficientUpdate = "slip";
  // implicit only. The fluid step takes the drag as beta_T (U_held - U_new) - impulse / T, exact
  // at U_new = U_held; its part beta_T (U_held - U_new) reached no grain (the grains meet U_new
  // in the next interval, whose impulse the fluid gets again). returned: that part of each cell,
  // Ksl (U_new - U_held), is added to the next step's explicit source, so that over the run the
  // fluid gets exactly the grains' drag impulse; kept: not, and a slaved grain's inertia is added
  // to the fluid's once more at every step (a mixture inertia up to m_f + 2 m_p).
  std::string implicitDragDefect = "returned";
  // pressureCoupling mixture only. held: the drag sees the fluid velocity sampled after the fluid
  // step, held over the interval; extrapolated: that velocity going on changing at the rate of
  // the step just taken, U + tau (U - U_before) / T, so the fluid the drag sees lags the fluid
  // step's by O(T^2) instead of O(T). A plastic drag (yield-stress liquids) meets any slip above
  // its regularisation's (~1e-5 m/s) with the full yield force, so a lag of the seen velocity by
  // a T holds the grains back whatever T is practical.
  std::string dragFluidVelocity = "held";
  // fluid: the fluid step's continuity sees the grains' displacement over the DEM interval just
  // run, and the next interval's drag uses the fluid as it was before that step.
  // mixture (implicit drag, dragFluidResponse none): the next interval's drag uses the fluid
  // after its step (sampled again), and that step's pressure equation already counts the share
  // sigma = 1 - (1 - exp(-s)) / s (s = beta T / m) of each grain's volume that the implicit drag
  // will carry with the new fluid velocity over the interval: mixture continuity, so a packed bed
  // in a viscous liquid compacts only as fast as its pore liquid can leave (partial elimination;
  // coupling/README.md, "Pressure coupling").
  std::string pressureCoupling = "mixture";
  // held only: the drag coefficient of a particle is limited to dragRelaxationLimit x m / T (T the
  // exchange interval), so the held drag never pushes it past the fluid velocity; 0 = no limit.
  double dragRelaxationLimit = 0.5;
  // held only: also beta <= dragCounterflowLimit / c x m / T with c = (1 - eps_f) / eps_f of the
  // particle's cell, so that c beta T / m stays below 1: the held drag's packed-bed counterflow
  // bound (coupling/README.md, "Exchange interval"); 0 = no limit.
  double dragCounterflowLimit = 0.5;
  // |U| above this (m/s) anywhere stops the run with the place and time (a diverging step).
  double maxVelocity = 100;

  static const Schema& schema();
  static CouplingProperties read(const std::string& file);
};

}  // namespace mixflow::coupling
