// mixflowExtract: alpha_s and the drift coefficients of the quasi two-phase model (docs/model.md
// §9) from a mixflow case, on the averaging grid and time windows of <case>/system/extractDict.
//   mixflowExtract [-case DIR] [-dict FILE] [-output BASE] [-overwrite] [-check] [-threads N]
// Exit status: 0 done, 2 bad input (message names the file, entry and allowed range), 1 other
// error.
#include <malloc.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "Dictionary.h"
#include "Extractor.h"

namespace {
void usage() {
  std::cout
      << "Usage: mixflowExtract [-case DIR] [-dict FILE] [-output BASE] [-overwrite] [-check]\n"
         "                      [-threads N]\n"
         "  Bins the particle snapshots (VTK/particles.vtk.series) and fluid fields of case DIR "
         "on\n"
         "  the grid and time windows of DIR/system/extractDict (or FILE) and appends the new,\n"
         "  complete windows to BASE.h5 (default DIR/postProcessing/mixture/mixture.h5), with\n"
         "  BASE.xdmf for ParaView and BASE_regions.csv. -overwrite starts the file again; -check\n"
         "  validates and lists the windows without writing; -threads parses N snapshot files at\n"
         "  once (default 1).\n";
}
}  // namespace

int main(int argc, char** argv) {
  // Each snapshot's arrays (MBs) are allocated and freed once per snapshot; by default glibc hands
  // them back to the kernel and faults zeroed pages in again, which costs more than reading a
  // binary snapshot. Kept in the heap, they are reused.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mixflow::mx::ExtractOptions opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "mixflowExtract: option '" << a << "' needs a value\n";
        usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "-case") {
      opt.caseDir = value();
    } else if (a == "-dict") {
      opt.dictFile = value();
    } else if (a == "-output") {
      opt.output = value();
    } else if (a == "-overwrite") {
      opt.overwrite = true;
    } else if (a == "-check") {
      opt.checkOnly = true;
    } else if (a == "-threads") {
      const std::string v = value();
      opt.threads = std::atoi(v.c_str());
      if (opt.threads < 1 || opt.threads > 64) {
        std::cerr << "mixflowExtract: -threads " << v << ": allowed range [1, 64]\n";
        return 2;
      }
    } else if (a == "-help" || a == "--help") {
      usage();
      return 0;
    } else {
      std::cerr << "mixflowExtract: unknown option '" << a << "'\n";
      usage();
      return 2;
    }
  }
  try {
    mixflow::mx::Extractor(opt, std::cout).run();
  } catch (const mixflow::InputError& e) {
    std::cerr << "mixflowExtract: input error: " << e.what() << std::endl;
    return 2;
  } catch (const mixflow::mx::IndexWriteError& e) {
    std::cerr << "mixflowExtract: extraction stopped: " << e.what() << std::endl;
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mixflowExtract: extraction stopped: " << e.what()
              << "\n  The output files are unchanged (updates go through temporary files)."
              << std::endl;
    return 1;
  }
  return 0;
}
