// The scene of a dam-break case, read from an OpenFOAM-style case directory:
//   constant/sceneProperties  geometry (sample, channel), content, particle material
//   system/demDict            DEM numerics (time step, softening, settling, outputs)
//   system/controlDict        endTime, writeInterval (as for any OpenFOAM case)
// Every entry is validated on reading; defaults are listed in docs/parameters.md (the
// sceneProperties and demDict tables are printed from their declarations in common/).
#pragma once

#include <string>

#include "DemDict.h"
#include "SceneProperties.h"

namespace mixflow::dem {

// The scene's entries (sceneProperties) are common to both halves: SceneProperties.h.
using mixflow::ChannelSpec;
using mixflow::ParticleMaterial;
using mixflow::SampleSpec;

// demDict's entries: DemDict.h.
using mixflow::DemSpec;
using mixflow::SettleSpec;

struct Scene {
  std::string caseDir;
  std::string name;
  std::string content;  // particles | liquid | mixture
  SampleSpec sample;
  ChannelSpec channel;
  GateSpec gate;  // removed at once at t = 0, or lifted (LiftedGate.h)
  ParticleMaterial particles;
  double fluidDensity = 0;  // kg/m3: the liquid of a mixture (liquid.density); 0 for a dry scene
  SettleSpec settle;
  DemSpec dem;
  double endTime = 2.0;
  double writeInterval = 0.05;

  static Scene read(const std::string& caseDir);

  // Derived quantities (all with the softened moduli).
  double youngModulusUsed() const { return particles.youngModulus * dem.youngModulusFactor; }
  double wallYoungModulusUsed() const {
    return particles.wallYoungModulus * dem.youngModulusFactor;
  }
  double rayleighTime() const;
  double maxImpactSpeed() const;  // sqrt(2 g H): free fall over the sample height
  double hertzTimeMin() const;    // shortest elastic Hertz contact (particle-particle or -wall)
  double stableTimeStepLimit() const;
  double timeStepUsed() const;
  // Empty, or a warning that the auto step rayleighFraction T_R asks for is above the
  // stability limit (the step then runs at the limit).
  std::string autoStepWarning() const;  // validated: throws InputError above the limit
  long particleCount() const;           // N = phi L H W / Vp

  // demDict settle.stiffenFrom > 0: the sample settles softer, then is stiffened.
  bool stiffensSettled() const { return settle.stiffenFrom > 0; }
  // This scene at the settle's step (settle.rayleighFraction; a set timeStep as is): where the
  // settle ends (the last stiffening step, the relaxation at the real friction).
  Scene settledScene() const;
  // The scene the sample settles in: settledScene(), or (stiffening) the same with
  // youngModulusFactor settle.stiffenFrom and its auto step.
  Scene settlingScene() const;
  // Step k = 1 .. settle.stiffenSteps of the stiffening: youngModulusFactor stiffenFrom r^k with
  // r = (factor / stiffenFrom)^(1/steps), at its auto step; the last is settledScene().
  Scene stiffeningScene(long k) const;
};

}  // namespace mixflow::dem
