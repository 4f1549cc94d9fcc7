// Writes the extractor's HDF5 file: one file per case, appended window by window.
//   /                 root attributes: mixflow version, case parameters, settings, conventions
//   /grid             x_edges, y_edges, z_edges, x, y (bin centres), bin_volume
//   /windows          t0, t1, t_mid, snapshot and fluid times and counts, max_pair_gap,
//                     n_valid_<field>, n_masked_<reason> (nw)
//   /fields/<name>    (nw, ny, nx) float64, attributes units, meaning, mask
//   /masks            valid_<name> (uint8) and reasons (uint16 bit set, bits in the attributes)
//   /counts           particle_samples, particle_equivalents, fluid_samples (nw, ny, nx)
//   /regions/<name>/  region averages (nw): <field>, valid_<field>, reasons, counts
// An update works on a copy (<file>.tmp) that is renamed over the file only when complete, so an
// interrupted run leaves the previous file intact. HDF5's exit handler is switched off: after a
// failed write (a full disk) the library's state of that file is unsafe to close (HDF5 1.10
// segfaults closing it, also at exit), so a failed file is left to the operating system and the
// process exits with its own status.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "AveragingGrid.h"
#include "ExtractSettings.h"
#include "WindowResult.h"

namespace mixflow::mx {

struct RootAttributes {
  std::vector<std::pair<std::string, std::string>> text;
  std::vector<std::pair<std::string, double>> numbers;
};

class H5Output {
 public:
  // Opens `path` for update. An existing file is checked (same grid and settings fingerprint; else
  // InputError unless overwrite) and copied to path + ".tmp"; otherwise a new file is started
  // there.
  H5Output(const std::string& path, const AveragingGrid& grid, const ExtractSettings& settings,
           const RootAttributes& attrs, bool overwrite);
  ~H5Output();  // removes the temporary file unless commit() ran
  H5Output(const H5Output&) = delete;
  H5Output& operator=(const H5Output&) = delete;

  // Windows already in the file (t0, t1).
  const std::vector<std::pair<double, double>>& existingWindows() const { return existing_; }
  void append(const WindowResult& w);
  // Closes the temporary file and renames it over `path`.
  void commit();

 private:
  void create(bool resume, const RootAttributes& attrs);
  void appendRows(const WindowResult& w);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::pair<double, double>> existing_;
};

}  // namespace mixflow::mx
