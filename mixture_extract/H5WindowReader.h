// Reads a mixture file that is already there (layout in H5Output.h): its windows, checked against
// the settings before a grown case is appended to, and the series from which the XDMF and CSV
// writers (TextOutputs.h) rebuild their files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ExtractSettings.h"

namespace mixflow::mx {

// What the XDMF and CSV writers need from a finished file.
struct StoredOutput {
  int nx = 0, ny = 0;
  std::vector<double> t0, t1, tMid;
  std::vector<long> snapshots, fluidTimes;
  std::vector<std::string> fields;  // datasets in /fields
  std::map<std::string, std::string> units;
  struct RegionSeries {
    std::string name;
    std::vector<std::string> quantities;
    std::map<std::string, std::vector<double>> values;
    std::map<std::string, std::vector<std::uint8_t>> valid;
    std::vector<std::uint16_t> reasons;
    std::vector<double> particleSamples, fluidSamples;
  };
  std::vector<RegionSeries> regions;
};
StoredOutput readStoredOutput(const std::string& path);

// The windows (t0, t1) of an existing output file, checked read-only against the settings before
// anything is written: InputError (naming the file, the entry and the stored value) when the file
// was made with other settings (fingerprint), another window kind, start or width, or holds a
// window overlapping one of the settings' windows without matching it (two widths interleaved).
std::vector<std::pair<double, double>> existingWindows(const std::string& path,
                                                       const ExtractSettings& settings);

}  // namespace mixflow::mx
