#include "run/engine_run.h"

#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "run/engine_registry.h"
#include "run/reference_engine.h"
#include "util/relayed_text.h"

namespace rockbench {

std::vector<std::string> AvailableEngines() {
  std::vector<std::string> names = {TheReference().name()};
  for (const std::string& n : BuiltEngineNames()) names.push_back(n);
  return names;
}

EngineRun RunEngine(const std::string& name, const Scene& scene, const GroundMotion& motion,
                    const SimulateOptions& options) {
  const Engine* engine = FindEngine(name);
  if (engine == nullptr) {
    ParseEngineList(name);  // throws, naming what this build has and what it left out
    throw SceneError("unknown engine '" + name + "'");
  }
  CheckBuildsBodies(*engine, scene);
  EngineResult result = engine->Simulate(scene, motion, options);
  EngineRun run;
  run.engine = name;
  run.one_line = engine->SummaryLine(result);
  run.summary_pointer = engine->SummaryPointer();
  if (IsNonFinite(result.outcome.status)) {
    // The detail may quote an external engine's output: escaped and capped.
    run.one_line +=
        "\n  FAILED: " + EscapedText(result.summary.value("status_detail", std::string()));
  }
  run.history = std::move(result.history);
  run.outcome = std::move(result.outcome);
  run.summary = std::move(result.summary);
  run.wall_s = result.wall_s;
  run.extension = std::move(result.extension);
  return run;
}

std::string NonFiniteText(const EngineRun& run) {
  if (!IsNonFinite(run.outcome.status)) return "";
  return run.engine + ": " +
         EscapedText(run.summary.value("status_detail", std::string("not finite")));
}

void AddRunSummary(nlohmann::json& summary, const EngineRun& run) {
  if (run.summary_pointer.empty()) {
    for (auto it = run.summary.begin(); it != run.summary.end(); ++it) summary[it.key()] = *it;
    return;
  }
  summary[nlohmann::json::json_pointer(run.summary_pointer)] = run.summary;
}

void WriteEngineFiles(const EngineRun& run, const std::filesystem::path& out_dir) {
  const auto dir = out_dir / run.engine;
  std::filesystem::create_directories(dir);
  WriteFileAtomic(dir / "history.csv", HistoryToCsv(run.history));
  WriteFileAtomic(dir / "events.csv", EventsToCsv(run.history));
}

}  // namespace rockbench
