#include "LiggghtsSession.h"

// LIGGGHTS headers
#include <atom.h>
#include <input.h>
#include <lammps.h>
#include <timer.h>
#include <update.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace mixflow::dem {

namespace {
// LIGGGHTS ends the process itself on an input or run-time error (error->all calls exit), with the
// message only in its screen file. This exit hook repeats that message where the user looks.
std::string gScreenFile;

void reportLiggghtsError() {
  std::ifstream in(gScreenFile);
  std::string line, error;
  while (std::getline(in, line))
    if (line.rfind("ERROR", 0) == 0) error = line;
  if (!error.empty())
    std::cerr << "mixflow: LIGGGHTS stopped the run: " << error
              << "\n  (full LIGGGHTS output: " << gScreenFile
              << "; outputs written so far are kept)" << std::endl;
}
}  // namespace

LiggghtsSession::LiggghtsSession(MPI_Comm comm, const std::string& logDir) : comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  const std::string log = logDir + "/log.liggghts", screen = logDir + "/screen.liggghts";
  // "-screen none" crashes LIGGGHTS 3.8 in fix insert/pack; a file is safe.
  std::vector<std::string> args = {"liggghts", "-log", log, "-screen", screen, "-echo", "none"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm);
  if (rank_ == 0) {
    script_.open(logDir + "/in.liggghts");
    if (gScreenFile.empty()) std::atexit(reportLiggghtsError);
    gScreenFile = screen;
  }
}

LiggghtsSession::~LiggghtsSession() { delete lmp_; }

void LiggghtsSession::command(const std::string& line) {
  if (rank_ == 0) script_ << line << '\n' << std::flush;
  lmp_->input->one(line.c_str());
}

void LiggghtsSession::commands(const std::vector<std::string>& lines) {
  for (const auto& l : lines) command(l);
}

void LiggghtsSession::writeRestart(const std::string& file) {
  command("write_restart " + file);
  needSetup_ = true;
}

void LiggghtsSession::run(long nSteps) {
  if (nSteps <= 0) return;
  const double t0 = MPI_Wtime();
  command("run " + std::to_string(nSteps) + (needSetup_ ? " post no" : " pre no post no"));
  runSeconds_ += MPI_Wtime() - t0;
  // `run` zeroes the timers at its start, so they hold this run's split.
  const double* timer = lmp_->timer->array;
  computeSeconds_ += timer[TIME_PAIR] + timer[TIME_NEIGHBOR] + timer[TIME_MODIFY];
  commSeconds_ += timer[TIME_COMM];
  needSetup_ = false;
}

ParticleView LiggghtsSession::particles() const {
  LAMMPS_NS::Atom* a = lmp_->atom;
  ParticleView p;
  p.n = a->nlocal;
  p.x = a->x;
  p.v = a->v;
  p.omega = a->omega;
  p.radius = a->radius;
  p.mass = a->rmass;
  return p;
}

long LiggghtsSession::atomCount() const { return static_cast<long>(lmp_->atom->natoms); }
long LiggghtsSession::step() const { return static_cast<long>(lmp_->update->ntimestep); }
double LiggghtsSession::timeStep() const { return lmp_->update->dt; }

}  // namespace mixflow::dem
