// LIGGGHTS input-script lines for a scene. Kept as plain strings so the same lines drive the
// library (our executable) and a plain `liggghts -in` run (the benchmark), and can be checked in
// tests.
#pragma once

#include <string>
#include <vector>

#include "Scene.h"

namespace mixflow::dem {

// Atom types: 1 = particles, 2 = wall material (walls are LIGGGHTS primitives of type 2).
constexpr int kParticleType = 1;
constexpr int kWallType = 2;

// "model hertz tangential history [rolling_friction X]" shared by pair and walls.
std::string contactModel(const ParticleMaterial& p);
// Model settings ("limitForce on"): after the model for pair_style, after the primitive for walls.
std::string contactSettings(bool limitForce);

// fix property/global lines for the two atom types. Settling passes its own particle friction and
// rolling friction (re-issuing a fix with the same ID replaces its values at the next run).
// The settling's gravity (demDict settle.gravity): none for `full` or a dry scene; for `buoyant`
// in a mixture, gravity replaced by g (1 - rho_f / rho_s).
std::vector<std::string> settleGravityCommands(const Scene& s);
// demDict settle.sedimentationSpeed > 0: a drag on every grain while it settles (and its removal).
std::vector<std::string> settleDragCommands(const Scene& s);
std::vector<std::string> settleDragOffCommands(const Scene& s);

std::vector<std::string> materialCommands(const ParticleMaterial& p, double youngModulusFactor,
                                          double particleFriction, double rollingFriction);

// Stiffness switches, materials, pair style and coefficients: the complete particle contact law.
std::vector<std::string> contactCommands(const ParticleMaterial& p, double youngModulusFactor,
                                         bool limitForce);

// One primitive wall of the wall material: e.g. wallCommand("wBack", p, true, "xplane", 0.0).
// options: keywords LIGGGHTS takes between the plane and the contact settings (" store_force yes").
std::string wallCommand(const std::string& id, const ParticleMaterial& p, bool limitForce,
                        const std::string& plane, double position, const std::string& options = "");

// The DEM step as every command here gives it (the digits LIGGGHTS runs at).
std::string timestepCommand(double timeStep);

// Raises a sample settled softer (demDict settle.stiffenFrom) to the scene's moduli and DEM step,
// keeping the settling friction and no rolling resistance; takes effect at the next run.
std::vector<std::string> stiffenCommands(const Scene& s, double timeStep);

// Simulation box (fluid-free dam-break channel) bounds: x, y, z lo/hi.
struct Box {
  double xlo, xhi, ylo, yhi, zlo, zhi;
};
Box channelBox(const Scene& s, double fillTop);

// Everything before the particles' first run: pair style, materials, gravity, walls, integrator.
// The box and atoms come from a data file (read_data), written by SampleFill.
std::vector<std::string> sceneSetupCommands(const Scene& s, const std::string& dataFile,
                                            double timeStep);

// The same scene continued from a LIGGGHTS restart file written after the gate opened (no gate).
std::vector<std::string> resumeSetupCommands(const Scene& s, const std::string& restartFile,
                                             double timeStep, bool withGate = false);

}  // namespace mixflow::dem
