// Physical and resource limits of the inputs (scene/limits.h, docs/limits.md): every limit is
// refused with a message naming the file, line, key, value and the limit; input files must be
// regular files; readers refuse CR-only line endings and impossible NPTS; messages never echo
// long values in full.
#include "scene/limits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "scene/engine_settings.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"
#include "tests/common/scene_text.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "'" << (needle) << "' not in '" << (haystack) << "'"

// A valid two-block scene; tests append or edit tables.
const std::string& kBlocks = testing_util::kThesisBlocksToml;
const std::string kHarmonic =
    "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.3\nfrequency_hz = 2.0\n";

// Every limited key, at a value past its limit, through the override that a user (or a study)
// would write: the message names the override, the key, the value and the limit.
TEST(SceneLimits, EveryLimitedKeyNamesItsLimit) {
  struct Case {
    std::string set, piece;
  };
  const std::vector<Case> cases = {
      {"block1.width=5e-324", "block1.width: expected a positive number (m) from 0.0001 to 10000"},
      {"block1.height=1e5", "block1.height: expected a positive number (m) from 0.0001 to 10000"},
      {"block2.depth=1e-9", "block2.depth: expected"},
      {"block1.density=1e9", "block1.density: expected a positive number (kg/m^3) from 0.001"},
      {"run.duration=1e9", "run.duration: expected a positive number (s) at most 86400"},
      {"run.gravity=1e300", "run.gravity: expected a positive number (m/s^2) from 0.01 to 1000"},
      {"model.rtol=1e-300", "model.rtol: expected a positive number from 1e-15 to 0.1"},
      {"model.atol=1e-300", "model.atol: expected a positive number (rad, rad/s) from 1e-20"},
      {"model.overturn_angle=2",
       "model.overturn_angle: expected a positive number (rad) at most "
       "1.5707963267948966"},
      {"initial.omega1=1e6",
       "initial.omega1: expected a finite number (rad/s) with magnitude at "
       "most 100"},
      {"base.horizontal.frequency_hz=1e12",
       "base.horizontal.frequency_hz: expected a positive "
       "number (Hz) at most 1000"},
      {"base.horizontal.amplitude_g=1e308",
       "base.horizontal.amplitude_g: expected a finite number "
       "(g) with magnitude at most 100"},
      {"base.horizontal.duration_s=1e12", "base.horizontal.duration_s: expected"},
      {"base.horizontal.start_s=1e12", "base.horizontal.start_s: expected"},
  };
  const std::string scene = kBlocks + kHarmonic;
  ASSERT_EQ(testing_util::SceneErrorOf(scene), "");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.set);
    const std::string e = testing_util::SceneErrorOf(scene, {c.set});
    EXPECT_CONTAINS(e, "scenes/x.toml: override \"" + c.set + "\"");
    EXPECT_CONTAINS(e, c.piece);
  }
}

// A value in the file is named with its line.
TEST(SceneLimits, AFileValueIsNamedWithItsLine) {
  const std::string e = testing_util::SceneErrorOf(
      "[block1]\nwidth = 1.25\nheight = 5e-324\ndensity = 2500.0\n" + kHarmonic);
  EXPECT_CONTAINS(e, "scenes/x.toml:3: block1.height:");
  EXPECT_CONTAINS(e, "got 5e-324");
}

// amplitude_g and scale are each within the limit, their product is not: the scale is named.
TEST(SceneLimits, AnOverflowingScaleIsNamed) {
  const std::string e = testing_util::SceneErrorOf(kBlocks + kHarmonic + "scale = 1e307\n");
  EXPECT_CONTAINS(e, "base.horizontal.scale: amplitude_g * scale = 3e+306 g");
  EXPECT_CONTAINS(e, "expected an acceleration (g) with magnitude at most 100 (far above");
}

// A mass given by density is checked as a mass.
TEST(SceneLimits, AMassFromDensityIsWithinTheMassLimit) {
  const std::string e = testing_util::SceneErrorOf(
      "[block1]\nwidth = 10000\nheight = 10000\ndepth = 10000\ndensity = 100000\n" + kHarmonic);
  EXPECT_CONTAINS(e, "block1.density: density * width * height * depth = 1e+17 kg");
}

// One validity rule for every engine: the scene reader (which every engine's run goes through)
// refuses what the reference cannot describe, naming the key, value and line.
TEST(SceneLimits, TheStackRulesAreTheReaders) {
  const std::string single =
      "[block1]\nwidth = 0.2\nheight = 1.0\ndensity = 2000.0\n[initial]\ntheta1 = 2.0\n";
  const std::string e = testing_util::SceneErrorOf(single);
  EXPECT_CONTAINS(e,
                  "scenes/x.toml:6: initial.theta1: expected |theta1| below "
                  "model.overturn_angle (1.5707963267948966 rad");
  EXPECT_CONTAINS(e, "got 2");
  // With a smaller overturn angle the same rule follows it.
  EXPECT_CONTAINS(testing_util::SceneErrorOf(
                      kBlocks + "[initial]\ntheta2 = 0.5\n[model]\noverturn_angle = 0.4\n"),
                  "initial.theta2: expected |theta2| below model.overturn_angle (0.4 rad");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"block2.width=1.5"}),
                  "block2.width: expected at most block1.width (1.25 m");
  // A scene built in code gets the same rules from ValidateScene.
  Scene s = ParseScene(kBlocks, "scenes/x.toml");
  s.initial.theta_rad[0] = -1.6;
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { ValidateScene(s); }),
                  "initial.theta1: expected |theta1| below model.overturn_angle");
  s.initial.theta_rad[0] = 0.0;
  s.blocks[0].width_m = 5e-324;
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { ValidateScene(s); }),
                  "block1.width: expected a positive number (m) from 0.0001");
}

// Messages echo a long value as a short excerpt.
TEST(SceneLimits, LongValuesAreCutToAnExcerpt) {
  const std::string huge(1 << 20, 'x');
  const std::string e =
      testing_util::SceneErrorOf(kBlocks + "[model]\nintegrator = \"" + huge + "\"\n");
  EXPECT_CONTAINS(e, "model.integrator: expected \"dopri5\", \"dop853\" or \"rk4\", got \"xxx");
  EXPECT_CONTAINS(e, "... (1048576 bytes)");
  EXPECT_LT(e.size(), 400u);
  const std::string o = testing_util::SceneErrorOf(kBlocks, {"block1." + huge + "=1"});
  EXPECT_LT(o.size(), 400u);
  EXPECT_CONTAINS(o, "unknown key");
  EXPECT_EQ(Excerpt(std::string_view("a\rb\n\t\0\x01", 7)), "a\\rb\\n\\t\\0\\x01");
}

class InputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("rockbench_limits_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  fs::path dir_;
};

std::string LoadError(const fs::path& p) {
  try {
    LoadScene(p);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST_F(InputFiles, AFolderADeviceAMissingFileAndANulAreNamed) {
  EXPECT_CONTAINS(LoadError(dir_), "is a folder; expected a scene file");
  EXPECT_CONTAINS(LoadError("/dev/zero"),
                  "/dev/zero: is not a regular file (a device, pipe or "
                  "socket); expected a scene file");
  EXPECT_CONTAINS(LoadError(dir_ / "none.toml"), "none.toml: no such scene file");
  EXPECT_CONTAINS(LoadError(fs::path(std::string("a\0b.toml", 8))),
                  "a\\0b.toml: the path holds "
                  "a NUL character");
  const std::string long_name(100000, 'a');
  const std::string e = LoadError(dir_ / long_name);
  EXPECT_LT(e.size(), 400u);
  EXPECT_CONTAINS(e, "bytes)");
  // A record that is a device: named as such, not "file not found".
  const fs::path scene = Write("s.toml", kBlocks +
                                             "[base.horizontal]\nfile = \"/dev/null\"\n"
                                             "units = \"g\"\ndt = 0.01\n");
  EXPECT_CONTAINS(LoadError(scene),
                  "s.toml:10: base.horizontal.file: /dev/null: is not a regular "
                  "file");
}

std::string RecordError(const fs::path& p) {
  try {
    if (IsAt2File(p)) {
      ReadAt2(p);
    } else {
      ReadPlain(p, 0.01);
    }
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const std::string kAt2Head =
    "PEER NGA STRONG MOTION DATABASE RECORD\nSomewhere, 1/1/2000, X, 0\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n";

TEST_F(InputFiles, RecordsRefuseCrOnlyLinesAndImpossibleNpts) {
  // CR-only line endings: named at the line the first CR ends, without echoing the file.
  std::string cr = kAt2Head + "NPTS=    3, DT=   .0100 SEC\n  .1  .2  .3\n";
  for (char& c : cr) c = c == '\n' ? '\r' : c;
  cr += std::string(200000, ' ');
  const std::string e = RecordError(Write("cr.AT2", cr));
  EXPECT_CONTAINS(e, "cr.AT2:1: a line ends with a carriage return (CR) alone");
  EXPECT_LT(e.size(), 400u);
  // CR LF is read as before.
  std::string crlf = kAt2Head + "NPTS=    3, DT=   .0100 SEC\n  .1  .2  .3\n";
  std::string converted;
  for (char c : crlf) converted += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(ReadAt2(Write("crlf.AT2", converted)).values.size(), 3u);
  // NPTS must be a whole number that the file can hold.
  EXPECT_CONTAINS(RecordError(Write("half.AT2", kAt2Head + "NPTS= 3.5, DT= .01 SEC\n.1 .2 .3\n")),
                  "half.AT2:4: expected NPTS as a positive whole number, got '3.5'");
  EXPECT_CONTAINS(RecordError(Write("e9.AT2", kAt2Head + "NPTS= 1e9, DT= .01 SEC\n.1 .2 .3\n")),
                  "e9.AT2:4: expected NPTS as a positive whole number, got '1e9'");
  EXPECT_CONTAINS(
      RecordError(Write("big.AT2", kAt2Head + "NPTS= 100000000, DT= .01 SEC\n.1 .2 .3\n")),
      "big.AT2:4: NPTS = 100000000 values cannot fit in the file's");
  EXPECT_CONTAINS(RecordError("/dev/zero"), "/dev/zero: is not a regular file");
}

// Fuzz findings (tests/fuzz/regressions): a header line of tens of kB overflowed std::regex's
// recursion (a segmentation fault, no message); a time column spanning 1e308 s gave an infinite
// PGV. Both are refused naming the line.
TEST_F(InputFiles, LongHeaderLinesAndAbsurdTimesAreRefused) {
  const std::string units = "ACCELERATION " + std::string(100000, 'x');
  const std::string e = RecordError(
      Write("long.AT2", "PEER\nSomewhere\n" + units + "\nNPTS= 3, DT= .01 SEC\n.1 .2 .3\n"));
  EXPECT_CONTAINS(e, "long.AT2:3: header line of 100013 characters");
  EXPECT_CONTAINS(e, "expected at most 1024");
  EXPECT_LT(e.size(), 400u);
  const auto two_columns = [&](const std::string& name, const std::string& text) {
    try {
      ReadPlain(Write(name, text), 0.0);
    } catch (const SceneError& err) {
      return std::string(err.what());
    }
    return std::string();
  };
  EXPECT_CONTAINS(two_columns("t.txt", "-1e308 0.1\n0 0.2\n"),
                  "t.txt:1: time -1e+308 s; expected a time with magnitude at most 86400 s");
  EXPECT_CONTAINS(RecordError(Write("dt.AT2", kAt2Head + "NPTS= 3, DT= 100 SEC\n.1 .2 .3\n")),
                  "dt.AT2:4: DT = 100 s: expected a sample interval from 1e-06 to 1 s");
  EXPECT_CONTAINS(two_columns("slow.txt", "0 0.1\n50 0.2\n"),
                  "slow.txt:2: the time step 50 s: expected a sample interval");
}

// A finite but absurd sample (1e20 g) is refused with its line, never run.
TEST_F(InputFiles, AnAbsurdSampleIsRefusedWithItsLine) {
  MotionDef d;
  d.key = "base.horizontal";
  d.kind = MotionKind::kFile;
  d.file = Write("abs.AT2", kAt2Head + "NPTS= 3, DT= .01 SEC\n.1 .2\n1e20\n");
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { MotionComponent::FromDef(d); }),
                  "abs.AT2:6: sample 3 = 1e+20 g; expected an acceleration with "
                  "magnitude at most 100 g");
  // A plain file in cm/s2 scaled past the limit names the scale.
  d.file = Write("abs.txt", "0.1\n0.2\n100\n");
  d.units = AccelUnits::kCmps2;
  d.units_given = true;
  d.dt_s = 0.01;
  d.scale = 2000.0;
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { MotionComponent::FromDef(d); }),
                  "abs.txt:3: sample 3 = 100 cm/s2 times base.horizontal.scale = "
                  "2000 is 203.943 g");
}

// Every engine number is at most 1e6 in magnitude and not subnormal (MuJoCo's impratio =
// 1e300 made every step non-finite); inf stays allowed where the schema allows it.
TEST(SceneLimits, EngineNumbersAreBounded) {
  EngineSettingsSchema schema;
  schema.engine = "fake";
  schema.Number("impratio", 1.0, SettingRange::kPositive, "", "1", "ratio")
      .Number("friction", 0.5, SettingRange::kNonNegativeOrInfinite, "", "-", "mu");
  const auto error = [&](const std::string& table) {
    try {
      ResolveEngineSettings(ParseScene(kBlocks + "[fake]\n" + table, "scenes/x.toml"), schema);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_CONTAINS(error("impratio = 1e300\n"),
                  "scenes/x.toml:10: fake.impratio: expected a positive number, with magnitude at "
                  "most 1e6 and not subnormal (docs/limits.md), got 1e+300");
  EXPECT_CONTAINS(error("impratio = 5e-324\n"), "not subnormal");
  EXPECT_EQ(error("impratio = 1e6\nfriction = inf\n"), "");
  EXPECT_CONTAINS(error("friction = 1e7\n"), "fake.friction: expected a number >= 0, or inf");
  // compare.sample_precision: at most 100 half-digits (1e300 made every member non-finite).
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"compare.sample_precision=1e300"}),
                  "compare.sample_precision: expected a number >= 0 at most 100");
}

TEST(ResourceBudget, AnEstimatePastTheBudgetNamesKeyAndFigures) {
  ResourceBudget budget;
  budget.memory_bytes = 1024.0 * 1024 * 1024;
  CheckMemoryEstimate(1e9, budget, "x.toml", "run.output_interval", "rows");
  try {
    CheckMemoryEstimate(3.0 * 1024 * 1024 * 1024, budget, "x.toml", "run.output_interval",
                        "3e9 history rows");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "x.toml: run.output_interval: needs an estimated 3 GiB (3e9 history rows), more "
              "than the memory budget of 1 GiB: shorten or coarsen it, or raise the budget with "
              "--memory-budget GIB");
  }
  EXPECT_EQ(ByteText(1536.0), "1.5 KiB");
  EXPECT_EQ(ByteText(std::numeric_limits<double>::infinity()), "an unbounded amount");
}

}  // namespace
}  // namespace rockbench
