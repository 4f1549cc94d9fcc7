#include "H5Output.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "H5Calls.h"
#include "H5WindowReader.h"

namespace mixflow::mx {

namespace fs = std::filesystem;
using namespace h5;

namespace {

// Copies src to dst, naming the system's reason on failure (std::filesystem::copy_file reports
// a full disk as an input/output error).
void copyFile(const std::string& src, const std::string& dst) {
  auto fail = [&](const std::string& what, int err) {
    throw std::runtime_error(dst + ": cannot copy " + src + " (" + what + ": " +
                             std::strerror(err) + ")");
  };
  const int in = ::open(src.c_str(), O_RDONLY);
  if (in < 0) fail("open", errno);
  const int out = ::open(dst.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (out < 0) {
    const int e = errno;
    ::close(in);
    fail("create", e);
  }
  std::vector<char> buf(1 << 20);
  int err = 0;
  const char* what = "";
  for (;;) {
    const ssize_t n = ::read(in, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      err = errno;
      what = "read";
      break;
    }
    if (n == 0) break;
    for (ssize_t done = 0; done < n && !err;) {
      const ssize_t w = ::write(out, buf.data() + done, static_cast<size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) {
        err = errno;
        what = "write";
      } else {
        done += w;
      }
    }
    if (err) break;
  }
  ::close(in);
  if (::close(out) != 0 && !err) {
    err = errno;
    what = "close";
  }
  if (err) fail(what, err);
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

void removeAttr(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) > 0)
    check(H5Adelete(obj, name.c_str()), "delete attribute " + name);
}

void textAttr(hid_t obj, const std::string& name, const std::string& value) {
  removeAttr(obj, name);
  Id type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  check(H5Tset_size(type, H5T_VARIABLE), "string size");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "string cset");
  Id space(check(H5Screate(H5S_SCALAR), "scalar space"), H5Sclose);
  Id a(check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
             "attribute " + name),
       H5Aclose);
  const char* p = value.c_str();
  check(H5Awrite(a, type, &p), "write attribute " + name);
}

void numberAttr(hid_t obj, const std::string& name, double value) {
  removeAttr(obj, name);
  Id space(check(H5Screate(H5S_SCALAR), "scalar space"), H5Sclose);
  Id a(check(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
             "attribute " + name),
       H5Aclose);
  check(H5Awrite(a, H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

hid_t group(hid_t parent, const std::string& name) {
  if (H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0)
    return check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "open group " + name);
  return check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               "create group " + name);
}

void fixed1d(hid_t parent, const std::string& name, const std::vector<double>& v) {
  const hsize_t n = v.size();
  Id space(check(H5Screate_simple(1, &n, nullptr), "space"), H5Sclose);
  Id d(check(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                        H5P_DEFAULT),
             "create " + name),
       H5Dclose);
  check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "write " + name);
}

// Dataset growing along its first dimension (one row per window); inner = the other dimensions.
void extendible(hid_t parent, const std::string& name, hid_t type,
                const std::vector<hsize_t>& inner, const std::string& units,
                const std::string& meaning) {
  std::vector<hsize_t> dims{0}, maxd{H5S_UNLIMITED}, chunk{1};
  for (hsize_t k : inner) {
    dims.push_back(k);
    maxd.push_back(k);
    chunk.push_back(k);
  }
  if (inner.empty()) chunk[0] = 64;
  Id space(
      check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxd.data()), "space"),
      H5Sclose);
  Id dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "dcpl"), H5Pclose);
  check(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), "chunk " + name);
  if (!inner.empty() && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    check(H5Pset_shuffle(dcpl), "shuffle");
    check(H5Pset_deflate(dcpl, 4), "deflate");
  }
  Id d(check(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
             "create " + name),
       H5Dclose);
  if (!units.empty()) textAttr(d, "units", units);
  if (!meaning.empty()) textAttr(d, "meaning", meaning);
}

// Appends one row (the data of one window) to an extendible dataset.
void appendRow(hid_t parent, const std::string& name, hid_t memType, const void* data) {
  Id d(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  Id fspace0(check(H5Dget_space(d), "space " + name), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(fspace0);
  std::vector<hsize_t> dims(rank);
  H5Sget_simple_extent_dims(fspace0, dims.data(), nullptr);
  std::vector<hsize_t> start(rank, 0), count(dims);
  start[0] = dims[0];
  count[0] = 1;
  dims[0] += 1;
  check(H5Dset_extent(d, dims.data()), "extend " + name);
  Id fspace(check(H5Dget_space(d), "space " + name), H5Sclose);
  check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select " + name);
  Id mspace(check(H5Screate_simple(rank, count.data(), nullptr), "mspace"), H5Sclose);
  check(H5Dwrite(d, memType, mspace, fspace, H5P_DEFAULT, data), "write " + name);
}

std::vector<FieldId> regionFields(const ExtractSettings& s) {
  std::vector<FieldId> out;
  for (FieldId f : outputFields(s))
    if (f != fMassResidual && f != fMassScale) out.push_back(f);
  return out;
}

const char* kCoordinates =
    "x along the channel (down-channel, the paper's x), y vertical up (the paper's z; velocities "
    "along it are named w), z across the width; every bin spans the whole width W";

}  // namespace

struct H5Output::Impl {
  std::string path, tmp;
  hid_t file = -1;
  const AveragingGrid* grid = nullptr;
  const ExtractSettings* settings = nullptr;
  bool committed = false;
  bool failed = false;  // an HDF5 call on the file failed: never touch it again
  fs::path createdDir;  // the outermost directory this run created for the file (else empty)
  // Without a commit: removes the temporary file and the directories this run created.
  void discard() {
    std::error_code ec;
    if (fs::is_regular_file(tmp, ec)) fs::remove(tmp, ec);
    if (!createdDir.empty())
      for (fs::path d = fs::path(path).parent_path();; d = d.parent_path()) {
        if (!fs::remove(d, ec) || d == createdDir) break;  // stops at a non-empty directory
      }
  }
};

H5Output::H5Output(const std::string& path, const AveragingGrid& grid,
                   const ExtractSettings& settings, const RootAttributes& attrs, bool overwrite)
    : impl_(std::make_unique<Impl>()) {
  initHdf5();
  Impl& m = *impl_;
  m.path = path;
  m.tmp = path + ".tmp";
  m.grid = &grid;
  m.settings = &settings;
  for (fs::path d = fs::path(path).parent_path(); !d.empty() && !fs::exists(d); d = d.parent_path())
    m.createdDir = d;
  fs::create_directories(fs::path(path).parent_path());
  fs::remove(m.tmp);  // left by an interrupted run
  const bool resume = fs::exists(path) && !overwrite;
  if (resume) existing_ = mx::existingWindows(path, settings);
  try {
    create(resume, attrs);
  } catch (...) {
    // The constructor did not finish, so no destructor runs: leave no temporary file behind.
    m.failed = true;
    m.discard();
    throw;
  }
}

void H5Output::create(bool resume, const RootAttributes& attrs) {
  Impl& m = *impl_;
  const AveragingGrid& grid = *m.grid;
  const ExtractSettings& settings = *m.settings;
  if (resume) {
    copyFile(m.path, m.tmp);
    m.file = check(H5Fopen(m.tmp.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open " + m.tmp);
  } else {
    m.file =
        check(H5Fcreate(m.tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create " + m.tmp);
    textAttr(m.file, "created_utc", utcNow());
    textAttr(m.file, "settings_fingerprint", settings.fingerprint());
    textAttr(m.file, "windows_kind", settings.windowsGenerated ? "start/end/width" : "list");
    if (settings.windowsGenerated) {
      numberAttr(m.file, "windows_start_s", settings.windowStart);
      numberAttr(m.file, "windows_width_s", settings.windowWidth);
    }
    const hsize_t ny = grid.ny(), nx = grid.nx();
    {
      Id g(group(m.file, "grid"), H5Gclose);
      fixed1d(g, "x_edges", grid.xEdges());
      fixed1d(g, "y_edges", grid.yEdges());
      fixed1d(g, "z_edges", {0.0, grid.width()});
      fixed1d(g, "x", grid.xCentres());
      fixed1d(g, "y", grid.yCentres());
      textAttr(g, "units", "m");
      textAttr(g, "coordinates", kCoordinates);
      numberAttr(g, "bin_volume_m3", grid.binVolume());
      numberAttr(g, "width_m", grid.width());
      textAttr(g, "layout",
               "fields are (window, y bin, x bin); bin (i, j) spans [x_edges[i], "
               "x_edges[i+1]) x [y_edges[j], y_edges[j+1]) x [0, width]");
    }
    const std::vector<FieldId> fields = outputFields(settings);
    {
      Id g(group(m.file, "windows"), H5Gclose);
      textAttr(g, "rule",
               "a window holds the snapshots t with t0 - tol <= t < t1 - tol, tol = "
               "timeTolerance (root attribute time_tolerance_s); with fluid data, only the "
               "snapshots paired with a solved fluid time (nearest, within pair_tolerance_s; "
               "the t = 0 fluid write is the unsolved initial state and is left out), each "
               "averaged with its fluid time (root attribute fluid_times)");
      extendible(g, "t0", H5T_IEEE_F64LE, {}, "s", "window start");
      extendible(g, "t1", H5T_IEEE_F64LE, {}, "s", "window end");
      extendible(g, "t_mid", H5T_IEEE_F64LE, {}, "s", "(t0 + t1) / 2, the time given to ParaView");
      extendible(g, "t_first_snapshot", H5T_IEEE_F64LE, {}, "s",
                 "first particle snapshot in the window");
      extendible(g, "t_last_snapshot", H5T_IEEE_F64LE, {}, "s",
                 "last particle snapshot in the window");
      extendible(g, "t_first_fluid", H5T_IEEE_F64LE, {}, "s",
                 "first fluid time in the window (NaN without fluid data)");
      extendible(g, "t_last_fluid", H5T_IEEE_F64LE, {}, "s",
                 "last fluid time in the window (NaN without fluid data)");
      extendible(g, "max_pair_gap", H5T_IEEE_F64LE, {}, "s",
                 "largest |fluid time - its snapshot's time| over the window's pairs (NaN "
                 "without fluid data)");
      extendible(g, "n_snapshots", H5T_STD_I64LE, {}, "1", "particle snapshots averaged");
      extendible(g, "n_fluid_times", H5T_STD_I64LE, {}, "1",
                 "fluid time directories averaged (one per paired snapshot)");
      extendible(g, "particles_mean", H5T_IEEE_F64LE, {}, "1", "particles per snapshot");
      extendible(g, "particle_volume_mean", H5T_IEEE_F64LE, {}, "m3",
                 "particle volume per snapshot");
      extendible(g, "particle_volume_outside_grid", H5T_IEEE_F64LE, {}, "m3",
                 "particle volume per snapshot outside the averaging grid (not binned)");
      for (FieldId f : fields)
        if (fieldDef(f).invalidIf)
          extendible(g, std::string("n_valid_") + fieldDef(f).name, H5T_STD_I64LE, {}, "1",
                     std::string("bins where ") + fieldDef(f).name + " is valid");
      for (const MaskBitInfo& b : maskBits())
        extendible(g, std::string("n_masked_") + b.name, H5T_STD_I64LE, {}, "1",
                   std::string("bins with mask reason: ") + b.meaning);
    }
    {
      Id g(group(m.file, "fields"), H5Gclose);
      textAttr(g, "coordinates", kCoordinates);
      for (FieldId f : fields) {
        const FieldDef& d = fieldDef(f);
        extendible(g, d.name, H5T_IEEE_F64LE, {ny, nx}, d.unit, d.meaning);
        Id ds(check(H5Dopen2(g, d.name, H5P_DEFAULT), "open"), H5Dclose);
        textAttr(ds, "mask",
                 d.invalidIf ? std::string("/masks/valid_") + d.name +
                                   " (masked entries are NaN; /masks/reasons says why)"
                             : std::string("always valid"));
      }
    }
    {
      Id g(group(m.file, "masks"), H5Gclose);
      for (FieldId f : fields)
        if (fieldDef(f).invalidIf)
          extendible(g, std::string("valid_") + fieldDef(f).name, H5T_STD_U8LE, {ny, nx}, "1",
                     std::string("1 where ") + fieldDef(f).name + " is valid, 0 where masked");
      extendible(g, "reasons", H5T_STD_U16LE, {ny, nx}, "1",
                 "bit set of the conditions that mask values (bit_<value> attributes)");
      Id ds(check(H5Dopen2(g, "reasons", H5P_DEFAULT), "open"), H5Dclose);
      for (const MaskBitInfo& b : maskBits())
        textAttr(ds, "bit_" + std::to_string(b.bit), std::string(b.name) + ": " + b.meaning);
    }
    {
      Id g(group(m.file, "counts"), H5Gclose);
      extendible(g, "particle_samples", H5T_STD_I64LE, {ny, nx}, "1",
                 "(particle, snapshot) pairs overlapping the bin in the window");
      extendible(g, "particle_equivalents", H5T_IEEE_F64LE, {ny, nx}, "1",
                 "sum over snapshots of V_i,bin / V_i (particles' worth of volume sampled)");
      extendible(g, "fluid_samples", H5T_STD_I64LE, {ny, nx}, "1",
                 "(fluid cell, time) pairs with the cell centre in the bin");
    }
    {
      Id g(group(m.file, "regions"), H5Gclose);
      textAttr(g, "meaning",
               "region averages: the bins' additive sums (volumes, momenta, stress x "
               "volume, liquid volumes) added over the bins whose centre lies in "
               "the region, then the same formulas as per bin");
      for (const Region& r : settings.regions) {
        Id rg(group(g, r.name), H5Gclose);
        numberAttr(rg, "x0", r.x0);
        numberAttr(rg, "x1", r.x1);
        numberAttr(rg, "y0", r.y0);
        numberAttr(rg, "y1", r.y1);
        numberAttr(rg, "n_bins", static_cast<double>(regionBins(grid, r).size()));
        for (FieldId f : regionFields(settings)) {
          const FieldDef& d = fieldDef(f);
          extendible(rg, d.name, H5T_IEEE_F64LE, {}, d.unit, d.meaning);
          if (d.invalidIf)
            extendible(rg, std::string("valid_") + d.name, H5T_STD_U8LE, {}, "1", "1 where valid");
        }
        extendible(rg, "reasons", H5T_STD_U16LE, {}, "1", "mask bit set (see /masks/reasons)");
        extendible(rg, "particle_samples", H5T_IEEE_F64LE, {}, "1", "(particle, snapshot) pairs");
        extendible(rg, "fluid_samples", H5T_IEEE_F64LE, {}, "1", "(fluid cell, time) pairs");
        extendible(rg, "mass_balance_residual_rms", H5T_IEEE_F64LE, {}, "1/s",
                   "RMS of the bins' Eq. 9 residual over the region's bins where it is valid");
        extendible(rg, "mass_balance_scale_rms", H5T_IEEE_F64LE, {}, "1/s",
                   "RMS of mass_balance_scale over the same bins");
        extendible(rg, "mass_balance_bins", H5T_STD_I64LE, {}, "1",
                   "bins behind mass_balance_residual_rms");
      }
    }
  }
  for (const auto& [k, v] : attrs.text) textAttr(m.file, k, v);
  for (const auto& [k, v] : attrs.numbers) numberAttr(m.file, k, v);
  textAttr(m.file, "updated_utc", utcNow());
}

H5Output::~H5Output() {
  if (impl_->file >= 0 && !impl_->failed) H5Fclose(impl_->file);
  if (!impl_->committed) impl_->discard();
}

void H5Output::append(const WindowResult& w) {
  try {
    appendRows(w);
  } catch (...) {
    impl_->failed = true;
    throw;
  }
  existing_.emplace_back(w.window.t0, w.window.t1);
}

void H5Output::appendRows(const WindowResult& w) {
  Impl& m = *impl_;
  const AveragingGrid& g = *m.grid;
  const int nb = g.size();
  const std::vector<FieldId> fields = outputFields(*m.settings);
  {
    Id gw(check(H5Gopen2(m.file, "windows", H5P_DEFAULT), "open /windows"), H5Gclose);
    const double tMid = 0.5 * (w.window.t0 + w.window.t1);
    const long long ns = w.snapshots, nf = w.fluidTimes;
    appendRow(gw, "t0", H5T_NATIVE_DOUBLE, &w.window.t0);
    appendRow(gw, "t1", H5T_NATIVE_DOUBLE, &w.window.t1);
    appendRow(gw, "t_mid", H5T_NATIVE_DOUBLE, &tMid);
    appendRow(gw, "t_first_snapshot", H5T_NATIVE_DOUBLE, &w.tFirst);
    appendRow(gw, "t_last_snapshot", H5T_NATIVE_DOUBLE, &w.tLast);
    appendRow(gw, "t_first_fluid", H5T_NATIVE_DOUBLE, &w.tFirstFluid);
    appendRow(gw, "t_last_fluid", H5T_NATIVE_DOUBLE, &w.tLastFluid);
    appendRow(gw, "max_pair_gap", H5T_NATIVE_DOUBLE, &w.maxPairGap);
    appendRow(gw, "n_snapshots", H5T_NATIVE_LLONG, &ns);
    appendRow(gw, "n_fluid_times", H5T_NATIVE_LLONG, &nf);
    appendRow(gw, "particles_mean", H5T_NATIVE_DOUBLE, &w.particlesMean);
    appendRow(gw, "particle_volume_mean", H5T_NATIVE_DOUBLE, &w.particleVolumeMean);
    appendRow(gw, "particle_volume_outside_grid", H5T_NATIVE_DOUBLE, &w.particleVolumeOutsideMean);
    for (FieldId f : fields)
      if (fieldDef(f).invalidIf) {
        long long n = 0;
        for (const auto& b : w.bins) n += b.valid(f);
        appendRow(gw, std::string("n_valid_") + fieldDef(f).name, H5T_NATIVE_LLONG, &n);
      }
    for (const MaskBitInfo& bit : maskBits()) {
      long long n = 0;
      for (const auto& b : w.bins) n += (b.reasons & bit.bit) != 0;
      appendRow(gw, std::string("n_masked_") + bit.name, H5T_NATIVE_LLONG, &n);
    }
  }
  std::vector<double> buf(nb);
  std::vector<std::uint8_t> valid(nb);
  {
    Id gf(check(H5Gopen2(m.file, "fields", H5P_DEFAULT), "open /fields"), H5Gclose);
    Id gm(check(H5Gopen2(m.file, "masks", H5P_DEFAULT), "open /masks"), H5Gclose);
    for (FieldId f : fields) {
      const FieldDef& d = fieldDef(f);
      for (int b = 0; b < nb; ++b) {
        const bool ok = w.bins[b].valid(f);
        valid[b] = ok;
        buf[b] = ok ? w.bins[b].value[f] : std::nan("");
      }
      appendRow(gf, d.name, H5T_NATIVE_DOUBLE, buf.data());
      if (d.invalidIf)
        appendRow(gm, std::string("valid_") + d.name, H5T_NATIVE_UINT8, valid.data());
    }
    std::vector<std::uint16_t> reasons(nb);
    for (int b = 0; b < nb; ++b) reasons[b] = w.bins[b].reasons;
    appendRow(gm, "reasons", H5T_NATIVE_UINT16, reasons.data());
  }
  {
    Id gc(check(H5Gopen2(m.file, "counts", H5P_DEFAULT), "open /counts"), H5Gclose);
    std::vector<long long> n(nb);
    for (int b = 0; b < nb; ++b) n[b] = std::llround(w.sums[b].particleSamples);
    appendRow(gc, "particle_samples", H5T_NATIVE_LLONG, n.data());
    for (int b = 0; b < nb; ++b) buf[b] = w.sums[b].particleEquivalents;
    appendRow(gc, "particle_equivalents", H5T_NATIVE_DOUBLE, buf.data());
    for (int b = 0; b < nb; ++b) n[b] = std::llround(w.sums[b].fluidSamples);
    appendRow(gc, "fluid_samples", H5T_NATIVE_LLONG, n.data());
  }
  {
    Id gr(check(H5Gopen2(m.file, "regions", H5P_DEFAULT), "open /regions"), H5Gclose);
    for (size_t k = 0; k < m.settings->regions.size(); ++k) {
      const RegionResult& r = w.regions[k];
      Id rg(check(H5Gopen2(gr, m.settings->regions[k].name.c_str(), H5P_DEFAULT), "open region"),
            H5Gclose);
      for (FieldId f : regionFields(*m.settings)) {
        const FieldDef& d = fieldDef(f);
        const bool ok = r.values.valid(f);
        const double v = ok ? r.values.value[f] : std::nan("");
        const std::uint8_t vb = ok;
        appendRow(rg, d.name, H5T_NATIVE_DOUBLE, &v);
        if (d.invalidIf) appendRow(rg, std::string("valid_") + d.name, H5T_NATIVE_UINT8, &vb);
      }
      appendRow(rg, "reasons", H5T_NATIVE_UINT16, &r.values.reasons);
      appendRow(rg, "particle_samples", H5T_NATIVE_DOUBLE, &r.sums.particleSamples);
      appendRow(rg, "fluid_samples", H5T_NATIVE_DOUBLE, &r.sums.fluidSamples);
      const double rms = r.residualBins ? r.residualRms : std::nan("");
      const double srms = r.residualBins ? r.residualScaleRms : std::nan("");
      const long long nbins = r.residualBins;
      appendRow(rg, "mass_balance_residual_rms", H5T_NATIVE_DOUBLE, &rms);
      appendRow(rg, "mass_balance_scale_rms", H5T_NATIVE_DOUBLE, &srms);
      appendRow(rg, "mass_balance_bins", H5T_NATIVE_LLONG, &nbins);
    }
  }
}

void H5Output::commit() {
  Impl& m = *impl_;
  try {
    check(H5Fflush(m.file, H5F_SCOPE_GLOBAL), "flush " + m.tmp);
    check(H5Fclose(m.file), "close " + m.tmp);
  } catch (...) {
    m.failed = true;
    throw;
  }
  m.file = -1;
  fs::rename(m.tmp, m.path);
  m.committed = true;
}

}  // namespace mixflow::mx
