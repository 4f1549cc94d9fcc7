#include "MixtureMonitor.h"

#include <filesystem>
#include <ostream>
#include <stdexcept>

#include "CoupledResume.h"
#include "DemDriver.h"
#include "Dictionary.h"
#include "SceneProperties.h"
#include "SlabBalance.h"

namespace mixflow::coupling {

namespace fs = std::filesystem;

std::unique_ptr<MixtureMonitor> MixtureMonitor::createIfMixture(const std::string& caseDir,
                                                                dem::LiggghtsSession& lig,
                                                                std::ostream& out, bool resume) {
  const fs::path props = fs::path(caseDir) / "constant" / "sceneProperties";
  if (!fs::exists(props)) return nullptr;
  if (SceneProperties::readContent(Dictionary::readFile(props.string())) != "mixture")
    return nullptr;
  return std::make_unique<MixtureMonitor>(dem::Scene::read(caseDir), lig, out, resume);
}

MixtureMonitor::MixtureMonitor(const dem::Scene& scene, dem::LiggghtsSession& lig,
                               std::ostream& out, bool resume)
    : scene_(scene), lig_(lig), out_(out), resumed_(resume) {
  rank_ = lig.rank();
  const fs::path state = fs::path(scene_.caseDir) / "dem" / "settled.state";
  settled_ = dem::readSettledDict(Dictionary::readFile(state.string()).subDict("settled"));
  // The settled sample was saved at step 0 = the gate opening (DemDriver::writeSettledState), and
  // a resume state's restart carries the steps since: time = step x dt either way.
  rec_ = std::make_unique<dem::CollapseRecorder>(scene_, lig_, lig_.comm(), 0, resume);
  lastSampleStep_ = lig_.step();
  if (resume) {
    // Rows after the resumed time were cut by resumeMixtureCase; the counters come back.
    const CoupledResumeState st = CoupledResumeState::read(scene_.caseDir);
    if (lig_.step() != st.step)
      throw std::runtime_error(
          CoupledResumeState::path(scene_.caseDir) + ": entry 'step': " + std::to_string(st.step) +
          ", but the particles read are at step " + std::to_string(lig_.step()));
    rep_.deletedOutlet = st.deletedOutlet;
    rep_.deletedTop = st.deletedTop;
    rep_.lost = st.lost;
    profileDone_ = st.profileDone;
    lastSampleStep_ = st.lastSampleStep;  // rows at the uninterrupted run's steps
  } else {
    rec_->sample(rep_);
  }
  rec_->startSnapshots();
  progress_ =
      std::make_unique<Progress>("coupled " + scene_.name, rec_->time(), scene_.endTime, out_);
}

void MixtureMonitor::afterWrite(const std::string& timeName) {
  // Two alternating restart files: a failure while writing one leaves the other and its state.
  CoupledResumeState st;
  st.restartFile = "dem/coupled_" + std::to_string(restartSlot_) + ".restart";
  restartSlot_ = 1 - restartSlot_;
  lig_.writeRestart((fs::path(scene_.caseDir) / st.restartFile).string());
  if (rank_ != 0) return;
  st.timeName = timeName;
  st.time = rec_->time();
  st.step = lig_.step();
  st.lastSampleStep = lastSampleStep_;
  st.deletedOutlet = rep_.deletedOutlet;
  st.deletedTop = rep_.deletedTop;
  st.lost = rep_.lost;
  st.profileDone = profileDone_;
  st.slabSplits = dem::slabSplits(lig_);
  st.write(scene_.caseDir);
}

void MixtureMonitor::afterStep() {
  if (lig_.step() - lastSampleStep_ < rec_->sampleEvery()) return;
  lastSampleStep_ = lig_.step();
  rec_->deleteLeavers(rep_);
  rec_->sample(rep_);
  rec_->profileIfDue(profileDone_);
  rec_->indexSnapshots();
  if (rank_ == 0)
    progress_->update(rec_->time(), false,
                      ", granular front " + mixflow::formatNumber(rep_.front, 4) + " m");
}

void MixtureMonitor::finish() {
  if (lig_.step() != lastSampleStep_) {  // the end time is a row too
    rec_->deleteLeavers(rep_);
    rec_->sample(rep_);
  }
  rep_.stopReason = "endTime";
  if (resumed_ && rep_.remaining == 0) rep_.remaining = lig_.atomCount();
  rec_->finish(rep_);
  rec_->indexSnapshots();
  rec_->writeSummary(
      settled_, rep_,
      "  \"liquid_density_kg_m3\": " + mixflow::formatNumber(scene_.fluidDensity) + ",\n");
  if (rank_ == 0) {
    progress_->update(rec_->time(), true);
    // The DEM share of the wall time (bench/coupled_vs_dry.py splits DEM, coupling and fluid).
    out_ << "[coupled " << scene_.name << "] wall time " << progress_->wallSeconds()
         << " s, of which inside LIGGGHTS runs " << lig_.runSeconds() << " s\n[coupled "
         << scene_.name << "] time loop CPU " << progress_->cpuSeconds() << " s (rank 0)"
         << std::endl;
  }
}

}  // namespace mixflow::coupling
