// A settle's checkpoint (demDict settle.checkpointInterval > 0): every interval of simulated
// settling the particles' LIGGGHTS restart and dem/settle.checkpoint.state (its time, which of two
// restart files holds it, and the fingerprint of the settling inputs, SettledSample.h). A settle
// that finds the checkpoint of the same inputs continues from it instead of starting again; the
// settled sample removes it. The two restart files alternate, so a run killed while writing one
// keeps the other and the state that names it.
// With the packing control (demDict settle.packingControl friction) the state also lists the
// earlier trials (friction, solid fraction), so the search goes on where it stopped; between two
// trials it names no restart ("none"): the next trial starts from the loose fill.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "PackingSearch.h"

namespace mixflow::dem {

struct SettleCheckpoint {
  double time = 0;                              // s of settling
  std::string restartFile;                      // relative to the case directory
  std::string fingerprint;                      // of the settling inputs it was made from
  std::vector<PackingSearch::Trial> trials;     // finished trials of the packing control
  static constexpr const char* kNone = "none";  // restartFile between two trials

  static std::string statePath(const std::string& caseDir);
  // The restart file of slot 0 or 1, relative to the case directory.
  static std::string slotFile(int slot);
  // The checkpoint of this fingerprint, if any; one of other inputs is reported on `out` and
  // ignored (the settle then starts again and replaces it).
  static std::optional<SettleCheckpoint> find(const std::string& caseDir,
                                              const std::string& fingerprint, std::ostream& out);
  // Written to a temporary file, then renamed (never half-written).
  void write(const std::string& caseDir) const;
  static void remove(const std::string& caseDir);
};

}  // namespace mixflow::dem
