// Fuzz target scene_run: a scene read (rockbench::ParseScene) and, when it is valid and its base
// motions are analytic or synthetic (no record file), run by the reference model
// (rockbench::reference::Simulate on GroundMotion::FromScene), as `rockbench run` does.
// Input: a scene file's text. Findings: an exception other than SceneError, a crash or
// sanitizer report, a run that takes longer than libFuzzer's -timeout or more memory than its
// -rss_limit_mb (scripts/fuzz.sh sets both), and a run whose summary says "completed" with a
// non-finite angle or rate in its history or a non-finite peak in its summary.
//
// Not run (not findings): scenes longer than kMaxDuration_s simulated seconds or with more than
// kMaxRows output rows. Their cost is what the input asks for, in proportion (the program's
// --wall-limit and memory budget bound it); what is looked for here is cost out of proportion.
#include <cmath>
#include <string>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

constexpr double kMaxDuration_s = 30.0;
constexpr double kMaxRows = 1e5;

bool UsesFile(const std::optional<rockbench::MotionDef>& m) {
  return m && m->kind == rockbench::MotionKind::kFile;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  static const std::filesystem::path path =
      rockbench::fuzz::SourceDir() / "scenes" / "fuzz_run.toml";
  rockbench::fuzz::ExpectOnlySceneErrors("scene_run", [&] {
    const rockbench::Scene scene = rockbench::ParseScene(text, path);
    if (UsesFile(scene.horizontal) || UsesFile(scene.vertical)) return;
    if (!(scene.run.duration_s <= kMaxDuration_s)) return;
    if (!(scene.run.duration_s / scene.run.output_interval_s <= kMaxRows)) return;
    const rockbench::GroundMotion motion = rockbench::GroundMotion::FromScene(scene);
    const rockbench::reference::Result r = rockbench::reference::Simulate(scene, motion);
    const rockbench::reference::Summary& s = r.summary;
    // A stated outcome (overturned, non_finite, ...).
    if (s.status != rockbench::RunStatus::kCompleted) return;
    const auto check = [&](const std::string& what, double v, double t) {
      if (!std::isfinite(v)) {
        rockbench::fuzz::Finding(std::string("scene_run: status completed, but ") + what + " = " +
                                 rockbench::ShortestText(v) +
                                 " at t = " + rockbench::ShortestText(t) + " s");
      }
    };
    for (int k = 0; k < s.blocks(); ++k) {
      check("peak_theta" + std::to_string(k + 1), s.peak_theta_rad[k], s.peak_theta_t_s[k]);
    }
    for (const rockbench::Sample& x : r.history.samples) {
      check("t", x.t_s, x.t_s);
      check("theta1 in history", x.theta_rad[0], x.t_s);
      check("omega1 in history", x.omega_radps[0], x.t_s);
      if (r.history.blocks == 2) {
        check("theta2 in history", x.theta_rad[1], x.t_s);
        check("omega2 in history", x.omega_radps[1], x.t_s);
      }
    }
  });
  return 0;
}
