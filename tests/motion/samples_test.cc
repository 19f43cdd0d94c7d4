// A base-motion table given by its samples (`samples = [...]`, dt, units) is the same motion as a
// plain one-column record file holding those samples' shortest texts with that dt and units:
// the same accelerations, peak, padding, resolution, intensity measures and reference run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "run/engine_run.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = std::numbers::pi;
const fs::path kScenes = fs::path(ROCKBENCH_SOURCE_DIR) / "scenes";

class SamplesTest : public testing_util::ScratchDirTest {};

// The blocks of the shipped scene (the thesis's geometry), a start tilt so that the stack rocks
// whatever the ground does, and a 1 s run.
std::string BlocksAndRun() {
  const Scene shipped = LoadScene(kScenes / "harmonic.toml");
  std::string out;
  for (int k = 1; k <= shipped.block_count(); ++k) {
    const BlockDef& b = shipped.blocks[k - 1];
    out += "[block" + std::to_string(k) + "]\nwidth = " + ShortestText(b.width_m) +
           "\nheight = " + ShortestText(b.height_m) +
           "\ndensity = " + ShortestText(b.density_kgpm3) + "\n";
  }
  return out +
         "[initial]\ntheta1 = 0.02\n[run]\nduration = 1.0\noutput_interval = 0.005\n"
         "[compare]\nmembers = 0\n";
}

// amp sin(2 pi f t) at t = i dt, i = 0..n-1, in the table's units.
std::vector<double> Sine(double amp, double f_hz, double dt_s, int n) {
  std::vector<double> a;
  for (int i = 0; i < n; ++i) a.push_back(amp * std::sin(2.0 * kPi * f_hz * i * dt_s));
  return a;
}

// The values as a one-column file (their shortest texts, one a line, under a header line) and as
// a TOML array.
std::string ColumnText(const std::vector<double>& a) {
  std::string out = "acceleration\n";
  for (double v : a) out += ShortestText(v) + "\n";
  return out;
}
std::string TomlArray(const std::vector<double>& a) {
  std::string out = "[";
  for (size_t i = 0; i < a.size(); ++i) out += (i > 0 ? ", " : "") + ShortestText(a[i]);
  return out + "]";
}

// One base-motion table: `source` is `file = "..."` or `samples = [...]`.
std::string MotionTable(const std::string& key, const std::string& source, const std::string& units,
                        double dt_s, const std::string& more = "") {
  return "[base." + key + "]\n" + source + "\nunits = \"" + units +
         "\"\ndt = " + ShortestText(dt_s) + "\n" + more;
}

// Both components agree sample for sample, at many times between and beyond the samples, in
// peak, padding, resolution and intensity measures.
void ExpectSameComponent(const MotionComponent& file, const MotionComponent& samples,
                         double t_end_s) {
  EXPECT_EQ(file.info().format, "plain-1col");
  EXPECT_EQ(samples.info().format, "samples");
  EXPECT_EQ(samples.info().source,
            "samples (" +
                std::to_string(file.samples_mps2().size() -
                               static_cast<size_t>(file.info().padded_samples)) +
                " values)");
  EXPECT_EQ(samples.samples_mps2(), file.samples_mps2());
  EXPECT_EQ(samples.sample_resolution_mps2(), file.sample_resolution_mps2());
  EXPECT_EQ(samples.t0_s(), file.t0_s());
  EXPECT_EQ(samples.dt_s(), file.dt_s());
  EXPECT_EQ(samples.end_s(), file.end_s());
  EXPECT_EQ(samples.info().npts, file.info().npts);
  EXPECT_EQ(samples.info().dt_s, file.info().dt_s);
  EXPECT_EQ(samples.info().duration_s, file.info().duration_s);
  EXPECT_EQ(samples.info().peak_g, file.info().peak_g);
  EXPECT_EQ(samples.info().peak_t_s, file.info().peak_t_s);
  EXPECT_EQ(samples.info().padded_samples, file.info().padded_samples);
  // 10007 times (a prime count: most fall between samples), from before the start to past the end.
  for (int i = 0; i <= 10007; ++i) {
    const double t = -0.1 + (t_end_s + 0.2) * i / 10007.0;
    ASSERT_EQ(samples.accel_mps2(t), file.accel_mps2(t)) << t;
    ASSERT_EQ(samples.next_breakpoint_after(t), file.next_breakpoint_after(t)) << t;
  }
  const IntensityMeasures a = MeasureIntensity(file, t_end_s);
  const IntensityMeasures b = MeasureIntensity(samples, t_end_s);
  EXPECT_EQ(b.pga_mps2, a.pga_mps2);
  EXPECT_EQ(b.pga_t_s, a.pga_t_s);
  EXPECT_EQ(b.pgv_mps, a.pgv_mps);
  EXPECT_EQ(b.pgd_m, a.pgd_m);
  EXPECT_EQ(b.arias_mps, a.arias_mps);
  EXPECT_EQ(b.significant_duration_s, a.significant_duration_s);
}

// The reference's history of a scene as history.csv's text.
std::string ReferenceCsv(const Scene& scene, const GroundMotion& motion) {
  return HistoryToCsv(RunEngine("reference", scene, motion).history);
}

TEST_F(SamplesTest, SameMotionAsAPlainFileInMps2) {
  // 0.3 g at 2 Hz, in m/s^2, every 5 ms for 1 s (201 samples).
  const double dt = 0.005;
  const std::vector<double> a = Sine(0.3 * kStandardGravity_mps2, 2.0, dt, 201);
  Write("motion.txt", ColumnText(a));
  const std::string head = BlocksAndRun();
  const Scene from_file = ParseScene(
      head + MotionTable("horizontal", "file = \"motion.txt\"", "m/s2", dt), dir_ / "a.toml");
  const Scene from_samples = ParseScene(
      head + MotionTable("horizontal", "samples = " + TomlArray(a), "m/s2", dt), dir_ / "b.toml");
  ASSERT_TRUE(from_samples.horizontal->from_samples());
  EXPECT_EQ(from_samples.horizontal->samples, a);
  const GroundMotion gf = GroundMotion::FromScene(from_file);
  const GroundMotion gs = GroundMotion::FromScene(from_samples);
  ASSERT_TRUE(gf.horizontal() && gs.horizontal());
  ASSERT_EQ(gs.horizontal()->samples_mps2().size(), 201u);
  ExpectSameComponent(*gf.horizontal(), *gs.horizontal(), 1.0);
  // The peak is the largest |sample| (0.3 g at a quarter period, 0.125 s, up to the sampling).
  EXPECT_NEAR(gs.horizontal()->info().peak_g, 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(gs.horizontal()->info().peak_t_s, 0.125);
  // summary.json's base part says where the motion came from.
  const nlohmann::json base = BaseMotionJson(gs);
  EXPECT_EQ(base["horizontal"]["source"], "samples (201 values)");
  EXPECT_EQ(base["horizontal"]["format"], "samples");
  EXPECT_EQ(base["horizontal"]["npts"], 201);
  const std::string csv_file = ReferenceCsv(from_file, gf);
  EXPECT_EQ(ReferenceCsv(from_samples, gs), csv_file);
  // The motion moves the stack: without it the history differs (the comparison can fail).
  const Scene still = ParseScene(head, dir_ / "c.toml");
  EXPECT_NE(ReferenceCsv(still, GroundMotion::FromScene(still)), csv_file);
}

TEST_F(SamplesTest, SameMotionAsAPlainFileInGWithScaleStartAndPadding) {
  // Horizontal: 0.4 g at 2 Hz times scale 0.75 (0.3 g), from start_s = 0.1 s, every 5 ms for
  // 0.8 s; vertical: 0.05 g at 3 Hz for 0.5 s, padded with zeros to the horizontal's end.
  const double dt = 0.005;
  const std::vector<double> h = Sine(0.4, 2.0, dt, 161);
  const std::vector<double> v = Sine(0.05, 3.0, dt, 101);
  Write("h.txt", ColumnText(h));
  Write("v.txt", ColumnText(v));
  const std::string more = "scale = 0.75\nstart_s = 0.1\n";
  const std::string head = BlocksAndRun();
  const Scene from_file =
      ParseScene(head + MotionTable("horizontal", "file = \"h.txt\"", "g", dt, more) +
                     MotionTable("vertical", "file = \"v.txt\"", "g", dt, "start_s = 0.1\n"),
                 dir_ / "a.toml");
  const Scene from_samples = ParseScene(
      head + MotionTable("horizontal", "samples = " + TomlArray(h), "g", dt, more) +
          MotionTable("vertical", "samples = " + TomlArray(v), "g", dt, "start_s = 0.1\n"),
      dir_ / "b.toml");
  const GroundMotion gf = GroundMotion::FromScene(from_file);
  const GroundMotion gs = GroundMotion::FromScene(from_samples);
  ASSERT_TRUE(gf.horizontal() && gs.horizontal() && gf.vertical() && gs.vertical());
  ExpectSameComponent(*gf.horizontal(), *gs.horizontal(), 1.0);
  ExpectSameComponent(*gf.vertical(), *gs.vertical(), 1.0);
  // The vertical's 101 samples end at 0.6 s; zeros up to the horizontal's end at 0.9 s: 60.
  EXPECT_EQ(gs.vertical()->info().padded_samples, 60);
  EXPECT_EQ(gs.horizontal()->info().padded_samples, 0);
  EXPECT_NEAR(gs.horizontal()->info().peak_g, 0.3, 1e-12);
  EXPECT_EQ(gs.horizontal()->accel_mps2(0.1 - 1e-9), 0.0);
  EXPECT_EQ(ReferenceCsv(from_samples, gs), ReferenceCsv(from_file, gf));
}

TEST_F(SamplesTest, AStatedResolutionIsEverySamplesWhateverItsText) {
  // resolution = R (in units) replaces the texts' digits: 0 for exact, computed samples. In
  // cm/s^2 with scale -3: R * (0.01 m/s^2 * 3) for every sample, the exact 0 and 12 included
  // (the product the reader makes: the resolution times the units' factor and |scale|).
  MotionDef d;
  d.key = "base.horizontal";
  d.samples = {0.0, 0.012, 12.0};
  d.units = AccelUnits::kCmps2;
  d.units_given = true;
  d.dt_s = 0.01;
  d.scale = -3.0;
  d.samples_resolution = 0.5;
  const MotionComponent stated = MotionComponent::FromDef(d);
  ASSERT_EQ(stated.sample_resolution_mps2().size(), 3u);
  const double factor = 0.01 * 3.0;
  for (double r : stated.sample_resolution_mps2()) EXPECT_EQ(r, 0.5 * factor);
  d.samples_resolution = 0.0;
  const MotionComponent exact = MotionComponent::FromDef(d);
  for (double r : exact.sample_resolution_mps2()) EXPECT_EQ(r, 0.0);
  // Without it, the texts' digits: "0" and "12" are known to 1 unit, "0.012" to 0.001.
  d.samples_resolution.reset();
  const MotionComponent digits = MotionComponent::FromDef(d);
  EXPECT_EQ(digits.sample_resolution_mps2()[0], 1.0 * factor);
  EXPECT_EQ(digits.sample_resolution_mps2()[1], 1e-3 * factor);
  // The accelerations are the same either way.
  EXPECT_EQ(digits.samples_mps2(), stated.samples_mps2());
}

TEST_F(SamplesTest, ResolutionIsOneUnitOfTheShortestTextsLastDigit) {
  // The resolution of a value written as its shortest text, by hand: 0.012 -> 0.001,
  // -1.5e-07 -> 1e-08, 12 -> 1, 0.25 -> 0.01; in g times g0 and |scale|.
  MotionDef d;
  d.key = "base.horizontal";
  d.samples = {0.012, -1.5e-07, 12.0, 0.25};
  d.units = AccelUnits::kG;
  d.units_given = true;
  d.dt_s = 0.01;
  d.scale = -2.0;
  const MotionComponent c = MotionComponent::FromDef(d);
  const double g0 = kStandardGravity_mps2;
  const std::vector<double> expected = {1e-3 * g0 * 2.0, 1e-8 * g0 * 2.0, 1.0 * g0 * 2.0,
                                        1e-2 * g0 * 2.0};
  ASSERT_EQ(c.sample_resolution_mps2().size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    // The same product of the same three doubles (1e-k is the nearest double to 10^-k).
    EXPECT_EQ(c.sample_resolution_mps2()[i], expected[i]) << i;
  }
  EXPECT_EQ(c.samples_mps2()[0], 0.012 * (g0 * -2.0));
  EXPECT_EQ(c.info().source, "samples (4 values)");
}

TEST_F(SamplesTest, FromDefChecksWhatTheValidatorChecks) {
  // A definition handed straight to FromDef (no scene validation): each rule still holds, named
  // by its key; GroundMotion::FromScene puts the scene's file first.
  MotionDef d;
  d.key = "base.horizontal";
  d.samples = {0.0, 0.1};
  d.units = AccelUnits::kG;
  d.units_given = true;
  d.dt_s = 0.01;
  EXPECT_NO_THROW(MotionComponent::FromDef(d));
  const auto error = [&](MotionDef bad) {
    return testing_util::ErrorOf([&] { MotionComponent::FromDef(bad); });
  };
  MotionDef one = d;
  one.samples = {0.1};
  EXPECT_EQ(error(one).rfind("base.horizontal.samples: expected at least 2 samples", 0), 0u)
      << error(one);
  MotionDef nan = d;
  nan.samples[1] = std::nan("");
  EXPECT_EQ(error(nan), "base.horizontal.samples[1]: expected a finite number, got nan");
  MotionDef big = d;
  big.samples[1] = 100.5;
  EXPECT_EQ(error(big).rfind("base.horizontal.samples[1] = 100.5 g; expected an acceleration with "
                             "magnitude at most 100 g",
                             0),
            0u)
      << error(big);
  MotionDef no_units = d;
  no_units.units_given = false;
  EXPECT_EQ(error(no_units).rfind("base.horizontal.units: samples must state their units", 0), 0u)
      << error(no_units);
  MotionDef no_dt = d;
  no_dt.dt_s = 0.0;
  EXPECT_EQ(error(no_dt).rfind("base.horizontal.dt: ", 0), 0u) << error(no_dt);
  MotionDef with_file = d;
  with_file.file = "x.txt";
  EXPECT_NE(error(with_file).find("give one of file, kind or samples"), std::string::npos)
      << error(with_file);
  MotionDef with_kind = d;
  with_kind.kind = MotionKind::kHarmonic;
  EXPECT_NE(error(with_kind).find("give one of file, kind or samples"), std::string::npos)
      << error(with_kind);
  Scene scene;
  scene.path = "in_code.toml";
  scene.horizontal = big;
  EXPECT_EQ(testing_util::ErrorOf([&] {
              GroundMotion::FromScene(scene);
            }).rfind("in_code.toml: base.horizontal.samples[1] = 100.5 g", 0),
            0u);
}

}  // namespace
}  // namespace rockbench
