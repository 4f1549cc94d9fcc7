// The granular half of a mixture scene's outputs in mixflowCoupled (the fluid half is the
// liquidObservables function object): every demDict sampleInterval it deletes the particles that
// left through the outlet or the top and writes the row of postProcessing/dem/timeSeries.csv
// (granular fronts, energies, Savage number at x = 0.8 m with rho_f = the liquid's density); it
// writes particle snapshots (VTK/), u(y) at its section and time, and at the end the deposit
// profile and summary.json -- the same files, columns and rules as a dry scene (dem/
// CollapseRecorder.h), so the two compare directly.
// With every field write it saves what a resumed run needs (CoupledResume.h); resumed, it appends
// to the outputs instead of starting them.
// Active when constant/sceneProperties says content mixture; plain C++ (no OpenFOAM).
#pragma once

#include <iosfwd>
#include <memory>
#include <string>

#include "CollapseRecorder.h"
#include "Progress.h"
#include "Scene.h"

namespace mixflow::coupling {

class MixtureMonitor {
 public:
  // nullptr unless caseDir holds a mixture scene. resume: the run continues from the state of
  // dem/coupled.resume.state, whose particles LIGGGHTS has read.
  static std::unique_ptr<MixtureMonitor> createIfMixture(const std::string& caseDir,
                                                         dem::LiggghtsSession& lig,
                                                         std::ostream& out, bool resume);
  MixtureMonitor(const dem::Scene& scene, dem::LiggghtsSession& lig, std::ostream& out,
                 bool resume);
  // After each coupled step (DEM interval, exchange, fluid step).
  void afterStep();
  // After the fluid wrote time directory timeName: the particles' restart and the counters, for
  // mixflowCoupled -resume (CoupledResume.h).
  void afterWrite(const std::string& timeName);
  // Deposit profile and summary.json.
  void finish();

 private:
  dem::Scene scene_;
  dem::LiggghtsSession& lig_;
  std::ostream& out_;
  int rank_ = 0;
  std::unique_ptr<dem::CollapseRecorder> rec_;
  std::unique_ptr<Progress> progress_;
  dem::CollapseReport rep_;
  dem::SettleReport settled_;
  long lastSampleStep_ = 0;
  bool profileDone_ = false;
  bool resumed_ = false;
  int restartSlot_ = 0;
};

}  // namespace mixflow::coupling
