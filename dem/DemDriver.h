// Runs a dry (particles-only) dam break on LIGGGHTS: loose fill, settling behind the gate, gate
// removal at t = 0, collapse with outlet/top deletion, and the granular outputs of physics.md §5.
// No fluid mesh is built and no fluid equation is solved for such a scene.
#pragma once

#include <mpi.h>

#include <iosfwd>
#include <memory>
#include <string>

#include "LiggghtsSession.h"
#include "Scene.h"

namespace mixflow::dem {

struct SettleReport {
  long particles = 0;
  double settledHeight = 0;   // mean over (x,z) columns of the highest particle top (m)
  double sampleFraction = 0;  // N Vp / (L W settledHeight)
  double bulkFraction = 0;    // measured in the interior slab 2d <= y <= settledHeight - 2d
  double settleTime = 0;      // simulated settling time (s)
  bool converged = false;
};

struct CollapseReport {
  double endTime = 0;
  std::string stopReason;
  double front = 0;
  double runout = 0;          // front - L
  double frontThickness = 0;  // end of the deposit at least one grain thick (thicknessFront)
  long remaining = 0, deletedOutlet = 0, deletedTop = 0, lost = 0;
};

class DemDriver {
 public:
  DemDriver(const Scene& scene, MPI_Comm comm, std::ostream& out);
  ~DemDriver();

  SettleReport settle();
  // Opens the gate (t = 0) and runs the collapse to endTime or arrest.
  CollapseReport collapse(const SettleReport& settled);
  // Continues a collapse from the last restart state in <case>/dem/resume.state (written with every
  // particle snapshot), e.g. after a crash or with a later endTime. Returns the settle report too.
  CollapseReport resume(SettleReport& settled);
  void writeSummary(const SettleReport& s, const CollapseReport& c) const;
  LiggghtsSession& session() { return *lig_; }
  const std::string& outputDir() const { return outDir_; }

 private:
  double simTime() const;
  long deleteLeavers(long& outlet, long& top);
  void startSnapshots();
  void indexSnapshots(long lastStep) const;
  void writeResumeState(const CollapseReport& rep, bool profileDone);
  CollapseReport runCollapse(CollapseReport rep, bool profileDone, bool appendSeries);
  SettleReport measureSample(double settleTime, bool converged);

  const Scene& scene_;
  MPI_Comm comm_;
  int rank_ = 0;
  std::ostream& out_;
  std::string outDir_;
  std::unique_ptr<LiggghtsSession> lig_;
  double dt_ = 0;
  long step0_ = 0;  // step at which the gate opened (t = 0)
  long snapshotEvery_ = 1;
  long sampleEvery_ = 1;
  int restartSlot_ = 0;
  SettleReport settled_;
};

}  // namespace mixflow::dem
