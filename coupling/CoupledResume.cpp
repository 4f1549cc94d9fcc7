#include "CoupledResume.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "Dictionary.h"

namespace mixflow::coupling {

namespace fs = std::filesystem;

std::string CoupledResumeState::path(const std::string& caseDir) {
  return (fs::path(caseDir) / "dem" / "coupled.resume.state").string();
}

std::string CoupledResumeState::previousPath(const std::string& caseDir) {
  return path(caseDir) + ".previous";
}

unsigned long posixCksum(const std::string& file, unsigned long long& bytes) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i << 24;
      for (int k = 0; k < 8; ++k) c = (c & 0x80000000u) ? (c << 1) ^ 0x04C11DB7u : c << 1;
      t[i] = c;
    }
    return t;
  }();
  std::ifstream in(file, std::ios::binary);
  std::uint32_t crc = 0;
  bytes = 0;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i)
      crc = (crc << 8) ^ table[((crc >> 24) ^ static_cast<unsigned char>(buf[i])) & 0xFF];
    bytes += static_cast<unsigned long long>(n);
  }
  for (unsigned long long len = bytes; len; len >>= 8)
    crc = (crc << 8) ^ table[((crc >> 24) ^ (len & 0xFF)) & 0xFF];
  return static_cast<unsigned long>(~crc);
}

CoupledResumeState CoupledResumeState::read(const std::string& caseDir) {
  const std::string file = path(caseDir);
  if (!fs::exists(file))
    throw InputError(file +
                     ": cannot open file: nothing to resume from (the coupled run wrote no "
                     "fields after its start; run it again with Allrun)");
  const Dictionary d = Dictionary::readFile(file);
  CoupledResumeState s;
  s.restartFile = d.word("restartFile", {});
  s.timeName = d.word("timeName", {});
  s.time = d.scalar("time", Range::nonNegative());
  s.step = d.integer("step", 0, 9000000000000000000L);
  s.lastSampleStep = d.integer("lastSampleStep", 0, s.step);
  s.deletedOutlet = d.integer("deletedOutlet", 0, 2000000000);
  s.deletedTop = d.integer("deletedTop", 0, 2000000000);
  s.lost = d.integer("lost", 0, 2000000000);
  s.profileDone = d.switchOr("profileDone", false);
  if (d.has("slabSplits")) s.slabSplits = d.scalars("slabSplits", Range::closed(0, 1));
  if (d.has("restartBytes")) s.restartBytes = d.integer("restartBytes", 0, 9000000000000000000L);
  if (d.has("restartCrc")) s.restartCrc = d.integer("restartCrc", 0, 4294967295L);
  return s;
}

void CoupledResumeState::verifyRestart(const std::string& caseDir) const {
  const std::string file = path(caseDir);
  const std::string previous = fs::exists(previousPath(caseDir))
                                   ? "; the write before is intact: mv " + previousPath(caseDir) +
                                         " " + file + ", then resume again from it"
                                   : "; no earlier resume point is kept: run it again with Allrun";
  const std::string restart = (fs::path(caseDir) / restartFile).string();
  if (!fs::exists(restart))
    throw InputError(file + ": entry 'restartFile': " + restartFile + " does not exist" + previous);
  if (restartBytes == 0) return;  // a state that recorded no cksum
  unsigned long long bytes = 0;
  const unsigned long crc = posixCksum(restart, bytes);
  if (bytes != restartBytes || crc != restartCrc)
    throw InputError(file + ": entry 'restartFile': " + restart + " is damaged (" +
                     std::to_string(bytes) + " bytes, cksum " + std::to_string(crc) +
                     "; written as " + std::to_string(restartBytes) + " bytes, cksum " +
                     std::to_string(restartCrc) + ")" + previous);
}

void CoupledResumeState::write(const std::string& caseDir) {
  const std::string file = path(caseDir);
  restartCrc = posixCksum((fs::path(caseDir) / restartFile).string(), restartBytes);
  {
    std::ofstream f(file + ".tmp");
    f << "// Written by mixflowCoupled with every field write; read by mixflowCoupled -resume.\n"
      << "restartFile \"" << restartFile << "\";   // relative to the case directory\n"
      << "timeName \"" << timeName << "\";\ntime " << formatNumber(time, 17) << ";\nstep " << step
      << ";\nlastSampleStep " << lastSampleStep << ";\ndeletedOutlet " << deletedOutlet
      << ";\ndeletedTop " << deletedTop << ";\nlost " << lost << ";\nprofileDone "
      << (profileDone ? "yes" : "no") << ";\nslabSplits (";
    for (size_t i = 0; i < slabSplits.size(); ++i)
      f << (i ? " " : "") << formatNumber(slabSplits[i], 17);
    f << ");\nrestartBytes " << restartBytes << ";   // cksum " << restartFile
      << " prints these two\nrestartCrc " << restartCrc << ";\n";
  }
  if (fs::exists(file)) fs::rename(file, previousPath(caseDir));
  fs::rename(file + ".tmp", file);
}

}  // namespace mixflow::coupling
