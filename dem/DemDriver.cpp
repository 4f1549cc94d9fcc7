#include "DemDriver.h"

#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "ContactTimes.h"
#include "Dictionary.h"
#include "LiggghtsCommands.h"
#include "Observables.h"
#include "Progress.h"
#include "SampleFill.h"
#include "SettleCheckpoint.h"
#include "SettledSample.h"
#include "SlabBalance.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

namespace {
constexpr double kG = 9.81;
std::string fmt(double v, int precision = 10) { return formatNumber(v, precision); }

// Keeps the header and the rows of a CSV whose first column (time) is <= tMax.
void dropRowsAfter(const fs::path& csv, double tMax) {
  if (!fs::exists(csv)) return;
  std::ifstream in(csv);
  std::string line, kept;
  for (bool header = true; std::getline(in, line); header = false)
    if (header || std::stod(line.substr(0, line.find(','))) <= tMax) kept += line + '\n';
  in.close();
  std::ofstream(csv.string() + ".tmp") << kept;
  fs::rename(csv.string() + ".tmp", csv);
}

double meanKineticPerParticle(const Energies& e) {
  return e.count > 0 ? e.kinetic() / static_cast<double>(e.count) : 0.0;
}
}  // namespace

DemDriver::DemDriver(const Scene& scene, MPI_Comm comm, std::ostream& out)
    : scene_(scene), comm_(comm), out_(out) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  outDir_ = (fs::path(scene.caseDir) / "postProcessing" / "dem").string();
  const std::string demDir = (fs::path(scene.caseDir) / "dem").string();
  if (rank_ == 0) fs::create_directories(demDir);
  MPI_Barrier(comm);
  lig_ = std::make_unique<LiggghtsSession>(comm, demDir);
  dt_ = scene.timeStepUsed();
}

DemDriver::~DemDriver() = default;

double DemDriver::simTime() const { return (lig_->step() - step0_) * dt_; }

SettleReport DemDriver::settle() {
  const Scene& s = scene_;
  const SettleSpec& ss = s.settle;
  const bool control = ss.packingControl == "friction";
  const std::string fingerprint = fingerprintOf(settleInputs(s));
  std::ostringstream note;  // find() reports an ignored checkpoint; rank 0 prints it
  std::optional<SettleCheckpoint> from = SettleCheckpoint::find(s.caseDir, fingerprint, note);
  if (rank_ == 0) out_ << note.str();
  PackingSearch search(s.sample.solidFraction, ss.packingTolerance, ss.minFriction, ss.maxFriction,
                       ss.friction);
  if (from)
    for (const PackingSearch::Trial& tr : from->trials) search.add(tr.friction, tr.fraction);
  if (from && from->restartFile == SettleCheckpoint::kNone) from.reset();  // between two trials
  SettleReport r;
  double friction = ss.friction;
  for (int run = 0;; ++run) {
    if (control) {
      const std::optional<double> next = search.next();
      if (!next || static_cast<long>(search.trials().size()) >= ss.maxSettles)
        throw PackingMiss(packingMiss(search, next ? "" : search.whyNot()));
      friction = *next;
      // Each trial settles the same loose fill from LIGGGHTS' initial state (`clear`; a second
      // instance in one process re-registers LIGGGHTS' styles with a warning per style).
      if (run > 0) {
        lig_->command("clear");
        lig_->invalidateSetup();
      }
    }
    r = settleTrial(friction, from, fingerprint, search.trials());
    from.reset();
    if (!control) break;
    search.add(friction, r.sampleFraction);
    if (rank_ == 0)
      out_ << "[dem] packing control: settle " << search.trials().size() << " at friction "
           << fmt(friction, 4) << " gave " << fmt(r.sampleFraction, 4) << " (target "
           << s.sample.solidFraction << " ± " << ss.packingTolerance << ")" << std::endl;
    if (search.landed()) break;
    if (ss.checkpointInterval > 0 && rank_ == 0) writeBetweenTrials(fingerprint, search.trials());
  }
  MPI_Barrier(comm_);
  if (rank_ == 0) SettleCheckpoint::remove(s.caseDir);  // the settled sample supersedes it
  r.packingControl = ss.packingControl;
  r.settleFriction = friction;
  r.settles = control ? static_cast<long>(search.trials().size()) : 1;
  r.packingTolerance = control ? ss.packingTolerance : 0.0;
  if (!control && rank_ == 0) warnOffTarget(r.sampleFraction);
  return r;
}

void DemDriver::writeBetweenTrials(const std::string& fingerprint,
                                   const std::vector<PackingSearch::Trial>& trials) const {
  SettleCheckpoint between;
  between.restartFile = SettleCheckpoint::kNone;
  between.fingerprint = fingerprint;
  between.trials = trials;
  between.write(scene_.caseDir);
}

void DemDriver::warnOffTarget(double sampleFraction) const {
  const Scene& s = scene_;
  const double off = sampleFraction / s.sample.solidFraction - 1.0;
  if (std::abs(off) > kSettledFractionTolerance)
    out_ << "[dem] warning: the settled sample solid fraction " << fmt(sampleFraction, 4) << " is "
         << fmt(100 * std::abs(off), 2) << " % " << (off < 0 ? "below" : "above")
         << " sample.solidFraction " << s.sample.solidFraction
         << " (constant/sceneProperties): with demDict settle.packingControl off the target sets "
            "the grain count only; settle.friction sets the packing (looser with more friction), "
            "softened contacts (youngModulusFactor) compact it"
         << std::endl;
}

std::string DemDriver::packingMiss(const PackingSearch& search, const std::string& why) const {
  const Scene& s = scene_;
  const SettleSpec& ss = s.settle;
  const PackingSearch::Trial* best = nullptr;
  std::string list;
  for (const PackingSearch::Trial& tr : search.trials()) {
    if (!best || std::abs(tr.fraction - s.sample.solidFraction) <
                     std::abs(best->fraction - s.sample.solidFraction))
      best = &tr;
    list += (list.empty() ? "" : ", ") + fmt(tr.friction, 4) + " -> " + fmt(tr.fraction, 4);
  }
  std::ostringstream m;
  m << "packing control: no settle of the loose fill reached sample.solidFraction "
    << s.sample.solidFraction << " ± " << ss.packingTolerance << " (constant/sceneProperties, "
    << "system/demDict settle.packingTolerance)";
  if (best)
    m << "; the nearest, at settle friction " << fmt(best->friction, 4) << ", gave "
      << fmt(best->fraction, 4);
  m << " after " << search.trials().size() << " settles (friction -> fraction: " << list << ")";
  if (!why.empty()) m << ": " << why;
  m << ". Change system/demDict settle.maxSettles (now " << ss.maxSettles
    << ", allowed 1-50), settle.minFriction / settle.maxFriction (now " << ss.minFriction << " / "
    << ss.maxFriction << ", allowed 0-2), settle.packingTolerance (now " << ss.packingTolerance
    << ", allowed 1e-4 to 0.05), or sample.solidFraction (allowed (0, 0.64]) to one this "
       "softening reaches; settle.packingControl off settles once at settle.friction. No "
       "settled sample was written";
  return m.str();
}

SettleReport DemDriver::settleTrial(double friction, const std::optional<SettleCheckpoint>& from,
                                    const std::string& fingerprint,
                                    const std::vector<PackingSearch::Trial>& trials) {
  const Scene& s = scene_;
  // The scene the grains settle in: s, or s softened to settle.stiffenFrom with its own step.
  const Scene st = s.settlingScene();
  double t = 0;
  const double top = placeSettlingGrains(st, from, t);
  // Settling friction sets the packing density (lower friction packs denser). Rolling resistance is
  // off while settling unless settle.rollingFriction asks for it (a loose sample): a constant
  // rolling torque chatters at rest and can keep the sample from settling.
  lig_->commands(materialCommands(st.particles, st.dem.youngModulusFactor, friction,
                                  st.settle.rollingFriction));
  lig_->commands(settleGravityCommands(s));
  lig_->commands(settleDragCommands(s));
  const bool converged = settleUnderGravity(st.timeStepUsed(), top, t, fingerprint, trials);
  lig_->commands(settleDragOffCommands(s));
  if (s.stiffensSettled()) t += stiffenSettled();
  t += relaxAtRealFriction();
  SettleReport r = measureSample(t, converged);
  if (rank_ == 0)
    out_ << "[dem] settled in " << fmt(t, 4) << " s" << (converged ? "" : " (NOT converged)")
         << ": height " << fmt(r.settledHeight, 4) << " m (target " << s.sample.height
         << "), sample solid fraction " << fmt(r.sampleFraction, 4) << " (target "
         << s.sample.solidFraction << "), bulk fraction " << fmt(r.bulkFraction, 4) << std::endl;
  return r;
}

double DemDriver::placeSettlingGrains(const Scene& st, const std::optional<SettleCheckpoint>& from,
                                      double& t) {
  const Scene& s = scene_;
  const double dtSettle = st.timeStepUsed();
  if (from) {
    // The box, atoms and gate as the checkpoint left them; the settling materials follow.
    lig_->commands(resumeSetupCommands(st, (fs::path(s.caseDir) / from->restartFile).string(),
                                       dtSettle, true));
    t = from->time;
    settleSlot_ = from->restartFile == SettleCheckpoint::slotFile(0) ? 1 : 0;
    if (rank_ == 0)
      out_ << "[dem] settling continues from its checkpoint at t = " << fmt(t, 6) << " s ("
           << SettleCheckpoint::statePath(s.caseDir) << ")" << std::endl;
    return s.sample.height;  // only sets the free-fall time, which has passed
  }
  const Fill fill = makeLooseFill(s);
  const Box box = channelBox(s, fill.top);
  const std::string dataFile = (fs::path(s.caseDir) / "dem" / "initial.data").string();
  if (rank_ == 0) writeDataFile(dataFile, fill, s.particles, box);
  MPI_Barrier(comm_);
  if (rank_ == 0)
    out_ << "[dem] " << fill.centres.size() << " particles (d = " << s.particles.diameter
         << " m), E = " << s.youngModulusUsed() << " Pa (factor " << s.dem.youngModulusFactor
         << "), dt = " << dt_ << " s = " << fmt(dt_ / s.rayleighTime(), 3) << " T_R (limit "
         << fmt(s.stableTimeStepLimit(), 4) << " s)" << std::endl;
  if (rank_ == 0 && s.stiffensSettled())
    out_ << "[dem] settling at E = " << st.youngModulusUsed() << " Pa (settle.stiffenFrom "
         << s.settle.stiffenFrom << "), dt = " << dtSettle << " s, then stiffened" << std::endl;
  lig_->commands(sceneSetupCommands(st, dataFile, dtSettle));
  return fill.top;
}

bool DemDriver::settleUnderGravity(double dtSettle, double top, double& t,
                                   const std::string& fingerprint,
                                   const std::vector<PackingSearch::Trial>& trials) {
  const Scene& s = scene_;
  const double m = s.particles.mass(), d = s.particles.diameter;
  const long nChunk = std::max(1L, std::lround(kSettleCheckInterval / dtSettle));
  const double tFall = std::sqrt(2.0 * top / kG);
  const double every = s.settle.checkpointInterval;
  double nextCheckpoint = every > 0 ? (std::floor(t / every + 1e-9) + 1) * every : 0;
  Progress progress("settle", t, s.settle.maxTime, out_);
  // The sample stays behind the gate while it settles: one balance at the start holds.
  if (s.dem.balanceInterval > 0 &&
      !balanceSlabs(*lig_, comm_, balanceWeight(s.dem.balanceWeight)) && rank_ == 0 && size_ > 1)
    out_ << "[dem] balanceInterval: the processor grid is not x slabs (set processors \"* 1 1\") "
            "or there is one rank; the slabs stay equal"
         << std::endl;
  while (t < s.settle.maxTime) {
    lig_->run(nChunk);
    t += nChunk * dtSettle;
    const Energies e = energies(lig_->particles(), kG, comm_);
    if (!std::isfinite(e.kinetic()))
      throw std::runtime_error("NaN in particle kinetic energy during settling at t = " + fmt(t) +
                               " s: time step too large for the contact stiffness?");
    const double keRatio = meanKineticPerParticle(e) / (m * kG * d);
    if (rank_ == 0) progress.update(t, false, ", KE/(N m g d) = " + fmt(keRatio, 3));
    if (t > tFall && keRatio < s.settle.kineticTolerance) return true;
    if (every > 0 && t >= nextCheckpoint - 0.5 * dtSettle) {
      writeSettleCheckpoint(t, fingerprint, trials);
      nextCheckpoint += every;
    }
  }
  return false;
}

double DemDriver::stiffenSettled() {
  const Scene& s = scene_;
  // Up to the scene's moduli and step in geometric steps at the settling friction: each sheds
  // part of the soft overlaps (SettleSpec::stiffenSteps).
  double tStiff = 0;
  Energies e;
  for (long k = 1; k <= s.settle.stiffenSteps; ++k) {
    const Scene step = s.stiffeningScene(k);
    const double dtStep = step.timeStepUsed();  // the last step is the settle's final step
    lig_->commands(stiffenCommands(step, dtStep));
    lig_->invalidateSetup();
    const long n = std::max(1L, std::lround(s.settle.stiffenStepTime / dtStep));
    lig_->run(n);
    tStiff += n * dtStep;
    e = energies(lig_->particles(), kG, comm_);
  }
  if (rank_ == 0)
    out_ << "[dem] stiffened to E = " << s.youngModulusUsed() << " Pa in " << s.settle.stiffenSteps
         << " steps, " << fmt(tStiff, 4) << " s: KE/(N m g d) = "
         << fmt(meanKineticPerParticle(e) / (s.particles.mass() * kG * s.particles.diameter), 3)
         << std::endl;
  return tStiff;
}

double DemDriver::relaxAtRealFriction() {
  const Scene& s = scene_;
  // Back to the real friction, and a short relaxation so the contacts carry it.
  lig_->commands(materialCommands(s.particles, s.dem.youngModulusFactor, s.particles.friction,
                                  s.particles.rollingFriction));
  // At the step the settle ended at (its own, settledScene), whatever the collapse's step.
  const double dt = s.settledScene().timeStepUsed();
  lig_->invalidateSetup();
  const long nRelax = std::lround(s.settle.relaxTime / dt);
  lig_->run(nRelax);
  return nRelax * dt;
}

void DemDriver::writeSettleCheckpoint(double t, const std::string& fingerprint,
                                      const std::vector<PackingSearch::Trial>& trials) {
  SettleCheckpoint c;
  c.trials = trials;
  c.time = t;
  c.fingerprint = fingerprint;
  c.restartFile = SettleCheckpoint::slotFile(settleSlot_);
  settleSlot_ = 1 - settleSlot_;  // the state keeps naming the other until this one is written
  lig_->writeRestart((fs::path(scene_.caseDir) / c.restartFile).string());
  if (rank_ == 0) c.write(scene_.caseDir);
}

SettleReport DemDriver::measureSample(double settleTime, bool converged) {
  const Scene& s = scene_;
  const auto centres = gatherCentres(lig_->particles(), comm_);
  SettleReport r;
  r.settleTime = settleTime;
  r.converged = converged;
  r.particles = static_cast<long>(centres.size());
  double buf[3] = {0, 0, 0};
  if (rank_ == 0) {
    const double d = s.particles.diameter, rad = 0.5 * d;
    const Profile top = depositProfile(centres, rad, s.sample.width, 2 * d, 2 * d, s.sample.length,
                                       s.sample.solidFraction);
    double h = 0;
    int nb = 0;
    for (size_t i = 0; i < top.x.size(); ++i)
      if (top.x[i] < s.sample.length) h += top.hTop[i], ++nb;
    h /= std::max(nb, 1);
    const double lo = 2 * d, hi = h - 2 * d;
    double vol = 0;
    for (const auto& c : centres) vol += sphereSlabVolume(c[1], rad, lo, hi);
    buf[0] = h;
    buf[1] = r.particles * s.particles.volume() / (s.sample.length * s.sample.width * h);
    buf[2] = hi > lo ? vol / (s.sample.length * s.sample.width * (hi - lo)) : 0.0;
  }
  MPI_Bcast(buf, 3, MPI_DOUBLE, 0, comm_);
  r.settledHeight = buf[0];
  r.sampleFraction = buf[1];
  r.bulkFraction = buf[2];
  return r;
}

CollapseReport DemDriver::collapse(const SettleReport& settled) {
  settled_ = settled;
  // The collapse's step, where the settle ran at another (settle.rayleighFraction).
  if (scene_.settledScene().timeStepUsed() != dt_) lig_->command(timestepCommand(dt_));
  // t = 0 at the gate opening is step 0, so periodic dumps fall on multiples of writeInterval.
  lig_->command("reset_timestep 0");
  step0_ = lig_->step();
  lig_->command("unfix wGate");
  placeLiftedGate(0.0, step0_);
  lig_->invalidateSetup();
  return runCollapse(CollapseReport{}, false, false);
}

void DemDriver::placeLiftedGate(double t, long step0) {
  if (!scene_.gate.lifted()) return;
  auto gate = std::make_unique<LiftedGate>(scene_, settled_.settledHeight);
  if (gate->removedAt(t)) return;
  const std::string file = (fs::path(scene_.caseDir) / "dem" / "gate.stl").string();
  if (rank_ == 0) std::ofstream(file) << gate->stl(scene_.gate.height(t));
  MPI_Barrier(comm_);
  lig_->commands(gate->commands(file, dt_, step0));
  lig_->command("run 0");  // sets the mesh up: a restart written before it would fail
  if (rank_ == 0)
    out_ << "[dem] gate lifted: plate at x = " << fmt(scene_.sample.length, 6) << " m, "
         << fmt(gate->plateHeight(), 4) << " m tall, lower edge at "
         << fmt(scene_.gate.height(t), 4) << " m at t = " << fmt(t, 6) << " s, removed once above "
         << fmt(gate->removalHeight(), 4) << " m" << std::endl;
  gate_ = std::move(gate);
}

void DemDriver::removeLiftedGateIfPassed(double t) {
  if (!gate_ || !gate_->removedAt(t)) return;
  lig_->commands(LiftedGate::removeCommands());
  lig_->invalidateSetup();
  gate_.reset();
  if (rank_ == 0)
    out_ << "[dem] gate lifted past the column at t = " << fmt(t, 6) << " s: plate removed"
         << std::endl;
}

void DemDriver::writeResumeState(const CollapseReport& rep, bool profileDone) {
  // Two alternating restart files: a crash while writing one leaves the other and its state intact.
  const fs::path dir = fs::path(scene_.caseDir) / "dem";
  const std::string file = (dir / ("restart_" + std::to_string(restartSlot_) + ".bin")).string();
  restartSlot_ = 1 - restartSlot_;
  lig_->writeRestart(file);
  if (rank_ != 0) return;
  const fs::path tmp = dir / "resume.state.tmp";
  {
    std::ofstream f(tmp);
    f << "// Written by mixflowDem with each particle snapshot; read by mixflowDem -resume.\n"
      << "restartFile \"" << file << "\";\ntime " << fmt(simTime(), 17) << ";\nstep "
      << lig_->step() << ";\ndeletedOutlet " << rep.deletedOutlet << ";\ndeletedTop "
      << rep.deletedTop << ";\nlost " << rep.lost << ";\nprofileDone "
      << (profileDone ? "yes" : "no") << ";\nlastBalance " << lastBalance_ << ";\nslabSplits (";
    const std::vector<double> splits = slabSplits(*lig_);
    for (size_t i = 0; i < splits.size(); ++i) f << (i ? " " : "") << fmt(splits[i], 17);
    f << ");\nsettled\n";
    writeSettledDict(f, settled_);
  }
  fs::rename(tmp, dir / "resume.state");
}

CollapseReport DemDriver::resume(SettleReport& settled) {
  const fs::path statePath = fs::path(scene_.caseDir) / "dem" / "resume.state";
  if (!fs::exists(statePath))
    throw InputError(statePath.string() +
                     ": cannot open file: no restart state to resume from (run without -resume)");
  const Dictionary st = Dictionary::readFile(statePath.string());
  const std::string restartFile = st.word("restartFile", {});
  const double t = st.scalar("time", Range::nonNegative());
  settled = readSettledDict(st.subDict("settled"));
  settled_ = settled;
  CollapseReport rep;
  rep.deletedOutlet = st.integer("deletedOutlet", 0, 2000000000);
  rep.deletedTop = st.integer("deletedTop", 0, 2000000000);
  rep.lost = st.integer("lost", 0, 2000000000);
  if (rank_ == 0)
    out_ << "[dem] resuming at t = " << fmt(t, 6) << " s from " << restartFile << std::endl;
  lig_->commands(resumeSetupCommands(scene_, restartFile, dt_));
  step0_ = 0;  // the restart carries the step count since the gate opened
  placeLiftedGate(t, step0_);
  // The stopped run's slabs, re-balance count and atom order, so the resumed run goes on as the
  // uninterrupted one (as mixflowCoupled -resume does, coupling/DemStartup.cpp). The setup run
  // first makes the pair's contact-history fix from the restart's per-atom data.
  lastBalance_ = st.has("lastBalance") ? st.integer("lastBalance", -1, 2000000000) : -1;
  if (st.has("slabSplits")) {
    lig_->command("run 0");
    setSlabSplits(*lig_, st.scalars("slabSplits", Range::closed(0, 1)));
    lig_->orderByTag();
  }
  // Rows written after the restart state are recomputed: drop them.
  if (rank_ == 0)
    for (const char* name : {"timeSeries.csv", "rankLoad.csv"})
      dropRowsAfter(fs::path(outDir_) / name, t + 0.5 * dt_);
  return runCollapse(rep, st.switchOr("profileDone", false), true);
}

CollapseReport DemDriver::runCollapse(CollapseReport rep, bool profileDone, bool appendSeries) {
  const Scene& s = scene_;
  const double d = s.particles.diameter, m = s.particles.mass();
  rec_ = std::make_unique<CollapseRecorder>(s, *lig_, comm_, step0_, appendSeries);
  CollapseRecorder& rec = *rec_;
  double t = rec.time();
  if (!appendSeries) rec.sample(rep);
  rec.startSnapshots();
  if (!appendSeries) writeResumeState(rep, profileDone);
  Progress progress("dem " + s.name, t, s.endTime, out_);
  std::deque<std::pair<double, double>> frontHistory;  // (t, front) over the arrest window
  rep.stopReason = "endTime";
  while (t < s.endTime - 0.5 * dt_) {
    // At the first chunk from each multiple of balanceInterval: a resumed run (lastBalance_ from
    // its state) re-balances where the uninterrupted one did.
    const long k = s.dem.balanceInterval > 0
                       ? static_cast<long>(std::floor((t + 0.5 * dt_) / s.dem.balanceInterval))
                       : -1;
    if (k > lastBalance_) {
      balanceSlabs(*lig_, comm_, balanceWeight(s.dem.balanceWeight));
      lastBalance_ = k;
    }
    const long n = std::min(rec.sampleEvery(), std::max(1L, std::lround((s.endTime - t) / dt_)));
    lig_->run(n);
    t = rec.time();
    removeLiftedGateIfPassed(t);
    rec.deleteLeavers(rep);
    const Energies e = rec.sample(rep);
    rec.profileIfDue(profileDone);
    rec.indexSnapshots();
    if (rec.atSnapshot()) writeResumeState(rep, profileDone);
    if (rank_ == 0) progress.update(t);
    // Arrest test on rank 0 (which holds the front history), decision shared with all ranks.
    int arrested = 0;
    if (rank_ == 0) {
      frontHistory.emplace_back(t, rep.front);
      while (frontHistory.size() > 1 && frontHistory[1].first <= t - s.dem.arrestWindow)
        frontHistory.pop_front();
      const bool windowFull = frontHistory.front().first <= t - s.dem.arrestWindow + 0.5 * dt_;
      double lo = 1e300, hi = -1e300;
      for (const auto& tf : frontHistory)
        lo = std::min(lo, tf.second), hi = std::max(hi, tf.second);
      arrested = s.dem.stopWhenArrested && t >= s.dem.arrestMinTime && windowFull &&
                 hi - lo <= s.dem.arrestFrontDiameters * d &&
                 meanKineticPerParticle(e) < s.dem.arrestKineticTolerance * m * kG * d;
    }
    MPI_Bcast(&arrested, 1, MPI_INT, 0, comm_);
    if (arrested) {
      rep.stopReason = "arrested";
      break;
    }
  }
  if (appendSeries && rep.remaining == 0) rep.remaining = lig_->atomCount();
  if (rank_ == 0) progress.update(t, true);
  rec.finish(rep);
  return rep;
}

void DemDriver::writeSummary(const SettleReport& st, const CollapseReport& c) const {
  if (rec_) rec_->writeSummary(st, c);
}

void DemDriver::writeSettledState(const SettleReport& st) {
  const fs::path dir = fs::path(scene_.caseDir) / "dem";
  // Step 0 = the gate opening for the coupled run that restarts from this file (after a
  // read_restart LIGGGHTS accepts reset_timestep only right before a run).
  lig_->command("reset_timestep 0");
  lig_->writeRestart((dir / "settled.restart").string());
  if (rank_ != 0) return;
  // What it was made from, for a later run that would reuse it (SettledSample.h).
  const std::string inputs = settleInputs(scene_);
  SettleReport recorded = st;
  recorded.fingerprint = fingerprintOf(inputs);
  {
    std::ofstream f(dir / "settled.state.tmp");
    f << "// Written by mixflowDem -settleOnly: the settled sample of a mixture scene.\n"
      << "restartFile \"dem/settled.restart\";   // relative to the case directory\n"
      << "settled\n";
    writeSettledDict(f, recorded);
  }
  std::ofstream(dir / "settled.inputs") << inputs;
  std::ofstream(dir / "settled.entries") << settleEntries(scene_);
  fs::rename(dir / "settled.state.tmp", dir / "settled.state");
}

void writeSettledDict(std::ostream& f, const SettleReport& st) {
  f << "{\n  particles " << st.particles << ";\n  height " << fmt(st.settledHeight, 17)
    << ";\n  sampleFraction " << fmt(st.sampleFraction, 17) << ";\n  bulkFraction "
    << fmt(st.bulkFraction, 17) << ";\n  settleTime " << fmt(st.settleTime, 17) << ";\n  converged "
    << (st.converged ? "yes" : "no") << ";\n  packingControl " << st.packingControl
    << ";\n  packingTolerance " << fmt(st.packingTolerance) << ";\n  settleFriction "
    << fmt(st.settleFriction, 17) << ";\n  settles " << st.settles << ";\n";
  if (!st.fingerprint.empty()) f << "  fingerprint \"" << st.fingerprint << "\";\n";
  f << "}\n";
}

SettleReport readSettledDict(const Dictionary& sd) {
  SettleReport st;
  st.particles = sd.integer("particles", 0, 2000000000);
  st.settledHeight = sd.scalar("height", Range::nonNegative());
  st.sampleFraction = sd.scalar("sampleFraction", Range::nonNegative());
  st.bulkFraction = sd.scalar("bulkFraction", Range::nonNegative());
  st.settleTime = sd.scalar("settleTime", Range::nonNegative());
  st.converged = sd.switchOr("converged", false);
  // Samples settled before the packing control record none of it.
  if (sd.has("packingControl")) {
    st.packingControl = sd.word("packingControl", {"friction", "off"});
    st.packingTolerance = sd.scalar("packingTolerance", Range::nonNegative());
    st.settleFriction = sd.scalar("settleFriction", Range::nonNegative());
    st.settles = sd.integer("settles", 1, 1000);
  }
  if (sd.has("fingerprint")) st.fingerprint = sd.word("fingerprint", {});
  return st;
}

}  // namespace mixflow::dem
