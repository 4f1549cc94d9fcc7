// Runs a dry (particles-only) dam break on LIGGGHTS: loose fill, settling behind the gate, gate
// removal at t = 0, collapse with outlet/top deletion, and the granular outputs of docs/model.md
// §8. No fluid mesh is built and no fluid equation is solved for such a scene.
#pragma once

#include <mpi.h>

#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "CollapseRecorder.h"
#include "Dictionary.h"
#include "LiftedGate.h"
#include "LiggghtsSession.h"
#include "PackingSearch.h"
#include "Scene.h"
#include "SettleCheckpoint.h"

namespace mixflow::dem {

// The settled{} sub-dictionary of dem/resume.state and dem/settled.state.
void writeSettledDict(std::ostream& f, const SettleReport& st);
SettleReport readSettledDict(const Dictionary& d);

// A controlled settle (demDict settle.packingControl friction) that found no settling friction
// within the tolerance: the preparation stops, its message naming the fraction achieved, the
// target and the entries to change.
class PackingMiss : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class DemDriver {
 public:
  // With settle.packingControl off, settle() warns when the settled sample's solid fraction is
  // this far (relative) from the target (docs/parameters.md, sample.solidFraction).
  static constexpr double kSettledFractionTolerance = 0.03;
  DemDriver(const Scene& scene, MPI_Comm comm, std::ostream& out);
  ~DemDriver();

  // Settles the loose fill behind the gate; with settle.packingControl friction, again from the
  // same fill at the frictions PackingSearch proposes until the solid fraction lands (else throws
  // naming the achieved fraction, the target and the entries to change).
  SettleReport settle();
  // Opens the gate (t = 0) and runs the collapse to endTime or arrest.
  CollapseReport collapse(const SettleReport& settled);
  // Continues a collapse from the last restart state in <case>/dem/resume.state (written with every
  // particle snapshot), e.g. after a crash or with a later endTime. Returns the settle report too.
  CollapseReport resume(SettleReport& settled);
  void writeSummary(const SettleReport& s, const CollapseReport& c) const;
  // Saves the settled sample for a mixture scene: dem/settled.restart (LIGGGHTS restart) and
  // dem/settled.state (what settle() reported), read by mixflowPrepare and mixflowCoupled.
  void writeSettledState(const SettleReport& s);
  LiggghtsSession& session() { return *lig_; }
  const std::string& outputDir() const { return outDir_; }

 private:
  // One settle of the loose fill (or from its checkpoint) at this settling friction, stiffened
  // and relaxed at the real friction, measured.
  SettleReport settleTrial(double friction, const std::optional<SettleCheckpoint>& from,
                           const std::string& fingerprint,
                           const std::vector<PackingSearch::Trial>& trials);
  // settleTrial's steps. The grains in LIGGGHTS: a fresh loose fill, or the checkpoint's state
  // (t set to its time); returns the fill's top, which sets the free-fall time.
  double placeSettlingGrains(const Scene& st, const std::optional<SettleCheckpoint>& from,
                             double& t);
  // Runs until the grains are at rest (KE/(N m g d) below settle.kineticTolerance after the free
  // fall) or t reaches settle.maxTime, writing checkpoints; returns whether they came to rest.
  bool settleUnderGravity(double dtSettle, double top, double& t, const std::string& fingerprint,
                          const std::vector<PackingSearch::Trial>& trials);
  // Softened settle (settle.stiffenFrom): up to the scene's moduli; returns the time it took.
  double stiffenSettled();
  // The real friction and rolling resistance, then a short relaxation; returns its time.
  double relaxAtRealFriction();
  // Between two settles of the packing control: a checkpoint without a restart, with the
  // finished settles (SettleCheckpoint.h), so that an interrupted search goes on from them.
  void writeBetweenTrials(const std::string& fingerprint,
                          const std::vector<PackingSearch::Trial>& trials) const;
  // Without the packing control the target fraction only sets the grain count: a warning when
  // the settled sample is off it by more than kSettledFractionTolerance.
  void warnOffTarget(double sampleFraction) const;
  // The message of a packing control that found no friction within tolerance.
  std::string packingMiss(const PackingSearch& search, const std::string& why) const;
  // The settle's checkpoint at t (SettleCheckpoint.h), with the control's finished trials.
  void writeSettleCheckpoint(double t, const std::string& fingerprint,
                             const std::vector<PackingSearch::Trial>& trials);
  double simTime() const;
  void writeResumeState(const CollapseReport& rep, bool profileDone);
  CollapseReport runCollapse(CollapseReport rep, bool profileDone, bool appendSeries);
  // A lifted gate (sceneProperties gate): its plate placed at h(t), moving from step step0 on.
  void placeLiftedGate(double t, long step0);
  // Its removal once the lower edge has passed the column.
  void removeLiftedGateIfPassed(double t);
  SettleReport measureSample(double settleTime, bool converged);

  const Scene& scene_;
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  std::ostream& out_;
  std::string outDir_;
  std::unique_ptr<LiggghtsSession> lig_;
  double dt_ = 0;
  long step0_ = 0;  // step at which the gate opened (t = 0)
  std::unique_ptr<CollapseRecorder> rec_;
  int restartSlot_ = 0;
  long lastBalance_ = -1;  // k of the collapse's last re-balance, at k x balanceInterval
  int settleSlot_ = 0;     // the settle checkpoint's next restart file (SettleCheckpoint::slotFile)
  SettleReport settled_;
  std::unique_ptr<LiftedGate> gate_;  // while the lifted gate's plate is in LIGGGHTS
};

}  // namespace mixflow::dem
