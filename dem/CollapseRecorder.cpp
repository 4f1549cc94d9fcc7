#include "CollapseRecorder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ContactDumps.h"
#include "Dictionary.h"
#include "SnapshotFiles.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

namespace {
constexpr double kG = 9.81;
std::string fmt(double v, int precision = 10) { return formatNumber(v, precision); }

// postProcessing/dem (returned) and VTK/particles, made on rank 0.
std::string createOutputDirs(const Scene& scene, MPI_Comm comm) {
  const fs::path out = fs::path(scene.caseDir) / "postProcessing" / "dem";
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    fs::create_directories(out);
    fs::create_directories(fs::path(scene.caseDir) / "VTK" / "particles");
  }
  return out.string();
}
}  // namespace

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

CollapseRecorder::CollapseRecorder(const Scene& scene, LiggghtsSession& lig, MPI_Comm comm,
                                   long step0, bool append)
    : scene_(scene),
      lig_(lig),
      comm_(comm),
      step0_(step0),
      outDir_(createOutputDirs(scene, comm)),
      load_(outDir_, comm, append) {
  MPI_Comm_rank(comm, &rank_);
  dt_ = lig.timeStep();
  sampleEvery_ = std::max(1L, std::lround(scene.dem.sampleInterval / dt_));
  if (rank_ == 0) {
    series_.open(fs::path(outDir_) / "timeSeries.csv", append ? std::ios::app : std::ios::trunc);
    if (!series_) throw std::runtime_error("cannot write " + outDir_ + "/timeSeries.csv");
    if (!append)
      series_ << "time_s,particles,deleted_outlet,deleted_top,lost,front_x_m,runout_m,"
                 "front_thickness_x_m,ke_translational_J,ke_rotational_J,pe_J,"
                 "savage_section_x_m,savage_surface_y_m,shear_rate_top_1_s,savage_paper,"
                 "savage_iverson\n";
  }
  // Particles now; any later shortfall beyond the deletions left the box between passes (lost).
  expected_ = energies(lig_.particles(), kG, comm_).count;
}

double CollapseRecorder::time() const { return (lig_.step() - step0_) * dt_; }

void CollapseRecorder::deleteLeavers(CollapseReport& rep) {
  const ParticleView p = lig_.particles();
  long local[2] = {0, 0}, total[2];
  for (int i = 0; i < p.n; ++i) {
    if (p.x[i][0] > scene_.channel.length)
      ++local[0];
    else if (p.x[i][1] > scene_.channel.height)
      ++local[1];
  }
  MPI_Allreduce(local, total, 2, MPI_LONG, MPI_SUM, comm_);
  if (total[0] > 0) lig_.command("delete_atoms region outletRegion compress no");
  if (total[1] > 0) lig_.command("delete_atoms region topRegion compress no");
  if (total[0] + total[1] > 0) lig_.invalidateSetup();
  rep.deletedOutlet += total[0];
  rep.deletedTop += total[1];
  expected_ -= total[0] + total[1];
}

Energies CollapseRecorder::sample(CollapseReport& rep) {
  const Scene& s = scene_;
  const double t = time();
  const double d = s.particles.diameter, rad = 0.5 * d;
  const double periodicWidth = s.channel.sideWalls == "periodic" ? s.sample.width : 0.0;
  const ParticleView p = lig_.particles();
  const Energies e = energies(p, kG, comm_);
  if (!std::isfinite(e.kinetic()) || !std::isfinite(e.potential))
    throw std::runtime_error("NaN in particle energies at t = " + fmt(t) +
                             " s (outputs up to the previous sample are in " + outDir_ + ")");
  rep.lost += expected_ - e.count;
  expected_ = e.count;
  rep.remaining = e.count;
  load_.sample(t, lig_);
  // Savage number at the section: u(y) on bins of d in the slab |x - x_s| <= d.
  const VelocityProfile vp = velocityProfile(p, s.dem.savageX, d, d, s.channel.height, comm_);
  const TopShear top = topLayerShear(vp, d, s.dem.savageLayers, 2);
  const auto centres = gatherCentres(p, comm_);
  if (rank_ == 0) {
    rep.front = granularFront(centres, rad, s.dem.frontGapDiameters * d, periodicWidth);
    rep.runout = rep.front - s.sample.length;
    // Second rule: where the width-averaged deposit thins below one grain (robust to a sparse
    // tail).
    const Profile prof = depositProfile(centres, rad, s.sample.width, d, 2 * d, s.channel.length,
                                        s.sample.solidFraction);
    rep.frontThickness = thicknessFront(prof, d, s.sample.length, d);
    series_ << fmt(t) << ',' << e.count << ',' << rep.deletedOutlet << ',' << rep.deletedTop << ','
            << rep.lost << ',' << fmt(rep.front) << ',' << fmt(rep.runout) << ','
            << fmt(rep.frontThickness) << ',' << fmt(e.kineticTranslational) << ','
            << fmt(e.kineticRotational) << ',' << fmt(e.potential) << ',' << fmt(s.dem.savageX)
            << ',';
    if (top.valid) {
      const double rs = s.particles.density, rf = s.fluidDensity, tp = s.dem.savageTanPhi;
      series_ << fmt(top.surface) << ',' << fmt(top.rate) << ','
              << fmt(savagePaper(d, rs, rf, top.rate, kG, tp)) << ','
              << fmt(savageIverson(d, top.surface, rs, rf, top.rate, kG, tp));
    } else {
      series_ << ",,,";  // no flow at the section: blank cells, never a made-up number
    }
    series_ << '\n' << std::flush;
  }
  return e;
}

void CollapseRecorder::profileIfDue(bool& profileDone) {
  const Scene& s = scene_;
  const double t = time(), d = s.particles.diameter;
  if (profileDone || t < s.dem.profileTime - 0.5 * dt_) return;
  profileDone = true;
  const VelocityProfile vp = velocityProfile(
      lig_.particles(), s.dem.profileX, d, s.dem.profileBinDiameters * d, s.channel.height, comm_);
  if (rank_ != 0) return;
  std::ofstream f(fs::path(outDir_) / "velocityProfile.csv");
  f << "y_m,u_x_m_s,particles,x_section_m,time_s\n";
  for (size_t j = 0; j < vp.y.size(); ++j)
    f << fmt(vp.y[j]) << ',' << fmt(vp.u[j]) << ',' << vp.count[j] << ',' << s.dem.profileX << ','
      << fmt(t) << '\n';
}

void CollapseRecorder::startSnapshots() {
  // A periodic dump (not write_dump): LIGGGHTS tallies the per-atom contact virial only on steps a
  // dump has announced. Files are particles_<step>.vtk with the step counted from the gate
  // opening, which must be LIGGGHTS step 0 (reset_timestep 0) so dumps fall on writeInterval.
  snapshotEvery_ =
      sampleEvery_ * std::max(1L, std::lround(scene_.writeInterval / (sampleEvery_ * dt_)));
  const std::string every = std::to_string(snapshotEvery_) + " ";
  lig_.command("dump snap all custom/vtk " + every + snapshotPattern(scene_.caseDir, "vtk") + " " +
               snapshotColumns());
  // The same columns in LAMMPS' binary dump (a .bin name selects it): what mixflowExtract reads.
  if (scene_.dem.binarySnapshots)
    lig_.command("dump snapbin all custom " + every + snapshotPattern(scene_.caseDir, "bin") + " " +
                 snapshotColumns());
  else if (rank_ == 0)
    removeBinarySnapshots(scene_.caseDir);  // an earlier run's: the extractor would prefer them
  // Contact forces at the same steps: the extractor's coarse-grained stress (ContactDumps.h).
  if (!scene_.dem.contactSnapshots && rank_ == 0) removeContactDumps(scene_.caseDir);
  lig_.commands(contactDumpCommands(scene_, snapshotEvery_));
}

bool CollapseRecorder::atSnapshot() const { return (lig_.step() - step0_) % snapshotEvery_ == 0; }

void CollapseRecorder::indexSnapshots() const {
  if (rank_ != 0) return;
  // ParaView's file-series index of the snapshots written so far, with their simulated times.
  const long lastStep = lig_.step() - step0_;
  std::ofstream f(fs::path(scene_.caseDir) / "VTK" / "particles.vtk.series");
  f << "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
  for (long step = 0; step <= lastStep; step += snapshotEvery_)
    f << "    { \"name\" : \"particles/particles_" << step
      << ".vtk\", \"time\" : " << fmt(step * dt_) << " }"
      << (step + snapshotEvery_ <= lastStep ? "," : "") << "\n";
  f << "  ]\n}\n";
}

void CollapseRecorder::finish(CollapseReport& rep) {
  const Scene& s = scene_;
  const double d = s.particles.diameter;
  rep.endTime = time();
  const auto centres = gatherCentres(lig_.particles(), comm_);
  if (rank_ == 0) {
    const Profile prof = depositProfile(centres, 0.5 * d, s.sample.width, d, 2 * d,
                                        s.channel.length, s.sample.solidFraction);
    std::ofstream f(fs::path(outDir_) / "depositProfile.csv");
    f << "x_m,h_top_m,h_volume_m,time_s\n";
    for (size_t i = 0; i < prof.x.size(); ++i)
      f << fmt(prof.x[i]) << ',' << fmt(prof.hTop[i]) << ',' << fmt(prof.hVolume[i]) << ','
        << fmt(rep.endTime) << '\n';
  }
  MPI_Bcast(&rep.front, 1, MPI_DOUBLE, 0, comm_);
  MPI_Bcast(&rep.frontThickness, 1, MPI_DOUBLE, 0, comm_);
  rep.runout = rep.front - s.sample.length;
}

double CollapseRecorder::finalFrontMax(double endTime, double fallback) const {
  // From the time series on disk (complete across resumes): the largest granular front over the
  // last arrestWindow s. A creeping deposit's cluster front can drop by a few d within one sample
  // when its tip detaches; the deposit reached the largest value. (No NaN is compared: OpenFOAM's
  // solvers trap floating-point exceptions, and an ordered comparison with NaN raises one.)
  std::ifstream in(fs::path(outDir_) / "timeSeries.csv");
  std::string line;
  if (!std::getline(in, line)) return fallback;
  std::vector<std::string> head;
  for (std::stringstream h(line); std::getline(h, line, ',');) head.push_back(line);
  const auto col = [&](const std::string& name) {
    return static_cast<long>(std::find(head.begin(), head.end(), name) - head.begin());
  };
  const long it = col("time_s"), iff = col("front_x_m");
  bool found = false;
  double best = fallback;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    for (std::stringstream r(line); std::getline(r, line, ',');) cells.push_back(line);
    if (static_cast<long>(cells.size()) <= std::max(it, iff) || cells[it].empty() ||
        cells[iff].empty())
      continue;
    const double t = std::stod(cells[it]), x = std::stod(cells[iff]);
    if (!std::isfinite(t) || !std::isfinite(x)) continue;
    if (t >= endTime - scene_.dem.arrestWindow - 1e-9 && (!found || x > best)) {
      best = x;
      found = true;
    }
  }
  return best;
}

void CollapseRecorder::writeSummary(const SettleReport& st, const CollapseReport& c,
                                    const std::string& extraJson) const {
  if (rank_ != 0) return;
  const Scene& s = scene_;
  const double frontFinal = finalFrontMax(c.endTime, c.front);
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  std::ofstream f(fs::path(outDir_) / "summary.json");
  f << "{\n"
    << "  \"case\": \"" << s.name << "\",\n"
    << "  \"content\": \"" << s.content << "\",\n"
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
    << ", \"converged\": " << (st.converged ? "true" : "false") << ", \"packing_control\": \""
    << st.packingControl << "\""
    << ", \"packing_tolerance\": " << fmt(st.packingTolerance)
    << ", \"settle_friction\": " << fmt(st.settleFriction) << ", \"settles\": " << st.settles
    << "},\n"
    << "  \"young_modulus_pa\": " << fmt(s.youngModulusUsed()) << ",\n"
    << "  \"wall_young_modulus_pa\": " << fmt(s.wallYoungModulusUsed()) << ",\n"
    << "  \"young_modulus_factor\": " << fmt(s.dem.youngModulusFactor) << ",\n"
    << "  \"time_step_s\": " << fmt(dt_) << ",\n"
    << "  \"rayleigh_time_s\": " << fmt(s.rayleighTime()) << ",\n"
    << "  \"rolling_model\": \"" << s.particles.rollingModel << "\",\n"
    << "  \"side_walls\": \"" << s.channel.sideWalls << "\",\n"
    << "  \"channel_length_m\": " << fmt(s.channel.length) << ",\n"
    << "  \"end_time_s\": " << fmt(c.endTime) << ",\n"
    << "  \"stop_reason\": \"" << c.stopReason << "\",\n"
    << "  \"front_x_m\": " << fmt(c.front) << ",\n"
    << "  \"runout_m\": " << fmt(c.runout) << ",\n"
    << "  \"normalised_runout\": " << fmt(c.runout / s.sample.length) << ",\n"
    << "  \"runout_final_m\": " << fmt(frontFinal - s.sample.length) << ",\n"
    << "  \"runout_final_rule\": \"the largest granular front over the last arrestWindow ("
    << fmt(s.dem.arrestWindow) << " s) minus L\",\n"
    << "  \"front_thickness_x_m\": " << fmt(c.frontThickness) << ",\n"
    << "  \"runout_thickness_m\": " << fmt(c.frontThickness - s.sample.length) << ",\n"
    << "  \"particles_remaining\": " << c.remaining << ",\n"
    << "  \"deleted_outlet\": " << c.deletedOutlet << ",\n"
    << "  \"deleted_top\": " << c.deletedTop << ",\n"
    << extraJson << "  \"lost\": " << c.lost << "\n"
    << "}\n";
}

}  // namespace mixflow::dem
