// OpenFOAM ASCII reader of the fluid source (mixture_extract/FoamFluidSource.cpp): uniform and
// nonuniform internal fields, C and V from postProcess, a serial and a decomposed case, errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "Dictionary.h"
#include "FluidSource.h"

using namespace mixflow::mx;
namespace fs = std::filesystem;

namespace {

void field(const fs::path& file, const std::string& cls, const std::string& internal) {
  fs::create_directories(file.parent_path());
  std::ofstream f(file);
  f << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " << cls << ";\n    object "
    << file.filename().string() << ";\n}\n"
    << "dimensions [0 0 0 0 0 0 0];\n\ninternalField " << internal
    << ";\n\nboundaryField\n{\n    walls { type zeroGradient; }\n}\n";
}

// Three cells at x = 0.1, 0.2, 0.3 (offset shifts them), time 0.5.
void writeRoot(const fs::path& root, double offset, bool uniformAlpha) {
  const std::string t = "0.5";
  auto x = [&](int i) { return std::to_string(0.1 * (i + 1) + offset); };
  field(root / t / "C", "volVectorField",
        "nonuniform List<vector> \n3\n(\n(" + x(0) + " 0.05 0.01)\n(" + x(1) + " 0.05 0.01)\n(" +
            x(2) + " 0.15 0.01)\n)\n");
  field(root / "constant" / "V", "volScalarField", "nonuniform List<scalar> 3(1e-6 2e-6 3e-6)");
  field(root / t / "U", "volVectorField", "nonuniform List<vector> 3((1 2 0) (3 4 0) (5 6 0.5))");
  field(root / t / "p", "volScalarField", "uniform 101325");
  field(root / t / "alpha.water", "volScalarField",
        uniformAlpha ? "uniform 1" : "nonuniform List<scalar>\n3\n(\n1\n0.5\n0\n)\n");
  field(root / t / "voidfraction", "volScalarField", "uniform 0.4");
}

}  // namespace

TEST(FoamFluidSource, ReadsSerialCase) {
  const fs::path dir = fs::temp_directory_path() / "mx_foam_serial";
  fs::remove_all(dir);
  writeRoot(dir, 0.0, false);
  field(dir / "0" / "U", "volVectorField", "uniform (0 0 0)");  // 0/ without p: still a time
  FoamFieldNames names;
  ASSERT_TRUE(FoamFluidSource::present(dir.string(), names));
  FoamFluidSource src(dir.string(), names);
  ASSERT_EQ(src.times().size(), 2u);
  EXPECT_EQ(src.times()[1], 0.5);
  const FluidCells c = src.cells(0.5);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_DOUBLE_EQ(c.x[2], 0.3);
  EXPECT_DOUBLE_EQ(c.y[2], 0.15);
  EXPECT_DOUBLE_EQ(c.volume[1], 2e-6);
  EXPECT_DOUBLE_EQ(c.ux[1], 3);
  EXPECT_DOUBLE_EQ(c.uy[2], 6);
  EXPECT_DOUBLE_EQ(c.p[0], 101325);
  EXPECT_DOUBLE_EQ(c.alphaL[1], 0.5);
  EXPECT_DOUBLE_EQ(c.epsF[2], 0.4);
  // 0/ lacks the cell centres: a clear message naming the file and the command that writes it.
  try {
    src.cells(0.0);
    FAIL() << "expected an InputError";
  } catch (const mixflow::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/0/C"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("writeCellCentres"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(FoamFluidSource, ConcatenatesProcessors) {
  const fs::path dir = fs::temp_directory_path() / "mx_foam_decomposed";
  fs::remove_all(dir);
  writeRoot(dir / "processor0", 0.0, true);
  writeRoot(dir / "processor1", 1.0, false);
  FoamFieldNames names;
  FoamFluidSource src(dir.string(), names);
  ASSERT_EQ(src.times().size(), 1u);
  const FluidCells c = src.cells(0.5);
  ASSERT_EQ(c.size(), 6u);
  EXPECT_DOUBLE_EQ(c.x[3], 1.1);
  EXPECT_DOUBLE_EQ(c.alphaL[1], 1.0);
  EXPECT_DOUBLE_EQ(c.alphaL[4], 0.5);
  fs::remove_all(dir);
}

TEST(FoamFluidSource, BadFieldsNameTheFile) {
  const fs::path dir = fs::temp_directory_path() / "mx_foam_bad";
  fs::remove_all(dir);
  writeRoot(dir, 0.0, false);
  field(dir / "0.5" / "p", "volScalarField", "nonuniform List<scalar> 2(1 2)");
  FoamFieldNames names;
  FoamFluidSource src(dir.string(), names);
  try {
    src.cells(0.5);
    FAIL() << "expected an InputError";
  } catch (const mixflow::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("0.5/p"), std::string::npos) << m;
    EXPECT_NE(m.find("2 cells"), std::string::npos) << m;
  }
  names.voidFraction = "none";
  names.volumes = "Vmissing";
  FoamFluidSource src2(dir.string(), names);
  try {
    src2.cells(0.5);
    FAIL() << "expected an InputError";
  } catch (const mixflow::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Vmissing"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}
