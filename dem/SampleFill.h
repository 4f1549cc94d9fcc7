// Initial loose fill of the sample: exactly N = phi L H W / Vp particles on a jittered lattice
// above the floor, behind the gate. Gravity then settles them (DemDriver::settle) into a random
// packing whose height and solid fraction are measured and reported.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "LiggghtsCommands.h"
#include "Scene.h"

namespace mixflow::dem {

struct Fill {
  std::vector<std::array<double, 3>> centres;
  double top = 0;  // highest particle top (m)
};

Fill makeLooseFill(const Scene& s);

// LAMMPS data file for atom_style granular ("id type diameter density x y z"): its text, and
// the file.
std::string dataFileText(const Fill& fill, const ParticleMaterial& p, const Box& box);
void writeDataFile(const std::string& path, const Fill& fill, const ParticleMaterial& p,
                   const Box& box);

}  // namespace mixflow::dem
