#include "report/run/run_readers.h"

#include <algorithm>
#include <stdexcept>

#include "files/history_csv.h"
#include "report/common/json_keys.h"
#include "report/common/names.h"
#include "run/engine_registry.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Line colours of the engines after the reference (black): distinct in hue and in greyscale.
constexpr const char* kEngineColours[] = {"#d95f02", "#1b9e77", "#7570b3", "#e7298a", "#66a61e"};

// "one block", "two blocks", "N blocks"; with `count_only`: "one", "two", "N".
std::string BlocksText(int n, bool count_only = false) {
  const std::string count = n == 1 ? "one" : n == 2 ? "two" : std::to_string(n);
  return count_only ? count : count + (n == 1 ? " block" : " blocks");
}

// The reference ensemble of a compare folder, when it has one.
void ReadReferenceEnsemble(RunData& run) {
  const int nb = run.scene.block_count();
  if (run.comparison) {
    run.predictability = ReadPredictability(*run.comparison, run.comparison_path, nb);
  }
  const fs::path csv = run.dir / "reference" / "ensemble_band.csv";
  run.band = ReadEnsembleBand(csv);
  // The file's theta columns say how many blocks it has.
  const bool band_differs = run.band && run.band->blocks != nb;
  if (band_differs) {
    throw std::runtime_error(csv.string() + ": has " + BlocksText(run.band->blocks) +
                             " but the scene " + run.scene.path.string() + " has " +
                             BlocksText(nb, true));
  }
}

// summary.json, the overrides it lists and the scene it names, reloaded.
void ReadSummaryAndScene(const fs::path& run_dir, RunData& run) {
  if (!fs::is_directory(run_dir)) {
    throw std::runtime_error(run_dir.string() +
                             ": not a folder (expected a run folder written by " +
                             "`rockbench run` or `rockbench compare`)");
  }
  run.summary_path = run_dir / "summary.json";
  if (!fs::exists(run.summary_path)) {
    throw std::runtime_error(run.summary_path.string() +
                             ": not found (a run folder from `rockbench run` or `rockbench "
                             "compare` has one)");
  }
  run.summary = ReadJson(run.summary_path);
  if (!run.summary.is_object()) {
    throw std::runtime_error(run.summary_path.string() + ": expected a JSON object");
  }
  const std::string scene_path = OptString(run.summary, "scene.path", run.summary_path);
  if (scene_path.empty()) {
    throw std::runtime_error(run.summary_path.string() +
                             ": key 'scene.path' is missing (the scene file the run used)");
  }
  if (const json* o = Find(run.summary, "scene.overrides"); o != nullptr && !o->is_null()) {
    if (!o->is_array()) {
      throw std::runtime_error(run.summary_path.string() +
                               ": key 'scene.overrides' must be a list of \"key=value\" strings");
    }
    for (const json& v : *o) {
      if (!v.is_string()) {
        throw std::runtime_error(run.summary_path.string() +
                                 ": key 'scene.overrides' must be a list of strings, found " +
                                 v.dump());
      }
      run.overrides.push_back(v.get<std::string>());
    }
  }
  if (!fs::exists(scene_path)) {
    throw std::runtime_error("the scene file " + scene_path + " (scene.path in " +
                             run.summary_path.string() +
                             ") is gone: the report reloads it for the geometry, base motion "
                             "and friction");
  }
  run.scene = LoadScene(scene_path, run.overrides);
}

// The reference's and every engine's history.csv and events.csv, with colour and label.
void ReadEngines(const fs::path& run_dir, RunData& run) {
  const std::string scene_path = run.scene.path.string();
  // Engines: the reference, then those in summary.json's "engines" (sorted by name).
  std::vector<std::string> names;
  if (!fs::exists(run_dir / "reference" / "history.csv")) {
    throw std::runtime_error(
        (run_dir / "reference" / "history.csv").string() +
        ": not found; a report compares with the reference model, so the run "
        "folder needs it (`rockbench run SCENE` or `rockbench compare SCENE`)");
  }
  names.push_back("reference");
  if (const json* e = Find(run.summary, "engines"); e != nullptr && !e->is_null()) {
    if (!e->is_object()) {
      throw std::runtime_error(run.summary_path.string() + ": key 'engines' must be an object");
    }
    for (auto it = e->begin(); it != e->end(); ++it) {
      // A key names a folder of the run and reaches figures and pages: engine names only.
      RequireEngineName(it.key(), run.summary_path.string() + ": key 'engines'");
      if (!IsReference(it.key())) names.push_back(it.key());
    }
  }
  int colour = 0;
  for (const std::string& name : names) {
    EngineData d;
    d.name = name;
    d.history = ReadHistoryCsv(run_dir / name / "history.csv");
    d.events = ReadEventsCsv(run_dir / name / "events.csv", d.history.blocks, d.history.shape);
    if (d.history.samples.empty()) {
      throw std::runtime_error((run_dir / name / "history.csv").string() + ": has no samples");
    }
    if (d.history.blocks != run.scene.block_count()) {
      throw std::runtime_error((run_dir / name / "history.csv").string() + ": has " +
                               BlocksText(d.history.blocks) + " but the scene " + scene_path +
                               " has " + BlocksText(run.scene.block_count(), true));
    }
    if (IsReference(name)) {
      d.summary = run.summary;
      d.colour = "#000000";
      d.label = "reference model";
    } else {
      d.summary = run.summary["engines"][name];
      d.colour = kEngineColours[colour++ % std::size(kEngineColours)];
      d.label = name;
    }
    run.t_end_s = std::max(run.t_end_s, d.history.samples.back().t_s);
    run.engines.push_back(std::move(d));
  }
}

}  // namespace

RunData ReadRunFolder(const fs::path& run_dir) {
  RunData run;
  run.dir = run_dir;
  ReadSummaryAndScene(run_dir, run);
  run.comparison_path = run_dir / "comparison.json";
  if (fs::exists(run.comparison_path)) run.comparison = ReadJson(run.comparison_path);
  ReadReferenceEnsemble(run);

  ReadEngines(run_dir, run);
  return run;
}

}  // namespace rockbench::report
