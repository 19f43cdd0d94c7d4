// `rockbench run SCENE --out DIR`: runs the reference model (or another engine) on a scene.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "files/atomic_file.h"
#include "motion/ground_motion.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/resource_estimate.h"
#include "run/summary.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> engines = {"reference"};
  std::vector<std::string> overrides;
  LimitOptions limits;
};

void Execute(const RunOptions& opt) {
  const ResourceBudget budget = StartLimits(opt.limits, opt.out, "run");
  const Scene scene = LoadScene(opt.scene, opt.overrides);
  CheckEngineTables(scene);
  CheckRunEstimate(EstimateRun(scene, opt.engines, 0, 0, 1), budget, opt.scene);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  for (const std::string& note : PaddingNotes(motion)) {
    std::fprintf(stderr, "rockbench: %s\n", note.c_str());
  }
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);
  std::vector<std::string> failed;        // runs that ended non_finite
  std::vector<std::string> undetermined;  // runs whose model stopped deciding the motion
  std::vector<EngineRun> runs;
  for (const std::string& name : opt.engines) {
    runs.push_back(RunEngine(name, scene, motion));
    const EngineRun& run = runs.back();
    if (const std::string f = NonFiniteText(run); !f.empty()) failed.push_back(f);
    if (const auto u = run.summary.find("undetermined"); u != run.summary.end() && u->is_object()) {
      undetermined.push_back(
          name + ": " + StopsDecidingText(u->value("t_s", 0.0), u->value("detail", std::string())) +
          "; the history after it is one admissible outcome the rule chose");
    }
    WriteEngineFiles(run, out);
    std::printf("%s\n", run.one_line.c_str());
  }
  std::vector<const EngineRun*> written;
  for (const EngineRun& run : runs) written.push_back(&run);
  const nlohmann::json summary = RunSummaryJson(opt.scene, opt.overrides, scene, motion, written);
  WriteFileAtomic(out / "summary.json", summary.dump(2) + "\n");
  std::printf("outputs in %s (summary.json", out.string().c_str());
  for (const std::string& name : opt.engines) std::printf(", %s/history.csv", name.c_str());
  std::printf(")\n");
  // The outputs say how far each run got; a run that ended non_finite failed.
  if (!failed.empty()) {
    std::fflush(stdout);
    for (const std::string& f : failed) {
      std::fprintf(stderr, "rockbench: run failed: %s\n", f.c_str());
    }
    throw CLI::RuntimeError(kExitRunFailed);
  }
  if (!undetermined.empty()) {
    std::fflush(stdout);
    for (const std::string& u : undetermined) std::fprintf(stderr, "rockbench: %s\n", u.c_str());
    throw CLI::RuntimeError(kExitUndetermined);
  }
}

}  // namespace

void RegisterRun(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "Run the reference model (or --engine NAME) on a scene");
  cmd->add_option("scene", opt->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  cmd->add_option("--engine,-e", opt->engines,
                  "Engine(s): reference or an engine of `rockbench engines`")
      ->capture_default_str();
  cmd->add_option("--set", opt->overrides, "Override a scene value: key=value (repeatable)");
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
