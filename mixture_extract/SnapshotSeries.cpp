#include "SnapshotSeries.h"

#include <algorithm>
#include <charconv>
#include <filesystem>

#include "BinarySnapshot.h"
#include "Dictionary.h"
#include "SnapshotFiles.h"
#include "VtkSnapshot.h"

namespace mixflow::mx {

namespace fs = std::filesystem;

std::vector<SnapshotEntry> readSnapshotSeries(const std::string& caseDir) {
  const fs::path vtkDir = fs::path(caseDir) / "VTK";
  const std::string path = (vtkDir / "particles.vtk.series").string();
  if (!fs::exists(path))
    throw InputError(path +
                     ": cannot open file (missing): no particle snapshots in this case "
                     "(mixflowDem writes VTK/particles.vtk.series as it runs)");
  const std::string text = readTextFile(path);
  auto fail = [&](const std::string& why) { throw InputError(path + ": " + why); };
  const size_t files = text.find("\"files\"");
  if (files == std::string::npos) fail("no \"files\" list (not a ParaView .series file)");
  std::vector<SnapshotEntry> out;
  size_t p = text.find('[', files);
  if (p == std::string::npos) fail("\"files\" is not a list");
  const size_t listEnd = text.find(']', p);
  if (listEnd == std::string::npos) fail("unterminated \"files\" list (file being written?)");
  for (;;) {
    const size_t ob = text.find('{', p);
    if (ob == std::string::npos || ob > listEnd) break;
    const size_t cb = text.find('}', ob);
    if (cb == std::string::npos || cb > listEnd) fail("unterminated entry in \"files\"");
    const std::string obj = text.substr(ob, cb - ob);
    SnapshotEntry e;
    const size_t kn = obj.find("\"name\"");
    const size_t kt = obj.find("\"time\"");
    if (kn == std::string::npos || kt == std::string::npos)
      fail("entry " + std::to_string(out.size()) + " lacks \"name\" or \"time\"");
    const size_t q0 = obj.find('"', obj.find(':', kn) + 1);
    const size_t q1 = obj.find('"', q0 + 1);
    if (q0 == std::string::npos || q1 == std::string::npos)
      fail("entry " + std::to_string(out.size()) + ": \"name\" is not a string");
    e.file = (vtkDir / obj.substr(q0 + 1, q1 - q0 - 1)).string();
    const size_t c = obj.find(':', kt);
    const size_t b = obj.find_first_not_of(" \t\r\n", c + 1);
    if (b == std::string::npos ||
        std::from_chars(obj.data() + b, obj.data() + obj.size(), e.time).ec != std::errc())
      fail("entry " + std::to_string(out.size()) + ": \"time\" is not a number");
    out.push_back(e);
    p = cb + 1;
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const SnapshotEntry& a, const SnapshotEntry& b) { return a.time < b.time; });
  for (size_t i = 1; i < out.size(); ++i)
    if (out[i].time == out[i - 1].time)
      fail("two snapshots with the same time " + std::to_string(out[i].time));
  return out;
}

ParticleSnapshot readSnapshot(const SnapshotEntry& e) {
  const std::string bin = dem::binarySnapshotPath(e.file);
  return fs::is_regular_file(bin) ? readBinarySnapshot(bin, e.time)
                                  : readVtkSnapshot(e.file, e.time);
}

bool snapshotExists(const SnapshotEntry& e) {
  return fs::is_regular_file(e.file) || fs::is_regular_file(dem::binarySnapshotPath(e.file));
}

}  // namespace mixflow::mx
