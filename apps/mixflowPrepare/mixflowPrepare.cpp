// mixflowPrepare: writes the OpenFOAM files of a liquid (or mixture) dam-break case for
// mixflowFoam from the scene description the DEM half reads too.
//   mixflowPrepare [-case DIR] [-np N] [-check] [-solver]
// Reads DIR/constant/sceneProperties (content, sample, channel, liquid), DIR/system/cfdDict and
// DIR/system/controlDict (endTime, writeInterval); writes blockMeshDict, controlDict, fvSchemes,
// fvSolution, decomposeParDict (N ranks), transportProperties, g, turbulenceProperties and 0/.
// A mixture also needs its settled sample (dem/settled.state), system/demDict and
// constant/couplingProperties, and gets the DEM restart script (MixtureCase.h); with cfdDict
// mixtureModel bulk it is the bulk model's case instead (constant/bulkProperties, BulkModel.h).
// -solver prints the solver the case runs (mixflowFoam, mixflowCoupled, mixflowBulkFoam).
// -check validates every dictionary of a case of any content and prints what it derives, writing
// nothing and running nothing, in well under a second: particles (sceneProperties, demDict,
// controlDict as mixflowDem reads them), liquid (sceneProperties, cfdDict, controlDict), mixture
// (all five, couplingProperties with the models it names) without the settled sample: at the
// scene's nominal sample height and packing; it names the checks left for the settled sample.
// Exit status: 0 ok, 2 bad input (message names file, entry and allowed range), 1 other errors.
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "Dictionary.h"
#include "FoamCaseWriter.h"
#include "LiquidCase.h"
#include "MixtureCase.h"
#include "Scene.h"
#include "SceneProperties.h"

namespace {
void usage() {
  std::cout << "Usage: mixflowPrepare [-case DIR] [-np N] [-check] [-solver]\n"
               "  Writes the OpenFOAM case files for mixflowFoam from DIR/constant/"
               "sceneProperties,\n  DIR/system/cfdDict and DIR/system/controlDict; -np N writes "
               "a decomposeParDict for N ranks.\n  -check only validates and reports, "
               "for a case of any content (a mixture\n  without its settled sample), writing "
               "nothing.\n  -solver prints the solver the case runs and exits.\n";
}

// constant/sceneProperties' content, read ahead of the reader of that content.
std::string sceneContent(const std::string& caseDir) {
  return mixflow::SceneProperties::readContent(
      mixflow::Dictionary::readFile(caseDir + "/constant/sceneProperties"));
}
}  // namespace

int main(int argc, char** argv) {
  std::string caseDir = ".";
  bool checkOnly = false;
  bool printSolver = false;  // -solver: print the solver the case runs (after the checks)
  int ranks = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-case" && i + 1 < argc) {
      caseDir = argv[++i];
    } else if (a == "-np" && i + 1 < argc) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 1 || n > 100000) {
        std::cerr << "mixflowPrepare: -np needs a positive integer, got '" << argv[i] << "'\n";
        return 2;
      }
      ranks = static_cast<int>(n);
    } else if (a == "-check") {
      checkOnly = true;
    } else if (a == "-solver") {
      printSolver = true;
    } else if (a == "-help" || a == "--help") {
      usage();
      return 0;
    } else {
      std::cerr << "mixflowPrepare: unknown option '" << a << "'\n";
      usage();
      return 2;
    }
  }

  using namespace mixflow;
  try {
    if (checkOnly && sceneContent(caseDir) == "particles") {
      // A dry scene has no fluid case: its dictionaries are the DEM half's. An error there is
      // reported with the content that asked for them.
      dem::Scene scene;
      try {
        scene = dem::Scene::read(caseDir);
      } catch (const InputError& e) {
        throw InputError(caseDir +
                         "/constant/sceneProperties: entry 'content': particles (a dry "
                         "scene, checked as mixflowDem reads it): " +
                         e.what());
      }
      std::cout << "[mixflowPrepare] case " << scene.name << ": content particles (mixflowDem "
                << "runs it), " << scene.particleCount() << " particles, DEM step "
                << scene.timeStepUsed() << " s; sceneProperties, demDict and controlDict pass"
                << std::endl;
      return 0;
    }
    cfd::LiquidCase c = cfd::LiquidCase::read(caseDir);
    if (printSolver) {
      std::cout << cfd::solverName(c) << std::endl;
      return 0;
    }
    // The CFD-DEM mixture needs its grains (settled sample, coupling); the bulk model does not.
    const bool grains = c.content == "mixture" && !c.bulkModel();
    cfd::MixtureSetup mixture;
    if (grains) mixture = checkOnly ? cfd::checkMixture(c) : cfd::prepareMixture(c);
    cfd::describe(c, ranks, std::cout);
    if (grains) cfd::describeMixture(mixture, c, std::cout);
    if (!checkOnly) {
      cfd::writeFoamCase(c, ranks);
      if (grains) cfd::writeMixtureDemScript(mixture);
      std::cout << "[mixflowPrepare] wrote system/{blockMeshDict,controlDict,fvSchemes,"
                   "fvSolution,decomposeParDict}, constant/{transportProperties,g,"
                   "turbulenceProperties"
                << (c.gate.lifted() ? ",fvOptions" : "") << "}, 0/{alpha.liquid,U,p_rgh}"
                << std::endl;
    }
  } catch (const InputError& e) {
    std::cerr << "mixflowPrepare: input error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mixflowPrepare: error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
