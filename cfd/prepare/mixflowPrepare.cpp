// mixflowPrepare: writes the OpenFOAM files of a liquid (or mixture) dam-break case for
// mixflowFoam from the scene description the DEM half reads too.
//   mixflowPrepare [-case DIR] [-np N] [-check]
// Reads DIR/constant/sceneProperties (content, sample, channel, liquid), DIR/system/cfdDict and
// DIR/system/controlDict (endTime, writeInterval); writes blockMeshDict, controlDict, fvSchemes,
// fvSolution, decomposeParDict (N ranks), transportProperties, g, turbulenceProperties and 0/.
// -check validates the input and prints the derived mesh and coefficients without writing.
// Exit status: 0 ok, 2 bad input (message names file, entry and allowed range), 1 other errors.
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "Dictionary.h"
#include "FoamCaseWriter.h"
#include "LiquidCase.h"
#include "MixtureCase.h"

namespace {
void usage() {
  std::cout << "Usage: mixflowPrepare [-case DIR] [-np N] [-check]\n"
               "  Writes the OpenFOAM case files for mixflowFoam from DIR/constant/"
               "sceneProperties,\n  DIR/system/cfdDict and DIR/system/controlDict; -np N writes "
               "a decomposeParDict for N ranks.\n  -check only validates and reports.\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string caseDir = ".";
  bool checkOnly = false;
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
    cfd::LiquidCase c = cfd::LiquidCase::read(caseDir);
    cfd::MixtureSetup mixture;
    if (c.content == "mixture") mixture = cfd::prepareMixture(c);
    cfd::describe(c, ranks, std::cout);
    if (c.content == "mixture") cfd::describeMixture(mixture, c, std::cout);
    if (!checkOnly) {
      cfd::writeFoamCase(c, ranks);
      if (c.content == "mixture") cfd::writeMixtureDemScript(mixture);
      std::cout << "[mixflowPrepare] wrote system/{blockMeshDict,controlDict,fvSchemes,"
                   "fvSolution,decomposeParDict}, constant/{transportProperties,g,"
                   "turbulenceProperties}, 0/{alpha.liquid,U,p_rgh}"
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
