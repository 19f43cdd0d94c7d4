#pragma once
/// A run folder read back (`rockbench compare` or `rockbench run` output): summary.json, the
/// scene it names (reloaded with its overrides), comparison.json when present, the reference
/// ensemble's band, and every engine's history.csv and events.csv, the reference first.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "report/compare/predictability.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::report {

/// One run of the folder: the reference model or an engine.
struct EngineData {
  std::string name;
  History history;
  std::vector<Event> events;
  nlohmann::json summary;  ///< the engine's part of summary.json (the reference: the whole)
  std::string colour;      ///< line colour on every figure
  std::string label;       ///< legend text
};

/// Everything a run report reads from a run folder.
struct RunData {
  std::filesystem::path dir;
  std::filesystem::path summary_path, comparison_path;
  nlohmann::json summary;
  std::optional<nlohmann::json> comparison;
  Scene scene;
  std::vector<std::string> overrides;
  std::vector<EngineData> engines;  ///< the reference first
  double t_end_s = 0.0;             ///< the latest sample of any history, s
  /// The reference ensemble (comparison.json "predictability"; reference/ensemble_band.csv):
  /// nullopt when none was run.
  std::optional<Predictability> predictability;
  std::optional<EnsembleBand> band;
};

/// Reads a run folder. Throws std::runtime_error naming the file (and key) that is missing or
/// malformed, or the scene file that is gone; SceneError for a scene that no longer loads.
RunData ReadRunFolder(const std::filesystem::path& run_dir);

}  // namespace rockbench::report
