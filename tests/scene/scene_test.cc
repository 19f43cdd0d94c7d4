// Scene files: the shipped scenes, the full schema, every validation error, overrides.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "tests/common/error_of.h"
#include "tests/common/scene_text.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(ROCKBENCH_SOURCE_DIR);
const fs::path kScenes = kRoot / "scenes";
const fs::path kRecords = kRoot / "records";

// A valid two-block scene; tests append or edit tables.
const std::string& kBlocks = testing_util::kThesisBlocksToml;

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "'" << (needle) << "' not in '" << (haystack) << "'"

TEST(ShippedScenes, AllParseAndTheirMotionLoads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    const Scene s = LoadScene(entry.path());
    EXPECT_FALSE(s.title.empty());
    EXPECT_EQ(s.path, entry.path());
    const GroundMotion gm = GroundMotion::FromScene(s);
    EXPECT_EQ(gm.has_horizontal(), s.horizontal.has_value());
    EXPECT_EQ(gm.has_vertical(), s.vertical.has_value());
  }
  EXPECT_GE(count, 5);
}

TEST(ShippedScenes, ThesisFreeRocking) {
  // Thesis 6.3.1: B1 = H1 = 1.25 m, B2 = 1.0 m, H2 = 2.5 m, 2500 kg/m^3, theta = 0.15 rad.
  const Scene s = LoadScene(kScenes / "thesis_free_rocking.toml");
  ASSERT_TRUE(s.block_count() == 2);
  EXPECT_EQ(s.blocks[0].width_m, 1.25);
  EXPECT_EQ(s.blocks[0].height_m, 1.25);
  EXPECT_EQ(s.blocks[0].depth_m, 1.0);
  EXPECT_EQ(s.blocks[0].density_kgpm3, 2500.0);
  EXPECT_DOUBLE_EQ(s.blocks[0].mass_kg, 2500.0 * 1.25 * 1.25);
  EXPECT_EQ(s.blocks[1].width_m, 1.0);
  EXPECT_EQ(s.blocks[1].height_m, 2.5);
  EXPECT_DOUBLE_EQ(s.blocks[1].mass_kg, 6250.0);
  EXPECT_EQ(s.initial.theta_rad[0], 0.15);
  EXPECT_EQ(s.initial.theta_rad[1], 0.15);
  EXPECT_EQ(s.initial.omega_radps[0], 0.0);
  EXPECT_EQ(s.initial.omega_radps[1], 0.0);
  EXPECT_FALSE(s.horizontal || s.vertical);
  EXPECT_EQ(s.run.duration_s, 6.0);
  EXPECT_EQ(s.run.output_interval_s, 0.005);
  EXPECT_EQ(s.run.gravity_mps2, 9.81);
}

TEST(ShippedScenes, ThesisRinaldiResolvesTheRecordNextToTheScene) {
  const Scene s = LoadScene(kScenes / "thesis_rinaldi228.toml");
  ASSERT_TRUE(s.horizontal);
  EXPECT_FALSE(s.vertical);
  EXPECT_EQ(s.horizontal->kind, MotionKind::kFile);
  EXPECT_EQ(s.horizontal->file_as_written,
            "../records/northridge1994_rinaldi_receiving_sta_228.AT2");
  EXPECT_TRUE(fs::equivalent(s.horizontal->file,
                             kRecords / "northridge1994_rinaldi_receiving_sta_228.AT2"));
  EXPECT_FALSE(s.horizontal->units_given);
  EXPECT_EQ(s.run.duration_s, 20.0);
  const GroundMotion gm = GroundMotion::FromScene(s);
  EXPECT_NEAR(gm.horizontal()->info().peak_g, 0.8741, 0.5e-4);  // records/SOURCES.md
}

TEST(ShippedScenes, HousnerIsASingleBlockAtHalfItsSlenderness) {
  const Scene s = LoadScene(kScenes / "housner_free_rocking.toml");
  EXPECT_FALSE(s.block_count() == 2);
  const double theta_c = std::atan(s.blocks[0].width_m / s.blocks[0].height_m);
  EXPECT_DOUBLE_EQ(s.initial.theta_rad[0], 0.5 * theta_c);
  EXPECT_EQ(s.run.duration_s, 4.0);
}

TEST(ShippedScenes, HarmonicAndRinaldiWithVertical) {
  const Scene h = LoadScene(kScenes / "harmonic.toml");
  ASSERT_TRUE(h.horizontal);
  EXPECT_EQ(h.horizontal->kind, MotionKind::kHarmonic);
  EXPECT_EQ(h.horizontal->amplitude_g, 0.4);
  EXPECT_EQ(h.horizontal->frequency_hz, 2.0);
  EXPECT_EQ(h.horizontal->duration_s, 3.0);
  EXPECT_EQ(h.run.duration_s, 8.0);
  const Scene r = LoadScene(kScenes / "rinaldi_with_vertical.toml");
  ASSERT_TRUE(r.horizontal && r.vertical);
  EXPECT_EQ(r.vertical->key, "base.vertical");
  const GroundMotion gm = GroundMotion::FromScene(r);
  EXPECT_NEAR(gm.vertical()->info().peak_g, 0.9582, 0.5e-4);  // records/SOURCES.md
  EXPECT_EQ(gm.vertical()->info().padded_samples, 0);         // same length as 228
}

TEST(ShippedScenes, RunGravityLeavesTheBaseMotionAlone) {
  // [run] gravity is the simulation's; records in g and amplitude_g use standard gravity.
  for (const char* scene : {"rinaldi_with_vertical.toml", "harmonic.toml"}) {
    SCOPED_TRACE(scene);
    const GroundMotion a = GroundMotion::FromScene(LoadScene(kScenes / scene));
    const GroundMotion b = GroundMotion::FromScene(LoadScene(kScenes / scene, {"run.gravity=9.5"}));
    for (double t = 0.0; t < 8.0; t += 0.0137) {
      ASSERT_EQ(a.xg_mps2(t), b.xg_mps2(t)) << t;
      ASSERT_EQ(a.yg_mps2(t), b.yg_mps2(t)) << t;
    }
    EXPECT_EQ(a.horizontal()->info().peak_g, b.horizontal()->info().peak_g);
  }
}

TEST(Parse, DefaultsOfAMinimalScene) {
  const Scene s = ParseScene("[block1]\nwidth = 1\nheight = 2\nmass = 100\n", "");
  const Scene d;
  EXPECT_FALSE(s.block_count() == 2);
  EXPECT_EQ(s.blocks[0].mass_kg, 100.0);
  EXPECT_EQ(s.blocks[0].density_kgpm3, 0.0);
  EXPECT_EQ(s.blocks[0].depth_m, 1.0);
  EXPECT_EQ(s.run.duration_s, d.run.duration_s);
  EXPECT_EQ(s.run.output_interval_s, d.run.output_interval_s);
  EXPECT_EQ(s.run.gravity_mps2, d.run.gravity_mps2);
  EXPECT_EQ(s.model.integrator, d.model.integrator);
  EXPECT_EQ(s.model.rtol, d.model.rtol);
  EXPECT_TRUE(s.engine_tables.empty());  // engines' settings: their own defaults
  EXPECT_FALSE(s.compare.tolerance_rad);
  EXPECT_EQ(s.initial.theta_rad[0], 0.0);
}

TEST(Parse, EveryKeyOfTheSchema) {
  const std::string text = R"(
title = "all keys"
[block1]
width = 2
height = 3.0
density = 2000.0
depth = 0.5
[block2]
width = 1.0
height = 1.5
mass = 700.0
depth = 0.5
[initial]
theta1 = 0.01
theta2 = -0.02
omega1 = 0.3
omega2 = -0.4
[base.horizontal]
kind = "ricker"
amplitude_g = 0.25
frequency_hz = 1.5
start_s = 0.5
scale = 2.0
[base.vertical]
kind = "rectangular_pulse"
amplitude_g = -0.1
duration_s = 0.4
[run]
duration = 5.0
output_interval = 0.02
gravity = 9.80665
[model]
integrator = "rk4"
rtol = 1e-6
atol = 1e-9
step = 2e-4
events = "thesis"
equations = "linearized"
overturn_angle = 1.0
rest_rate_rel = 1e-6
check_transitions = false
[bullet]
time_step = 5e-4
solver_iterations = 20
precision = "float"
drive = "kinematic"
erp = 0.3
erp2 = 0.7
split_impulse = false
split_impulse_threshold = -0.01
restitution = 0.1
friction = 0.8
rolling_friction = 0.05
restitution_velocity_threshold = 0.5
margin = 0.001
ground_depth = 2.0
kinematic_highpass_hz = 0.2
[compare]
tolerance = 0.02
members = 40
engine_members = 12
amplitude_rel = 1e-3
sample_precision = 0.5
initial_rel = 2e-3
seed = 7
)";
  const Scene s = ParseScene(text, "");
  EXPECT_EQ(s.title, "all keys");
  EXPECT_EQ(s.blocks[0].width_m, 2.0);  // a TOML integer is accepted as a number
  EXPECT_DOUBLE_EQ(s.blocks[0].mass_kg, 2000.0 * 2.0 * 3.0 * 0.5);
  EXPECT_EQ(s.blocks[1].mass_kg, 700.0);
  EXPECT_EQ(s.blocks[1].density_kgpm3, 0.0);
  EXPECT_EQ(s.blocks[1].depth_m, 0.5);
  EXPECT_EQ(s.initial.theta_rad[1], -0.02);
  EXPECT_EQ(s.initial.omega_radps[1], -0.4);
  EXPECT_EQ(s.horizontal->kind, MotionKind::kRicker);
  EXPECT_EQ(s.horizontal->key, "base.horizontal");
  EXPECT_EQ(s.horizontal->amplitude_g, 0.25);
  EXPECT_EQ(s.horizontal->frequency_hz, 1.5);
  EXPECT_EQ(s.horizontal->start_s, 0.5);
  EXPECT_EQ(s.horizontal->scale, 2.0);
  EXPECT_EQ(s.vertical->kind, MotionKind::kRectangularPulse);
  EXPECT_EQ(s.vertical->duration_s, 0.4);
  EXPECT_EQ(s.run.gravity_mps2, 9.80665);
  EXPECT_EQ(s.model.integrator, Integrator::kRk4);
  EXPECT_EQ(s.model.rtol, 1e-6);
  EXPECT_EQ(s.model.atol, 1e-9);
  EXPECT_EQ(s.model.step_s, 2e-4);
  EXPECT_EQ(s.model.events, EventScheme::kThesis);
  EXPECT_EQ(s.model.equations, Equations::kLinearized);
  EXPECT_EQ(s.model.overturn_rad, 1.0);
  EXPECT_EQ(s.model.rest_rate_rel, 1e-6);
  EXPECT_FALSE(s.model.check_transitions);
  // An engine's table is kept as written, with where each value came from; the engine checks it
  // (tests/bullet/engine_input_test).
  const RawEngineTable& b = s.engine_tables.at("bullet");
  EXPECT_EQ(std::get<double>(b.values.at("time_step").value), 5e-4);
  EXPECT_EQ(std::get<std::int64_t>(b.values.at("solver_iterations").value), 20);
  EXPECT_EQ(std::get<std::string>(b.values.at("precision").value), "float");
  EXPECT_EQ(std::get<bool>(b.values.at("split_impulse").value), false);
  EXPECT_NE(b.values.at("time_step").where.find(":"), std::string::npos);
  ASSERT_TRUE(s.compare.tolerance_rad);
  EXPECT_EQ(*s.compare.tolerance_rad, 0.02);
  EXPECT_EQ(s.compare.members, 40);
  EXPECT_EQ(s.compare.engine_members, 12);
  EXPECT_EQ(s.compare.amplitude_rel, 1e-3);
  EXPECT_EQ(s.compare.sample_precision, 0.5);
  EXPECT_EQ(s.compare.initial_rel, 2e-3);
  EXPECT_EQ(s.compare.seed, 7u);
}

TEST(Parse, HarmonicWithoutDurationLastsForever) {
  const Scene s = ParseScene(
      kBlocks + "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 1\n",
      "");
  EXPECT_EQ(s.horizontal->duration_s, std::numeric_limits<double>::infinity());
}

TEST(Parse, PlainRecordWithUnitsAndDt) {
  const std::string text =
      kBlocks +
      "[base.horizontal]\nfile = \"../records/tabas1978_FN_plain_g_dt0p02.txt\""
      "\nunits = \"g\"\ndt = 0.02\n";
  const Scene s = ParseScene(text, kScenes / "virtual.toml");
  EXPECT_EQ(s.horizontal->dt_s, 0.02);
  EXPECT_TRUE(s.horizontal->units_given);
  EXPECT_EQ(s.horizontal->units, AccelUnits::kG);
  EXPECT_EQ(GroundMotion::FromScene(s).horizontal()->info().npts, 2500);
}

TEST(Errors, TheMessageOfTheIssue) {
  EXPECT_EQ(testing_util::SceneErrorOf(
                "title = \"x\"\n[block1]\nheight = 1.0\nwidth = -1\ndensity = 2500\n"),
            "scenes/x.toml:4: block1.width: expected a positive number (m), got -1");
}

TEST(Errors, UnknownKeysAndTables) {
  const std::string e1 = testing_util::SceneErrorOf(kBlocks + "[run]\nduration = 3\nduraton = 4\n");
  EXPECT_CONTAINS(e1, "scenes/x.toml:11:");
  EXPECT_CONTAINS(e1, "run.duraton");
  EXPECT_CONTAINS(e1, "unknown key");
  // Any other table may be an engine's: the scene keeps it raw, with where it was, for the
  // harness to check against the engines of the build (tests/run/engine_registry_test.cc).
  const Scene t = ParseScene(kBlocks + "\n[blok3]\nwidth = 1\n", "scenes/x.toml");
  ASSERT_EQ(t.engine_tables.count("blok3"), 1u);
  EXPECT_EQ(t.engine_tables.at("blok3").where, "scenes/x.toml:10");
  EXPECT_EQ(t.engine_tables.at("blok3").values.at("width").where, "scenes/x.toml:11");
  const std::string e3 = testing_util::SceneErrorOf(kBlocks +
                                                    "[base.horizontal]\nkind = \"harmonic\"\n"
                                                    "amplitude_g = 0.1\nfrequency = 2\n");
  EXPECT_CONTAINS(e3, "scenes/x.toml:12:");
  EXPECT_CONTAINS(e3, "base.horizontal.frequency");
  const std::string e4 =
      testing_util::SceneErrorOf(kBlocks + "[base.sideways]\nkind = \"harmonic\"\n");
  EXPECT_CONTAINS(e4, "scenes/x.toml:9:");
  EXPECT_CONTAINS(e4, "base.sideways");
}

TEST(Errors, TomlSyntaxErrorHasLineAndColumn) {
  const std::string e = testing_util::SceneErrorOf("[block1]\nwidth = 1.0\nheight = = 2\n");
  EXPECT_CONTAINS(e, "scenes/x.toml:3:");
  EXPECT_CONTAINS(e, "TOML syntax error");
  // file:line:column
  EXPECT_TRUE(e.rfind("scenes/x.toml:3:", 0) == 0 && std::isdigit(e[16])) << e;
}

// One bad scene, the line of the error and pieces of its message.
struct BadCase {
  std::string name;
  std::string text;
  std::string where;  // "scenes/x.toml:N:" or "scenes/x.toml:"
  std::vector<std::string> pieces;
};

TEST(Errors, Validation) {
  const std::string b1 = "[block1]\nwidth = 1.0\nheight = 2.0\ndensity = 2500\n";  // lines 1-4
  const std::string at2 = "\"../records/northridge1994_rinaldi_receiving_sta_228.AT2\"";
  const std::string plain = "\"../records/tabas1978_FN_plain_g_dt0p02.txt\"";
  const std::vector<BadCase> cases = {
      {"zero height",
       "[block1]\nwidth = 1.0\nheight = 0\ndensity = 2500\n",
       ":3:",
       {"block1.height", "expected a positive number (m), got 0"}},
      {"zero mass",
       "[block1]\nwidth = 1.0\nheight = 1\nmass = 0.0\n",
       ":4:",
       {"block1.mass", "positive number (kg), got 0"}},
      {"negative density",
       "[block1]\nwidth = 1.0\nheight = 1\ndensity = -3\n",
       ":4:",
       {"block1.density", "positive number (kg/m^3), got -3"}},
      {"zero depth", b1 + "depth = 0\n", ":5:", {"block1.depth", "positive"}},
      {"nan",
       "[block1]\nwidth = nan\nheight = 1\ndensity = 1\n",
       ":2:",
       {"block1.width", "got nan"}},
      {"inf", b1 + "[initial]\ntheta1 = inf\n", ":6:", {"initial.theta1", "finite", "got inf"}},
      {"string for a number",
       "[block1]\nwidth = \"wide\"\nheight = 1\ndensity = 1\n",
       ":2:",
       {"block1.width", "expected a positive number (m), got \"wide\""}},
      {"bool for a number", b1 + "[run]\nduration = true\n", ":6:", {"run.duration", "got true"}},
      {"table for a number", b1 + "[run.duration]\nx = 1\n", ":5:", {"run.duration", "a table"}},
      {"both density and mass",
       b1 + "mass = 3.0\n",
       ":5:",
       {"block1.mass", "either density or mass"}},
      {"neither density nor mass",
       "[block1]\nwidth = 1.0\nheight = 1\n",
       ":1:",
       {"block1", "density", "mass"}},
      {"missing width", "[block1]\nheight = 1\ndensity = 1\n", ":1:", {"block1.width", "missing"}},
      {"missing block1", "title = \"no blocks\"\n", ":", {"block1", "missing"}},
      {"block1 not a table", "block1 = 3\n", ":1:", {"block1", "expected a table"}},
      {"output interval zero",
       b1 + "[run]\noutput_interval = 0.0\n",
       ":6:",
       {"run.output_interval", "positive number (s), got 0"}},
      {"output interval above duration",
       b1 + "[run]\nduration = 1.0\noutput_interval = 2.0\n",
       ":7:",
       {"run.output_interval", "must not exceed run.duration"}},
      {"duration below the default output interval",
       b1 + "[run]\nduration = 0.005\n",
       ":6:",
       {"run.duration", "at least run.output_interval (0.01 s, the default), got 0.005"}},
      {"negative duration",
       b1 + "[run]\nduration = -1.0\n",
       ":6:",
       {"run.duration", "positive number (s), got -1"}},
      {"theta2 in a single block",
       b1 + "[initial]\ntheta1 = 0.1\ntheta2 = 0.1\n",
       ":7:",
       {"initial.theta2", "single-block"}},
      {"omega2 in a single block",
       b1 + "[initial]\nomega2 = 0.0\n",
       ":6:",
       {"initial.omega2", "single-block"}},
      {"file and kind",
       b1 + "[base.horizontal]\nfile = " + at2 + "\nkind = \"harmonic\"\n",
       ":5:",
       {"base.horizontal", "either file or kind"}},
      {"neither file nor kind",
       b1 + "[base.vertical]\nscale = 2.0\n",
       ":5:",
       {"base.vertical", "missing file"}},
      {"harmonic without frequency",
       b1 + "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.3\n",
       ":5:",
       {"base.horizontal.frequency_hz", "missing", "Hz"}},
      {"ricker without amplitude",
       b1 + "[base.horizontal]\nkind = \"ricker\"\nfrequency_hz = 1\n",
       ":5:",
       {"base.horizontal.amplitude_g", "missing"}},
      {"rectangular without duration",
       b1 + "[base.horizontal]\nkind = \"rectangular_pulse\"\namplitude_g = 0.3\n",
       ":5:",
       {"base.horizontal.duration_s", "missing"}},
      {"rectangular with frequency",
       b1 + "[base.horizontal]\nkind = \"rectangular_pulse\"\namplitude_g = 0.3\n"
            "duration_s = 1\nfrequency_hz = 2\n",
       ":9:",
       {"base.horizontal.frequency_hz", "not used"}},
      {"sine pulse with duration",
       b1 + "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\nfrequency_hz = 2\n"
            "duration_s = 1\n",
       ":9:",
       {"base.horizontal.duration_s", "not used"}},
      {"zero frequency",
       b1 + "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\nfrequency_hz = 0\n",
       ":8:",
       {"base.horizontal.frequency_hz", "positive number (Hz), got 0"}},
      {"unknown kind",
       b1 + "[base.horizontal]\nkind = \"square\"\n",
       ":6:",
       {"base.horizontal.kind", "\"harmonic\"", "\"ricker\"", "got \"square\""}},
      {"unknown integrator",
       b1 + "[model]\nintegrator = \"euler\"\n",
       ":6:",
       {"model.integrator", "\"dopri5\", \"dop853\" or \"rk4\"", "got \"euler\""}},
      {"unknown events", b1 + "[model]\nevents = \"exact\"\n", ":6:", {"model.events", "thesis"}},
      {"unknown equations",
       b1 + "[model]\nequations = \"linear\"\n",
       ":6:",
       {"model.equations", "linearized"}},
      {"unknown units",
       b1 + "[base.horizontal]\nfile = " + at2 + "\nunits = \"ft/s2\"\n",
       ":7:",
       {"base.horizontal.units", "\"m/s2\"", "ft/s2"}},
      {"plain file without units",
       b1 + "[base.horizontal]\nfile = " + plain + "\ndt = 0.02\n",
       ":5:",
       {"base.horizontal.units", "missing", "plain"}},
      {"dt for an AT2",
       b1 + "[base.horizontal]\nfile = " + at2 + "\ndt = 0.01\n",
       ":7:",
       {"base.horizontal.dt", "AT2"}},
      {"amplitude for a file",
       b1 + "[base.horizontal]\nfile = " + at2 + "\namplitude_g = 1\n",
       ":7:",
       {"base.horizontal.amplitude_g", "analytic"}},
      {"units for a kind",
       b1 + "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.3\nfrequency_hz = 2\n"
            "units = \"g\"\n",
       ":9:",
       {"base.horizontal.units", "not used"}},
      {"missing record file",
       b1 + "[base.horizontal]\nfile = \"nowhere.AT2\"\n",
       ":6:",
       {"base.horizontal.file", "no such record file", "nowhere.AT2"}},
      {"negative start",
       b1 + "[base.horizontal]\nfile = " + at2 + "\nstart_s = -1\n",
       ":7:",
       {"base.horizontal.start_s", ">= 0"}},
      {"string for a bool",
       b1 + "[model]\ncheck_transitions = \"yes\"\n",
       ":6:",
       {"model.check_transitions", "true or false"}},
      {"zero tolerance", b1 + "[compare]\ntolerance = 0\n", ":6:", {"compare.tolerance"}},
      {"negative members", b1 + "[compare]\nmembers = -1\n", ":6:", {"compare.members"}},
      {"fractional members", b1 + "[compare]\nmembers = 2.5\n", ":6:", {"compare.members"}},
      {"amplitude_rel above 1",
       b1 + "[compare]\namplitude_rel = 2\n",
       ":6:",
       {"compare.amplitude_rel"}},
      {"negative sample_precision",
       b1 + "[compare]\nsample_precision = -1\n",
       ":6:",
       {"compare.sample_precision"}},
      {"removed absolute rest rate",
       b1 + "[model]\nrest_rate = 1e-4\n",
       ":6:",
       {"model.rest_rate", "rest_rate_rel"}},
      {"zero rtol", b1 + "[model]\nrtol = 0\n", ":6:", {"model.rtol"}},
      {"title not a string", "title = 3\n" + b1, ":1:", {"title", "string"}},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string e = testing_util::SceneErrorOf(c.text, {}, kScenes / "x.toml");
    ASSERT_FALSE(e.empty()) << "no error";
    EXPECT_EQ(e.rfind((kScenes / "x.toml").string() + c.where, 0), 0u) << e;
    for (const auto& piece : c.pieces) EXPECT_CONTAINS(e, piece);
  }
}

TEST(Errors, MissingSceneFile) {
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { LoadScene(kScenes / "does_not_exist.toml"); }),
                  "does_not_exist.toml");
}

TEST(Overrides, AppliedBeforeValidation) {
  const Scene s =
      LoadScene(kScenes / "thesis_rinaldi228.toml",
                {"run.duration=3", "base.horizontal.scale=0.5", "model.integrator=\"rk4\"",
                 "bullet.precision=float", " model.rtol = 1e-6 ", "title=Bare words here"});
  EXPECT_EQ(s.run.duration_s, 3.0);
  EXPECT_EQ(s.horizontal->scale, 0.5);
  EXPECT_EQ(s.model.integrator, Integrator::kRk4);
  EXPECT_EQ(std::get<std::string>(s.engine_tables.at("bullet").values.at("precision").value),
            "float");
  EXPECT_EQ(s.model.rtol, 1e-6);
  EXPECT_EQ(s.title, "Bare words here");
  // The scaled record's peak halves (records/SOURCES.md: 0.8741 g).
  EXPECT_NEAR(GroundMotion::FromScene(s).horizontal()->info().peak_g, 0.5 * 0.8741, 0.25e-4);
}

TEST(Overrides, CreateMissingTablesAndKeys) {
  const Scene s =
      ParseScene(kBlocks, "",
                 {"initial.theta1=0.05", "compare.tolerance=0.02", "base.vertical.kind=sine_pulse",
                  "base.vertical.amplitude_g=0.2", "base.vertical.frequency_hz=3"});
  EXPECT_EQ(s.initial.theta_rad[0], 0.05);
  EXPECT_EQ(*s.compare.tolerance_rad, 0.02);
  ASSERT_TRUE(s.vertical);
  EXPECT_EQ(s.vertical->kind, MotionKind::kSinePulse);
  EXPECT_EQ(s.vertical->frequency_hz, 3.0);
}

TEST(Overrides, Errors) {
  const std::string unknown = testing_util::SceneErrorOf(kBlocks, {"run.duraton=3"});
  EXPECT_CONTAINS(unknown, "override \"run.duraton=3\"");
  EXPECT_CONTAINS(unknown, "unknown key run.duraton");
  // A two-part key may be an engine's (checked by the harness); a deeper one may not.
  EXPECT_EQ(testing_util::SceneErrorOf(kBlocks, {"nosuch.key=1"}), "");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"nosuch.key.deeper=1"}),
                  "unknown key nosuch");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"run"}), "expected key=value");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"run=3"}), "is a table");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"title.x=3"}), "title is not a table");
  // A bad value names the override, the key and what was expected.
  const std::string bad = testing_util::SceneErrorOf(kBlocks, {"run.duration=-2"});
  EXPECT_CONTAINS(bad,
                  "scenes/x.toml: override \"run.duration=-2\": run.duration: expected a "
                  "positive number (s), got -2");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks, {"model.integrator=euler"}), "got \"euler\"");
  // An override that makes a single-block scene set theta2 is refused like the file would be.
  EXPECT_CONTAINS(testing_util::SceneErrorOf("[block1]\nwidth = 1\nheight = 1\nmass = 1\n",
                                             {"initial.theta2=0.1"}),
                  "single-block");
}

TEST(Validate, SceneBuiltInCode) {
  Scene s;
  s.blocks = {BlockDef{1.0, 2.0, 1.0, 100.0, 0.0}};
  EXPECT_NO_THROW(ValidateScene(s));
  s.blocks[0].width_m = -1.0;
  EXPECT_EQ(testing_util::ErrorOf([&] { ValidateScene(s); }),
            "scene: block1.width: expected a positive number (m), got -1");
  s.blocks[0].width_m = 1.0;
  s.initial.theta_rad[1] = 0.1;  // no block 2
  EXPECT_THROW(ValidateScene(s), SceneError);
  s.initial.theta_rad[1] = 0.0;
  s.run.output_interval_s = 20.0;
  EXPECT_THROW(ValidateScene(s), SceneError);
  s.run.output_interval_s = 0.01;
  MotionDef m;
  m.key = "base.horizontal";
  m.kind = MotionKind::kHarmonic;
  m.amplitude_g = 0.1;
  m.frequency_hz = 0.0;
  s.horizontal = m;
  EXPECT_THROW(ValidateScene(s), SceneError);
  s.horizontal->frequency_hz = 2.0;
  EXPECT_NO_THROW(ValidateScene(s));
  s.horizontal->kind = MotionKind::kFile;
  s.horizontal->file = kRecords / "tabas1978_FN_plain_g_dt0p02.txt";
  EXPECT_THROW(ValidateScene(s), SceneError);  // plain file without units
  s.horizontal->units_given = true;
  EXPECT_NO_THROW(ValidateScene(s));
}

// ---- N blocks: [[block]] tables, [initial] arrays and per-block keys, overrides ----

// `n` [[block]] tables, block k (1-based) width 2 / k, height 1 + k, density 2000 + 10 k (block 1
// given its mass instead when `mass_for_block1`).
std::string BlockTables(int n, bool mass_for_block1 = false) {
  std::string out;
  for (int k = 1; k <= n; ++k) {
    out += "[[block]]\nwidth = " + ShortestText(2.0 / k) + "\nheight = " + ShortestText(1.0 + k) +
           "\n";
    out += k == 1 && mass_for_block1 ? "mass = 1500.0\n"
                                     : "density = " + ShortestText(2000.0 + 10.0 * k) + "\n";
  }
  return out;
}

TEST(BlockTables, ThreeAndSixBlocksReadBackExactly) {
  for (const int n : {3, 6}) {
    SCOPED_TRACE(n);
    const Scene s = ParseScene(BlockTables(n, true), "");
    ASSERT_EQ(s.block_count(), n);
    for (int k = 1; k <= n; ++k) {
      const BlockDef& b = s.blocks[k - 1];
      EXPECT_EQ(b.width_m, 2.0 / k) << k;
      EXPECT_EQ(b.height_m, 1.0 + k) << k;
      EXPECT_EQ(b.depth_m, 1.0) << k;
      if (k == 1) {
        EXPECT_EQ(b.mass_kg, 1500.0);
        EXPECT_EQ(b.density_kgpm3, 0.0);
      } else {
        EXPECT_EQ(b.density_kgpm3, 2000.0 + 10.0 * k) << k;
        EXPECT_EQ(b.mass_kg, (2000.0 + 10.0 * k) * (2.0 / k) * (1.0 + k) * 1.0) << k;
      }
    }
    for (int k = 0; k < kMaxBlocks; ++k) {
      EXPECT_EQ(s.initial.theta_rad[k], 0.0);
      EXPECT_EQ(s.initial.omega_radps[k], 0.0);
    }
  }
}

// Everything a reader fills, compared field by field (Scene has no ==).
void ExpectSameScene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.block_count(), b.block_count());
  for (int k = 0; k < a.block_count(); ++k) {
    EXPECT_EQ(a.blocks[k].width_m, b.blocks[k].width_m) << k;
    EXPECT_EQ(a.blocks[k].height_m, b.blocks[k].height_m) << k;
    EXPECT_EQ(a.blocks[k].depth_m, b.blocks[k].depth_m) << k;
    EXPECT_EQ(a.blocks[k].mass_kg, b.blocks[k].mass_kg) << k;
    EXPECT_EQ(a.blocks[k].density_kgpm3, b.blocks[k].density_kgpm3) << k;
  }
  EXPECT_EQ(a.initial.theta_rad, b.initial.theta_rad);
  EXPECT_EQ(a.initial.omega_radps, b.initial.omega_radps);
  EXPECT_EQ(a.title, b.title);
  EXPECT_EQ(a.run.duration_s, b.run.duration_s);
  EXPECT_EQ(a.model.integrator, b.model.integrator);
  EXPECT_EQ(a.horizontal.has_value(), b.horizontal.has_value());
}

TEST(BlockTables, TheLegacyTablesGiveTheSameScene) {
  const std::string rest =
      "[initial]\ntheta1 = 0.15\ntheta2 = 0.1\nomega2 = -0.2\n[run]\nduration = 3\n";
  const Scene legacy = ParseScene(
      "[block1]\nwidth = 1.25\nheight = 1.25\ndensity = 2500.0\n"
      "[block2]\nwidth = 1.0\nheight = 2.5\nmass = 6250.0\ndepth = 2\n" +
          rest,
      "");
  const Scene tables = ParseScene(
      "[[block]]\nwidth = 1.25\nheight = 1.25\ndensity = 2500.0\n"
      "[[block]]\nwidth = 1.0\nheight = 2.5\nmass = 6250.0\ndepth = 2\n" +
          rest,
      "");
  ExpectSameScene(legacy, tables);
  EXPECT_EQ(tables.block_count(), 2);
  EXPECT_EQ(tables.initial.omega_radps[1], -0.2);
  // One block, both ways.
  ExpectSameScene(ParseScene("[block1]\nwidth = 1\nheight = 4\nmass = 10\n", ""),
                  ParseScene("[[block]]\nwidth = 1\nheight = 4\nmass = 10\n", ""));
  // The same scene file as the shipped thesis scene, written with [[block]] tables.
  const Scene shipped = LoadScene(kScenes / "thesis_free_rocking.toml");
  const Scene rewritten = ParseScene(
      "title = \"" + shipped.title + "\"\n" +
          "[[block]]\nwidth = 1.25\nheight = 1.25\ndensity = 2500.0\n"
          "[[block]]\nwidth = 1.0\nheight = 2.5\ndensity = 2500.0\n"
          "[initial]\ntheta = [0.15, 0.15]\n[run]\nduration = 6.0\noutput_interval = 0.005\n",
      "");
  ExpectSameScene(shipped, rewritten);
}

TEST(BlockTables, BothStylesInOneFileAreAnError) {
  const std::string e =
      testing_util::SceneErrorOf("[block1]\nwidth = 1\nheight = 1\nmass = 1\n" + BlockTables(2));
  EXPECT_CONTAINS(e, "scenes/x.toml:1: block1: a [block1] table beside [[block]] tables");
  EXPECT_CONTAINS(e, "not both");
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf(BlockTables(2) + "[block2]\nwidth = 1\nheight = 1\nmass = 1\n"),
      "block2: a [block2] table beside [[block]] tables");
  // A [block3] table is not an engine's: more than two blocks are [[block]] tables.
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf(kBlocks + "[block3]\nwidth = 1\nheight = 1\nmass = 1\n"),
      "block3: unknown table: [block1] and [block2] give one or two blocks");
  // block = ... that is not an array of tables.
  EXPECT_CONTAINS(testing_util::SceneErrorOf("block = 3\n"), "block: expected [[block]] tables");
  EXPECT_CONTAINS(testing_util::SceneErrorOf("block = []\n"),
                  "block: expected at least one [[block]] table");
}

// A block's friction (issue 24): >= 0 or inf, infinite when absent; a finite one needs the
// unilateral model, which takes at most kUnilateralMaxBlocks blocks.
TEST(BlockTables, FrictionIsNonNegativeAndNeedsAStackTheUnilateralModelTakes) {
  const Scene absent = ParseScene("[block1]\nwidth = 1\nheight = 2\nmass = 100\n", "");
  EXPECT_TRUE(std::isinf(absent.blocks[0].friction));
  EXPECT_FALSE(absent.has_finite_friction());
  const Scene given =
      ParseScene("[block1]\nwidth = 1\nheight = 2\nmass = 100\nfriction = 0.3\n", "");
  EXPECT_EQ(given.blocks[0].friction, 0.3);
  EXPECT_TRUE(given.tracks_slip_and_lift());
  EXPECT_TRUE(
      std::isinf(ParseScene("[block1]\nwidth = 1\nheight = 2\nmass = 100\nfriction = inf\n", "")
                     .blocks[0]
                     .friction));
  EXPECT_EQ(
      testing_util::SceneErrorOf("[block1]\nwidth = 1\nheight = 2\nmass = 100\nfriction = -0.1\n"),
      "scenes/x.toml:5: block1.friction: expected a number >= 0 or inf, got -0.1");
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf("[block1]\nwidth = 1\nheight = 2\nmass = 100\nfriction = nan\n"),
      "block1.friction: expected a number >= 0 or inf");
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf(BlockTables(kUnilateralMaxBlocks + 1) + "friction = 0.5\n"),
      "block" + std::to_string(kUnilateralMaxBlocks + 1) +
          ".friction: a finite friction needs the unilateral model");
}

TEST(BlockTables, AnErrorNamesTheBlockByItsIndex) {
  // Lines: block 1 is lines 1-4, block 2 lines 5-8, block 3 lines 9-12.
  const std::string three = BlockTables(2) + "[[block]]\nwidth = -1\nheight = 2\ndensity = 10\n";
  EXPECT_EQ(testing_util::SceneErrorOf(three),
            "scenes/x.toml:10: block3.width: expected a positive number (m), got -1");
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf(BlockTables(2) + "[[block]]\nwidth = 1\ndensity = 10\n"),
      "block3.height: missing; expected a positive number (m)");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(2) + "[[block]]\nwidth = 1\nheight = 1\n"),
                  "block3: missing density (kg/m^3) or mass (kg)");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(
                      BlockTables(2) + "[[block]]\nwidth = 1\nheight = 1\nmass = 1\nfoo = 2\n"),
                  "block3.foo: unknown key (expected one of: width, height, density, mass, depth, "
                  "friction, shape, diameter)");
}

TEST(BlockTables, EveryBlockIsNoWiderThanTheOneBelow) {
  const std::string wide = BlockTables(2) + "[[block]]\nwidth = 1.5\nheight = 1\nmass = 1\n";
  EXPECT_EQ(testing_util::SceneErrorOf(wide),
            "scenes/x.toml:10: block3.width: expected at most block2.width (1 m: block 3 would "
            "pivot outside block 2's top face, which the model does not describe), got 1.5");
  // Today's message for block 2, either style.
  const std::string legacy =
      "[block1]\nwidth = 1\nheight = 1\nmass = 1\n"
      "[block2]\nwidth = 2\nheight = 1\nmass = 1\n";
  EXPECT_EQ(testing_util::SceneErrorOf(legacy),
            "scenes/x.toml:6: block2.width: expected at most block1.width (1 m: block 2 would "
            "pivot outside block 1's top face, which the model does not describe), got 2");
  Scene s = ParseScene(BlockTables(4), "");
  s.blocks[3].width_m = 10.0;
  EXPECT_CONTAINS(testing_util::ErrorOf([&] { ValidateScene(s); }),
                  "scene: block4.width: expected at most block3.width");
}

TEST(BlockTables, AtMostMaxBlocks) {
  EXPECT_EQ(testing_util::SceneErrorOf(BlockTables(kMaxBlocks)), "");
  const std::string e = testing_util::SceneErrorOf(BlockTables(kMaxBlocks + 1));
  EXPECT_CONTAINS(e, "scenes/x.toml:257: block: expected at most 64 [[block]] tables");
  EXPECT_CONTAINS(e, "got 65");
  Scene s;
  s.blocks.assign(kMaxBlocks + 1, BlockDef{1.0, 1.0, 1.0, 1.0, 0.0});
  EXPECT_THROW(ValidateScene(s), SceneError);
  s.blocks.clear();
  EXPECT_THROW(ValidateScene(s), SceneError);
}

TEST(InitialArrays, OneEntryPerBlock) {
  const Scene s = ParseScene(
      BlockTables(3) + "[initial]\ntheta = [0.1, 0.2, -0.3]\nomega = [0, 1, -2.5]\n", "");
  EXPECT_EQ(s.initial.theta_rad[0], 0.1);
  EXPECT_EQ(s.initial.theta_rad[1], 0.2);
  EXPECT_EQ(s.initial.theta_rad[2], -0.3);
  EXPECT_EQ(s.initial.omega_radps[1], 1.0);
  EXPECT_EQ(s.initial.omega_radps[2], -2.5);
  EXPECT_EQ(s.initial.theta_rad[3], 0.0);
  // The arrays work for the legacy tables too, and give what theta1, theta2, ... give.
  ExpectSameScene(
      ParseScene(kBlocks + "[initial]\ntheta = [0.15, 0.1]\nomega = [0, 0.5]\n", ""),
      ParseScene(kBlocks + "[initial]\ntheta1 = 0.15\ntheta2 = 0.1\nomega2 = 0.5\n", ""));
}

TEST(InitialArrays, TheLengthMustBeTheBlockCount) {
  EXPECT_EQ(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\ntheta = [0.1, 0.2]\n"),
            "scenes/x.toml:14: initial.theta: expected an array of 3 numbers (rad, one per "
            "block, bottom first): the scene has 3 blocks, got 2 entries");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks + "[initial]\nomega = [0.1, 0.2, 0.3]\n"),
                  "initial.omega: expected an array of 2 numbers (rad/s, one per block, bottom "
                  "first): the scene has 2 blocks, got 3 entries");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\ntheta = 0.1\n"),
                  "initial.theta: expected an array of 3 numbers");
  EXPECT_CONTAINS(
      testing_util::SceneErrorOf(BlockTables(3) + "[initial]\ntheta = [0.1, \"x\", 0]\n"),
      "initial.theta2: expected a finite number (rad) (entry 2 of initial.theta), "
      "got \"x\"");
  // Each entry is held to today's rules, named by its block.
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\nomega = [0, 0, 200]\n"),
                  "initial.omega3: expected a finite number (rad/s) with magnitude at most");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\ntheta = [0, 0, 2]\n"),
                  "initial.theta3: expected |theta3| below model.overturn_angle");
}

TEST(InitialArrays, AnArrayAndAPerBlockKeyOfOneQuantityAreAnError) {
  EXPECT_EQ(testing_util::SceneErrorOf(BlockTables(3) +
                                       "[initial]\ntheta = [0.1, 0.2, 0.3]\ntheta2 = 0.2\n"),
            "scenes/x.toml:15: initial.theta2: give either initial.theta (an array, one entry "
            "per block) or initial.theta2, not both");
  // An array of one quantity and per-block keys of the other are fine.
  const Scene s =
      ParseScene(BlockTables(3) + "[initial]\ntheta = [0.1, 0.2, 0.3]\nomega3 = 1\n", "");
  EXPECT_EQ(s.initial.omega_radps[2], 1.0);
}

TEST(InitialArrays, PerBlockKeysOfAnyBlock) {
  const Scene s = ParseScene(BlockTables(3) + "[initial]\ntheta3 = 0.25\nomega1 = -0.5\n", "");
  EXPECT_EQ(s.initial.theta_rad[2], 0.25);
  EXPECT_EQ(s.initial.omega_radps[0], -0.5);
  EXPECT_EQ(s.initial.theta_rad[0], 0.0);
  // A block the scene does not have.
  EXPECT_EQ(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\ntheta4 = 0.1\n"),
            "scenes/x.toml:14: initial.theta4: not allowed: the scene has 3 blocks (no block 4)");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(kBlocks + "[initial]\nomega3 = 0.1\n"),
                  "initial.omega3: not allowed: the scene has 2 blocks (no block 3)");
  // One block: today's message, whichever style.
  EXPECT_CONTAINS(testing_util::SceneErrorOf(
                      "[[block]]\nwidth = 1\nheight = 1\nmass = 1\n[initial]\ntheta2 = 0.1\n"),
                  "initial.theta2: not allowed in a single-block scene (there is no [block2])");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3) + "[initial]\nphi = 1\n"),
                  "initial.phi: unknown key (expected one of: theta1 to theta3, omega1 to omega3, "
                  "theta, omega)");
  // Built in code: the entries beyond the block count must be zero, named by their key.
  Scene c = ParseScene(BlockTables(3), "");
  c.initial.omega_radps[4] = 0.5;
  EXPECT_EQ(testing_util::ErrorOf([&] { ValidateScene(c); }),
            "scene: initial.omega5: must be 0: the scene has 3 blocks (no block 5)");
}

TEST(Overrides, BlockKOfEitherStyle) {
  const Scene s = ParseScene(BlockTables(3, true), "", {"block3.width=0.5", "block1.mass=7"});
  EXPECT_EQ(s.blocks[2].width_m, 0.5);
  EXPECT_EQ(s.blocks[0].mass_kg, 7.0);
  EXPECT_EQ(s.blocks[0].density_kgpm3, 0.0);
  EXPECT_EQ(s.blocks[1].width_m, 1.0);
  // Legacy tables: block1 and block2 as today.
  const Scene l = ParseScene(kBlocks, "", {"block2.width=0.5"});
  EXPECT_EQ(l.blocks[1].width_m, 0.5);
  // A block the scene does not have: the key and the block count.
  EXPECT_EQ(testing_util::SceneErrorOf(kBlocks, {"block3.width=0.5"}),
            "scenes/x.toml: override \"block3.width=0.5\": block3.width: no block 3 (the scene "
            "has 2 blocks)");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3), {"block4.height=1"}),
                  "block4.height: no block 4 (the scene has 3 blocks)");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3), {"block3.size=1"}),
                  "unknown key block3.size");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3), {"block3=1"}), "block3 is a table");
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3), {"block.width=1"}),
                  "set by their index: blockK.key");
  // A bad value of an override names the override and the block.
  EXPECT_CONTAINS(testing_util::SceneErrorOf(BlockTables(3), {"block3.width=-1"}),
                  "override \"block3.width=-1\": block3.width: expected a positive number (m)");
  // [initial]'s per-block keys and arrays.
  const Scene i =
      ParseScene(BlockTables(3), "", {"initial.theta3=0.05", "initial.omega=[1, 2, 3]"});
  EXPECT_EQ(i.initial.theta_rad[2], 0.05);
  EXPECT_EQ(i.initial.omega_radps[1], 2.0);
}

TEST(Validate, RequireAtMostTwoBlocks) {
  EXPECT_NO_THROW(RequireAtMostTwoBlocks(ParseScene(kBlocks, ""), "x"));
  EXPECT_EQ(testing_util::ErrorOf([&] {
              RequireAtMostTwoBlocks(ParseScene(BlockTables(3), "scenes/three.toml"),
                                     "reference model");
            }),
            "scenes/three.toml: reference model: N-block scenes (3 blocks) are not simulated "
            "yet (issue 23); 1 or 2 blocks");
}

TEST(Helpers, NamesAndUnits) {
  EXPECT_TRUE(IsAt2File("a/b/X.AT2"));
  EXPECT_TRUE(IsAt2File("x.at2"));
  EXPECT_FALSE(IsAt2File("x.txt"));
  EXPECT_EQ(MotionKindName(MotionKind::kCosinePulse), "cosine_pulse");
  EXPECT_EQ(AccelUnitsName(AccelUnits::kCmps2), "cm/s2");
  // g is standard gravity by definition, whatever a scene's [run] gravity.
  EXPECT_EQ(AccelUnitsToMps2(AccelUnits::kG), 9.80665);
  EXPECT_EQ(kStandardGravity_mps2, 9.80665);
  EXPECT_EQ(AccelUnitsToMps2(AccelUnits::kMps2), 1.0);
  EXPECT_EQ(AccelUnitsToMps2(AccelUnits::kCmps2), 0.01);
}

}  // namespace
}  // namespace rockbench
