// `samples = [...]` in a base-motion table: what the reader and ValidateScene accept and what they
// refuse, each refusal naming the key (and the sample's index) and what was expected, next to a
// value that passes the same rule.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

using testing_util::ErrorOf;

class SamplesSceneTest : public testing_util::ScratchDirTest {};

// Lines 1-4: one block; line 5: [base.horizontal].
const std::string kBlock = "[block1]\nwidth = 1\nheight = 2\nmass = 100\n[base.horizontal]\n";

// The message of parsing kBlock + `table` as scene.toml, or "no error".
std::string ParseError(const std::string& table, const std::vector<std::string>& overrides = {}) {
  return ErrorOf([&] { ParseScene(kBlock + table, "scene.toml", overrides); });
}

// Whether `text` starts with `prefix`.
bool Starts(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

TEST_F(SamplesSceneTest, ReadsNumbersAndIntegers) {
  const Scene s =
      ParseScene(kBlock +
                     "units = \"cm/s2\"\ndt = 0.01\nscale = 2\nstart_s = 0.5\nsamples = [0, "
                     "1.5, -2, 1e-3]\n",
                 "scene.toml");
  ASSERT_TRUE(s.horizontal);
  EXPECT_EQ(s.horizontal->kind, MotionKind::kFile);
  EXPECT_TRUE(s.horizontal->file.empty());
  EXPECT_TRUE(s.horizontal->from_samples());
  EXPECT_EQ(s.horizontal->samples, (std::vector<double>{0.0, 1.5, -2.0, 1e-3}));
  EXPECT_EQ(s.horizontal->units, AccelUnits::kCmps2);
  EXPECT_EQ(s.horizontal->dt_s, 0.01);
  EXPECT_EQ(s.horizontal->scale, 2.0);
  EXPECT_EQ(s.horizontal->start_s, 0.5);
  // cm/s^2 times scale 2: -2 cm/s^2 is -0.04 m/s^2, at start_s + 2 dt.
  const GroundMotion g = GroundMotion::FromScene(s);
  EXPECT_EQ(g.horizontal()->samples_mps2()[2], -2.0 * (0.01 * 2.0));
  EXPECT_EQ(g.horizontal()->t0_s(), 0.5);
}

TEST_F(SamplesSceneTest, ResolutionOnlyForSamplesAndNotNegative) {
  const std::string samples = "units = \"g\"\ndt = 0.01\nsamples = [0, 0.1]\n";
  const Scene s = ParseScene(kBlock + samples + "resolution = 0\n", "scene.toml");
  ASSERT_TRUE(s.horizontal->samples_resolution);
  EXPECT_EQ(*s.horizontal->samples_resolution, 0.0);
  EXPECT_FALSE(ParseScene(kBlock + samples, "scene.toml").horizontal->samples_resolution);
  const std::string negative = ParseError(samples + "resolution = -0.001\n");
  EXPECT_TRUE(Starts(negative, "scene.toml:9: base.horizontal.resolution: expected a number >= 0"))
      << negative;
  const std::string analytic =
      ParseError("kind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 1\nresolution = 0\n");
  EXPECT_NE(analytic.find("base.horizontal.resolution"), std::string::npos) << analytic;
  EXPECT_NE(analytic.find("only for samples"), std::string::npos) << analytic;
  // A scene built in code: ValidateScene refuses a resolution without samples.
  Scene built = ParseScene(kBlock + "kind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 1\n",
                           "scene.toml");
  built.horizontal->samples_resolution = 0.0;
  const std::string code = ErrorOf([&] { ValidateScene(built); });
  EXPECT_NE(code.find("base.horizontal.resolution: only for samples"), std::string::npos) << code;
}

TEST_F(SamplesSceneTest, TheExampleOfScenesMd) {
  // docs/scenes.md's triangle: 0, 0.3, 0, -0.3, 0 g every 0.125 s from 0.5 s, linear between.
  const Scene s = ParseScene(kBlock +
                                 "samples = [0.0, 0.3, 0.0, -0.3, 0.0]\nunits = \"g\"\ndt = "
                                 "0.125\nstart_s = 0.5\n",
                             "scene.toml");
  const GroundMotion g = GroundMotion::FromScene(s);
  const MotionComponent& h = *g.horizontal();
  EXPECT_EQ(h.end_s(), 1.0);
  EXPECT_EQ(h.info().peak_g, 0.3 * kStandardGravity_mps2 / kStandardGravity_mps2);
  EXPECT_EQ(h.info().peak_t_s, 0.625);
  // Half way up the first ramp: 0.15 g (1e-15 m/s^2: the interpolation's rounding).
  EXPECT_NEAR(h.accel_mps2(0.5625), 0.15 * kStandardGravity_mps2, 1e-15);
  EXPECT_EQ(h.accel_mps2(0.5 - 1e-9), 0.0);
  EXPECT_EQ(h.accel_mps2(1.0 + 1e-9), 0.0);
}

TEST_F(SamplesSceneTest, EachSampleIsAFiniteNumberNamedByItsIndexAndLine) {
  // Lines 6-13: units, dt and the array, one sample a line.
  const std::string head = "units = \"g\"\ndt = 0.01\nsamples = [\n  0.0,\n  0.1,\n  -0.2,\n";
  EXPECT_EQ(ParseError(head + "  0.3,\n]\n"), "no error");
  EXPECT_EQ(ParseError(head + "  \"abc\",\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got \"abc\"");
  EXPECT_EQ(ParseError(head + "  nan,\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got nan");
  EXPECT_EQ(ParseError(head + "  inf,\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got inf");
  EXPECT_EQ(ParseError(head + "  -inf,\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got -inf");
  EXPECT_EQ(ParseError(head + "  true,\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got true");
  EXPECT_EQ(ParseError(head + "  [1],\n]\n"),
            "scene.toml:12: base.horizontal.samples[3]: expected a finite number, got an array");
  EXPECT_EQ(ParseError("units = \"g\"\ndt = 0.01\nsamples = 0.5\n"),
            "scene.toml:8: base.horizontal.samples: expected an array of numbers (the "
            "acceleration in units, one every dt), got 0.5");
}

TEST_F(SamplesSceneTest, BeyondTheAccelerationLimitAsARecordFileSaysIt) {
  // 100 g passes; 100.5 g does not: the message is the file's, with the key and index in place
  // of the file, line and sample number.
  const std::string g = "units = \"g\"\ndt = 0.01\n";
  EXPECT_EQ(ParseError(g + "samples = [0, 100, -100]\n"), "no error");
  const std::string samples_msg = ParseError(g + "samples = [0, 100, -100.5]\n");
  Write("x.txt", "0\n100\n-100.5\n");
  const std::string file_msg = ErrorOf([&] {
    GroundMotion::FromScene(ParseScene(kBlock + g + "file = \"x.txt\"\n", dir_ / "s.toml"));
  });
  const std::string file_where = (dir_ / "x.txt").string() + ":3: sample 3";
  ASSERT_TRUE(Starts(file_msg, file_where)) << file_msg;
  EXPECT_EQ(samples_msg,
            "scene.toml:8: base.horizontal.samples[2]" + file_msg.substr(file_where.size()));
  EXPECT_EQ(samples_msg,
            "scene.toml:8: base.horizontal.samples[2] = -100.5 g; expected an acceleration with "
            "magnitude at most 100 g (far above any recorded ground motion, about 4 g; "
            "docs/limits.md)");
  // In m/s2 with a scale: the same words as the file's, with the scale and the value in g.
  const std::string mps2 = "units = \"m/s2\"\ndt = 0.01\nscale = 2\n";
  EXPECT_EQ(ParseError(mps2 + "samples = [0, 490]\n"), "no error");
  Write("y.txt", "0\n491\n");
  const std::string file_scaled = ErrorOf([&] {
    GroundMotion::FromScene(ParseScene(kBlock + mps2 + "file = \"y.txt\"\n", dir_ / "s.toml"));
  });
  const std::string where_scaled = (dir_ / "y.txt").string() + ":2: sample 2";
  ASSERT_TRUE(Starts(file_scaled, where_scaled)) << file_scaled;
  EXPECT_EQ(ParseError(mps2 + "samples = [0, 491]\n"),
            "scene.toml:9: base.horizontal.samples[1]" + file_scaled.substr(where_scaled.size()));
  EXPECT_NE(file_scaled.find(" = 491 m/s2 times base.horizontal.scale = 2 is 100.136 g;"),
            std::string::npos)
      << file_scaled;
}

TEST_F(SamplesSceneTest, AtLeastTwoSamples) {
  const std::string head = "units = \"g\"\ndt = 0.01\n";
  EXPECT_EQ(ParseError(head + "samples = [0, 0.1]\n"), "no error");
  EXPECT_EQ(ParseError(head + "samples = [0.1]\n"),
            "scene.toml:8: base.horizontal.samples: expected at least 2 samples (a record lasts "
            "from its first sample to its last), got 1");
  EXPECT_TRUE(Starts(ParseError(head + "samples = []\n"),
                     "scene.toml:8: base.horizontal.samples: expected at least 2 samples"));
  EXPECT_NE(ParseError(head + "samples = []\n").find("got 0"), std::string::npos);
}

TEST_F(SamplesSceneTest, OneOfFileKindOrSamples) {
  const std::string samples = "units = \"g\"\ndt = 0.01\nsamples = [0, 0.1]\n";
  Write("x.txt", "0\n0.1\n");
  const std::string with_file =
      ErrorOf([&] { ParseScene(kBlock + samples + "file = \"x.txt\"\n", dir_ / "s.toml"); });
  EXPECT_EQ(with_file, (dir_ / "s.toml").string() +
                           ":5: base.horizontal: give one of file, kind or samples, not several "
                           "(file and samples)");
  EXPECT_EQ(ParseError(samples + "kind = \"harmonic\"\n"),
            "scene.toml:5: base.horizontal: give one of file, kind or samples, not several (kind "
            "and samples)");
  EXPECT_TRUE(Starts(ParseError("scale = 1\n"),
                     "scene.toml:5: base.horizontal: missing file = \"...\", samples = [...] or "
                     "kind = "));
}

TEST_F(SamplesSceneTest, UnitsAndDtAreRequired) {
  EXPECT_EQ(ParseError("dt = 0.01\nsamples = [0, 0.1]\n"),
            "scene.toml:5: base.horizontal.units: missing; samples must state their units: "
            "\"g\", \"m/s2\" or \"cm/s2\"");
  EXPECT_EQ(ParseError("units = \"g\"\nsamples = [0, 0.1]\n"),
            "scene.toml:5: base.horizontal.dt: missing; samples need their sample interval: dt "
            "= ... (s)");
  EXPECT_TRUE(Starts(ParseError("units = \"mm/s2\"\ndt = 0.01\nsamples = [0, 0.1]\n"),
                     "scene.toml:6: base.horizontal.units: expected \"g\", \"m/s2\" or "
                     "\"cm/s2\", got \"mm/s2\""));
  // dt: a record's sample interval, 1e-6 to 1 s (as for a one-column file).
  EXPECT_EQ(ParseError("units = \"g\"\ndt = 1\nsamples = [0, 0.1]\n"), "no error");
  EXPECT_TRUE(Starts(ParseError("units = \"g\"\ndt = 2\nsamples = [0, 0.1]\n"),
                     "scene.toml:7: base.horizontal.dt: expected a positive number (s) from "
                     "1e-06 to 1"));
  EXPECT_TRUE(Starts(ParseError("units = \"g\"\ndt = -0.01\nsamples = [0, 0.1]\n"),
                     "scene.toml:7: base.horizontal.dt: expected a positive number (s)"));
}

TEST_F(SamplesSceneTest, AnalyticAndSyntheticKeysAreRefused) {
  const std::string samples = "units = \"g\"\ndt = 0.01\nsamples = [0, 0.1]\n";
  for (const std::string key : {"amplitude_g", "frequency_hz", "duration_s"}) {
    EXPECT_EQ(ParseError(samples + key + " = 1\n"),
              "scene.toml:9: base.horizontal." + key +
                  ": only for analytic kinds (kind = ...), not for samples");
  }
  for (const std::string key : {"intensity", "ground_frequency_hz", "seed", "rise_s"}) {
    EXPECT_EQ(ParseError(samples + key + " = 1\n"),
              "scene.toml:9: base.horizontal." + key +
                  ": only for kind = \"kanai_tajimi\", not for samples");
  }
  EXPECT_TRUE(Starts(ParseError(samples + "speed = 1\n"),
                     "scene.toml:9: base.horizontal.speed: unknown key"));
}

TEST_F(SamplesSceneTest, AtMostADayLong) {
  // 86401 samples at dt = 1 s last 86400 s (a day): fine; one more is refused.
  std::string array = "samples = [0";
  for (int i = 1; i < 86401; ++i) array += ",0";
  const std::string head = "units = \"g\"\ndt = 1\n";
  EXPECT_EQ(ParseError(head + array + "]\n"), "no error");
  EXPECT_EQ(ParseError(head + array + ",0]\n"),
            "scene.toml: base.horizontal.samples: 86402 samples at dt = 1 s last more than a day "
            "(86400 s; docs/limits.md)");
}

TEST_F(SamplesSceneTest, Overrides) {
  const std::string table = "units = \"g\"\ndt = 0.01\nsamples = [0, 0]\n";
  const Scene s = ParseScene(kBlock + table, "scene.toml", {"base.horizontal.samples=[0, 0.2, 1]"});
  EXPECT_EQ(s.horizontal->samples, (std::vector<double>{0.0, 0.2, 1.0}));
  EXPECT_EQ(ParseError(table, {"base.horizontal.samples=[0, 0.2, \"x\"]"}),
            "scene.toml: override \"base.horizontal.samples=[0, 0.2, \"x\"]\": "
            "base.horizontal.samples[2]: expected a finite number, got \"x\"");
}

TEST_F(SamplesSceneTest, ValidateSceneChecksASceneBuiltInCode) {
  Scene s = ParseScene(kBlock + "units = \"g\"\ndt = 0.01\nsamples = [0, 0.1]\n", "");
  EXPECT_NO_THROW(ValidateScene(s));
  const MotionDef good = *s.horizontal;
  const auto error = [&](const MotionDef& m) {
    Scene t = s;
    t.horizontal = m;
    return ErrorOf([&] { ValidateScene(t); });
  };
  MotionDef m = good;
  m.samples = {0.0};
  EXPECT_EQ(error(m),
            "scene: base.horizontal.samples: expected at least 2 samples (a record lasts from its "
            "first sample to its last), got 1");
  m = good;
  m.samples[1] = std::nan("");
  EXPECT_EQ(error(m), "scene: base.horizontal.samples[1]: expected a finite number, got nan");
  m.samples[1] = -INFINITY;
  EXPECT_EQ(error(m), "scene: base.horizontal.samples[1]: expected a finite number, got -inf");
  m.samples[1] = 100.0;
  EXPECT_EQ(error(m), "no error");
  m.samples[1] = 100.5;
  EXPECT_EQ(error(m),
            "scene: base.horizontal.samples[1] = 100.5 g; expected an acceleration with magnitude "
            "at most 100 g (far above any recorded ground motion, about 4 g; docs/limits.md)");
  m = good;
  m.units_given = false;
  EXPECT_TRUE(Starts(error(m), "scene: base.horizontal.units: missing")) << error(m);
  m = good;
  m.dt_s = 0.0;
  EXPECT_TRUE(Starts(error(m), "scene: base.horizontal.dt: missing")) << error(m);
  m.dt_s = 2.0;
  EXPECT_TRUE(Starts(error(m),
                     "scene: base.horizontal.dt: expected a positive number (s) from "
                     "1e-06 to 1"))
      << error(m);
  m = good;
  m.file = "x.txt";
  EXPECT_EQ(error(m),
            "scene: base.horizontal: give one of file, kind or samples, not several (file and "
            "samples)");
  m = good;
  m.kind = MotionKind::kRicker;
  m.amplitude_g = 0.1;
  m.frequency_hz = 1.0;
  EXPECT_EQ(error(m),
            "scene: base.horizontal: give one of file, kind or samples, not several (kind = "
            "\"ricker\" and samples)");
  m.samples.clear();
  EXPECT_EQ(error(m), "no error");
}

}  // namespace
}  // namespace rockbench
