// Resource limits as a user meets them (docs/limits.md): a run estimated to need more memory or
// time than the command's budget is refused before it starts, naming the key and the estimate,
// with exit code 2 and no output folder; the budget flags raise or lower it; one validity rule
// holds for the reference and every engine.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/shell_test.h"

namespace fs = std::filesystem;
using rockbench::testing_util::Shell;
using rockbench::testing_util::ShellRun;

namespace {

const std::string kExe = ROCKBENCH_EXE;
const std::string kSrc = ROCKBENCH_SOURCE_DIR;

fs::path Out(const std::string& name) {
  const fs::path d = fs::temp_directory_path() /
                     ("rockbench_limits_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "'" << (needle) << "' not in '" << (haystack) << "'"

// 8e10 rows at 256 B: tens of TiB, refused before a byte is allocated or a folder made.
TEST(LimitsCli, AHugeOutputIsRefusedUpFront) {
  const fs::path out = Out("rows");
  const ShellRun r = Shell(kExe + " run " + kSrc +
                           "/scenes/harmonic.toml --set run.duration=80000 --set "
                           "run.output_interval=1e-6 --out " +
                           out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_CONTAINS(r.output, "harmonic.toml: run.output_interval: needs an estimated");
  EXPECT_CONTAINS(r.output, "8e+10 history rows");
  EXPECT_CONTAINS(r.output, "more than the memory budget of 2 GiB");
  EXPECT_CONTAINS(r.output, "--memory-budget GIB");
  EXPECT_FALSE(fs::exists(out));
}

// rk4 at 1e-12 s: refused naming model.step.
TEST(LimitsCli, ATinyFixedStepIsRefusedNamingIt) {
  const ShellRun r =
      Shell(kExe + " run " + kSrc +
            "/scenes/harmonic.toml --set 'model.integrator=\"rk4\"' --set model.step=1e-12 --out " +
            Out("rk4").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_CONTAINS(r.output, "model.step: needs an estimated");
}

// The budget flag lowers and raises the limit: 1e5 rows (about 51 MiB estimated) are refused
// under 1 MiB and run under 1 GiB.
TEST(LimitsCli, TheMemoryBudgetFlagMovesTheLimit) {
  const std::string run = kExe + " run " + kSrc +
                          "/scenes/harmonic.toml --set run.output_interval=1e-4 --out " +
                          Out("budget").string();
  const ShellRun low = Shell(run + " --memory-budget 0.001");
  EXPECT_EQ(low.exit_code, 2) << low.output;
  EXPECT_CONTAINS(low.output, "more than the memory budget of 1.02 MiB");
  const ShellRun high = Shell(run + " --memory-budget 1 --wall-limit 120");
  EXPECT_EQ(high.exit_code, 0) << high.output;
  fs::remove_all(Out("budget"));
}

// An estimate longer than --wall-limit is refused up front, naming the engine's step.
TEST(LimitsCli, AnEstimateBeyondTheWallLimitIsRefused) {
  const ShellRun r = Shell(kExe + " compare " + kSrc +
                           "/scenes/harmonic.toml --engines bullet --set bullet.time_step=2e-5 "
                           "--wall-limit 5 --out " +
                           Out("wall").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_CONTAINS(r.output, "bullet.time_step: needs an estimated");
  EXPECT_CONTAINS(r.output, "more than the time budget of 5 s");
}

// One validity rule: a block released beyond overturning is refused by the reference and by
// an engine with the same message, naming the line, key, value and limit.
TEST(LimitsCli, EveryEngineRefusesWhatTheReferenceRefuses) {
  const fs::path dir = Out("rule");
  fs::create_directories(dir);
  const fs::path scene = dir / "tilted.toml";
  {
    std::ofstream f(scene);
    f << "[block1]\nwidth = 0.2\nheight = 1.0\ndensity = 2000.0\n[initial]\ntheta1 = 2.0\n";
  }
  std::string first;
  for (const std::string engine : {"reference", "bullet"}) {
    const ShellRun r = Shell(kExe + " run " + scene.string() + " --engine " + engine + " --out " +
                             (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << engine << ": " << r.output;
    EXPECT_CONTAINS(r.output,
                    "tilted.toml:6: initial.theta1: expected |theta1| below "
                    "model.overturn_angle (1.5707963267948966 rad; the block would "
                    "have overturned), got 2");
    if (first.empty()) first = r.output;
    EXPECT_EQ(r.output, first) << engine;
  }
  fs::remove_all(dir);
}

}  // namespace
