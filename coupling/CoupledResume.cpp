#include "CoupledResume.h"

#include <filesystem>
#include <fstream>

#include "Dictionary.h"

namespace mixflow::coupling {

namespace fs = std::filesystem;

std::string CoupledResumeState::path(const std::string& caseDir) {
  return (fs::path(caseDir) / "dem" / "coupled.resume.state").string();
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
  if (!fs::exists(fs::path(caseDir) / s.restartFile))
    throw InputError(file + ": entry 'restartFile': " + s.restartFile + " does not exist");
  return s;
}

void CoupledResumeState::write(const std::string& caseDir) const {
  const std::string file = path(caseDir);
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
    f << ");\n";
  }
  fs::rename(file + ".tmp", file);
}

}  // namespace mixflow::coupling
