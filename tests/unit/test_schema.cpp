// Unit tests of the declaration tables: an entry is read as declared (default, range, required),
// undeclared entries are refused naming file, entry and the allowed ones, and the Markdown table
// shows every declared entry with its default, range and unit.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include "MixflowProperties.h"
#include "SceneProperties.h"
#include "Schema.h"

using mixflow::Dictionary;
using mixflow::InputError;
using mixflow::MixflowProperties;
using mixflow::Range;
using mixflow::SceneProperties;

namespace {
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A temporary file holding `text`, removed at the end of the test.
struct TempFile {
  std::string path;
  explicit TempFile(const std::string& text) {
    static int count = 0;
    path = ::testing::TempDir() + "mixflowProperties." + std::to_string(++count);
    std::ofstream(path) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

constexpr SceneProperties::Half kGrains = SceneProperties::Half::grains;

const std::string kDryScene =
    "content particles;\n"
    "sample { length 0.25; height 0.17; width 0.1; }\n"
    "channel { length 0.8; height 0.4; }\n";
}  // namespace

TEST(Schema, ReadsDefaultsRangesAndRequiredEntriesAsDeclared) {
  const mixflow::Schema s("f", {mixflow::scalarParam("a", 2.5, Range::positive(), "m", ""),
                                mixflow::requiredScalar("b", Range::closed(0, 1), "Pa", "")});
  const Dictionary d = Dictionary::parse("b 0.5;", "f");
  EXPECT_DOUBLE_EQ(s.scalar(d, "a"), 2.5);
  EXPECT_DOUBLE_EQ(s.scalar(d, "b"), 0.5);
  const std::string missing = errorOf([&] { s.scalar(Dictionary::parse("", "f"), "b"); });
  EXPECT_TRUE(has(missing, "missing (required)") && has(missing, "Pa") && has(missing, "[0, 1]"))
      << missing;
  EXPECT_TRUE(has(errorOf([&] { s.scalar(Dictionary::parse("a -1;", "f"), "a"); }), "(0, inf)"));
  EXPECT_THROW(s.param("c"), std::logic_error);  // undeclared: a programming error
}

TEST(Schema, MarkdownRowsCarryDefaultRangeAndUnit) {
  const std::string md = SceneProperties::schema().markdown({"particles"});
  EXPECT_TRUE(has(md, "| `particles.diameter` | 0.024 | > 0 | m |")) << md;
  EXPECT_TRUE(has(md, "| `particles.youngModulus` | 7e10 | > 0 | Pa |")) << md;
  EXPECT_FALSE(has(md, "`sample.length`"));
}

TEST(SceneProperties, DefaultsAreTheStructInitializers) {
  const SceneProperties s =
      SceneProperties::read(Dictionary::parse(kDryScene, "sceneProperties"), kGrains);
  const mixflow::ParticleMaterial paper{};
  EXPECT_DOUBLE_EQ(s.particles.diameter, paper.diameter);
  EXPECT_DOUBLE_EQ(s.particles.wallYoungModulus, paper.wallYoungModulus);
  EXPECT_DOUBLE_EQ(s.sample.solidFraction, mixflow::SampleSpec{}.solidFraction);
}

// The geometry rules: the outlet beyond the gate (and one grain), the open top above the column.
TEST(SceneProperties, ChannelMustExceedTheSample) {
  std::string text = kDryScene;
  text.replace(text.find("length 0.8"), 10, "length 0.26");  // L < length <= L + d
  std::string msg = errorOf([&] { SceneProperties::read(Dictionary::parse(text, "sp"), kGrains); });
  EXPECT_TRUE(has(msg, "channel.length") && has(msg, "plus one particle diameter")) << msg;
  text = kDryScene;
  text.replace(text.find("height 0.4"), 10, "height 0.17");  // = H
  msg = errorOf([&] { SceneProperties::read(Dictionary::parse(text, "sp"), kGrains); });
  EXPECT_TRUE(has(msg, "channel.height") && has(msg, "sample height")) << msg;
}

// The DEM half of a mixture takes only liquid.density; the fluid half needs the whole liquid.
TEST(SceneProperties, EachHalfReadsWhatItUses) {
  std::string text = kDryScene + "liquid { density 1260; }\n";
  text.replace(text.find("particles"), 9, "mixture");
  const Dictionary d = Dictionary::parse(text, "sp");
  EXPECT_DOUBLE_EQ(SceneProperties::read(d, kGrains).liquid.density, 1260);
  const std::string msg = errorOf([&] { SceneProperties::read(d, SceneProperties::Half::fluid); });
  EXPECT_TRUE(has(msg, "liquid.rheology") && has(msg, "missing (required)")) << msg;
}

TEST(MixflowProperties, AbsentFileGivesTheDefaults) {
  const MixflowProperties m = MixflowProperties::read("");
  EXPECT_EQ(m.formulation, "B");
  EXPECT_DOUBLE_EQ(m.voidfractionMin, 0.05);
  EXPECT_TRUE(m.continuityVoidfractionRate);
}

TEST(MixflowProperties, ReadsEntriesAndRefusesUnknownOnes) {
  const TempFile ok(
      "FoamFile { version 2.0; }\nviscousStress voidfractionWeighted;\n"
      "continuityVoidfractionRate off;\nvoidfractionMin 0.1;\n"
      "particleRamp { type halfCosineRamp; start 0; duration 0.2; }\n");
  const MixflowProperties m = MixflowProperties::read(ok.path);
  EXPECT_EQ(m.viscousStress, "voidfractionWeighted");
  EXPECT_FALSE(m.continuityVoidfractionRate);
  EXPECT_DOUBLE_EQ(m.voidfractionMin, 0.1);
  EXPECT_TRUE(m.particleRamp);

  const TempFile typo("voidfractionMinimum 0.1;\n");
  const std::string msg = errorOf([&] { MixflowProperties::read(typo.path); });
  EXPECT_TRUE(has(msg, typo.path) && has(msg, "'voidfractionMinimum'") &&
              has(msg, "unknown entry") && has(msg, "voidfractionMin"))
      << msg;
  const TempFile range("voidfractionMin 1;\n");
  EXPECT_TRUE(has(errorOf([&] { MixflowProperties::read(range.path); }), "[0, 1)"));
  const TempFile formulation("formulation A;\n");
  EXPECT_TRUE(has(errorOf([&] { MixflowProperties::read(formulation.path); }), "one of: B"));
}
