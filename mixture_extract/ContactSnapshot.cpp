#include "ContactSnapshot.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "Dictionary.h"

namespace mixflow::mx {

namespace fs = std::filesystem;

namespace {

// A LAMMPS text dump of one step: the entry count after `countItem`, the column names after
// `columnsItem`, then one row of numbers per entry.
struct TextDump {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

TextDump readTextDump(const std::string& path, const std::string& countItem,
                      const std::string& columnsItem) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file (missing or unreadable)");
  auto fail = [&](const std::string& why) { throw InputError(path + ": " + why); };
  std::string line;
  long count = -1;
  TextDump d;
  while (std::getline(in, line)) {
    if (line.rfind("ITEM: " + countItem, 0) == 0) {
      if (!(in >> count) || count < 0) fail("no entry count after 'ITEM: " + countItem + "'");
    } else if (line.rfind("ITEM: " + columnsItem, 0) == 0) {
      std::istringstream ls(line.substr(6 + columnsItem.size()));
      for (std::string c; ls >> c;) d.columns.push_back(c);
      break;
    }
  }
  if (count < 0 || d.columns.empty())
    fail("not a LIGGGHTS dump (no 'ITEM: " + countItem + "' and 'ITEM: " + columnsItem + "')");
  d.rows.assign(count, std::vector<double>(d.columns.size()));
  for (long r = 0; r < count; ++r)
    for (double& v : d.rows[r])
      if (!(in >> v))
        fail("holds " + std::to_string(r) + " complete rows, the header says " +
             std::to_string(count) + " (truncated dump?)");
  return d;
}

}  // namespace

bool contactSnapshotExists(const std::string& snapshotPath) {
  return fs::is_regular_file(dem::pairContactPath(snapshotPath)) &&
         fs::is_regular_file(dem::wallContactPath(snapshotPath));
}

ContactSnapshot readContactSnapshot(const std::string& snapshotPath,
                                    const std::vector<dem::WallPlane>& walls) {
  ContactSnapshot c;
  c.walls = walls;
  const std::string pairsPath = dem::pairContactPath(snapshotPath);
  const TextDump p = readTextDump(pairsPath, "NUMBER OF ENTRIES", "ENTRIES");
  if (p.columns.size() != 6)
    throw InputError(pairsPath + ": " + std::to_string(p.columns.size()) +
                     " columns, expected 6 (compute pair/gran/local id force)");
  c.pairs.reserve(p.rows.size());
  for (const auto& r : p.rows)
    c.pairs.push_back({std::lround(r[0]), std::lround(r[1]), {r[3], r[4], r[5]}});

  const std::string wallsPath = dem::wallContactPath(snapshotPath);
  const TextDump w = readTextDump(wallsPath, "NUMBER OF ATOMS", "ATOMS");
  if (w.columns.empty() || w.columns[0] != "id")
    throw InputError(wallsPath + ": the first column is not 'id'");
  // Column of each wall's x force: f_force_<wall>[1].
  std::vector<int> col(walls.size(), -1);
  for (size_t k = 0; k < walls.size(); ++k)
    for (size_t j = 0; j < w.columns.size(); ++j)
      if (w.columns[j] == "f_force_" + walls[k].id + "[1]") col[k] = static_cast<int>(j);
  for (size_t k = 0; k < walls.size(); ++k)
    if (col[k] < 0 || col[k] + 2 >= static_cast<int>(w.columns.size()))
      throw InputError(wallsPath + ": no columns f_force_" + walls[k].id +
                       "[1-3] (the wall's force; written by mixflowDem with contactSnapshots on)");
  for (const auto& r : w.rows)
    for (size_t k = 0; k < walls.size(); ++k) {
      const double* f = &r[col[k]];
      if (f[0] != 0 || f[1] != 0 || f[2] != 0)
        c.wallContacts.push_back({std::lround(r[0]), static_cast<int>(k), {f[0], f[1], f[2]}});
    }
  return c;
}

}  // namespace mixflow::mx
