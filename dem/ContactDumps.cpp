#include "ContactDumps.h"

#include <filesystem>

#include "Dictionary.h"

namespace mixflow::dem {

namespace fs = std::filesystem;

namespace {
std::string fmt(double v) { return formatNumber(v, 12); }
}  // namespace

std::vector<WallPlane> wallPlanes(const Scene& s) {
  std::vector<WallPlane> w = {{"wBottom", 1, 0.0}, {"wBack", 0, 0.0}};
  if (s.channel.sideWalls != "periodic") {
    w.push_back({"wSide0", 2, 0.0});
    w.push_back({"wSide1", 2, s.sample.width});
  }
  return w;
}

std::string wallForceOption(const Scene& s) {
  return s.dem.contactSnapshots ? " store_force yes" : "";
}

std::string pairContactCompute(const Scene& s) {
  return s.dem.contactSnapshots ? "compute pgl all pair/gran/local id force" : "";
}

std::vector<std::string> contactDumpCommands(const Scene& s, long every) {
  if (!s.dem.contactSnapshots) return {};
  const fs::path dir = fs::path(s.caseDir) / "VTK" / "contacts";
  fs::create_directories(dir);
  const std::string n = std::to_string(every) + " ";
  std::string pairs = "dump contacts all local " + n + (dir / "pairs_*.txt").string();
  for (int k = 1; k <= 6; ++k) pairs += " c_pgl[" + std::to_string(k) + "]";
  // Particles near a wall: a margin of 1 % over the radius keeps every overlapping sphere.
  const double reach = 1.01 * s.particles.radius();
  std::string near,
      walls = "dump wallContacts all custom " + n + (dir / "walls_*.txt").string() + " id";
  const char* coord[] = {"x", "y", "z"};
  for (const WallPlane& p : wallPlanes(s)) {
    near += std::string(near.empty() ? "" : "+") + "(abs(" + coord[p.axis] + "-(" +
            fmt(p.position) + "))<" + fmt(reach) + ")";
    for (int k = 1; k <= 3; ++k) walls += " f_force_" + p.id + "[" + std::to_string(k) + "]";
  }
  return {pairs, "dump_modify contacts format \"%.0f %.0f %.0f %.9g %.9g %.9g\"",
          "variable nearWall atom \"" + near + "\"", walls,
          "dump_modify wallContacts thresh v_nearWall > 0"};
}

void removeContactDumps(const std::string& caseDir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(caseDir) / "VTK" / "contacts", ec)) {
    const std::string name = e.path().filename().string();
    if ((name.rfind("pairs_", 0) == 0 || name.rfind("walls_", 0) == 0) &&
        e.path().extension() == ".txt")
      fs::remove(e.path());
  }
}

namespace {
std::string contactPath(const std::string& snapshotPath, const std::string& kind) {
  const fs::path p(snapshotPath);
  std::string stem = p.stem().string();  // particles_<step>
  const std::string step = stem.substr(stem.find('_') + 1);
  return (p.parent_path().parent_path() / "contacts" / (kind + "_" + step + ".txt")).string();
}
}  // namespace

std::string pairContactPath(const std::string& snapshotPath) {
  return contactPath(snapshotPath, "pairs");
}

std::string wallContactPath(const std::string& snapshotPath) {
  return contactPath(snapshotPath, "walls");
}

}  // namespace mixflow::dem
