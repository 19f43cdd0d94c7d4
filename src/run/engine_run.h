#pragma once
/// Runs an engine on a scene and writes its files: the one place the harness knows every engine.
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench {

/// What an engine run produced.
struct EngineRun {
  std::string engine;  ///< "reference", "bullet", ...
  History history;
  RunOutcome outcome;      ///< typed: status, peaks, impacts, violations
  nlohmann::json summary;  ///< the engine's part of summary.json (everything it measured)
  double wall_s = 0.0;     ///< wall-clock time of the simulation alone, s
  std::string one_line;    ///< one-line human summary
  /// Where `summary` goes in the run's summary.json (Engine::SummaryPointer): a JSON pointer,
  /// "" for the top level.
  std::string summary_pointer;
  /// The engine's richer result (the reference's: run/reference_engine.h ReferenceResultOf).
  std::shared_ptr<const EngineResultExtension> extension;
};

/// Whether `status` is non_finite, the status of a run (the reference's or an engine's) whose
/// state, energy, an event time or a contact force stopped being finite: the run failed. Its
/// history, events and summary end at its last finite state (summary.json "non_finite": quantity,
/// value, t_s, last_finite_t_s); it is never an agreement (compare/verdict.h) and `run` and
/// `compare` exit with a failure.
inline bool IsNonFinite(RunStatus status) {
  return status == RunStatus::kNonFinite;
}

/// "reference" and the engines this build has (run/engine_registry.h), in that order.
std::vector<std::string> AvailableEngines();

/// Runs engine `name` ("reference" or a physics engine: the same interface, scene/engine.h).
/// Throws SceneError for an unknown engine or impossible settings.
EngineRun RunEngine(const std::string& name, const Scene& scene, const GroundMotion& motion,
                    const SimulateOptions& options = {});

/// "NAME: DETAIL" (the status detail: quantity, value and time) when the run ended non_finite,
/// else "".
std::string NonFiniteText(const EngineRun& run);

/// Puts the run's summary in `summary` (summary.json) where its engine says
/// (EngineRun::summary_pointer): under that pointer, or its keys at the top level.
void AddRunSummary(nlohmann::json& summary, const EngineRun& run);

/// Writes DIR/<engine>/history.csv and DIR/<engine>/events.csv atomically.
void WriteEngineFiles(const EngineRun& run, const std::filesystem::path& out_dir);

/// summary.json's base part: {"horizontal": {...}, "vertical": {...}} (absent components omitted).
nlohmann::json BaseMotionJson(const GroundMotion& motion);

}  // namespace rockbench
