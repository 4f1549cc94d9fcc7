#include "TextOutputs.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace mixflow::mx {

namespace fs = std::filesystem;

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  bool ok = false;
  int err = 0;
  {
    std::ofstream f(tmp, std::ios::binary);
    if (f) {
      f << text;
      f.flush();
      if (f) f.close();
      ok = !f.fail();
    }
    err = errno;
  }
  if (!ok) {
    std::error_code ec;
    if (fs::is_regular_file(tmp, ec)) fs::remove(tmp, ec);
    throw std::runtime_error(tmp + ": write failed (" + std::strerror(err) + "); " + path +
                             " is left as it was");
  }
  fs::rename(tmp, path);
}

void writeXdmf(const std::string& xdmfPath, const std::string& h5Path, const StoredOutput& s) {
  // Data paths relative to the .xdmf so the pair can be moved together.
  const std::string h5 = fs::path(h5Path).filename().string();
  const int nx = s.nx, ny = s.ny;
  const size_t nw = s.t0.size();
  std::vector<size_t> order(nw);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return s.tMid[a] < s.tMid[b]; });
  std::ostringstream x;
  x << std::setprecision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n <Domain>\n"
    << "  <!-- mixflowExtract: bins of the (x, y) averaging grid, one cell across the width z;"
       " x down-channel, y up. Time = window centre. -->\n"
    << "  <Grid Name=\"mixture\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (size_t k : order) {
    x << "   <Grid Name=\"window_" << k << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << s.tMid[k] << "\"/>\n"
      << "    <Topology TopologyType=\"3DRectMesh\" Dimensions=\"2 " << ny + 1 << ' ' << nx + 1
      << "\"/>\n"
      << "    <Geometry GeometryType=\"VXVYVZ\">\n"
      << "     <DataItem Dimensions=\"" << nx + 1
      << "\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << h5 << ":/grid/x_edges</DataItem>\n"
      << "     <DataItem Dimensions=\"" << ny + 1
      << "\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << h5 << ":/grid/y_edges</DataItem>\n"
      << "     <DataItem Dimensions=\"2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
      << h5 << ":/grid/z_edges</DataItem>\n"
      << "    </Geometry>\n";
    for (const std::string& f : s.fields) {
      x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
        << "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"1 " << ny << ' ' << nx
        << "\" Type=\"HyperSlab\">\n"
        << "      <DataItem Dimensions=\"3 3\" Format=\"XML\">" << k << " 0 0 1 1 1 1 " << ny << ' '
        << nx << "</DataItem>\n"
        << "      <DataItem Dimensions=\"" << nw << ' ' << ny << ' ' << nx
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/fields/" << f
        << "</DataItem>\n"
        << "     </DataItem>\n    </Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  writeFileAtomically(xdmfPath, x.str());
}

void writeRegionsCsv(const std::string& csvPath, const StoredOutput& s) {
  std::ostringstream c;
  c << std::setprecision(10);
  c << "region,t0_s,t1_s,t_mid_s,quantity,unit,value,valid,mask_reasons,snapshots,fluid_times,"
       "particle_samples,fluid_samples\n";
  std::vector<size_t> order(s.t0.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return s.t0[a] < s.t0[b]; });
  for (const auto& r : s.regions)
    for (size_t k : order)
      for (const std::string& q : r.quantities) {
        const double v = r.values.at(q)[k];
        const auto it = r.valid.find(q);
        const bool ok = (it == r.valid.end() || it->second[k]) && std::isfinite(v);
        c << r.name << ',' << s.t0[k] << ',' << s.t1[k] << ',' << s.tMid[k] << ',' << q << ','
          << s.units.at(q) << ',';
        if (ok) c << v;
        c << ',' << (ok ? 1 : 0) << ',' << (r.reasons.empty() ? 0 : r.reasons[k]) << ','
          << s.snapshots[k] << ',' << s.fluidTimes[k] << ','
          << (r.particleSamples.empty() ? 0 : r.particleSamples[k]) << ','
          << (r.fluidSamples.empty() ? 0 : r.fluidSamples[k]) << '\n';
      }
  writeFileAtomically(csvPath, c.str());
}

}  // namespace mixflow::mx
