#include "LiggghtsSession.h"

// LIGGGHTS headers
#include <atom.h>
#include <atom_vec.h>
#include <fix.h>
#include <input.h>
#include <lammps.h>
#include <modify.h>
#include <timer.h>
#include <update.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <vector>

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
  orderByTag();
}

void LiggghtsSession::storeContactHistory() {
  // The pair's history fix copies only when the pair computed since its last copy (its own
  // guard), so a second call, or the next setup's, leaves the stored history alone.
  LAMMPS_NS::Modify* modify = lmp_->modify;
  for (int i = 0; i < modify->nfix; ++i)
    if (std::string(modify->fix[i]->style) == "contacthistory")
      modify->fix[i]->setup_pre_exchange();
}

void LiggghtsSession::orderByTag() {
  storeContactHistory();
  LAMMPS_NS::Atom* atom = lmp_->atom;
  const int n = atom->nlocal;
  // permute[i]: the atom that goes to slot i; the cycles are followed through a spare slot n,
  // as LAMMPS' own spatial sort does.
  std::vector<int> permute(n);
  std::iota(permute.begin(), permute.end(), 0);
  std::sort(permute.begin(), permute.end(),
            [&](int a, int b) { return atom->tag[a] < atom->tag[b]; });
  if (atom->nmax <= n) atom->avec->grow(0);
  std::vector<int> current(permute.size());
  std::iota(current.begin(), current.end(), 0);
  for (int i = 0; i < n; ++i) {
    if (current[i] == permute[i]) continue;
    atom->avec->copy(i, n, 0);
    int empty = i;
    while (permute[empty] != i) {
      atom->avec->copy(permute[empty], empty, 0);
      current[empty] = permute[empty];
      empty = permute[empty];
    }
    atom->avec->copy(n, empty, 0);
    current[empty] = permute[empty];
  }
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
