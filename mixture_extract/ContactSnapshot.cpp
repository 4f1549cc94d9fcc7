#include "ContactSnapshot.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file (missing or unreadable)");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) { throw InputError(path + ": " + why); };
  auto lineAfter = [&](const std::string& item) -> size_t {
    const size_t at = text.find("ITEM: " + item);
    return at == std::string::npos ? at : at + 6 + item.size();
  };
  const size_t countAt = lineAfter(countItem), columnsAt = lineAfter(columnsItem);
  if (countAt == std::string::npos || columnsAt == std::string::npos)
    fail("not a LIGGGHTS dump (no 'ITEM: " + countItem + "' and 'ITEM: " + columnsItem + "')");
  long count = -1;
  std::istringstream(text.substr(countAt, 32)) >> count;
  if (count < 0) fail("no entry count after 'ITEM: " + countItem + "'");
  TextDump d;
  const size_t eol = std::min(text.find('\n', columnsAt), text.size());
  std::istringstream ls(text.substr(columnsAt, eol - columnsAt));
  for (std::string c; ls >> c;) d.columns.push_back(c);
  if (d.columns.empty()) fail("no columns after 'ITEM: " + columnsItem + "'");
  // The rows: numbers parsed in place (the files hold millions of them).
  const char* p = text.data() + eol;
  const char* end = text.data() + text.size();
  d.rows.assign(count, std::vector<double>(d.columns.size()));
  for (long r = 0; r < count; ++r)
    for (double& v : d.rows[r]) {
      while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
      const auto res = std::from_chars(p, end, v);
      if (res.ec != std::errc())
        fail("holds " + std::to_string(r) + " complete rows, the header says " +
             std::to_string(count) + " (truncated dump?)");
      p = res.ptr;
    }
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
