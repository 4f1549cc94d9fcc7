#include "SettleCheckpoint.h"

#include <filesystem>
#include <fstream>

#include "Dictionary.h"

namespace fs = std::filesystem;

namespace mixflow::dem {

namespace {
const char* kRestarts[2] = {"dem/settle.checkpoint.a.restart", "dem/settle.checkpoint.b.restart"};
}

std::string SettleCheckpoint::statePath(const std::string& caseDir) {
  return (fs::path(caseDir) / "dem" / "settle.checkpoint.state").string();
}

std::string SettleCheckpoint::slotFile(int slot) { return kRestarts[slot == 0 ? 0 : 1]; }

std::optional<SettleCheckpoint> SettleCheckpoint::find(const std::string& caseDir,
                                                       const std::string& fingerprint,
                                                       std::ostream& out) {
  const fs::path state = statePath(caseDir);
  if (!fs::exists(state)) return std::nullopt;
  const Dictionary d = Dictionary::readFile(state.string());
  SettleCheckpoint c;
  c.time = d.scalar("time", Range::nonNegative());
  c.restartFile = d.word("restartFile", {kRestarts[0], kRestarts[1], kNone});
  c.fingerprint = d.word("fingerprint", {});
  if (c.fingerprint != fingerprint) {
    out << "[dem] " << state.string() << ": a checkpoint of other settling inputs (fingerprint "
        << c.fingerprint << ", this case's " << fingerprint << "): settling from the start"
        << std::endl;
    return std::nullopt;
  }
  if (d.has("trials")) {
    const std::vector<double> v = d.scalars("trials", Range::nonNegative());
    if (v.size() % 2 != 0)
      throw InputError(state.string() + ": entry 'trials': " + std::to_string(v.size()) +
                       " numbers, expected (friction fraction) pairs");
    for (size_t i = 0; i < v.size(); i += 2) c.trials.push_back({v[i], v[i + 1]});
  }
  if (c.restartFile != kNone && !fs::exists(fs::path(caseDir) / c.restartFile))
    throw InputError(state.string() + ": entry 'restartFile': " + c.restartFile +
                     ": cannot open file");
  return c;
}

void SettleCheckpoint::write(const std::string& caseDir) const {
  const std::string path = statePath(caseDir);
  {
    std::ofstream f(path + ".tmp");
    f.precision(17);
    f << "// Written by mixflowDem while settling (demDict settle.checkpointInterval): a settle "
         "of\n"
      << "// the same inputs continues from here.\n"
      << "time        " << time << ";\nrestartFile \"" << restartFile << "\";\nfingerprint \""
      << fingerprint << "\";\n";
    if (!trials.empty()) {
      f << "trials     (";
      for (size_t i = 0; i < trials.size(); ++i)
        f << (i ? " " : "") << trials[i].friction << ' ' << trials[i].fraction;
      f << ");   // earlier settles: friction, sample solid fraction\n";
    }
  }
  fs::rename(path + ".tmp", path);
}

void SettleCheckpoint::remove(const std::string& caseDir) {
  fs::remove(statePath(caseDir));
  for (const char* r : kRestarts) fs::remove(fs::path(caseDir) / r);
}

}  // namespace mixflow::dem
