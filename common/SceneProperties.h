// constant/sceneProperties: the scene both halves read (mixflowDem's DEM half, mixflowPrepare's
// fluid half): content, sample, channel, particles (grains), liquid (fluid). One declaration table
// (SceneProperties.cpp) gives every entry's type, default, range, unit and meaning; the defaults
// are the initializers below, the table refers to them. docs/parameters.md's tables are printed
// from it (mixflowSchema).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "Dictionary.h"
#include "Schema.h"

namespace mixflow {

struct SampleSpec {
  double length = 0;              // L along x (m), from the back wall x = 0 to the gate
  double height = 0;              // H along y (m)
  double width = 0;               // W along z (m): also the channel width (side walls at z = 0, W)
  double solidFraction = 0.6056;  // target packing of the grains (sets their count)
};

struct ChannelSpec {
  double length = 0;                // x of the outlet (m); particles beyond are deleted
  double height = 0;                // y of the open top (m); particles above are deleted
  std::string sideWalls = "walls";  // walls | periodic (an infinitely wide channel)
  double liquidDepth = 0;           // m of still liquid over the whole floor; > 0: a closed tank
  bool tank() const { return liquidDepth > 0; }
};

// How the gate at x = L leaves the column at t = 0: removed at once (the paper's), or lifted as a
// plate whose lower edge rises from the channel floor by a law h(t) (liquid and dry scenes).
struct GateSpec {
  std::string removal = "instant";  // instant | lifted
  double speed = -1;                // m/s, h = speed t; < 0: the table `lift` gives h(t)
  std::vector<std::pair<double, double>> lift;  // (t, h) points, linear between, held outside
  double thickness = 0;                         // m along x; 0: one cell (auto)
  bool lifted() const { return removal == "lifted"; }
  double height(double t) const;  // h(t) of the law (m above the floor)
};

struct ParticleMaterial {
  double diameter = 0.024;
  double density = 2500;
  double youngModulus = 70e9;       // particle-particle (paper value, before softening)
  double wallYoungModulus = 700e9;  // wall material (paper value, before softening)
  double poisson = 0.3;
  double restitution = 0.7;
  double friction = 0.7;
  double wallFriction = 0.7;
  double rollingFriction = 0.1;
  std::string rollingModel = "cdt";  // cdt | epsd2 | off
  double rollingViscousDamping = 0;  // epsd only
  double radius() const { return 0.5 * diameter; }
  double mass() const;
  double volume() const;
};

// Rheology in SI units (docs/model.md §5): tau = tau_c + kappa gamma_dot^n.
struct Rheology {
  std::string model;        // Newtonian | HerschelBulkley | Bingham
  double density = 0;       // rho (kg/m3)
  double viscosity = 0;     // Newtonian dynamic viscosity mu (Pa s)
  double yieldStress = 0;   // tau_c (Pa)
  double consistency = 0;   // kappa (Pa s^n); Bingham: the plastic viscosity (Pa s)
  double flowIndex = 1;     // n
  double viscosityCap = 0;  // regularisation mu_0 (Pa s); 0 for a Newtonian liquid
  bool yieldStressModel() const { return model != "Newtonian"; }
  // OpenFOAM's kinematic coefficients (HerschelBulkley viscosity model).
  double nu() const { return viscosity / density; }
  double tau0() const { return yieldStress / density; }
  double k() const { return consistency / density; }
  double nu0() const { return viscosityCap / density; }
};

struct AirProperties {
  double density = 1.0;        // kg/m3 (docs/model.md §4)
  double viscosity = 1.48e-5;  // Pa s (Table 2 gives kappa = 1.48e-5 with n = 1)
};

struct SceneProperties {
  std::string content;  // particles | liquid | mixture
  SampleSpec sample;
  ChannelSpec channel;
  ParticleMaterial particles;  // read for particles and mixture; defaults otherwise
  Rheology liquid;             // the fluid half: read for liquid and mixture
  AirProperties air;
  GateSpec gate;
  double surfaceTension = 0.07;  // N/m (water-air; the paper gives none)

  bool grains() const { return content != "liquid"; }
  bool fluid() const { return content != "particles"; }

  static const Schema& schema();
  // The content entry alone (a program refuses a content before reading the rest).
  static std::string readContent(const Dictionary& scene);
  // Which half reads the file: the DEM half takes of a mixture's liquid{} only its density (the
  // Savage number's rho_f; the rest is the fluid half's), the fluid half validates all of it.
  enum class Half { grains, fluid };
  // Every entry the content uses in that half, and the rules between entries (named by the entry
  // to change).
  static SceneProperties read(const Dictionary& scene, Half half);
};

}  // namespace mixflow
