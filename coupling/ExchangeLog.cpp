#include "ExchangeLog.H"

#include <mpi.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>

namespace mixflow::coupling {

namespace {

// Totals vector layout (summed over ranks, except the last entries: min, max).
enum Total {
  kParticles,
  kParticlesOutside,
  kParticleVolume,
  kOutsideVolume,
  kClippedVolume,
  kFluidSeenVolume,
  kFpX,
  kFpY,
  kFpZ,
  kFfX,
  kFfY,
  kFfZ,
  kForceScale,
  kDragX,
  kDragY,
  kDragZ,
  kVx,
  kVy,
  kVz,  // sum of particle velocities
  kX,
  kY,
  kZ,                    // sum of particle positions
  kRemote,               // particles whose fluid cell is on another rank than their DEM owner
  kDragLimited,          // particles whose drag coefficient was limited (dragRelaxationLimit)
  kCounterflowUnstable,  // implicit drag: particles beyond the packed-bed stability bound
  kNumSums,
  kMinVoidfraction = kNumSums,
  kCounterflowMax,  // implicit drag: max over particles of s (c - 1) / 2 (stable below 1)
  kNumTotals
};

}  // namespace

ExchangeLog::ExchangeLog(const Foam::Time& runTime, long exchangeEvery, long logEvery,
                         const std::vector<std::string>& modelNames, bool resume)
    : runTime_(runTime), exchangeEvery_(exchangeEvery), logEvery_(logEvery) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) return;
  const std::string dir = std::string(runTime.globalPath()) + "/postProcessing/coupling";
  std::filesystem::create_directories(dir);
  if (resume) {  // resumeMixtureCase cut the rows from the resumed time on: append
    csv_.open(dir + "/exchange.csv", std::ios::app);
    stages_.open(dir + "/stageTimes.csv", std::ios::app);
    return;
  }
  csv_.open(dir + "/exchange.csv");
  csv_ << "# mixflowCoupled exchange log: one line per exchange (every logEvery). Volumes in m3,"
          " forces in N.\n"
          "# volumeError = (fluidSeenVolume - (particleVolume - outsideVolume - clippedVolume))"
          " / particleVolume; actionReaction = |Fp + Ff| / forceScale, Fp = sum of fluid forces"
          " on particles, Ff = sum_c V_c [Ksl (Us - U) + fSource] at the exchange,"
          " forceScale = sum |F_i|.\n";
  csv_ << "time,demStep,particles,particlesOutside,particleVolume,outsideVolume,clippedVolume,"
          "fluidSeenVolume,volumeError,Fp_x,Fp_y,Fp_z,Ff_x,Ff_y,Ff_z,forceScale,actionReaction,"
          "minVoidfraction,meanVx,meanVy,meanVz,meanX,meanY,meanZ,remote,dragLimited,"
          "counterflowUnstable,counterflowMax";
  for (const auto& m : modelNames) csv_ << "," << m << "_x," << m << "_y," << m << "_z";
  csv_ << ",seconds\n";
  stages_.open(dir + "/stageTimes.csv");
  stages_ << "# mixflowCoupled stage wall times (rank 0) in s, rows as exchange.csv: the DEM "
             "interval and the fluid resampling before the exchange, then the exchange's stages.\n"
             "time,demStep";
  for (const char* s : StageClock::kNames) stages_ << "," << s;
  stages_ << "\n";
}

void ExchangeLog::reduce(const ExchangeTotals& t, double remote, const DragScheme::Counts& counts,
                         const std::vector<ParticleState>& own,
                         const std::vector<double>& modelTotals) {
  totals_.assign(kNumTotals, 0.0);
  totals_[kParticles] = t.particles;
  totals_[kParticlesOutside] = t.particlesOutside;
  totals_[kParticleVolume] = t.particleVolume;
  totals_[kOutsideVolume] = t.outsideVolume;
  totals_[kClippedVolume] = t.clippedVolume;
  totals_[kFluidSeenVolume] = t.fluidSeenVolume;
  for (int k = 0; k < 3; ++k) {
    totals_[kFpX + k] = t.forceOnParticles[k];
    totals_[kFfX + k] = t.forceOnFluid[k];
    totals_[kDragX + k] = t.dragOnParticles[k];
  }
  totals_[kForceScale] = t.forceScale;
  totals_[kRemote] = remote;
  totals_[kDragLimited] = counts.limited;
  totals_[kCounterflowUnstable] = counts.counterflowUnstable;
  for (const auto& p : own)
    for (int k = 0; k < 3; ++k) {
      totals_[kVx + k] += p.v[k];
      totals_[kX + k] += p.x[k];
    }
  MPI_Allreduce(MPI_IN_PLACE, totals_.data(), kNumSums, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double minVf = t.minVoidfraction;
  MPI_Allreduce(MPI_IN_PLACE, &minVf, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  totals_[kMinVoidfraction] = minVf;
  MPI_Allreduce(&counts.counterflowMax, &totals_[kCounterflowMax], 1, MPI_DOUBLE, MPI_MAX,
                MPI_COMM_WORLD);
  modelTotals_ = modelTotals;
  if (!modelTotals_.empty())
    MPI_Allreduce(MPI_IN_PLACE, modelTotals_.data(), static_cast<int>(modelTotals_.size()),
                  MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

void ExchangeLog::write(long exchange, long demStep, double seconds, const StageClock& clock,
                        bool row) {
  const std::vector<double>& T = totals_;
  const double vp = T[kParticleVolume];
  const double volumeError =
      vp > 0 ? (T[kFluidSeenVolume] - (vp - T[kOutsideVolume] - T[kClippedVolume])) / vp : 0.0;
  const Vec3 Fp(T[kFpX], T[kFpY], T[kFpZ]), Ff(T[kFfX], T[kFfY], T[kFfZ]);
  const double actionReaction = T[kForceScale] > 0 ? mag(Fp + Ff) / T[kForceScale] : 0.0;
  const double np = std::max(T[kParticles], 1.0);

  Foam::Info << "Coupling: " << static_cast<long>(T[kParticles]) << " particles ("
             << static_cast<long>(T[kParticlesOutside]) << " outside), volume error " << volumeError
             << ", outside " << T[kOutsideVolume] << " m3, clipped " << T[kClippedVolume]
             << " m3, action-reaction " << actionReaction << ", min voidfraction "
             << T[kMinVoidfraction] << ", fluid cell on another rank "
             << static_cast<long>(T[kRemote]) << ", drag limited "
             << static_cast<long>(T[kDragLimited]) << ", counterflow unstable "
             << static_cast<long>(T[kCounterflowUnstable]) << ", " << seconds << " s" << Foam::endl;
  if (T[kCounterflowUnstable] > 0 && !warnedCounterflow_) {
    warnedCounterflow_ = true;
    const long n = exchangeEvery_;
    const long stable = static_cast<long>(n / T[kCounterflowMax]);
    // std::string goes out quoted on a Foam stream: the advice is handed over as const char*.
    const std::string advice =
        stable >= 1
            ? " -> at most " + std::to_string(stable) + " brings them within the bound"
            : ": even exchangeEvery 1 exceeds the bound; dragIntegration held, or a smaller "
              "DEM step";
    Foam::Warning << "mixflowCoupled: at t = " << runTime_.value() << " s, "
                  << static_cast<long>(T[kCounterflowUnstable])
                  << " particles exceed the packed-bed stability bound of the implicit drag "
                     "(beta T / m ((1 - eps) / eps - 1) / 2 up to "
                  << T[kCounterflowMax] << " > 1): the exchange can oscillate and grow. "
                  << "constant/couplingProperties exchangeEvery " << n << advice.c_str()
                  << " (the bound is necessary, not sufficient, in a deep bed; coupling/README.md, "
                     "\"Exchange interval\")"
                  << Foam::endl;
  }

  if (!row || !csv_.is_open() || exchange % logEvery_ != 0) return;
  csv_ << std::setprecision(17) << runTime_.value() << "," << demStep << ","
       << static_cast<long>(T[kParticles]) << "," << static_cast<long>(T[kParticlesOutside]);
  for (Total k : {kParticleVolume, kOutsideVolume, kClippedVolume, kFluidSeenVolume})
    csv_ << "," << T[k];
  csv_ << "," << volumeError;
  for (Total k : {kFpX, kFpY, kFpZ, kFfX, kFfY, kFfZ, kForceScale}) csv_ << "," << T[k];
  csv_ << "," << actionReaction << "," << T[kMinVoidfraction];
  for (Total k : {kVx, kVy, kVz, kX, kY, kZ}) csv_ << "," << T[k] / np;
  csv_ << "," << static_cast<long>(T[kRemote]) << "," << static_cast<long>(T[kDragLimited]) << ","
       << static_cast<long>(T[kCounterflowUnstable]) << "," << T[kCounterflowMax];
  for (double v : modelTotals_) csv_ << "," << v;
  csv_ << "," << seconds << "\n" << std::flush;

  stages_ << std::setprecision(17) << runTime_.value() << "," << demStep << std::setprecision(6);
  for (double s : clock.seconds()) stages_ << "," << s;
  stages_ << "\n" << std::flush;
}

}  // namespace mixflow::coupling
