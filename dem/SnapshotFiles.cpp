#include "SnapshotFiles.h"

#include <filesystem>

namespace mixflow::dem {

namespace fs = std::filesystem;

const std::string& snapshotColumns() {
  static const std::string s =
      "id type x y z vx vy vz fx fy fz omegax omegay omegaz radius mass c_pstress[1] c_pstress[2] "
      "c_pstress[3] c_pstress[4] c_pstress[5] c_pstress[6]";
  return s;
}

std::string snapshotPattern(const std::string& caseDir, const std::string& ext) {
  return (fs::path(caseDir) / "VTK" / "particles" / ("particles_*." + ext)).string();
}

std::string binarySnapshotPath(const std::string& vtkPath) {
  return fs::path(vtkPath).replace_extension(".bin").string();
}

void removeBinarySnapshots(const std::string& caseDir) {
  const fs::path dir = fs::path(caseDir) / "VTK" / "particles";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("particles_", 0) == 0 && e.path().extension() == ".bin") fs::remove(e.path());
  }
}

}  // namespace mixflow::dem
