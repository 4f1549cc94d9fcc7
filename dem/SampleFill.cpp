#include "SampleFill.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>

#include "Dictionary.h"

namespace mixflow::dem {

Fill makeLooseFill(const Scene& s) {
  const double d = s.particles.diameter, r = 0.5 * d;
  const double spacing = s.settle.fillSpacing * d;
  const bool periodic = s.channel.sideWalls == "periodic";
  // Lattice sites strictly inside the walls; a periodic width is tiled without a seam.
  const long nx = static_cast<long>(std::floor((s.sample.length - d) / spacing)) + 1;
  const long nz = periodic ? static_cast<long>(std::floor(s.sample.width / spacing))
                           : static_cast<long>(std::floor((s.sample.width - d) / spacing)) + 1;
  if (nx < 1 || nz < 1)
    throw InputError(s.caseDir +
                     "/constant/sceneProperties: entry 'sample.width': the sample is "
                     "narrower than one particle lattice spacing");
  const double dz = periodic ? s.sample.width / nz : spacing;
  const double z0 = periodic ? 0.5 * dz : r;
  // Jitter of at most half the gap keeps every pair apart along each axis: no initial overlaps.
  const double jitter = 0.5 * (std::min(spacing, dz) - d) * 0.999;
  std::mt19937_64 rng(static_cast<unsigned long>(s.settle.seed));
  std::uniform_real_distribution<double> u(-jitter, jitter);

  Fill f;
  const long n = s.particleCount();
  f.centres.reserve(n);
  for (long layer = 0; static_cast<long>(f.centres.size()) < n; ++layer) {
    for (long k = 0; k < nz && static_cast<long>(f.centres.size()) < n; ++k)
      for (long i = 0; i < nx && static_cast<long>(f.centres.size()) < n; ++i) {
        const double x = r + i * spacing + u(rng);
        const double y = r + layer * spacing + u(rng) + jitter;
        const double z = z0 + k * dz + u(rng);
        // Off the back wall, the gate and side walls: an overlap of the jitter (up to 0.07 d) at
        // 700 GPa shoots grains out of the sample. Moving a grain in by at most the jitter keeps
        // it more than d from its lattice neighbours (spacing - jitter > d).
        f.centres.push_back({std::clamp(x, r, s.sample.length - r), y,
                             periodic ? z : std::clamp(z, r, s.sample.width - r)});
        f.top = std::max(f.top, y + r);
      }
  }
  return f;
}

std::string dataFileText(const Fill& fill, const ParticleMaterial& p, const Box& box) {
  std::string text;
  char line[256];
  std::snprintf(line, sizeof line, "mixflow loose fill\n\n%zu atoms\n2 atom types\n\n",
                fill.centres.size());
  text += line;
  std::snprintf(line, sizeof line,
                "%.12g %.12g xlo xhi\n%.12g %.12g ylo yhi\n%.12g %.12g zlo zhi\n\nAtoms\n\n",
                box.xlo, box.xhi, box.ylo, box.yhi, box.zlo, box.zhi);
  text += line;
  long id = 1;
  for (const auto& c : fill.centres) {
    std::snprintf(line, sizeof line, "%ld 1 %.12g %.12g %.12g %.12g %.12g\n", id++, p.diameter,
                  p.density, c[0], c[1], c[2]);
    text += line;
  }
  return text;
}

void writeDataFile(const std::string& path, const Fill& fill, const ParticleMaterial& p,
                   const Box& box) {
  std::ofstream out(path);
  out << dataFileText(fill, p, box);
  if (!out) throw std::runtime_error(path + ": cannot write the particle data file");
}

}  // namespace mixflow::dem
