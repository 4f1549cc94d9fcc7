#include "LiggghtsCommands.h"

#include <algorithm>

#include "ContactDumps.h"
#include "Dictionary.h"

namespace mixflow::dem {

namespace {
std::string fmt(double v) { return formatNumber(v, 12); }
}  // namespace

std::string contactModel(const ParticleMaterial& p) {
  std::string m = "model hertz tangential history";
  if (p.rollingModel != "off") m += " rolling_friction " + p.rollingModel;
  return m;
}

std::string contactSettings(bool limitForce) {
  return std::string("limitForce ") + (limitForce ? "on" : "off");
}

std::vector<std::string> materialCommands(const ParticleMaterial& p, double youngModulusFactor,
                                          double particleFriction, double rollingFriction) {
  const double eP = p.youngModulus * youngModulusFactor;
  const double eW = p.wallYoungModulus * youngModulusFactor;
  // Pair matrices are 2x2 in type order (1-1, 1-2, 2-1, 2-2); walls never touch each other.
  auto pairMatrix = [](double pp, double pw) {
    return "peratomtypepair 2 " + fmt(pp) + " " + fmt(pw) + " " + fmt(pw) + " " + fmt(pw);
  };
  std::vector<std::string> c = {
      "fix m1 all property/global youngsModulus peratomtype " + fmt(eP) + " " + fmt(eW),
      "fix m2 all property/global poissonsRatio peratomtype " + fmt(p.poisson) + " " +
          fmt(p.poisson),
      "fix m3 all property/global coefficientRestitution " +
          pairMatrix(p.restitution, p.restitution),
      "fix m4 all property/global coefficientFriction " +
          pairMatrix(particleFriction, p.wallFriction),
  };
  if (p.rollingModel != "off")
    c.push_back("fix m5 all property/global coefficientRollingFriction " +
                pairMatrix(rollingFriction, rollingFriction));
  if (p.rollingModel == "epsd2" || p.rollingViscousDamping > 0)
    c.push_back("fix m6 all property/global coefficientRollingViscousDamping " +
                pairMatrix(p.rollingViscousDamping, p.rollingViscousDamping));
  return c;
}

std::string wallCommand(const std::string& id, const ParticleMaterial& p, bool limitForce,
                        const std::string& plane, double position, const std::string& options) {
  return "fix " + id + " all wall/gran " + contactModel(p) + " primitive type " +
         std::to_string(kWallType) + " " + plane + " " + fmt(position) + options + " " +
         contactSettings(limitForce);
}

std::vector<std::string> contactCommands(const ParticleMaterial& p, double youngModulusFactor,
                                         bool limitForce) {
  std::vector<std::string> c;
  // LIGGGHTS refuses moduli above 1e9 Pa (or below 5e6 Pa) unless told the particles are that
  // stiff.
  const double eP = p.youngModulus * youngModulusFactor,
               eW = p.wallYoungModulus * youngModulusFactor;
  if (std::max(eP, eW) > 1e9) c.push_back("hard_particles yes");
  if (eP < 5e6) c.push_back("soft_particles yes");
  for (auto& m : materialCommands(p, youngModulusFactor, p.friction, p.rollingFriction))
    c.push_back(m);
  c.push_back("pair_style gran " + contactModel(p) + " " + contactSettings(limitForce));
  c.push_back("pair_coeff * *");
  return c;
}

std::string timestepCommand(double timeStep) { return "timestep " + fmt(timeStep); }

std::vector<std::string> stiffenCommands(const Scene& s, double timeStep) {
  std::vector<std::string> c;
  const ParticleMaterial& p = s.particles;
  if (std::max(s.youngModulusUsed(), s.wallYoungModulusUsed()) > 1e9)
    c.push_back("hard_particles yes");
  for (auto& m :
       materialCommands(p, s.dem.youngModulusFactor, s.settle.friction, s.settle.rollingFriction))
    c.push_back(m);
  c.push_back(timestepCommand(timeStep));
  return c;
}

Box channelBox(const Scene& s, double fillTop) {
  const double d = s.particles.diameter;
  Box b;
  // A margin beyond the outlet and the top keeps particles in the box until the next deletion pass.
  b.xlo = -d;
  b.xhi = s.channel.length + 0.5 * s.channel.length;
  b.ylo = -d;
  b.yhi = std::max(s.channel.height, fillTop) + 0.5 * s.channel.height;
  const bool periodic = s.channel.sideWalls == "periodic";
  b.zlo = periodic ? 0.0 : -d;
  b.zhi = periodic ? s.sample.width : s.sample.width + d;
  return b;
}

namespace {
// Contacts, gravity, walls, integrator, regions and output settings: what a restart file does not
// carry, so both a fresh start and a resume issue these lines.
std::vector<std::string> interactionCommands(const Scene& s, double timeStep, bool withGate) {
  const bool periodic = s.channel.sideWalls == "periodic";
  const double d = s.particles.diameter;
  std::vector<std::string> c = {
      "neighbor " + fmt(0.2 * d) + " bin",
      "neigh_modify delay 0",
  };
  for (auto& line : contactCommands(s.particles, s.dem.youngModulusFactor, s.dem.limitForce))
    c.push_back(line);
  const ParticleMaterial& p = s.particles;
  const bool lf = s.dem.limitForce;
  c.push_back(timestepCommand(timeStep));
  c.push_back("fix gravi all gravity 9.81 vector 0.0 -1.0 0.0");
  c.push_back(wallCommand("wBottom", p, lf, "yplane", 0.0, wallForceOption(s)));
  c.push_back(wallCommand("wBack", p, lf, "xplane", 0.0, wallForceOption(s)));
  if (!periodic) {
    c.push_back(wallCommand("wSide0", p, lf, "zplane", 0.0, wallForceOption(s)));
    c.push_back(wallCommand("wSide1", p, lf, "zplane", s.sample.width, wallForceOption(s)));
  }
  if (withGate)
    c.push_back(wallCommand("wGate", p, lf, "xplane", s.sample.length, wallForceOption(s)));
  c.push_back("fix integr all nve/sphere");
  // Per-particle contact stress (stress x volume, N m; particle-particle contacts only) for the
  // granular pressure p_s of mixture_extract.
  c.push_back("compute pstress all stress/atom");
  // Contact forces for the coarse-grained stress when contact snapshots are on (ContactDumps.h).
  if (const std::string pgl = pairContactCompute(s); !pgl.empty()) c.push_back(pgl);
  // Particles leave through the outlet and the top: deleted by region, counted by the driver.
  c.push_back("region outletRegion block " + fmt(s.channel.length) +
              " INF INF INF INF INF units box");
  c.push_back("region topRegion block INF " + fmt(s.channel.length) + " " + fmt(s.channel.height) +
              " INF INF INF units box");
  c.push_back("thermo_style custom step atoms ke");
  c.push_back("thermo_modify lost ignore norm no");
  c.push_back("compute_modify thermo_temp dynamic yes");
  c.push_back("thermo 100000");
  return c;
}
}  // namespace

namespace {
bool settlesBuoyant(const Scene& s) { return s.settle.gravity == "buoyant" && s.fluidDensity > 0; }
// The gravity the grains settle under: g, or g (1 - rho_f / rho_s) when they settle buoyant.
double settlingGravity(const Scene& s) {
  return 9.81 * (settlesBuoyant(s) ? 1.0 - s.fluidDensity / s.particles.density : 1.0);
}
}  // namespace

std::vector<std::string> settleGravityCommands(const Scene& s) {
  if (!settlesBuoyant(s)) return {};
  return {"unfix gravi",
          "fix gravi all gravity " + fmt(settlingGravity(s)) + " vector 0.0 -1.0 0.0"};
}

std::vector<std::string> settleDragCommands(const Scene& s) {
  if (s.settle.sedimentationSpeed <= 0) return {};
  // fix viscous: F = -gamma v, so the terminal speed m g' / gamma is sedimentationSpeed.
  return {"fix settleDrag all viscous " +
          fmt(s.particles.mass() * settlingGravity(s) / s.settle.sedimentationSpeed)};
}

std::vector<std::string> settleDragOffCommands(const Scene& s) {
  if (s.settle.sedimentationSpeed <= 0) return {};
  return {"unfix settleDrag"};
}

std::vector<std::string> sceneSetupCommands(const Scene& s, const std::string& dataFile,
                                            double timeStep) {
  const bool periodic = s.channel.sideWalls == "periodic";
  std::vector<std::string> c = {
      "units si",
      "atom_style granular",
      "atom_modify map array",
      std::string("boundary f f ") + (periodic ? "p" : "f"),
      "newton off",
      "communicate single vel yes",
      "processors " + s.dem.processors,
      "read_data " + dataFile,
  };
  for (auto& line : interactionCommands(s, timeStep, true)) c.push_back(line);
  return c;
}

std::vector<std::string> resumeSetupCommands(const Scene& s, const std::string& restartFile,
                                             double timeStep, bool withGate) {
  // Units, atom style, map, boundaries, box and atoms come back from the restart file.
  std::vector<std::string> c = {
      "processors " + s.dem.processors,
      "read_restart " + restartFile,
      "newton off",
      "communicate single vel yes",
  };
  for (auto& line : interactionCommands(s, timeStep, withGate)) c.push_back(line);
  return c;
}

}  // namespace mixflow::dem
