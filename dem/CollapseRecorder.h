// Records a granular collapse after the gate opened, for the dry driver (DemDriver) and the
// coupled solver (mixture scenes) alike: deletes the particles that left through the outlet or the
// top (counted), writes the time-series row (fronts, energies, Savage number at the section), the
// velocity profile u(y) at its time, the per-rank load (RankLoad.h), particle snapshots with their
// ParaView index, and at the end the deposit profile h(x) and summary.json. Outputs:
// <case>/postProcessing/dem, <case>/VTK.
#pragma once

#include <mpi.h>

#include <array>
#include <fstream>
#include <string>
#include <vector>

#include "LiggghtsSession.h"
#include "Observables.h"
#include "RankLoad.h"
#include "Scene.h"

namespace mixflow::dem {

struct SettleReport {
  long particles = 0;
  double settledHeight = 0;   // mean over (x,z) columns of the highest particle top (m)
  double sampleFraction = 0;  // N Vp / (L W settledHeight)
  double bulkFraction = 0;    // measured in the interior slab 2d <= y <= settledHeight - 2d
  double settleTime = 0;      // simulated settling time (s)
  bool converged = false;
  std::string fingerprint;  // hash of the settling's inputs (SettledSample.h); empty: not recorded
  // The deposition protocol (demDict settle.packingControl): the settling friction of the kept
  // sample, the settles run to find it, and the tolerance on |sampleFraction - target| (0: off).
  std::string packingControl = "off";
  double settleFriction = 0;
  long settles = 1;
  double packingTolerance = 0;
};

struct CollapseReport {
  double endTime = 0;
  std::string stopReason;
  double front = 0;
  double runout = 0;          // front - L
  double frontThickness = 0;  // end of the deposit at least one grain thick (thicknessFront)
  long remaining = 0, deletedOutlet = 0, deletedTop = 0, lost = 0;
};

// Particle centres (x, y, z) of all ranks, on rank 0 (empty elsewhere).
std::vector<std::array<double, 3>> gatherCentres(const ParticleView& p, MPI_Comm comm);

class CollapseRecorder {
 public:
  // step0: LIGGGHTS step at t = 0 (gate opening). append: continue an existing timeSeries.csv.
  CollapseRecorder(const Scene& scene, LiggghtsSession& lig, MPI_Comm comm, long step0,
                   bool append);

  double time() const;  // simulated time since the gate opened
  // Deletes the particles beyond the outlet or above the top (counted in rep).
  void deleteLeavers(CollapseReport& rep);
  // One time-series row at the current step; throws on NaN energies.
  Energies sample(CollapseReport& rep);
  // Writes u(y) at the velocity-profile section once its time is reached.
  void profileIfDue(bool& profileDone);
  // Periodic particle dumps every writeInterval (on a whole number of sampleEvery steps).
  void startSnapshots();
  void indexSnapshots() const;
  bool atSnapshot() const;
  long sampleEvery() const { return sampleEvery_; }
  // Deposit profile and final fronts (all ranks get them).
  void finish(CollapseReport& rep);
  void writeSummary(const SettleReport& st, const CollapseReport& c,
                    const std::string& extraJson = "") const;
  const std::string& outputDir() const { return outDir_; }
  // The largest granular front in timeSeries.csv over [endTime - arrestWindow, endTime]
  // (fallback when the series has no row there).
  double finalFrontMax(double endTime, double fallback) const;

 private:
  const Scene& scene_;
  LiggghtsSession& lig_;
  MPI_Comm comm_;
  int rank_ = 0;
  long step0_ = 0;
  double dt_ = 0;
  long sampleEvery_ = 1;
  long snapshotEvery_ = 1;
  long expected_ = 0;  // particles expected at the next sample (the shortfall was lost)
  std::string outDir_;
  std::ofstream series_;
  RankLoad load_;
};

}  // namespace mixflow::dem
