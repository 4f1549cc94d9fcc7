#include "DemStartup.H"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "CoupledResume.h"
#include "CouplingProperties.h"
#include "LiggghtsSession.h"
#include "SlabBalance.h"
#include "Time.H"

namespace mixflow::coupling {

namespace {

Vec3 toVec(const Foam::vector& v) { return Vec3(v.x(), v.y(), v.z()); }

[[noreturn]] void fatal(const std::string& msg) {
  FatalErrorInFunction << msg.c_str() << Foam::exit(Foam::FatalError);
  throw std::runtime_error(msg);  // not reached
}

// Parallel runs: LIGGGHTS' processor grid is made to match OpenFOAM's `simple` decomposition
// (n = (nx ny nz), processor index x-fastest, which is LIGGGHTS' `map xyz`), so that with the
// DEM box = the mesh's bounding box a particle's DEM owner usually also holds its fluid cells and
// R1-R3 of an exchange stay on the rank. Skipped if the DEM script sets `processors` itself or
// the decomposition is not `simple` (the exchange is then still correct, with more traffic; the
// log's "fluid cell on another rank" count shows how much).
void demProcessorGrid(const Foam::fvMesh& mesh, dem::LiggghtsSession& session,
                      const std::string& script) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size == 1) return;
  {
    std::ifstream in(script);
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string first;
      if (words >> first && first == "processors") {
        Foam::Info << "Coupling: the DEM script sets its own processor grid" << Foam::endl;
        return;
      }
    }
  }
  const std::string file = std::string(mesh.time().globalPath()) + "/system/decomposeParDict";
  try {
    const Dictionary d = Dictionary::readFile(file);
    const std::string method = d.text("method");
    if (method != "simple") {
      Foam::Info << "Coupling: decomposition method " << method.c_str()
                 << " has no matching LIGGGHTS grid; LIGGGHTS decomposes its box itself"
                 << Foam::endl;
      return;
    }
    const std::vector<double> n = d.subDict("simpleCoeffs").scalars("n", Range::positive());
    if (n.size() != 3 || n[0] * n[1] * n[2] != size)
      fatal(file + ": simpleCoeffs n must have 3 entries whose product is the rank count");
    std::ostringstream cmd;
    cmd << "processors " << n[0] << " " << n[1] << " " << n[2] << " map xyz";
    session.command(cmd.str());
    Foam::Info << "Coupling: LIGGGHTS grid " << cmd.str().c_str()
               << " (matches the simple decomposition)" << Foam::endl;
  } catch (const InputError& e) {
    fatal(e.what());
  }
}

// The stopped run's restart to resume from: its restart file and DEM slabs, after checking that
// the fluid starts at its time.
struct ResumePoint {
  std::string restart;         // LIGGGHTS restart file (path)
  std::vector<double> splits;  // the x slabs' splits (SlabBalance.h); empty: the script's grid
};

ResumePoint readResumePoint(const Foam::Time& runTime, const std::string& caseDir) {
  try {
    const CoupledResumeState st = CoupledResumeState::read(caseDir);
    st.verifyRestart(caseDir);
    const double t = runTime.value();
    // The time directory's name is rounded (OpenFOAM's timePrecision): within a thousandth of
    // a step is the same write.
    if (std::abs(t - st.time) > 1e-3 * std::max(runTime.deltaTValue(), 1e-300))
      fatal(CoupledResumeState::path(caseDir) + ": entry 'time': " + std::to_string(st.time) +
            " s, but the fluid starts at " + runTime.timeName() +
            " s: set startFrom latestTime and remove the time directories after " + st.timeName +
            " (scripts/ResumeFunctions, resumeMixtureCase, does both)");
    Foam::Info << "Coupling: resuming at t = " << st.timeName.c_str() << " s from "
               << st.restartFile.c_str() << Foam::endl;
    return {caseDir + "/" + st.restartFile, st.slabSplits};
  } catch (const InputError& e) {
    fatal(e.what());
  }
}

// The scene's LIGGGHTS commands, line by line ('&' continues a line, '#' starts a comment),
// through the session so that dem/in.liggghts replays the whole run. Resuming (restart not
// empty): the particles come from that restart instead of the script's read_restart (the settled
// sample); every other line (contacts, walls) is the script's.
void runScript(dem::LiggghtsSession& session, std::istream& in, const std::string& script,
               const std::string& restart) {
  const bool resume = !restart.empty();
  bool restartReplaced = false;
  std::string line, pending;
  while (std::getline(in, line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty() && line.back() == '&') {
      line.pop_back();
      pending += line + " ";
      continue;
    }
    line = pending + line;
    pending.clear();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (resume && line.compare(line.find_first_not_of(" \t"), 12, "read_restart") == 0) {
      line = "read_restart " + restart;
      restartReplaced = true;
    }
    session.command(line);
  }
  if (resume && !restartReplaced)
    fatal(script +
          ": -resume needs a DEM script that starts from read_restart (a mixture "
          "scene's system/in.liggghts)");
}

// The external force array is not initialised by LIGGGHTS: zero it before a setup run.
// Resuming: the restart's drag state (held forces, or the implicit drag's) is kept for the
// first interval.
void startDrag(DemLink& link, bool resume) {
  if (resume && link.adoptRestoredState()) return;
  std::vector<ParticleState> particles;
  std::vector<std::int64_t> tags;
  link.pull(particles, tags);
  if (link.mode() == DemLink::DragIntegration::held)
    link.push(std::vector<Vec3>(particles.size()));
  else
    link.pushImplicit(std::vector<AppliedDrag>(particles.size()));
}

// The stopped run's slabs (re-balanced, demDict balanceInterval) and its atom order
// (LiggghtsSession::writeRestart), so the resumed run goes on with the uninterrupted run's
// arrays. First a setup run: the pair style makes its contact-history fix there, reading the
// restart's per-atom data, which moving the atoms before would scramble.
void restoreStoppedRun(dem::LiggghtsSession& session, DemLink& link,
                       const std::vector<double>& splits) {
  session.command("run 0");
  if (!splits.empty() && !dem::setSlabSplits(session, splits) && Foam::Pstream::parRun())
    Foam::Info << "Coupling: the stopped run's DEM slabs (" << int(splits.size()) - 1
               << ") do not fit this run's processor grid; it starts from the script's"
               << Foam::endl;
  session.orderByTag();
  startDrag(link, true);
}

// Time steps: one CFD step is exchangeEvery DEM steps, fixed.
void checkTimeSteps(const Foam::Time& runTime, const CouplingProperties& props, double dtDem) {
  const double dtCfd = runTime.deltaTValue();
  const double expected = props.exchangeEvery * dtDem;
  if (std::abs(dtCfd - expected) > 1e-9 * expected)
    fatal("CFD deltaT " + std::to_string(dtCfd) + " s must equal exchangeEvery (" +
          std::to_string(props.exchangeEvery) + ") x DEM timestep (" + std::to_string(dtDem) +
          " s) = " + std::to_string(expected) + " s (system/controlDict deltaT)");
  if (runTime.controlDict().lookupOrDefault<bool>("adjustTimeStep", false))
    fatal("adjustTimeStep must be off in a coupled run (the CFD step is exchangeEvery DEM steps)");
}

// Gravity: the particles' weight (LIGGGHTS fix gravity) and the fluid's g must agree, or
// buoyancy and weight would not balance.
void checkGravity(const DemLink& link, const Foam::uniformDimensionedVectorField& g) {
  const Vec3 gDem = link.gravity();
  const Vec3 gCfd = toVec(g.value());
  if (mag(gDem - gCfd) > 1e-9 * std::max(mag(gCfd), 1e-300)) {
    std::ostringstream s;
    s << "gravity differs: LIGGGHTS fix gravity gives (" << gDem.x << " " << gDem.y << " " << gDem.z
      << "), constant/g (" << gCfd.x << " " << gCfd.y << " " << gCfd.z << ")";
    fatal(s.str());
  }
}

}  // namespace

DemStart startDem(const Foam::fvMesh& mesh, const CouplingProperties& props,
                  DemLink::DragIntegration mode, const Foam::uniformDimensionedVectorField& g,
                  bool resume) {
  DemStart d;
  const Foam::Time& runTime = mesh.time();
  const std::string caseDir = runTime.globalPath();
  const std::string demDir = caseDir + "/dem";
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::filesystem::create_directories(demDir);
  MPI_Barrier(MPI_COMM_WORLD);
  d.session = std::make_unique<dem::LiggghtsSession>(MPI_COMM_WORLD, demDir);

  const std::string script =
      props.demScript.front() == '/' ? props.demScript : caseDir + "/" + props.demScript;
  std::ifstream in(script);
  if (!in) fatal("cannot open the DEM script " + script + " (demScript in couplingProperties)");
  demProcessorGrid(mesh, *d.session, script);
  // ${mixflowCase} in the script is the case directory (scripts stay valid when a case moves).
  d.session->command("variable mixflowCase string " + caseDir);
  const ResumePoint from = resume ? readResumePoint(runTime, caseDir) : ResumePoint{};
  runScript(*d.session, in, script, from.restart);

  d.link = std::make_unique<DemLink>(*d.session, mode);
  startDrag(*d.link, resume);
  if (resume) restoreStoppedRun(*d.session, *d.link, from.splits);
  d.session->command("run 0");
  d.session->invalidateSetup();

  const double dtDem = d.link->timeStep();
  d.exchangeInterval = props.exchangeEvery * dtDem;
  checkTimeSteps(runTime, props, dtDem);
  checkGravity(*d.link, g);
  return d;
}

}  // namespace mixflow::coupling
