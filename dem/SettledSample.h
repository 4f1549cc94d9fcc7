// SettledSample: what a mixture scene's settled sample (dem/settled.{restart,state}) was made
// from, so that a later run reuses it only where settling again would make the very same sample.
//
// Settling at the paper's stiffness takes about an hour for the full sample, while a study of the
// liquid, the coupling, the mesh or the exchange interval keeps the same grains: reusing the
// sample saves that hour and takes the packing's run-to-run noise out of the comparison. The
// inputs of a settling are the loose fill (dem/initial.data), the LIGGGHTS set-up (contacts,
// walls, gate, box, time step), the settling and final materials, the settling schedule and a
// stiffening's steps (settle.stiffenFrom); they are written as text to dem/settled.inputs, and
// their hash is settled.state's `fingerprint`.
// The rank count is not an input: a restart file reads on any number of ranks, and ranks change
// a settling only by round-off.
#pragma once

#include <string>

#include "CollapseRecorder.h"
#include "Scene.h"

namespace mixflow::dem {

// Simulated seconds of settling between two kinetic-energy checks (DemDriver::settle).
constexpr double kSettleCheckInterval = 0.02;

// The inputs of settling scene s, one item per line (the loose fill by its hash and count).
std::string settleInputs(const Scene& s);

// FNV-1a 64-bit hash of text, as 16 hexadecimal digits.
std::string fingerprintOf(const std::string& text);

// The first line where two inputs texts differ, as "'here' against 'there'" (empty if equal).
std::string firstDifference(const std::string& here, const std::string& there);

// The entries of the case's constant/sceneProperties (sample, channel, particles) and
// system/demDict as read (defaults included), one "file entry value" a line. Written beside a
// settled sample (settled.entries; not part of its fingerprint), so that a sample made from
// other inputs is refused naming the entries that differ, not only a hash.
std::string settleEntries(const Scene& s);

// The entries of two settleEntries texts that differ, as "file entry: A here, B in the sample"
// joined by "; " (empty if none differs).
std::string entriesDifference(const std::string& here, const std::string& there);

// Empty if fingerprint is that of `here` (a case's settleInputs); else why not: "fingerprint
// 'F' is not this settling's 'G'", with the entries that differ when the sample's recorded
// entries (recordedEntries, its settled.entries) exist and differ from hereEntries, and the
// first differing line when its recorded inputs file (settled.inputs) exists. Used where a sample
// is reused and where it is prepared.
std::string inputsMismatch(const std::string& here, const std::string& fingerprint,
                           const std::string& recordedInputs, const std::string& hereEntries = "",
                           const std::string& recordedEntries = "");

// The settled sample of directory dir (settled.{restart,state,inputs,entries}, e.g. another
// run's dem/) if s's case can take it: its restart file is there and its fingerprint is that of
// s's settling; otherwise throws InputError naming the file, the entry 'fingerprint' and the
// entries (or first input) that differ. Copies nothing (mixflowDem -check -reuse).
SettleReport checkSettledSample(const Scene& s, const std::string& dir);

// checkSettledSample, then takes the sample into s's case: every rank checks; rank 0 copies.
// Returns the sample's report.
SettleReport reuseSettledSample(const Scene& s, const std::string& dir, int rank);

}  // namespace mixflow::dem
