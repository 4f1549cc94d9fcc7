#include "DemDriver.h"

#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "ContactTimes.h"
#include "Dictionary.h"
#include "LiggghtsCommands.h"
#include "Observables.h"
#include "Progress.h"
#include "SampleFill.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

namespace {
constexpr double kG = 9.81;

std::string fmt(double v, int precision = 10) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// Particle centres (x, y, z) of all ranks, on rank 0.
std::vector<std::array<double, 3>> gatherCentres(const ParticleView& p, MPI_Comm comm) {
  std::vector<double> local;
  local.reserve(3 * p.n);
  for (int i = 0; i < p.n; ++i)
    for (int k = 0; k < 3; ++k) local.push_back(p.x[i][k]);
  const std::vector<double> all = gatherOnRoot(local, comm);
  std::vector<std::array<double, 3>> c(all.size() / 3);
  for (size_t i = 0; i < c.size(); ++i) c[i] = {all[3 * i], all[3 * i + 1], all[3 * i + 2]};
  return c;
}

double meanKineticPerParticle(const Energies& e) {
  return e.count > 0 ? e.kinetic() / static_cast<double>(e.count) : 0.0;
}
}  // namespace

DemDriver::DemDriver(const Scene& scene, MPI_Comm comm, std::ostream& out)
    : scene_(scene), comm_(comm), out_(out) {
  MPI_Comm_rank(comm, &rank_);
  outDir_ = (fs::path(scene.caseDir) / "postProcessing" / "dem").string();
  const std::string demDir = (fs::path(scene.caseDir) / "dem").string();
  if (rank_ == 0) {
    fs::create_directories(outDir_);
    fs::create_directories(demDir);
    fs::create_directories(fs::path(scene.caseDir) / "VTK" / "particles");
  }
  MPI_Barrier(comm);
  lig_ = std::make_unique<LiggghtsSession>(comm, demDir);
  dt_ = scene.timeStepUsed();
  sampleEvery_ = std::max(1L, std::lround(scene.dem.sampleInterval / dt_));
}

DemDriver::~DemDriver() = default;

double DemDriver::simTime() const { return (lig_->step() - step0_) * dt_; }

SettleReport DemDriver::settle() {
  const Scene& s = scene_;
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

  lig_->commands(sceneSetupCommands(s, dataFile, dt_));
  // Settling friction sets the packing density (lower friction packs denser). Rolling resistance is
  // off while settling: a constant rolling torque chatters at rest and keeps the sample from
  // settling.
  lig_->commands(materialCommands(s.particles, s.dem.youngModulusFactor, s.settle.friction, 0.0));

  const double m = s.particles.mass(), d = s.particles.diameter;
  const double chunk = 0.02;
  const long nChunk = std::max(1L, std::lround(chunk / dt_));
  const double tFall = std::sqrt(2.0 * fill.top / kG);
  Progress progress("settle", 0.0, s.settle.maxTime, out_);
  double t = 0;
  bool converged = false;
  while (t < s.settle.maxTime) {
    lig_->run(nChunk);
    t += nChunk * dt_;
    const Energies e = energies(lig_->particles(), kG, comm_);
    if (!std::isfinite(e.kinetic()))
      throw std::runtime_error("NaN in particle kinetic energy during settling at t = " + fmt(t) +
                               " s: time step too large for the contact stiffness?");
    const double keRatio = meanKineticPerParticle(e) / (m * kG * d);
    if (rank_ == 0) progress.update(t, false, ", KE/(N m g d) = " + fmt(keRatio, 3));
    if (t > tFall && keRatio < s.settle.kineticTolerance) {
      converged = true;
      break;
    }
  }
  // Back to the real friction, and a short relaxation so the contacts carry it.
  lig_->commands(materialCommands(s.particles, s.dem.youngModulusFactor, s.particles.friction,
                                  s.particles.rollingFriction));
  lig_->invalidateSetup();
  const long nRelax = std::lround(s.settle.relaxTime / dt_);
  lig_->run(nRelax);
  t += nRelax * dt_;
  SettleReport r = measureSample(t, converged);
  if (rank_ == 0)
    out_ << "[dem] settled in " << fmt(t, 4) << " s" << (converged ? "" : " (NOT converged)")
         << ": height " << fmt(r.settledHeight, 4) << " m (target " << s.sample.height
         << "), sample solid fraction " << fmt(r.sampleFraction, 4) << " (target "
         << s.sample.solidFraction << "), bulk fraction " << fmt(r.bulkFraction, 4) << std::endl;
  return r;
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

long DemDriver::deleteLeavers(long& outlet, long& top) {
  const ParticleView p = lig_->particles();
  long local[2] = {0, 0}, total[2];
  for (int i = 0; i < p.n; ++i) {
    if (p.x[i][0] > scene_.channel.length)
      ++local[0];
    else if (p.x[i][1] > scene_.channel.height)
      ++local[1];
  }
  MPI_Allreduce(local, total, 2, MPI_LONG, MPI_SUM, comm_);
  if (total[0] > 0) lig_->command("delete_atoms region outletRegion compress no");
  if (total[1] > 0) lig_->command("delete_atoms region topRegion compress no");
  if (total[0] + total[1] > 0) lig_->invalidateSetup();
  outlet += total[0];
  top += total[1];
  return total[0] + total[1];
}

void DemDriver::startSnapshots() {
  // A periodic dump (not write_dump): LIGGGHTS tallies the per-atom contact virial only on steps a
  // dump has announced. Files are particles_<step>.vtk; step 0 is the gate opening.
  // Snapshots (and restart states) fall on sample boundaries: a whole number of sample chunks.
  snapshotEvery_ =
      sampleEvery_ * std::max(1L, std::lround(scene_.writeInterval / (sampleEvery_ * dt_)));
  lig_->command("dump snap all custom/vtk " + std::to_string(snapshotEvery_) + " " +
                (fs::path(scene_.caseDir) / "VTK" / "particles" / "particles_*.vtk").string() +
                " id type x y z vx vy vz fx fy fz omegax omegay omegaz radius mass c_pstress[1] "
                "c_pstress[2] c_pstress[3] c_pstress[4] c_pstress[5] c_pstress[6]");
}

void DemDriver::indexSnapshots(long lastStep) const {
  if (rank_ != 0) return;
  // ParaView's file-series index of the snapshots written so far, with their simulated times.
  std::ofstream f(fs::path(scene_.caseDir) / "VTK" / "particles.vtk.series");
  f << "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
  for (long step = 0; step <= lastStep; step += snapshotEvery_)
    f << "    { \"name\" : \"particles/particles_" << step
      << ".vtk\", \"time\" : " << fmt(step * dt_) << " }"
      << (step + snapshotEvery_ <= lastStep ? "," : "") << "\n";
  f << "  ]\n}\n";
}

CollapseReport DemDriver::collapse(const SettleReport& settled) {
  settled_ = settled;
  // t = 0 at the gate opening is step 0, so periodic dumps fall on multiples of writeInterval.
  lig_->command("reset_timestep 0");
  step0_ = lig_->step();
  lig_->command("unfix wGate");
  lig_->invalidateSetup();
  return runCollapse(CollapseReport{}, false, false);
}

void DemDriver::writeResumeState(const CollapseReport& rep, bool profileDone) {
  // Two alternating restart files: a crash while writing one leaves the other and its state intact.
  const fs::path dir = fs::path(scene_.caseDir) / "dem";
  const std::string file = (dir / ("restart_" + std::to_string(restartSlot_) + ".bin")).string();
  restartSlot_ = 1 - restartSlot_;
  lig_->command("write_restart " + file);
  if (rank_ != 0) return;
  const fs::path tmp = dir / "resume.state.tmp";
  {
    std::ofstream f(tmp);
    f << "// Written by mixflowDem with each particle snapshot; read by mixflowDem -resume.\n"
      << "restartFile \"" << file << "\";\ntime " << fmt(simTime(), 17) << ";\nstep "
      << lig_->step() << ";\ndeletedOutlet " << rep.deletedOutlet << ";\ndeletedTop "
      << rep.deletedTop << ";\nlost " << rep.lost << ";\nprofileDone "
      << (profileDone ? "yes" : "no") << ";\nsettled\n{\n  particles " << settled_.particles
      << ";\n  height " << fmt(settled_.settledHeight, 17) << ";\n  sampleFraction "
      << fmt(settled_.sampleFraction, 17) << ";\n  bulkFraction " << fmt(settled_.bulkFraction, 17)
      << ";\n  settleTime " << fmt(settled_.settleTime, 17) << ";\n  converged "
      << (settled_.converged ? "yes" : "no") << ";\n}\n";
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
  const Dictionary sd = st.subDict("settled");
  settled.particles = sd.integer("particles", 0, 2000000000);
  settled.settledHeight = sd.scalar("height", Range::nonNegative());
  settled.sampleFraction = sd.scalar("sampleFraction", Range::nonNegative());
  settled.bulkFraction = sd.scalar("bulkFraction", Range::nonNegative());
  settled.settleTime = sd.scalar("settleTime", Range::nonNegative());
  settled.converged = sd.switchOr("converged", false);
  settled_ = settled;
  CollapseReport rep;
  rep.deletedOutlet = st.integer("deletedOutlet", 0, 2000000000);
  rep.deletedTop = st.integer("deletedTop", 0, 2000000000);
  rep.lost = st.integer("lost", 0, 2000000000);
  if (rank_ == 0)
    out_ << "[dem] resuming at t = " << fmt(t, 6) << " s from " << restartFile << std::endl;
  lig_->commands(resumeSetupCommands(scene_, restartFile, dt_));
  step0_ = 0;  // the restart carries the step count since the gate opened
  // Rows written after the restart state are recomputed: drop them.
  if (rank_ == 0) {
    const fs::path csv = fs::path(outDir_) / "timeSeries.csv";
    std::ifstream in(csv);
    std::string line, kept;
    for (bool header = true; std::getline(in, line); header = false)
      if (header || std::stod(line.substr(0, line.find(','))) <= t + 0.5 * dt_) kept += line + '\n';
    in.close();
    std::ofstream(csv.string() + ".tmp") << kept;
    fs::rename(csv.string() + ".tmp", csv);
  }
  return runCollapse(rep, st.switchOr("profileDone", false), true);
}

CollapseReport DemDriver::runCollapse(CollapseReport rep, bool profileDone, bool appendSeries) {
  const Scene& s = scene_;
  const double d = s.particles.diameter, rad = 0.5 * d, m = s.particles.mass();
  const double periodicWidth = s.channel.sideWalls == "periodic" ? s.sample.width : 0.0;
  std::ofstream series;
  if (rank_ == 0) {
    const fs::path csv = fs::path(outDir_) / "timeSeries.csv";
    series.open(csv, appendSeries ? std::ios::app : std::ios::trunc);
    if (!appendSeries)
      series << "time_s,particles,deleted_outlet,deleted_top,lost,front_x_m,runout_m,"
                "front_thickness_x_m,ke_translational_J,ke_rotational_J,pe_J\n";
  }
  // Particles expected at the next sample: now, less what the deletion passes remove; any shortfall
  // left the box between passes (lost). Counted here so a resumed run starts from the right value.
  long expected = energies(lig_->particles(), kG, comm_).count;
  auto sample = [&](double t) {
    const ParticleView p = lig_->particles();
    const Energies e = energies(p, kG, comm_);
    if (!std::isfinite(e.kinetic()) || !std::isfinite(e.potential))
      throw std::runtime_error("NaN in particle energies at t = " + fmt(t) +
                               " s (outputs up to the previous sample are in " + outDir_ + ")");
    rep.lost += expected - e.count;  // left the box between two deletion passes
    expected = e.count;
    rep.remaining = e.count;
    const auto centres = gatherCentres(p, comm_);
    if (rank_ == 0) {
      rep.front = granularFront(centres, rad, s.dem.frontGapDiameters * d, periodicWidth);
      rep.runout = rep.front - s.sample.length;
      // Second rule: where the width-averaged deposit thins below one grain (robust to a sparse
      // tail).
      const Profile prof = depositProfile(centres, rad, s.sample.width, d, 2 * d, s.channel.length,
                                          s.sample.solidFraction);
      rep.frontThickness = thicknessFront(prof, d, s.sample.length, d);
      series << fmt(t) << ',' << e.count << ',' << rep.deletedOutlet << ',' << rep.deletedTop << ','
             << rep.lost << ',' << fmt(rep.front) << ',' << fmt(rep.runout) << ','
             << fmt(rep.frontThickness) << ',' << fmt(e.kineticTranslational) << ','
             << fmt(e.kineticRotational) << ',' << fmt(e.potential) << '\n'
             << std::flush;
    }
    return e;
  };

  double t = simTime();
  if (!appendSeries) sample(t);
  startSnapshots();
  if (!appendSeries) writeResumeState(rep, profileDone);
  Progress progress("dem " + s.name, t, s.endTime, out_);
  std::deque<std::pair<double, double>> frontHistory;  // (t, front) over the arrest window
  rep.stopReason = "endTime";
  while (t < s.endTime - 0.5 * dt_) {
    const long n = std::min(sampleEvery_, std::max(1L, std::lround((s.endTime - t) / dt_)));
    lig_->run(n);
    t = simTime();
    expected -= deleteLeavers(rep.deletedOutlet, rep.deletedTop);
    const Energies e = sample(t);
    if (!profileDone && t >= s.dem.profileTime - 0.5 * dt_) {
      profileDone = true;
      const VelocityProfile vp =
          velocityProfile(lig_->particles(), s.dem.profileX, d, s.dem.profileBinDiameters * d,
                          s.channel.height, comm_);
      if (rank_ == 0) {
        std::ofstream f(fs::path(outDir_) / "velocityProfile.csv");
        f << "y_m,u_x_m_s,particles,x_section_m,time_s\n";
        for (size_t j = 0; j < vp.y.size(); ++j)
          f << fmt(vp.y[j]) << ',' << fmt(vp.u[j]) << ',' << vp.count[j] << ',' << s.dem.profileX
            << ',' << fmt(t) << '\n';
      }
    }
    indexSnapshots(lig_->step() - step0_);
    if ((lig_->step() - step0_) % snapshotEvery_ == 0) writeResumeState(rep, profileDone);
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
  rep.endTime = t;
  if (rank_ == 0) progress.update(t, true);

  const auto centres = gatherCentres(lig_->particles(), comm_);
  if (rank_ == 0) {
    const Profile prof = depositProfile(centres, rad, s.sample.width, d, 2 * d, s.channel.length,
                                        s.sample.solidFraction);
    std::ofstream f(fs::path(outDir_) / "depositProfile.csv");
    f << "x_m,h_top_m,h_volume_m,time_s\n";
    for (size_t i = 0; i < prof.x.size(); ++i)
      f << fmt(prof.x[i]) << ',' << fmt(prof.hTop[i]) << ',' << fmt(prof.hVolume[i]) << ','
        << fmt(t) << '\n';
  }
  MPI_Bcast(&rep.front, 1, MPI_DOUBLE, 0, comm_);
  MPI_Bcast(&rep.frontThickness, 1, MPI_DOUBLE, 0, comm_);
  rep.runout = rep.front - s.sample.length;
  return rep;
}

void DemDriver::writeSummary(const SettleReport& st, const CollapseReport& c) const {
  if (rank_ != 0) return;
  const Scene& s = scene_;
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  std::ofstream f(fs::path(outDir_) / "summary.json");
  f << "{\n"
    << "  \"case\": \"" << s.name << "\",\n"
    << "  \"ranks\": " << ranks << ",\n"
    << "  \"sample\": {\"length_m\": " << s.sample.length << ", \"height_m\": " << s.sample.height
    << ", \"width_m\": " << s.sample.width
    << ", \"aspect_ratio\": " << fmt(s.sample.height / s.sample.length)
    << ", \"target_solid_fraction\": " << s.sample.solidFraction << "},\n"
    << "  \"settled\": {\"particles\": " << st.particles
    << ", \"height_m\": " << fmt(st.settledHeight)
    << ", \"sample_solid_fraction\": " << fmt(st.sampleFraction)
    << ", \"bulk_solid_fraction\": " << fmt(st.bulkFraction)
    << ", \"settle_time_s\": " << fmt(st.settleTime)
    << ", \"converged\": " << (st.converged ? "true" : "false") << "},\n"
    << "  \"young_modulus_pa\": " << fmt(s.youngModulusUsed()) << ",\n"
    << "  \"wall_young_modulus_pa\": " << fmt(s.wallYoungModulusUsed()) << ",\n"
    << "  \"young_modulus_factor\": " << fmt(s.dem.youngModulusFactor) << ",\n"
    << "  \"time_step_s\": " << fmt(dt_) << ",\n"
    << "  \"rayleigh_time_s\": " << fmt(s.rayleighTime()) << ",\n"
    << "  \"rolling_model\": \"" << s.particles.rollingModel << "\",\n"
    << "  \"side_walls\": \"" << s.channel.sideWalls << "\",\n"
    << "  \"end_time_s\": " << fmt(c.endTime) << ",\n"
    << "  \"stop_reason\": \"" << c.stopReason << "\",\n"
    << "  \"front_x_m\": " << fmt(c.front) << ",\n"
    << "  \"runout_m\": " << fmt(c.runout) << ",\n"
    << "  \"normalised_runout\": " << fmt(c.runout / s.sample.length) << ",\n"
    << "  \"front_thickness_x_m\": " << fmt(c.frontThickness) << ",\n"
    << "  \"runout_thickness_m\": " << fmt(c.frontThickness - s.sample.length) << ",\n"
    << "  \"particles_remaining\": " << c.remaining << ",\n"
    << "  \"deleted_outlet\": " << c.deletedOutlet << ",\n"
    << "  \"deleted_top\": " << c.deletedTop << ",\n"
    << "  \"lost\": " << c.lost << "\n"
    << "}\n";
}

}  // namespace mixflow::dem
