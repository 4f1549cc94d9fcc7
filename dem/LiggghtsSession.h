// One LIGGGHTS instance driven as a library: commands go through input->one() and are echoed into a
// script file so that any run can be replayed with the plain `liggghts -in` binary.
#pragma once

#include <mpi.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "Observables.h"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace mixflow::dem {

class LiggghtsSession {
 public:
  // logDir receives log.liggghts, screen.liggghts and the replay script in.liggghts.
  LiggghtsSession(MPI_Comm comm, const std::string& logDir);
  ~LiggghtsSession();
  LiggghtsSession(const LiggghtsSession&) = delete;
  LiggghtsSession& operator=(const LiggghtsSession&) = delete;

  void command(const std::string& line);
  void commands(const std::vector<std::string>& lines);
  // Advance nSteps; setup is skipped when nothing changed since the last run (faster chunks).
  void run(long nSteps);
  void invalidateSetup() { needSetup_ = true; }
  // write_restart, and a full setup before the next run: the command re-inits LIGGGHTS and moves
  // atoms and ghosts (comm exchange and borders) without rebuilding the neighbour lists, so a
  // `run pre no` after it computes contacts on stale lists (measured on a collapsing sample:
  // 11 % more kinetic energy 1000 steps later; with the setup, equal to round-off).
  // The atoms are then put in tag order (orderByTag), as a run reading the restart puts its own,
  // so that it continues with the writer's arrays whatever rank each atom was read on.
  void writeRestart(const std::string& file);
  // Puts this rank's atoms (with every per-atom array of the atom style and fixes) in increasing
  // tag order, and forces a setup before the next run. Force sums run over the atoms in array
  // order, so two runs with the same atoms in another order part at round-off and then, grains
  // being chaotic, visibly (1 mm on the front in 0.1 s of a collapse).
  void orderByTag();
  // Between runs the pair's contact history lives in the neighbour lists, indexed by the atoms'
  // places when they were built; the next setup copies it back to the atoms by those places.
  // Anything that moves atoms between runs (migration, reordering) calls this first: it stores
  // the history with the atoms now, as write_restart does, so it moves with them.
  void storeContactHistory();
  // Wall seconds spent inside LIGGGHTS `run` commands (the rest is the driver's own work).
  double runSeconds() const { return runSeconds_; }
  // This rank's share of those runs as LIGGGHTS' timers split it: compute (pair, neighbour lists,
  // fixes) and communication, which includes waiting for slower ranks (the imbalance's cost).
  double computeSeconds() const { return computeSeconds_; }
  double commSeconds() const { return commSeconds_; }

  ParticleView particles() const;
  long atomCount() const;
  long step() const;
  double timeStep() const;
  LAMMPS_NS::LAMMPS* lammps() { return lmp_; }
  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  LAMMPS_NS::LAMMPS* lmp_ = nullptr;
  std::ofstream script_;
  bool needSetup_ = true;
  double runSeconds_ = 0;
  double computeSeconds_ = 0;
  double commSeconds_ = 0;
};

}  // namespace mixflow::dem
