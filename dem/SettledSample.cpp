#include "SettledSample.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "DemDict.h"
#include "DemDriver.h"
#include "Dictionary.h"
#include "LiggghtsCommands.h"
#include "PackingSearch.h"
#include "SampleFill.h"
#include "SceneProperties.h"
#include "Schema.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

namespace {
// Bump when DemDriver::settle changes in a way its commands and settings do not show.
constexpr const char* kSettleVersion = "mixflow settling 1";
// The data file's path in the inputs text (the real one names the case directory).
constexpr const char* kDataFileName = "dem/initial.data";

void addLines(std::ostringstream& out, const std::vector<std::string>& lines) {
  for (const auto& l : lines) out << l << '\n';
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

std::string settleInputs(const Scene& s) {
  const Fill fill = makeLooseFill(s);
  const std::string data = dataFileText(fill, s.particles, channelBox(s, fill.top));
  // A stiffened sample settles in the softer scene (Scene::settlingScene), then is stiffened.
  const Scene st = s.settlingScene();
  const double dt = st.timeStepUsed();
  std::ostringstream out;
  out.precision(17);
  out << kSettleVersion << '\n'
      << kDataFileName << ": " << fill.centres.size() << " particles, fnv1a " << fingerprintOf(data)
      << '\n';
  // The processor grid is left out: how the ranks split the box is not part of the sample, which
  // serves any rank count and decomposition.
  std::vector<std::string> setup = sceneSetupCommands(st, kDataFileName, dt);
  setup.erase(std::remove_if(setup.begin(), setup.end(),
                             [](const std::string& l) { return l.rfind("processors", 0) == 0; }),
              setup.end());
  addLines(out, setup);
  out << "# settling materials\n";
  addLines(out, materialCommands(st.particles, st.dem.youngModulusFactor, st.settle.friction,
                                 st.settle.rollingFriction));
  addLines(out, settleGravityCommands(st));  // nothing for full gravity: older samples still match
  addLines(out, settleDragCommands(st));     // nothing without sedimentationSpeed
  // The friction above is the first trial's; the one found is an outcome (settled.state).
  if (s.settle.packingControl == "friction")
    out << "# packing control: settling friction searched from " << s.settle.friction << " in ["
        << s.settle.minFriction << ", " << s.settle.maxFriction << "], at most "
        << s.settle.maxSettles << " settles, until |sample fraction - " << s.sample.solidFraction
        << "| <= " << s.settle.packingTolerance << " (search " << PackingSearch::kVersion << ")\n";
  out << "# settling: check every " << kSettleCheckInterval << " s, at most " << s.settle.maxTime
      << " s, until the mean kinetic energy < " << s.settle.kineticTolerance << " m g d\n";
  // A checkpoint's restart write re-runs LIGGGHTS' setup, which changes the trajectory at
  // round-off: samples settled with and without checkpoints are not the same sample.
  if (s.settle.checkpointInterval > 0)
    out << "# checkpoints every " << s.settle.checkpointInterval << " s\n";
  if (s.stiffensSettled()) {
    out << "# stiffened from youngModulusFactor " << s.settle.stiffenFrom << " in "
        << s.settle.stiffenSteps << " steps of " << s.settle.stiffenStepTime << " s\n";
    for (long k = 1; k <= s.settle.stiffenSteps; ++k) {
      const Scene step = s.stiffeningScene(k);
      addLines(out, stiffenCommands(step, step.timeStepUsed()));
    }
  }
  out << "# then the real materials, relaxed for " << s.settle.relaxTime << " s\n";
  addLines(out, materialCommands(s.particles, s.dem.youngModulusFactor, s.particles.friction,
                                 s.particles.rollingFriction));
  return out.str();
}

std::string fingerprintOf(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64 offset basis
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;  // FNV-1a 64 prime
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::string firstDifference(const std::string& here, const std::string& there) {
  std::istringstream a(here), b(there);
  std::string la, lb;
  for (;;) {
    const bool ha = static_cast<bool>(std::getline(a, la));
    const bool hb = static_cast<bool>(std::getline(b, lb));
    if (!ha && !hb) return "";
    if (!ha) la = "(nothing)";
    if (!hb) lb = "(nothing)";
    if (la != lb) return "'" + la + "' against '" + lb + "'";
  }
}

namespace {
// The dictionary at the dotted section path of root ("" itself); absent parts are empty.
Dictionary sectionOf(const Dictionary& root, const std::string& section) {
  Dictionary d = root;
  size_t from = 0;
  while (from < section.size()) {
    const size_t dot = section.find('.', from);
    const std::string key = section.substr(from, dot == std::string::npos ? dot : dot - from);
    d = d.subDictOrEmpty(key);
    from = dot == std::string::npos ? section.size() : dot + 1;
  }
  return d;
}

// v with the fewest digits that read back as v (0.45, not 0.45000000000000001; 2600).
std::string exactNumber(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Each declared entry of the given sections as "file path value", read as the programs read it.
void addEntries(std::ostringstream& out, const Schema& sc, const Dictionary& root,
                const std::vector<std::string>& sections) {
  for (const Param& p : sc.params()) {
    if (std::find(sections.begin(), sections.end(), p.section()) == sections.end()) continue;
    const Dictionary d = sectionOf(root, p.section());
    std::string v;
    try {
      switch (p.type) {
        case Param::Type::Scalar:
          if (p.autoDefault) {
            const auto a = sc.scalarOrAuto(d, p.path);
            v = a ? exactNumber(*a) : "auto";
          } else {
            v = exactNumber(sc.scalar(d, p.path));
          }
          break;
        case Param::Type::Integer:
          if (p.autoDefault) {
            const auto a = sc.integerOrAuto(d, p.path);
            v = a ? std::to_string(*a) : "auto";
          } else {
            v = std::to_string(sc.integer(d, p.path));
          }
          break;
        case Param::Type::Word:
          v = sc.word(d, p.path);
          break;
        case Param::Type::Switch:
          v = sc.flag(d, p.path) ? "on" : "off";
          break;
        case Param::Type::Text:
          v = sc.text(d, p.path);
          break;
        default:
          continue;
      }
    } catch (const InputError&) {
      v = "(not read)";  // e.g. an entry of another selector value
    }
    out << sc.file() << ' ' << p.path << ' ' << v << '\n';
  }
}

// "file path" -> value of a settleEntries text.
std::map<std::string, std::string> entryMap(const std::string& text) {
  std::map<std::string, std::string> m;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find(' ');
    const size_t b = a == std::string::npos ? a : line.find(' ', a + 1);
    if (b == std::string::npos) continue;
    m[line.substr(0, b)] = line.substr(b + 1);
  }
  return m;
}
}  // namespace

std::string settleEntries(const Scene& s) {
  std::ostringstream out;
  const fs::path dir(s.caseDir);
  addEntries(out, SceneProperties::schema(),
             Dictionary::readFile((dir / "constant/sceneProperties").string()),
             {"sample", "channel", "particles"});
  const fs::path demDict = dir / "system/demDict";
  addEntries(out, DemDict::schema(),
             fs::exists(demDict) ? Dictionary::readFile(demDict.string())
                                 : Dictionary::parse("", demDict.string()),
             {"", "velocityProfile", "savage", "settle"});
  return out.str();
}

std::string entriesDifference(const std::string& here, const std::string& there) {
  const auto a = entryMap(here), b = entryMap(there);
  std::string out;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    const std::string other = it == b.end() ? "(none)" : it->second;
    if (other == value) continue;
    const size_t sp = key.find(' ');
    out += (out.empty() ? "" : "; ") + key.substr(0, sp) + " entry '" + key.substr(sp + 1) +
           "': " + value + " in this case, " + other + " in the sample";
  }
  return out;
}

std::string inputsMismatch(const std::string& here, const std::string& fingerprint,
                           const std::string& recordedInputs, const std::string& hereEntries,
                           const std::string& recordedEntries) {
  const std::string mine = fingerprintOf(here);
  if (fingerprint == mine) return "";
  std::string why = "fingerprint '" + fingerprint + "' is not this settling's '" + mine + "'";
  const std::string entries =
      !hereEntries.empty() && !recordedEntries.empty() && fs::exists(recordedEntries)
          ? entriesDifference(hereEntries, readText(recordedEntries))
          : "";
  if (!entries.empty()) why += "; entries that differ: " + entries;
  if (fs::exists(recordedInputs))
    why += "; first difference of the inputs (this case against the sample): " +
           firstDifference(here, readText(recordedInputs));
  return why;
}

SettleReport checkSettledSample(const Scene& s, const std::string& dir) {
  const fs::path from(dir);
  const fs::path statePath = from / "settled.state";
  if (!fs::exists(statePath))
    throw InputError(statePath.string() + ": cannot open file: no settled sample to reuse there");
  const Dictionary st = Dictionary::readFile(statePath.string());
  const SettleReport r = readSettledDict(st.subDict("settled"));
  const fs::path restart = from / "settled.restart";
  if (!fs::exists(restart))
    throw InputError(restart.string() + ": cannot open file: " + statePath.string() +
                     " has no restart file beside it, so there is no settled sample to reuse "
                     "there; settle again (without SETTLED_DIR), or name the dem/ directory of a "
                     "run that settled");
  if (r.fingerprint.empty())
    throw InputError(statePath.string() +
                     ": entry 'settled/fingerprint' is missing: the sample was settled before "
                     "mixflow recorded its inputs, so whether it is this case's cannot be "
                     "checked; settle again (without reusing)");
  const std::string why =
      inputsMismatch(settleInputs(s), r.fingerprint, (from / "settled.inputs").string(),
                     settleEntries(s), (from / "settled.entries").string());
  if (!why.empty())
    throw InputError(statePath.string() + ": entry 'settled/fingerprint': " + why +
                     ": the sample was made with other particles, walls, contacts, DEM step or "
                     "settling settings. Settle again (without reusing)");
  return r;
}

SettleReport reuseSettledSample(const Scene& s, const std::string& dir, int rank) {
  const SettleReport r = checkSettledSample(s, dir);
  const fs::path from(dir);
  const fs::path statePath = from / "settled.state";
  const fs::path restart = from / "settled.restart";
  const std::string here = settleInputs(s);
  const fs::path to = fs::path(s.caseDir) / "dem";
  const bool same = fs::exists(to) && fs::equivalent(from, to);
  if (rank == 0 && !same) {
    fs::create_directories(to);
    fs::copy_file(restart, to / "settled.restart", fs::copy_options::overwrite_existing);
    // The restart path in settled.state is relative to the case directory: the same here. The
    // copy says where it came from (replacing an earlier reusedFrom).
    std::istringstream state(readText(statePath));
    std::ofstream copy(to / "settled.state");
    for (std::string line; std::getline(state, line);)
      if (line.rfind("reusedFrom", 0) != 0) copy << line << '\n';
    copy << "reusedFrom \"" << fs::absolute(from).lexically_normal().string() << "\";\n";
    std::ofstream(to / "settled.inputs") << here;
    std::ofstream(to / "settled.entries") << settleEntries(s);
  }
  return r;
}

}  // namespace mixflow::dem
