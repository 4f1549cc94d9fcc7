// CoupledResume: the state a mixture scene's coupled run writes with every field write, so that
// after a failure (or with a later endTime) `mixflowCoupled -resume` continues from the last
// written time instead of starting again (scripts/ResumeFunctions, resumeMixtureCase).
//
// The fluid's state is its time directory (U, p_rgh, alpha, phi, rAUfLast, nu,
// uniform/mixflowFoamState, the function objects' uniform/ state; coupling/README.md "Mixture
// scenes and resume" lists why each is needed); the particles' is a LIGGGHTS restart written at
// the same step (contacts and their history included), in two alternating files so that a
// failure while writing one leaves the other and its state file intact. The granular outputs'
// counters come back from this file. The drag state (the held forces, or the implicit drag's
// beta, U, explicit force for the next interval and last step's drag) is part of the LIGGGHTS
// restart, so the resumed first interval runs as the uninterrupted one did (DemLink.h).
#pragma once

#include <string>
#include <vector>

namespace mixflow::coupling {

struct CoupledResumeState {
  std::string restartFile;  // LIGGGHTS restart, relative to the case directory
  std::string timeName;     // the OpenFOAM time directory written with it
  double time = 0;          // s since the gate opened
  long step = 0;            // DEM step (counted from the gate opening)
  long lastSampleStep = 0;  // step of MixtureMonitor's last granular row (its sampling chain)
  long deletedOutlet = 0, deletedTop = 0, lost = 0;  // MixtureMonitor's counts so far
  bool profileDone = false;                          // the u(y) profile was written
  // The DEM's x-slab boundaries at the write (dem/SlabBalance.h): the resumed run's decomposition
  // until its next re-balance, as the uninterrupted run's. Empty: the script's grid.
  std::vector<double> slabSplits;
  // The restart as written: its size and POSIX cksum CRC (`cksum FILE` prints both), checked
  // before a resume; 0 / 0: not recorded.
  unsigned long long restartBytes = 0;
  unsigned long restartCrc = 0;

  static std::string path(const std::string& caseDir);  // <case>/dem/coupled.resume.state
  // The state of the write before (its restart is the other alternating file, intact while the
  // latest one is written): offered when the latest restart is damaged.
  static std::string previousPath(const std::string& caseDir);
  // Throws InputError naming the file if it is missing or malformed.
  static CoupledResumeState read(const std::string& caseDir);
  // Before the particles are read: throws InputError if the restart is missing or its size or
  // checksum differs from the recorded ones, naming the previous state if one is kept.
  void verifyRestart(const std::string& caseDir) const;
  // Records the restart's size and checksum, keeps the state before as previousPath, and is
  // written to a temporary file, then renamed (never half-written).
  void write(const std::string& caseDir);
};

// POSIX cksum of a file (CRC-32, polynomial 0x04C11DB7, the length appended), as `cksum` prints.
unsigned long posixCksum(const std::string& file, unsigned long long& bytes);

}  // namespace mixflow::coupling
