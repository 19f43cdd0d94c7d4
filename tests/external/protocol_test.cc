// The external-engine protocol (engines/external, docs/external-engines.md): the input file
// holds exactly what the run input holds; the poses file is read back, and every way it can be
// wrong is an error naming the engine, the file and the line; the child process's limits; the
// manifest's errors; a faulty engine's failures through the engine interface; and the Python
// example (examples/python_housner) converging on Housner's block at first order, as its
// semi-implicit Euler must.
#include "engines/external/protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "common/bullet_steps.h"
#include "common/error_of.h"
#include "common/scratch_dir_test.h"
#include "compare/agreement.h"
#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/rocking_world.h"
#include "engines/external/command.h"
#include "engines/external/external_engine.h"
#include "engines/external/manifest.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "scene/stack_pose.h"

namespace rockbench::external {
namespace {

using testing_util::ErrorOf;

const std::string kSource = ROCKBENCH_SOURCE_DIR;

// A two-block stack under a short sine pulse, 0.01 s at dt 1e-3: 10 steps.
Scene StackScene(const std::string& extra = "") {
  return ParseScene(
      "[block1]\nwidth = 0.6\nheight = 2.0\ndensity = 2000.0\n"
      "[block2]\nwidth = 0.4\nheight = 1.0\ndensity = 2000.0\nfriction = 0.7\n"
      "[initial]\ntheta1 = 0.01\ntheta2 = 0.02\nomega2 = -0.1\n"
      "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.2\nfrequency_hz = 5.0\n"
      "[run]\nduration = 0.01\noutput_interval = 0.001\n" +
          extra,
      "stack.toml");
}

EngineInput StackInput(const Scene& s, double dt = 1e-3) {
  return MakeEngineInput(s, GroundMotion::FromScene(s), "faulty", dt, DriveKind::kInertial, 0.0);
}

TEST(ExternalRows, EveryNthStepFromZeroThenTheLast) {
  EXPECT_EQ(ExpectedRows(10, 1), 11);
  EXPECT_EQ(ExpectedRows(10, 5), 3);  // 0, 5, 10
  EXPECT_EQ(ExpectedRows(10, 3), 5);  // 0, 3, 6, 9, 10
  EXPECT_EQ(RowStep(4, 10, 3), 10);
  EXPECT_EQ(RowStep(2, 10, 3), 6);
}

TEST(ExternalInput, HoldsTheRunInputBitForBit) {
  const Scene s = StackScene();
  const EngineInput in = StackInput(s);
  EngineSettings settings;
  const nlohmann::json j = InputJson("faulty", s, in, settings, 1, "/x/poses.csv", "/x/c.csv");
  // Round trip through text: JSON keeps every double's shortest exact form.
  const nlohmann::json back = nlohmann::json::parse(j.dump());
  EXPECT_EQ(back.at("protocol_version"), 1);
  EXPECT_EQ(back.at("steps"), in.steps);
  EXPECT_EQ(back.at("rows"), in.steps + 1);
  EXPECT_EQ(back.at("time_step_s").get<double>(), in.time_step_s);
  ASSERT_EQ(back.at("drive").at("ax_mps2").size(), in.drive.ax_mps2.size());
  for (size_t n = 0; n < in.drive.ax_mps2.size(); ++n) {
    EXPECT_EQ(back.at("drive").at("ax_mps2")[n].get<double>(), in.drive.ax_mps2[n]) << n;
  }
  const StackPlacement placed = PlaceStack(in.blocks, in.initial);
  ASSERT_EQ(back.at("blocks").size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json& b = back.at("blocks")[static_cast<size_t>(k)];
    EXPECT_EQ(b.at("x_m").get<double>(), placed.blocks[static_cast<size_t>(k)].x_m);
    EXPECT_EQ(b.at("angle_rad").get<double>(), placed.blocks[static_cast<size_t>(k)].phi_rad);
    EXPECT_EQ(b.at("omega_radps").get<double>(), placed.blocks[static_cast<size_t>(k)].w_radps);
    // m (b^2 + h^2) / 3 about the centre.
    const double m = b.at("mass_kg").get<double>(), w = b.at("width_m").get<double>(),
                 h = b.at("height_m").get<double>();
    EXPECT_NEAR(b.at("inertia_kgm2").get<double>(), m * (w * w + h * h) / 12.0, 1e-12 * m);
  }
  // Block 1 states no friction (infinite: null, the engine's own), block 2 its 0.7.
  EXPECT_TRUE(back.at("blocks")[0].at("friction").is_null());
  EXPECT_EQ(back.at("blocks")[1].at("friction").get<double>(), 0.7);
  EXPECT_EQ(back.at("contact_pairs").size(), 3u);  // ground-1, 1-2, ground-2
  EXPECT_EQ(back.at("base_motion").at("horizontal").at("kind"), "sine_pulse");
  EXPECT_TRUE(back.at("base_motion").at("horizontal").at("analytic").get<bool>());
}

// The input as the JSON Schema (engines/external/input.schema.json) states it: at each level,
// every required key is written and every key written is a property of the schema.
void ExpectKeysMatch(const nlohmann::json& value, const nlohmann::json& schema,
                     const std::string& where) {
  for (const auto& key : schema.at("required")) {
    EXPECT_TRUE(value.contains(key.get<std::string>())) << where << ": missing " << key;
  }
  for (const auto& [key, v] : value.items()) {
    EXPECT_TRUE(schema.at("properties").contains(key)) << where << ": not in the schema: " << key;
  }
}

TEST(ExternalInput, IsWhatTheJsonSchemaSays) {
  std::ifstream in(kSource + "/engines/external/input.schema.json");
  const nlohmann::json schema = nlohmann::json::parse(in);
  for (const char* drive : {"inertial", "kinematic"}) {
    const Scene s = StackScene();
    const EngineInput input = MakeEngineInput(
        s, GroundMotion::FromScene(s), "faulty", 1e-3,
        std::string(drive) == "inertial" ? DriveKind::kInertial : DriveKind::kKinematic, 0.0);
    const nlohmann::json j = InputJson("faulty", s, input, EngineSettings(), 1, "/p", "/c");
    ExpectKeysMatch(j, schema, "top");
    EXPECT_EQ(j.at("protocol"), schema.at("properties").at("protocol").at("const"));
    EXPECT_EQ(j.at("protocol_version"), kProtocolVersion);
    for (const auto& b : j.at("blocks")) {
      ExpectKeysMatch(b, schema.at("properties").at("blocks").at("items"), "block");
    }
    for (const auto& p : j.at("contact_pairs")) {
      ExpectKeysMatch(p, schema.at("properties").at("contact_pairs").at("items"), "pair");
    }
    ExpectKeysMatch(j.at("ground"), schema.at("properties").at("ground"), "ground");
    const auto& variants = schema.at("properties").at("drive").at("oneOf");
    const auto& variant = variants[std::string(drive) == "inertial" ? 0 : 1];
    EXPECT_EQ(j.at("drive").at("kind"), variant.at("properties").at("kind").at("const"));
    ExpectKeysMatch(j.at("drive"), variant, drive);
    ExpectKeysMatch(j.at("base_motion").at("horizontal"), schema.at("$defs").at("motion"),
                    "motion");
  }
}

TEST(ExternalInput, TheMonitorSeesACoarserOutputAsLongerSteps) {
  const Scene s = StackScene();
  const EngineInput in = StackInput(s);
  const EngineInput m = MonitorInput(in, 3);
  EXPECT_EQ(m.steps, 4);  // rows 0, 3, 6, 9, 10
  EXPECT_DOUBLE_EQ(m.time_step_s, 3e-3);
  ASSERT_EQ(m.drive.ax_mps2.size(), 4u);
  // Each window keeps its largest acceleration: the pulse grows over the first steps.
  EXPECT_EQ(m.drive.ax_mps2[0], in.drive.ax_mps2[2]);
  EXPECT_EQ(m.drive.ax_mps2[3], in.drive.ax_mps2[9]);
}

class PosesTest : public testing_util::ScratchDirTest {
 protected:
  // A poses file of one block: header, then the rows `body` gives.
  std::string Error(const std::string& text, std::int64_t every = 1) {
    const Scene s = ParseScene(
        "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n"
        "[run]\nduration = 0.003\noutput_interval = 0.001\n",
        "one.toml");
    const EngineInput in =
        MakeEngineInput(s, GroundMotion(), "faulty", 1e-3, DriveKind::kInertial, 0.0);
    const auto file = Write("poses.csv", text);
    return ErrorOf([&] { ReadPoses("faulty", file, in, every); });
  }
  std::string File() const { return (dir_ / "poses.csv").string(); }
};

const char kHeader[] = "t_s,x1_m,y1_m,angle1_rad\n";

TEST_F(PosesTest, AValidFileIsRead) {
  EXPECT_EQ(Error(std::string("# a comment\n") + kHeader +
                  "0,0,2,0\n0.001,0,2,0\n0.002,0,2,0\n0.003,0,2,0\n"),
            "no error");
}

TEST_F(PosesTest, EveryFaultNamesTheEngineTheFileAndTheLine) {
  const std::string at = "faulty: " + File();
  EXPECT_EQ(Error("t_s,x1_m,y1_m\n0,0,2\n"),
            at + ":1: missing column 'angle1_rad' in the header (the scene has 1 blocks)");
  EXPECT_NE(Error("t_s,x1_m,y1_m,angle1_rad,theta1\n").find(at + ":1: unknown column 'theta1'"),
            std::string::npos);
  EXPECT_EQ(Error(std::string(kHeader) + "0,0,2,0\n0.001,0,2,abc\n"),
            at + ":3: column 4: expected a number, got 'abc'");
  EXPECT_NE(Error(std::string(kHeader) + "0,0,2,0\n0.001,0,2,0\n0.0005,0,2,0\n")
                .find(at + ":4: time 0.0005 s goes backwards"),
            std::string::npos);
  EXPECT_NE(Error(std::string(kHeader) + "0,0,2,0\n0.002,0,2,0\n")
                .find(at + ":3: row 1 is at t = 0.002 s, expected 0.001"),
            std::string::npos);
  EXPECT_NE(Error(std::string(kHeader) + "0,0,2,0\n0.001,0,2,0\n")
                .find(at + ":3: 2 rows, fewer than the 4 promised"),
            std::string::npos);
  EXPECT_NE(Error(std::string(kHeader) + "0,0,2,0\n0.001,0,2\n")
                .find(at + ":3: 3 fields, the header has 4 (a truncated row?)"),
            std::string::npos);
  EXPECT_NE(
      Error(std::string(kHeader) + "0,0,2,0\n0.001,0,2,0\n0.002,0,2,0\n0.003,0,2,0\n0.004,0,2,0\n")
          .find(at + ":6: more rows than the 4 promised"),
      std::string::npos);
  EXPECT_NE(Error("").find(at + ": empty poses file"), std::string::npos);
  EXPECT_NE(Error("t_s,x1_m,y1_m,angle1_rad,vx1_mps\n").find("give all three or none"),
            std::string::npos);
}

TEST_F(PosesTest, VelocitiesFromDifferencesAreExactForAUniformMotion) {
  // x = 0.5 t, phi = -0.2 t (after t = 0, whose velocities are the input's: at rest).
  const Scene s = ParseScene(
      "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n[run]\nduration = "
      "0.004\noutput_interval = 0.001\n",
      "one.toml");
  const EngineInput in =
      MakeEngineInput(s, GroundMotion(), "faulty", 1e-3, DriveKind::kInertial, 0.0);
  std::string text = kHeader;
  for (int n = 0; n <= 4; ++n) {
    const double t = n * 1e-3;
    char row[128];
    std::snprintf(row, sizeof row, "%.17g,%.17g,2,%.17g\n", t, 0.5 * t, -0.2 * t);
    text += row;
  }
  const PoseRows p = ReadPoses("faulty", Write("poses.csv", text), in, 1);
  ASSERT_EQ(p.rows.size(), 5u);
  EXPECT_FALSE(p.velocities_given);
  EXPECT_EQ(p.rows[0].blocks[0].vx_mps, 0.0);
  for (size_t i = 1; i < 5; ++i) {
    EXPECT_NEAR(p.rows[i].blocks[0].vx_mps, 0.5, 1e-12) << i;
    EXPECT_NEAR(p.rows[i].blocks[0].w_radps, -0.2, 1e-12) << i;
    EXPECT_NEAR(p.rows[i].blocks[0].cos_phi, std::cos(-0.2 * static_cast<double>(i) * 1e-3), 1e-15);
  }
}

TEST(ExternalCommand, EndsAreToldApart) {
  const auto dir = std::filesystem::temp_directory_path();
  CommandSpec spec;
  spec.working_dir = dir;
  spec.stderr_file = dir / ("rockbench_command_err_" + std::to_string(getpid()));
  spec.argv = {"sh", "-c", "echo bye >&2; exit 3"};
  CommandResult r = RunCommand(spec);
  EXPECT_TRUE(r.started);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(TailOfFile(spec.stderr_file), "bye");
  spec.argv = {"sh", "-c", "kill -SEGV $$"};
  r = RunCommand(spec);
  EXPECT_EQ(r.signal, SIGSEGV);
  EXPECT_EQ(r.Describe(spec), "killed by signal 11 (Segmentation fault)");
  // A hang is killed at its limit, with whatever it started (its process group): the sleep
  // in the background would otherwise live on.
  spec.argv = {"sh", "-c", "sleep 30 & sleep 30"};
  spec.wall_limit_s = 0.3;
  r = RunCommand(spec);
  EXPECT_TRUE(r.timed_out);
  EXPECT_LT(r.wall_s, 5.0);
  EXPECT_EQ(r.Describe(spec), "killed after its wall-clock limit of 0.3 s");
  spec.argv = {"no-such-program-rockbench"};
  r = RunCommand(spec);
  EXPECT_FALSE(r.started);
  EXPECT_EQ(r.Describe(spec).rfind("could not start: no-such-program-rockbench: ", 0), 0u)
      << r.Describe(spec);
  std::filesystem::remove(spec.stderr_file);
}

class ManifestTest : public testing_util::ScratchDirTest {
 protected:
  std::string Error(const std::string& text) {
    ExternalEngineRef ref;
    ref.name = "mine";
    ref.where = "scene.toml:3";
    ref.manifest = Write("manifest.toml", text);
    ref.base_dir = dir_;
    return ErrorOf([&] { LoadManifest(ref); });
  }
  std::string File() const { return (dir_ / "manifest.toml").string(); }
};

TEST_F(ManifestTest, ErrorsNameTheFileTheLineAndTheKey) {
  const std::string tail = " (the manifest of external engine mine)";
  EXPECT_EQ(Error("protocol = 2\ncommand = [\"sh\"]\n"),
            File() +
                ":1: protocol: expected protocol = 1 (the version of the external-engine "
                "protocol this rockbench speaks)" +
                tail);
  EXPECT_EQ(Error("protocol = 1\ncommand = [\"sh\"]\ncolour = 1\n"),
            File() +
                ":3: colour: unknown key (expected protocol, version, command, max_blocks, "
                "drives, requires, install_hint, wall_limit_s, memory_limit_mib, "
                "[settings.<key>], [sweep])" +
                tail);
  EXPECT_EQ(Error("protocol = 1\ncommand = [\"sh\"]\n[settings.iterations]\ntype = \"int\"\n"
                  "default = 4\n"),
            File() +
                ":4: settings.iterations.type: expected number, integer, flag or choice, "
                "got 'int'" +
                tail);
  EXPECT_EQ(Error("protocol = 1\ncommand = [\"sh\"]\n[settings.time_step]\ntype = \"number\"\n"
                  "default = 1e-3\n"),
            File() +
                ":3: settings.time_step: a standard key of every external engine's table "
                "(docs/external-engines.md); give it another name" +
                tail);
  EXPECT_EQ(Error("protocol = 1\ncommand = [\"sh\"]\n[[sweep.family]]\nname = \"a\"\nid = \"x\"\n"
                  "settings = { iterations = 3 }\n"),
            File() +
                ":6: sweep.family.settings.iterations: not a key of the engine's table (the "
                "step is the sweep's own)" +
                tail);
}

TEST_F(ManifestTest, AMissingProgramOrPackageLeavesTheEngineOutSayingWhy) {
  ExternalEngineRef ref;
  ref.name = "mine";
  ref.base_dir = dir_;
  ref.manifest = Write("manifest.toml",
                       "protocol = 1\ncommand = [\"no-such-program-rockbench\"]\n"
                       "install_hint = \"install it\"\n");
  EXPECT_EQ(LoadManifest(ref).missing_reason,
            "its program 'no-such-program-rockbench' is not installed (install it)");
  Write("manifest.toml", "protocol = 1\ncommand = [\"sh\"]\nrequires = [\"pkg/x.json\"]\n");
  EXPECT_EQ(LoadManifest(ref).missing_reason, (dir_ / "pkg/x.json").string() + " is missing");
}

// A faulty engine through the engine interface: each fault is an ExternalEngineError naming
// the engine and what went wrong, never a crash of rockbench.
class FaultyEngineTest : public testing_util::ScratchDirTest {
 protected:
  std::string Run(const std::string& mode, const std::string& settings = "") {
    const std::string name = "faulty_" + mode;
    const auto scene_file =
        Write("scene.toml", "[external." + name + "]\ncommand = [\"python3\", \"" + kSource +
                                "/tests/external/faulty_engine.py\", \"" + mode + "\"]\n" +
                                "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n"
                                "[run]\nduration = 0.02\n[" +
                                name + "]\ntime_step = 1e-3\n" + settings);
    const Scene s = LoadScene(scene_file);
    CheckEngineTables(s);
    return ErrorOf([&] { RunEngine(name, s, GroundMotion()); });
  }
};

TEST_F(FaultyEngineTest, EveryFailureIsAnErrorNamingTheEngine) {
  EXPECT_EQ(Run("good"), "no error");
  const std::string exit = Run("exit");
  EXPECT_NE(exit.find("faulty_exit: its command (python3 "), std::string::npos) << exit;
  EXPECT_NE(exit.find(") exit code 3;\nits last words:\n  | faulty engine: cannot simulate this on "
                      "purpose"),
            std::string::npos)
      << exit;
  EXPECT_NE(Run("crash").find("killed by signal 11 (Segmentation fault)"), std::string::npos);
  EXPECT_NE(Run("hang", "wall_limit_s = 1\n").find("killed after its wall-clock limit of 1 s"),
            std::string::npos);
  EXPECT_NE(Run("memory", "memory_limit_mib = 200\n").find("killed at its memory limit of 200 MiB"),
            std::string::npos);
  EXPECT_NE(Run("few_rows").find("poses.csv:11: 10 rows, fewer than the 21 promised"),
            std::string::npos);
  EXPECT_NE(Run("backwards").find("poses.csv:12: time 0.0080000000000000002 s goes backwards"),
            std::string::npos);
  EXPECT_NE(Run("missing_column").find("poses.csv:1: missing column 'angle1_rad'"),
            std::string::npos);
  EXPECT_NE(Run("no_file").find("no poses file: the engine ended without writing it"),
            std::string::npos);
}

// A value that is not finite is the engine's blow-up: the run ends non_finite at the last
// finite row (as a built-in engine's does), its detail naming the file, the line and the column.
TEST_F(FaultyEngineTest, ANanEndsTheRunNonFiniteNamingTheFileAndLine) {
  const auto scene_file =
      Write("scene.toml", "[external.faulty_nan]\ncommand = [\"python3\", \"" + kSource +
                              "/tests/external/faulty_engine.py\", \"nan\"]\n"
                              "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n"
                              "[run]\nduration = 0.02\noutput_interval = 0.001\n"
                              "[faulty_nan]\ntime_step = 1e-3\n");
  const Scene s = LoadScene(scene_file);
  CheckEngineTables(s);
  const EngineRun run = RunEngine("faulty_nan", s, GroundMotion());
  EXPECT_EQ(run.outcome.status, RunStatus::kNonFinite);
  const std::string detail = run.summary.value("status_detail", "");
  EXPECT_NE(detail.find("poses.csv:12: column 4 (angle1_rad) is 'nan'"), std::string::npos)
      << detail;
  // Rows 0 to 9 (t = 0 to 0.009 s) were read; the NaN is row 10.
  EXPECT_NEAR(run.history.samples.back().t_s, 0.009, 1e-12);
}

TEST_F(FaultyEngineTest, ASceneCannotTakeABuiltInEnginesName) {
  const auto scene_file = Write("scene.toml",
                                "[external.bullet]\ncommand = [\"sh\"]\n"
                                "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n");
  const Scene s = LoadScene(scene_file);
  EXPECT_EQ(ErrorOf([&] { CheckEngineTables(s); }),
            scene_file.string() +
                ":1: [external.bullet]: 'bullet' is a built-in engine's "
                "name; give the external engine another");
}

// Bullet's own steps, replayed through the protocol by a command that only copies them to the
// poses file: the monitor reads the same poses it reads in process (angles through their
// shortest text and back: a few ulps), so the histories agree to 1e-12 rad and the outcomes
// (status, impacts) are Bullet's.
class ReplayTest : public testing_util::ScratchDirTest {};

TEST_F(ReplayTest, ReplayingBulletsStepsGivesBulletsHistory) {
  const Scene s = LoadScene(kSource + "/scenes/thesis_free_rocking.toml",
                            {"run.duration=1.5", "bullet.time_step=1e-3"});
  const GroundMotion motion = GroundMotion::FromScene(s);
  const EngineRun bullet = RunEngine("bullet", s, motion);
  const bullet::BulletInput in = bullet::MakeBulletInput(s, motion);
  const std::vector<StepReadout> steps = testing_util::RecordBulletSteps(in);
  const auto saved = dir_ / "bullet_poses.csv";
  {
    std::ofstream out(saved);
    WritePoses(out, steps);
  }
  ExternalEngineRef ref;
  ref.name = "replay";
  ref.where = "test";
  ref.base_dir = dir_;
  ref.command = {"sh", "-c", "cp '" + saved.string() + "' \"$(dirname \"$0\")/poses.csv\""};
  const ExternalEngine replay(LoadManifest(ref));
  Scene rs = s;
  rs.engine_tables["replay"].values["time_step"] = RawSetting{1e-3, "test"};
  const EngineResult r = replay.Simulate(rs, motion, {});
  EXPECT_EQ(r.outcome.status, bullet.outcome.status);
  EXPECT_EQ(r.outcome.impacts(), bullet.outcome.impacts());
  ASSERT_EQ(r.history.samples.size(), bullet.history.samples.size());
  double worst = 0.0;
  for (size_t i = 0; i < r.history.samples.size(); ++i) {
    for (int k = 0; k < 2; ++k) {
      worst = std::max(worst, std::abs(r.history.samples[i].theta_rad[k] -
                                       bullet.history.samples[i].theta_rad[k]));
    }
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_EQ(r.summary.at("external").at("velocities"), "engine");
}

// The Python example (standard library only) through the protocol: Housner's block released
// from half its critical angle. Its integrator is semi-implicit Euler with impacts located to a
// step, first order: ten times the step, about ten times the error (order within [0.8, 1.25],
// a measured 0.96 on 2026-11-26), and every impact of the reference matched at 1e-4 s.
TEST(PythonExample, ConvergesAtFirstOrderOnHousnersBlock) {
  const Scene base = LoadScene(kSource + "/examples/python_housner/housner_python.toml");
  CheckEngineTables(base);
  const reference::Result ref = reference::Simulate(base, GroundMotion());
  double error[2] = {0.0, 0.0};
  int i = 0;
  for (const char* dt : {"1e-3", "1e-4"}) {
    const Scene s = LoadScene(kSource + "/examples/python_housner/housner_python.toml",
                              {std::string("housner_py.time_step=") + dt});
    const EngineRun run = RunEngine("housner_py", s, GroundMotion());
    const EngineAgreement a = CompareWithReference(s, ref, run);
    error[i++] = a.angle(1).max_abs_error_rad;
    if (i == 2) {
      EXPECT_EQ(a.impacts.matched, a.impacts.reference_impacts);
      EXPECT_EQ(a.impacts.reference_impacts, 4);
    }
  }
  const double order = std::log10(error[0] / error[1]);
  EXPECT_GT(order, 0.8) << error[0] << " " << error[1];
  EXPECT_LT(order, 1.25) << error[0] << " " << error[1];
}

}  // namespace
}  // namespace rockbench::external
