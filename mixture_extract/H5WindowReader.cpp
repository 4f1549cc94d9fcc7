#include "H5WindowReader.h"

#include <algorithm>
#include <cmath>

#include "Dictionary.h"
#include "DriftCoefficients.h"
#include "H5Calls.h"

namespace mixflow::mx {

using namespace h5;

namespace {

bool sameValue(double a, double b) {
  return std::fabs(a - b) <= 1e-12 * std::max(1.0, std::max(std::fabs(a), std::fabs(b)));
}

std::string num(double v) { return formatNumber(v, 8); }

double readNumberAttr(hid_t obj, const std::string& name, double def) {
  if (H5Aexists(obj, name.c_str()) <= 0) return def;
  Id a(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name), H5Aclose);
  double v = def;
  check(H5Aread(a, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

std::string readTextAttr(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) <= 0) return "";
  Id a(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name), H5Aclose);
  Id type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  check(H5Tset_size(type, H5T_VARIABLE), "string size");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "string cset");
  char* p = nullptr;
  check(H5Aread(a, type, &p), "read attribute " + name);
  std::string s = p ? p : "";
  H5free_memory(p);
  return s;
}

std::vector<double> read1d(hid_t parent, const std::string& name) {
  Id d(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  Id s(check(H5Dget_space(d), "space " + name), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(s);
  std::vector<double> v(static_cast<size_t>(n));
  if (n > 0)
    check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "read " + name);
  return v;
}

template <class T>
std::vector<T> read1dAs(hid_t parent, const std::string& name, hid_t memType) {
  Id d(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  Id s(check(H5Dget_space(d), "space " + name), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(s);
  std::vector<T> v(static_cast<size_t>(n));
  if (n > 0) check(H5Dread(d, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "read " + name);
  return v;
}

std::vector<std::string> children(hid_t g) {
  H5G_info_t info;
  check(H5Gget_info(g, &info), "group info");
  std::vector<std::string> out;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len =
        H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    std::string s(static_cast<size_t>(len), '\0');
    H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, s.data(), len + 1, H5P_DEFAULT);
    out.push_back(s);
  }
  return out;
}

}  // namespace

std::vector<std::pair<double, double>> existingWindows(const std::string& path,
                                                       const ExtractSettings& settings) {
  initHdf5();
  std::vector<std::pair<double, double>> existing;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    throw InputError(path +
                     ": exists but is not a readable HDF5 file; delete it or run with "
                     "-overwrite");
  Id file(f, H5Fclose);
  const std::string fp = readTextAttr(file, "settings_fingerprint");
  if (fp != settings.fingerprint())
    throw InputError(path +
                     ": was made with other extractor settings (grid, thresholds, "
                     "conventions, fluid or regions differ from " +
                     settings.dictFile +
                     "); delete it or run with -overwrite to start it again.\n  file:     " + fp +
                     "\n  settings: " + settings.fingerprint());
  const std::string again =
      ": appending would interleave two window series in one file and one XDMF series; run with "
      "-overwrite to start the file again, or give -output BASE for a second file";
  const std::string kind = readTextAttr(file, "windows_kind");
  const std::string kindNow = settings.windowsGenerated ? "start/end/width" : "list";
  if (!kind.empty() && kind != kindNow)
    throw InputError(path + ": holds windows from windows." +
                     (kind == "list" ? std::string("list") : std::string("start/end/width")) +
                     " (root attribute windows_kind '" + kind + "'), but " + settings.dictFile +
                     " now gives windows." + kindNow + again);
  if (kind == "start/end/width" && settings.windowsGenerated) {
    const double w = readNumberAttr(file, "windows_width_s", settings.windowWidth);
    const double t = readNumberAttr(file, "windows_start_s", settings.windowStart);
    if (!sameValue(w, settings.windowWidth))
      throw InputError(path + ": holds windows of width " + num(w) +
                       " s (root attribute windows_width_s), but " + settings.windowWidthWhere +
                       " is now " + num(settings.windowWidth) + " s" + again);
    if (!sameValue(t, settings.windowStart))
      throw InputError(path + ": holds windows starting from " + num(t) +
                       " s (root attribute windows_start_s), but " + settings.windowStartWhere +
                       " is now " + num(settings.windowStart) + " s" + again);
  }
  {
    Id w(check(H5Gopen2(file, "windows", H5P_DEFAULT), "open /windows"), H5Gclose);
    const std::vector<double> t0 = read1d(w, "t0"), t1 = read1d(w, "t1");
    for (size_t k = 0; k < t0.size(); ++k) existing.emplace_back(t0[k], t1[k]);
  }
  // A stored window overlapping a settings window must be that window. The settings' windows
  // sorted by start, with the running maximum of their ends, bound the search.
  std::vector<const TimeWindow*> sorted;
  for (const TimeWindow& w : settings.windows) sorted.push_back(&w);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const TimeWindow* a, const TimeWindow* b) { return a->t0 < b->t0; });
  std::vector<double> maxEnd(sorted.size());
  for (size_t k = 0; k < sorted.size(); ++k)
    maxEnd[k] = std::max(k ? maxEnd[k - 1] : sorted[k]->t1, sorted[k]->t1);
  for (const auto& [a, b] : existing) {
    size_t k = std::upper_bound(maxEnd.begin(), maxEnd.end(), a) - maxEnd.begin();
    for (; k < sorted.size() && sorted[k]->t0 < b; ++k) {
      const TimeWindow& w = *sorted[k];
      const bool same = sameValue(w.t0, a) && sameValue(w.t1, b);
      if (!same && w.t1 > a && w.t0 < b && !sameValue(w.t1, a) && !sameValue(w.t0, b))
        throw InputError(path + ": holds the window [" + num(a) + ", " + num(b) + ") s, which " +
                         w.origin + " [" + num(w.t0) + ", " + num(w.t1) +
                         ") s overlaps without matching it" + again);
    }
  }
  return existing;
}

StoredOutput readStoredOutput(const std::string& path) {
  initHdf5();
  StoredOutput out;
  Id file(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path), H5Fclose);
  {
    Id g(check(H5Gopen2(file, "grid", H5P_DEFAULT), "open /grid"), H5Gclose);
    out.nx = static_cast<int>(read1d(g, "x").size());
    out.ny = static_cast<int>(read1d(g, "y").size());
  }
  {
    Id g(check(H5Gopen2(file, "windows", H5P_DEFAULT), "open /windows"), H5Gclose);
    out.t0 = read1d(g, "t0");
    out.t1 = read1d(g, "t1");
    out.tMid = read1d(g, "t_mid");
    out.snapshots = read1dAs<long>(g, "n_snapshots", H5T_NATIVE_LONG);
    out.fluidTimes = read1dAs<long>(g, "n_fluid_times", H5T_NATIVE_LONG);
  }
  auto rank = [](const std::string& name) {
    for (int k = 0; k < kFieldCount; ++k)
      if (name == fieldDef(static_cast<FieldId>(k)).name) return k;
    return 1000;
  };
  auto byFieldOrder = [&](std::vector<std::string>& v) {
    std::stable_sort(v.begin(), v.end(),
                     [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  };
  {
    Id g(check(H5Gopen2(file, "fields", H5P_DEFAULT), "open /fields"), H5Gclose);
    out.fields = children(g);
    byFieldOrder(out.fields);
    for (const auto& f : out.fields) {
      Id d(check(H5Dopen2(g, f.c_str(), H5P_DEFAULT), "open " + f), H5Dclose);
      out.units[f] = readTextAttr(d, "units");
    }
  }
  Id gr(check(H5Gopen2(file, "regions", H5P_DEFAULT), "open /regions"), H5Gclose);
  for (const std::string& name : children(gr)) {
    Id rg(check(H5Gopen2(gr, name.c_str(), H5P_DEFAULT), "open region " + name), H5Gclose);
    StoredOutput::RegionSeries rs;
    rs.name = name;
    for (const std::string& ds : children(rg)) {
      if (ds == "reasons") {
        rs.reasons = read1dAs<std::uint16_t>(rg, ds, H5T_NATIVE_UINT16);
      } else if (ds == "particle_samples") {
        rs.particleSamples = read1d(rg, ds);
      } else if (ds == "fluid_samples") {
        rs.fluidSamples = read1d(rg, ds);
      } else if (ds.rfind("valid_", 0) == 0) {
        rs.valid[ds.substr(6)] = read1dAs<std::uint8_t>(rg, ds, H5T_NATIVE_UINT8);
      } else {
        rs.values[ds] = read1d(rg, ds);
        rs.quantities.push_back(ds);
        Id d(check(H5Dopen2(rg, ds.c_str(), H5P_DEFAULT), "open " + ds), H5Dclose);
        out.units[ds] = readTextAttr(d, "units");
      }
    }
    byFieldOrder(rs.quantities);
    out.regions.push_back(rs);
  }
  return out;
}

}  // namespace mixflow::mx
