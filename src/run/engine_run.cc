#include "run/engine_run.h"

#include <chrono>
#include <cstdio>

#include "run/reference_witness.h"
#include "run/engine_registry.h"
#include "run/summary.h"
#include "reference/simulate.h"

namespace rockbench {

std::vector<std::string> AvailableEngines() {
  std::vector<std::string> names = {"reference"};
  for (const std::string& n : BuiltEngineNames()) names.push_back(n);
  return names;
}

EngineRun RunEngine(const std::string& name, const Scene& scene, const GroundMotion& motion,
                    const RunEngineOptions& options) {
  if (name == "reference") {
    const CheckedReference checked = RunCheckedReference(scene, motion, options.reference_witness);
    EngineRun run = ReferenceRunOf(scene, checked);
    const reference::Summary& s = checked.used().summary;
    char line[256];
    std::snprintf(line, sizeof line,
                  "reference: %s, peak |theta1| %.4g rad at %.3f s, peak |theta2| %.4g rad at "
                  "%.3f s, %d impacts, %.3g ms",
                  s.status.c_str(), s.peak_theta1_rad, s.peak_theta1_t_s, s.peak_theta2_rad,
                  s.peak_theta2_t_s, s.impacts_ground + s.impacts_interface, run.wall_s * 1e3);
    run.one_line = line;
    if (checked.check && !checked.check->converged) {
      run.one_line += "\n  WARNING: " + ConvergenceWarning(*checked.check);
    }
    if (IsNonFinite(s.status)) run.one_line += "\n  FAILED: " + s.status_detail;
    return run;
  }
  const Engine* engine = FindEngine(name);
  if (engine == nullptr) {
    ParseEngineList(name);  // throws, naming what this build has and what it left out
    throw SceneError("unknown engine '" + name + "'");
  }
  SimulateOptions simulate;
  simulate.stop_at_rest_after_s = options.stop_at_rest_after_s;
  EngineResult result = engine->Simulate(scene, motion, simulate);
  EngineRun run;
  run.engine = name;
  run.history = std::move(result.history);
  run.outcome = std::move(result.outcome);
  run.summary = std::move(result.summary);
  run.wall_s = result.wall_s;
  const RunOutcome& o = run.outcome;
  std::string flags;
  for (const std::string& f : o.violations) flags += (flags.empty() ? "" : ",") + f;
  char line[320];
  std::snprintf(line, sizeof line,
                "%s (%s): %s, peak |theta1| %.4g rad at %.3f s, %d impacts, flags: %s, %.3g ms",
                name.c_str(), result.settings_line.c_str(), o.status.c_str(), o.peak_theta1_rad,
                o.peak_theta1_t_s, o.impacts(), flags.empty() ? "none" : flags.c_str(),
                run.wall_s * 1e3);
  run.one_line = line;
  if (IsNonFinite(o.status)) {
    run.one_line += "\n  FAILED: " + run.summary.value("status_detail", std::string());
  }
  return run;
}

std::string NonFiniteText(const EngineRun& run) {
  if (!IsNonFinite(run.outcome.status)) return "";
  return run.engine + ": " + run.summary.value("status_detail", std::string("not finite"));
}

void WriteEngineFiles(const EngineRun& run, const std::filesystem::path& out_dir) {
  const auto dir = out_dir / run.engine;
  std::filesystem::create_directories(dir);
  WriteFileAtomic(dir / "history.csv", HistoryToCsv(run.history));
  WriteFileAtomic(dir / "events.csv", EventsToCsv(run.history));
}

}  // namespace rockbench
