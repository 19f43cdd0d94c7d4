// `rockbench sweep SCENE --out DIR [--quick] [--repeat N] [--threads N] [--set k=v ...]`:
// accuracy and cost of every engine setting on the grid against a tight reference; writes
// DIR/sweep.csv (one row per run) and DIR/sweep.json (scene, options, simulated duration, tight
// reference, machine), both atomically, with progress on stderr when it is a terminal.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "files/atomic_file.h"
#include "motion/ground_motion.h"
#include "run/engine_registry.h"
#include "run/parallel.h"
#include "run/resource_estimate.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "sweep/sweep.h"

namespace rockbench::cli {
namespace {

struct SweepCliOptions {
  std::string scene;
  std::string out = "out";
  bool quick = false;
  int repeat = 1;
  int threads = 0;
  std::vector<std::string> overrides;
  std::string engines = "all";
  LimitOptions limits;
};

void Execute(const SweepCliOptions& opt) {
  const ResourceBudget budget = StartLimits(opt.limits, opt.out, "sweep");
  const Scene scene = LoadScene(opt.scene, opt.overrides);
  RequirePlanarBodies(scene, "sweep");
  CheckEngineTables(scene);
  // The engines beside the reference (always swept); none: `--engines reference`, a stack the
  // engines do not simulate yet.
  const std::vector<std::string> engines = ParseEnginesBesideReference(opt.engines);
  // An engine the scene brings runs only when the user names it: said, with how to opt in.
  std::fputs(NotRunNote(engines).c_str(), stderr);
  // The scene's own settings; the grid's finer steps are held by the wall-clock limit.
  CheckRunEstimate(EstimateRun(scene, engines, 0, 0, 1), budget, opt.scene);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  SweepOptions so;
  so.quick = opt.quick;
  so.repeat = opt.repeat;
  so.threads = opt.threads;
  so.engines = engines;
  // No engine: the reference's own grid (an empty list would mean every built engine).
  if (engines.empty()) so.points = SweepGrid(opt.quick, {});
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);

  // Progress on a terminal only (runs done, elapsed, remaining); quiet otherwise.
  ProgressLine line("sweep runs");
  auto progress = [&](int done, int total, const SweepPoint&) { line.Update(done, total); };
  SweepBaseline baseline;
  const std::vector<SweepRow> rows = RunSweep(scene, motion, so, progress, &baseline);
  WriteFileAtomic(out / "sweep.csv", SweepCsv(rows, scene.block_count()));
  WriteFileAtomic(out / "sweep.json",
                  SweepJson(scene, opt.overrides, so, baseline, rows).dump(2) + "\n");
  int failed = 0;
  for (const SweepRow& r : rows) failed += r.error.empty() ? 0 : 1;
  std::printf(
      "%zu runs (%d failed), tight reference %.3g s; outputs in %s (sweep.csv, sweep.json)\n",
      rows.size(), failed, baseline.wall_s, out.string().c_str());
}

}  // namespace

void RegisterSweep(CLI::App& app) {
  auto opt = std::make_shared<SweepCliOptions>();
  auto* cmd = app.add_subcommand(
      "sweep", "Accuracy and cost of engine settings against a tight reference (sweep.csv)");
  cmd->add_option("scene", opt->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  cmd->add_option("--engines,-e", opt->engines,
                  "Engines to sweep beside the reference: a comma-separated list, or all "
                  "(reference: the reference's grid alone)")
      ->capture_default_str();
  cmd->add_flag("--quick", opt->quick, "Small grid (a few minutes on the shipped scenes)");
  cmd->add_option("--repeat", opt->repeat, "Repetitions per run; the wall time is their minimum")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--threads", opt->threads, "Worker threads (0: one per core)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  cmd->add_option("--set", opt->overrides, "Override a scene value: key=value (repeatable)");
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
