// `rockbench compare SCENE --out DIR [--engines bullet] [--set k=v ...]`: runs the reference
// and each engine on the same scene and writes their histories, comparison.json,
// comparison.csv and summary.json.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/compare.h"
#include "harness/engines.h"
#include "harness/summary.h"
#include "reference/simulate.h"
#include "scene/ground_motion.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::cli {
namespace {

struct CompareOptions {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> engines = {"bullet"};
  std::vector<std::string> overrides;
};

void Execute(const CompareOptions& opt) {
  const Scene scene = LoadScene(opt.scene, opt.overrides);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  // Check the engine names before any work.
  const std::vector<std::string> available = AvailableEngines();
  std::vector<std::string> engines;
  for (const std::string& name : opt.engines) {
    if (name == "reference") continue;  // always run: it is what the others are compared with
    bool known = false;
    for (const std::string& a : available) known = known || a == name;
    if (!known) {
      std::string list;
      for (const std::string& a : available) list += (list.empty() ? "" : ", ") + a;
      throw SceneError("--engines: unknown engine '" + name + "' (this build has: " + list + ")");
    }
    engines.push_back(name);
  }
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);

  // The reference, kept whole: its dense trajectory is what the engines are compared with.
  const auto start = std::chrono::steady_clock::now();
  const reference::Result ref = reference::Simulate(scene, motion);
  const double ref_wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EngineRun ref_run;
  ref_run.engine = "reference";
  ref_run.history = ref.history;
  ref_run.wall_s = ref_wall_s;
  ref_run.summary = ReferenceSummaryJson(scene, ref, ref_wall_s);
  WriteEngineFiles(ref_run, out);

  nlohmann::json summary;
  summary["scene"] = {{"path", std::filesystem::absolute(opt.scene).lexically_normal().string()},
                      {"overrides", opt.overrides},
                      {"two_blocks", scene.two_blocks()}};
  summary["base"] = BaseMotionJson(motion);
  for (auto it = ref_run.summary.begin(); it != ref_run.summary.end(); ++it) {
    summary[it.key()] = *it;
  }
  std::printf("reference: %s, %zu events, %.3g ms\n", ref.summary.status.c_str(),
              ref.history.events.size(), ref_wall_s * 1e3);

  std::vector<EngineAgreement> agreements;
  for (const std::string& name : engines) {
    const EngineRun run = RunEngine(name, scene, motion);
    WriteEngineFiles(run, out);
    summary["engines"][name] = run.summary;
    std::printf("%s\n", run.one_line.c_str());
    agreements.push_back(CompareWithReference(scene, ref, run));
  }
  const nlohmann::json comparison = ComparisonJson(scene, ref, ref_wall_s, agreements);
  WriteFileAtomic(out / "comparison.json", comparison.dump(2) + "\n");
  WriteFileAtomic(out / "comparison.csv", ComparisonCsv(agreements));
  WriteFileAtomic(out / "summary.json", summary.dump(2) + "\n");

  for (const EngineAgreement& a : agreements) {
    for (int b = 1; b <= (a.theta2 ? 2 : 1); ++b) {
      const AngleAgreement& g = b == 1 ? a.theta1 : *a.theta2;
      std::printf(
          "  %s theta%d: max error %.3g rad, RMS %.3g rad, within %.3g rad until %.3f s, peak "
          "%+.2f%% (%+.4f s)\n",
          a.engine.c_str(), b, g.max_abs_error_rad, g.rms_error_rad, g.tolerance_rad, g.horizon_s,
          100.0 * g.peak_rel_error, g.peak_time_error_s);
    }
    std::printf("  %s impacts: %d of %d matched (engine %d), max time error %.3g ms%s%s\n",
                a.engine.c_str(), a.impacts.matched, a.impacts.reference_impacts,
                a.impacts.engine_impacts, a.impacts.max_abs_time_error_s * 1e3,
                a.impacts.first_mismatch.empty() ? "" : "; first mismatch: ",
                a.impacts.first_mismatch.c_str());
    std::printf("  %s overturning %s, final state %s\n", a.engine.c_str(),
                a.overturn_agree ? "agrees" : "DIFFERS", a.final_agree ? "agrees" : "DIFFERS");
  }
  std::printf("outputs in %s (comparison.json, comparison.csv, summary.json, reference/",
              out.string().c_str());
  for (const std::string& name : engines) std::printf(", %s/", name.c_str());
  std::printf(")\n");
}

}  // namespace

void RegisterCompare(CLI::App& app) {
  auto opt = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand(
      "compare", "Run the reference and engines on a scene and compare them with the reference");
  cmd->add_option("scene", opt->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  cmd->add_option("--engines,-e", opt->engines, "Engines to compare with the reference")
      ->capture_default_str();
  cmd->add_option("--set", opt->overrides, "Override a scene value: key=value (repeatable)");
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
