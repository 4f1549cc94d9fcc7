// mixflowDem: dry granular dam break on LIGGGHTS (no fluid mesh, no fluid equations).
//   mixflowDem [-case DIR] [-check]            serial
//   mpirun -np N mixflowDem -case DIR -parallel
// -check validates the case and prints the derived time step, then stops.
// -settleOnly settles the sample and saves it (dem/settled.restart, dem/settled.state): the first
// step of a mixture scene, whose collapse runs in mixflowCoupled (a mixture case's Allrun).
// -settleOnly -reuse DIR takes the sample settled in DIR (another run's dem/) instead, when it was
// made from this case's settling inputs (dem/SettledSample.h); otherwise it stops and says why.
// -check -settleOnly -reuse DIR checks that sample (restart file, settling inputs) without
// copying it: the Allrun of a mixture case does so before it moves anything.
#include <mpi.h>

#include <cstring>
#include <ctime>
#include <iostream>
#include <string>

#include "DemDriver.h"
#include "Dictionary.h"
#include "Progress.h"
#include "Scene.h"
#include "SettledSample.h"

namespace {
void usage() {
  std::cout << "Usage: mixflowDem [-case DIR] [-check] [-resume] [-settleOnly [-reuse DIR2]] "
               "[-parallel]\n"
               "  Runs the dry granular dam break described by DIR/constant/sceneProperties,\n"
               "  DIR/system/demDict and DIR/system/controlDict. Outputs: DIR/postProcessing/dem,\n"
               "  DIR/VTK (ParaView), DIR/dem (LIGGGHTS logs and replay script).\n"
               "  -resume continues from the last snapshot's restart state (after a crash, or\n"
               "  with a later endTime in system/controlDict).\n"
               "  -settleOnly settles the sample and saves it to DIR/dem/settled.{restart,state}\n"
               "  (content particles or mixture; a mixture then runs in mixflowCoupled).\n"
               "  -reuse DIR2 (with -settleOnly) takes the sample settled in DIR2 (e.g. another\n"
               "  run's dem/) when its fingerprint shows the same settling inputs (fill,\n"
               "  contacts, walls, DEM step, settling settings), else stops naming the first\n"
               "  difference; with -check it checks that sample, copying nothing.\n";
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string caseDir = ".", reuseDir;
  bool checkOnly = false, resume = false, settleOnly = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-case" && i + 1 < argc) {
      caseDir = argv[++i];
    } else if (a == "-check") {
      checkOnly = true;
    } else if (a == "-resume") {
      resume = true;
    } else if (a == "-settleOnly") {
      settleOnly = true;
    } else if (a == "-reuse" && i + 1 < argc) {
      reuseDir = argv[++i];
    } else if (a == "-parallel") {
      // Ranks come from mpirun; accepted for the OpenFOAM convention.
    } else if (a == "-help" || a == "--help") {
      if (rank == 0) usage();
      MPI_Finalize();
      return 0;
    } else {
      if (rank == 0) std::cerr << "mixflowDem: unknown option '" << a << "'\n", usage();
      MPI_Finalize();
      return 2;
    }
  }

  using namespace mixflow;
  int status = 0;
  try {
    const dem::Scene scene = dem::Scene::read(caseDir);
    if (scene.content == "liquid" || (scene.content == "mixture" && !settleOnly))
      throw InputError(caseDir + "/constant/sceneProperties: entry 'content': '" + scene.content +
                       "' needs the fluid solver; mixflowDem runs content 'particles' (and "
                       "settles a 'mixture' sample with -settleOnly)");
    if (rank == 0)
      std::cout << "[mixflowDem] case " << scene.name << ": " << scene.particleCount()
                << " particles, time step " << scene.timeStepUsed() << " s (stability limit "
                << scene.stableTimeStepLimit() << " s, Rayleigh time " << scene.rayleighTime()
                << " s)" << std::endl;
    if (rank == 0 && !scene.autoStepWarning().empty())
      std::cout << "[mixflowDem] warning: " << scene.autoStepWarning() << std::endl;
    if (!reuseDir.empty() && !settleOnly)
      throw InputError("mixflowDem: option -reuse " + reuseDir + " needs -settleOnly");
    if (checkOnly && !reuseDir.empty()) {
      // The sample to reuse is checked before anything is moved or run (Allrun SETTLED_DIR).
      const dem::SettleReport r = dem::checkSettledSample(scene, reuseDir);
      if (rank == 0)
        std::cout << "[mixflowDem] the settled sample of " << reuseDir << " (fingerprint "
                  << r.fingerprint << ", " << r.particles
                  << " particles) was settled from this case's settling inputs" << std::endl;
    } else if (!checkOnly && settleOnly && !reuseDir.empty()) {
      const dem::SettleReport r = dem::reuseSettledSample(scene, reuseDir, rank);
      MPI_Barrier(MPI_COMM_WORLD);  // rank 0's copy is complete before anyone goes on
      if (rank == 0)
        std::cout << "[dem] settled sample reused from " << reuseDir << " (fingerprint "
                  << r.fingerprint << ", the same settling inputs): " << r.particles
                  << " particles, height " << r.settledHeight << " m, sample solid fraction "
                  << r.sampleFraction << "; settled in " << r.settleTime << " s there\n"
                  << "[mixflowDem] settled sample saved: " << caseDir
                  << "/dem/settled.{restart,state}" << std::endl;
    } else if (!checkOnly && settleOnly) {
      dem::DemDriver driver(scene, MPI_COMM_WORLD, std::cout);
      driver.writeSettledState(driver.settle());
      if (rank == 0)
        std::cout << "[mixflowDem] settled sample saved: " << caseDir
                  << "/dem/settled.{restart,state}" << std::endl;
    } else if (!checkOnly) {
      const double wall0 = MPI_Wtime();
      dem::DemDriver driver(scene, MPI_COMM_WORLD, std::cout);
      dem::SettleReport settled;
      if (!resume) settled = driver.settle();
      // The collapse phase alone, for benchmarks against coupled runs that start settled.
      const double collapseWall0 = MPI_Wtime();
      const std::clock_t collapseCpu0 = std::clock();
      const auto collapse = resume ? driver.resume(settled) : driver.collapse(settled);
      const double collapseCpu = double(std::clock() - collapseCpu0) / CLOCKS_PER_SEC;
      const double collapseWall = MPI_Wtime() - collapseWall0;
      driver.writeSummary(settled, collapse);
      if (rank == 0)
        std::cout << "[mixflowDem] " << collapse.stopReason << " at t = " << collapse.endTime
                  << " s: front " << collapse.front << " m, runout " << collapse.runout
                  << " m; deleted " << collapse.deletedOutlet << " at outlet, "
                  << collapse.deletedTop << " at top, lost " << collapse.lost << "; outputs in "
                  << driver.outputDir() << "\n[mixflowDem] wall time " << MPI_Wtime() - wall0
                  << " s, of which inside LIGGGHTS runs " << driver.session().runSeconds() << " s"
                  << "\n[mixflowDem] collapse phase: wall " << collapseWall << " s, CPU "
                  << collapseCpu << " s (rank 0)" << std::endl;
    }
  } catch (const InputError& e) {
    if (rank == 0) std::cerr << "mixflowDem: input error: " << e.what() << std::endl;
    status = 2;
  } catch (const dem::PackingMiss& e) {
    if (rank == 0) std::cerr << "mixflowDem: sample preparation stopped: " << e.what() << std::endl;
    status = 1;
  } catch (const std::exception& e) {
    if (rank == 0)
      std::cerr << "mixflowDem: run stopped: " << e.what()
                << "\n  Outputs written so far are kept. To continue from the last particle "
                   "snapshot: mixflowDem -case "
                << caseDir << " -resume" << std::endl;
    status = 1;
  }
  MPI_Finalize();
  return status;
}
