// `rockbench compare SCENE --out DIR [--engines all|NAME,NAME] [--members N] [--quick] [--set k=v
// ...]`: runs the reference (checked against its witness), its perturbation members (runs on
// perturbed inputs: the predictability horizon), each engine, and each engine's perturbation
// members beyond the horizon (files ensemble.csv and ensemble_band.csv keep their names); writes
// histories, comparison.json, comparison.csv and summary.json, and prints one verdict per engine.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "compare/agreement.h"
#include "compare/compare_run.h"
#include "compare/perturbation_members.h"
#include "compare/verdict.h"
#include "engine/engine.h"
#include "files/atomic_file.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_witness.h"
#include "run/resource_estimate.h"
#include "run/summary.h"
#include "scene/body_kind.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "util/format.h"

namespace rockbench::cli {
namespace {

struct CompareCliOptions {
  std::string scene;
  std::string out = "out";
  std::string engines = "all";
  std::vector<std::string> overrides;
  int members = -1;         // -1: the scene's compare.members
  int engine_members = -1;  // -1: the scene's compare.engine_members
  bool quick = false;       // no perturbation members: pointwise comparison only
  int jobs = 0;             // 0: all hardware threads
  LimitOptions limits;
};

// Writes the comparison's files into `out`, each to a temporary name renamed when complete:
// every run's history, the perturbation members' files, comparison.json, comparison.csv and
// summary.json.
void WriteCompareFiles(const CompareCliOptions& opt, const std::vector<std::string>& overrides,
                       const Scene& scene, const GroundMotion& motion, const CompareRun& run,
                       const std::filesystem::path& out) {
  const int nb = scene.block_count();
  WriteEngineFiles(run.reference_run, out);
  const bool cylinder = run.cylinder_reference() != nullptr;
  // Each ensemble's members: a cylinder's with its transverse factor and fall azimuth.
  const auto outcomes_csv = [&](const std::vector<MemberOutcome>& outcomes) {
    const std::vector<MemberPerturbation>& p = run.perturbation_members->perturbations;
    return cylinder ? CylinderOutcomesCsv(outcomes, p) : OutcomesCsv(outcomes, p, nb);
  };
  if (run.perturbation_members) {
    WriteFileAtomic(out / "reference" / "ensemble_band.csv",
                    PerturbationBandCsv(*run.perturbation_members));
    WriteFileAtomic(out / "reference" / "ensemble.csv",
                    outcomes_csv(run.perturbation_members->outcomes));
  }
  nlohmann::json summary;
  summary["scene"] = {{"path", std::filesystem::absolute(opt.scene).lexically_normal().string()},
                      {"overrides", overrides},
                      {"two_blocks", nb == 2}};
  summary["base"] = BaseMotionJson(motion);
  for (auto it = run.reference_run.summary.begin(); it != run.reference_run.summary.end(); ++it) {
    summary[it.key()] = *it;
  }
  // The engines that ran (a failed engine is left out: its verdict says why), and what this
  // command wrote: render and report draw these folders only, never an older one left in DIR.
  nlohmann::json written = nlohmann::json::array({"reference"});
  for (size_t k = 0; k < run.engine_runs.size(); ++k) {
    const std::string& name = run.engine_runs[k].engine;
    WriteEngineFiles(run.engine_runs[k], out);
    summary["engines"][name] = run.engine_runs[k].summary;
    written.push_back(name);
    if (!run.engine_outcomes[k].empty()) {
      WriteFileAtomic(out / name / "ensemble.csv", outcomes_csv(run.engine_outcomes[k]));
    }
  }
  summary["engines_written"] = written;
  for (const FailedEngine& f : run.failed_engines) summary["failed_engines"][f.engine] = f.reason;
  WriteFileAtomic(out / "comparison.json", run.comparison.dump(2) + "\n");
  WriteFileAtomic(out / "comparison.csv", ComparisonCsv(run.agreements));
  WriteFileAtomic(out / "summary.json", summary.dump(2) + "\n");
}

// Prints one engine's agreement: every body's angle, slip and lift, the impacts (faster than
// `min_impact_rate_radps`), the outcomes and the final state.
void PrintAgreement(const EngineAgreement& a, double min_impact_rate_radps, bool cylinder) {
  // Every compared angle (a cylinder's tilt_x1 and tilt_y1), with its body.
  std::vector<std::pair<int, const AngleAgreement*>> angles;
  for (int b = 1; b <= a.blocks(); ++b) {
    angles.emplace_back(b, &a.angle(b));
    for (const AngleAgreement& g : a.body(b).more_angles) angles.emplace_back(b, &g);
  }
  for (const auto& [b, gp] : angles) {
    const AngleAgreement& g = *gp;
    std::printf(
        "  %s %s: max error %.3g rad (%.3g where the reference is predictable: %.3g x the "
        "local tolerance), RMS %.3g rad, within the local tolerance until %.3f s, ",
        a.engine.c_str(), BodyColumn(g.quantity, b).c_str(), g.max_abs_error_rad,
        g.max_abs_error_predictable_rad, g.max_error_ratio_predictable, g.rms_error_rad,
        g.horizon_s);
    if (g.judged) {
      std::printf("peak %+.2f%% (%+.4f s)\n", 100.0 * g.peak_rel_error, g.peak_time_error_s);
    } else {
      // Below the floor a relative peak error means nothing: the absolute one, and the peak
      // judgement that replaces the pointwise one.
      std::printf(
          "peak %.3g rad against the reference's %.3g rad (%+.3g rad); not judged point by "
          "point (the reference's peak is below %g x the tolerance floor %.3g rad): its peak "
          "%s the peak tolerance %.3g rad\n",
          g.peak_engine_rad, g.peak_reference_rad, g.peak_engine_rad - g.peak_reference_rad,
          kJudgedPeakOverFloor, g.floor_rad, g.peak_within_tolerance ? "within" : "BEYOND",
          g.peak_tolerance_rad);
    }
  }
  // Slip and lift, where the histories carry them.
  for (int b = 1; b <= a.blocks(); ++b) {
    for (const std::optional<SlipAgreement>* slip : {&a.body(b).slip, &a.body(b).lift}) {
      if (!*slip) continue;
      const SlipAgreement& g = **slip;
      const bool lift = g.quantity == "z";
      std::printf(
          "  %s %s (%s): max error %.3g m (%.3g m within a time slack of %g s; tolerance "
          "%.3g m: 10%% of the reference's peak %.3g m, at least %.3g m), %s, final %.4g m "
          "against the reference's %.4g m\n",
          a.engine.c_str(), BodyColumn(g.quantity, b).c_str(), lift ? "lift" : "slip",
          g.max_abs_error_m, g.max_abs_error_slack_m, g.time_slack_s, g.tolerance_m,
          g.peak_reference_m, g.floor_m,
          g.within_tolerance ? "within it throughout"
                             : ("LEAVES it at " + Format("%.3f", g.horizon_s) + " s").c_str(),
          g.final_engine_m, g.final_reference_m);
    }
  }
  // A cylinder's landings are not matched one by one (each summary counts them).
  if (!cylinder) {
    std::printf(
        "  %s impacts faster than %g rad/s: %d of %d matched (engine %d; all impacts: "
        "reference %d, engine %d), max time error %.3g ms%s%s\n",
        a.engine.c_str(), min_impact_rate_radps, a.impacts.matched, a.impacts.reference_impacts,
        a.impacts.engine_impacts, a.impacts.reference_impacts_all, a.impacts.engine_impacts_all,
        a.impacts.max_abs_time_error_s * 1e3,
        a.impacts.first_mismatch.empty() ? "" : "; first mismatch: ",
        a.impacts.first_mismatch.c_str());
  }
  // Leaving the support is named where either run had a block leave it.
  const bool left = a.left_support_block_reference || a.left_support_block_engine;
  // Outcomes after the instant the model stops deciding are not compared (agreement.h).
  const std::string decided = a.reference_undetermined_s
                                  ? Format(" up to %.4f s (the model does not decide after it)",
                                           *a.reference_undetermined_s)
                                  : std::string();
  // A cylinder's fall: toward which azimuth in each run.
  std::string fall;
  if (a.overturn_azimuth_reference_rad || a.overturn_azimuth_engine_rad) {
    const auto az = [](const std::optional<double>& v) {
      return v ? Format("%+.3f rad", *v) : std::string("none");
    };
    fall = " (fall azimuth: engine " + az(a.overturn_azimuth_engine_rad) + ", reference " +
           az(a.overturn_azimuth_reference_rad) + ")";
  }
  std::printf("  %s overturning %s%s%s%s%s, final state %s\n", a.engine.c_str(),
              a.overturn_agree ? "agrees" : "DIFFERS", fall.c_str(),
              left ? ", leaving the support " : "",
              !left ? "" : (a.left_support_agree ? "agrees" : "DIFFERS"), decided.c_str(),
              a.final_agree ? "agrees" : "DIFFERS");
}

void Execute(const CompareCliOptions& opt) {
  std::vector<std::string> overrides = opt.overrides;
  if (opt.members >= 0) overrides.push_back("compare.members=" + std::to_string(opt.members));
  if (opt.quick) overrides.push_back("compare.members=0");
  if (opt.engine_members >= 0) {
    overrides.push_back("compare.engine_members=" + std::to_string(opt.engine_members));
  }
  const ResourceBudget budget = StartLimits(opt.limits, opt.out, "compare");
  const Scene scene = LoadScene(opt.scene, overrides);
  CheckEngineTables(scene);
  std::vector<std::string> engines = ParseEnginesBesideReference(opt.engines);
  // "all" on a scene whose bodies an engine does not build (a cylinder in a planar engine): that
  // engine is left out, and said why; named on its own, it fails as any engine that cannot run.
  if (opt.engines == "all") {
    std::string not_run;
    engines = EnginesThatBuild(scene, engines, &not_run);
    std::fputs(not_run.c_str(), stderr);
  }
  // An engine the scene brings runs only when the user names it: said, with how to opt in.
  std::fputs(NotRunNote(engines).c_str(), stderr);
  const int threads =
      opt.jobs > 0 ? opt.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CheckRunEstimate(
      EstimateRun(scene, engines, scene.compare.members, scene.compare.engine_members, threads),
      budget, opt.scene);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);
  CompareRunOptions run_options;
  run_options.jobs = opt.jobs;
  run_options.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  const CompareRun run = RunCompare(scene, motion, engines, run_options);

  WriteCompareFiles(opt, overrides, scene, motion, run, out);
  const std::vector<EngineAgreement>& agreements = run.agreements;
  for (const EngineAgreement& a : agreements) {
    PrintAgreement(a,
                   run.comparison["impact_min_rate_radps"].is_number()
                       ? run.comparison["impact_min_rate_radps"].get<double>()
                       : 0.0,
                   run.cylinder_reference() != nullptr);
  }
  for (const EngineAgreement& a : agreements) {
    std::printf("verdict %s: %s: %s\n", a.engine.c_str(), VerdictLabel(a.verdict_kind).c_str(),
                a.verdict.c_str());
  }
  for (const FailedEngine& f : run.failed_engines) {
    std::printf("verdict %s: FAILED: %s\n", f.engine.c_str(), f.reason.c_str());
  }
  std::printf("outputs in %s (comparison.json, comparison.csv, summary.json, reference/",
              out.string().c_str());
  for (const EngineRun& r : run.engine_runs) std::printf(", %s/", r.engine.c_str());
  std::printf(")\n");
  // An engine that failed: the others' outputs are complete; the command failed.
  if (!run.failed_engines.empty()) {
    std::fflush(stdout);
    for (const FailedEngine& f : run.failed_engines) {
      std::fprintf(stderr,
                   "rockbench: compare failed: %s: %s (the other engines' outputs are "
                   "written)\n",
                   f.engine.c_str(), f.reason.c_str());
    }
    for (const std::string& f : run.failures) {
      std::fprintf(stderr, "rockbench: compare failed: %s\n", f.c_str());
    }
    throw CLI::RuntimeError(kExitRunFailed);
  }
  // A comparison resting on a run that ended non_finite failed.
  if (!run.failures.empty()) {
    std::fflush(stdout);
    for (const std::string& f : run.failures) {
      std::fprintf(stderr, "rockbench: compare failed: %s\n", f.c_str());
    }
    throw CLI::RuntimeError(kExitRunFailed);
  }
  // The reference's model stopped deciding the motion: said, and exit 5 as `run`. (A cylinder's
  // landing has one outcome.)
  if (run.cylinder_reference()) return;
  const reference::Summary& rs = run.reference().used().summary;
  if (rs.undetermined_from_s) {
    std::fflush(stdout);
    std::fprintf(stderr, "rockbench: reference: %s; no engine is compared after it\n",
                 StopsDecidingText(*rs.undetermined_from_s, rs.undetermined_detail).c_str());
    throw CLI::RuntimeError(kExitUndetermined);
  }
}

}  // namespace

void RegisterCompare(CLI::App& app) {
  auto opt = std::make_shared<CompareCliOptions>();
  auto* cmd = app.add_subcommand(
      "compare", "Run the reference and engines on a scene and compare them with the reference");
  cmd->add_option("scene", opt->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  cmd->add_option("--engines,-e", opt->engines,
                  "Engines to compare with the reference: a comma-separated list, or all "
                  "(`rockbench engines` lists them)")
      ->capture_default_str();
  cmd->add_option("--members", opt->members,
                  "Reference perturbation members, for the predictability horizon (default: the "
                  "scene's compare.members, 32); 0: pointwise comparison only")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option(
         "--engine-members", opt->engine_members,
         "Engine perturbation members beyond the horizon (default: compare.engine_members, 16)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quick", opt->quick, "No perturbation members: the pointwise comparison only");
  cmd->add_option("--jobs,-j", opt->jobs,
                  "Threads for the perturbation members (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--set", opt->overrides, "Override a scene value: key=value (repeatable)");
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
