#pragma once
/// The committed agreement tolerances (tests/agreement/tolerances.toml): reading and checking
/// the file, grouping its bounds into comparisons, running a comparison in process and checking
/// its measured metrics against the bounds. See docs/agreement.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockbench::agreement {

/// One [[bound]] entry of the tolerance file.
struct Bound {
  std::string file;                   ///< the tolerance file, for messages
  int line = 0;                       ///< line of the entry's first key (0 if unknown)
  int index = 0;                      ///< 1-based position in the file's [[bound]] array
  std::string scene;                  ///< scene file name, relative to the scenes folder
  std::filesystem::path scene_path;   ///< the scene file (exists)
  std::string engine;                 ///< "bullet", or "reference" (reference against itself)
  std::vector<std::string> settings;  ///< --set overrides for both runs ([] = scene as committed)
  /// Extra overrides for the reference run only (required with engine = "reference", where the
  /// engine run is the reference at `settings` and the reference run adds these: e.g. a tight
  /// tolerance).
  std::vector<std::string> reference_settings;
  std::string metric;         ///< as written: a dotted key under engines.<name>, or abs(key)
  std::string metric_path;    ///< the dotted key
  bool metric_abs = false;    ///< metric is abs(key): the bound applies to |value|
  std::optional<double> max;  ///< measured <= max
  std::optional<double> min;  ///< measured >= min
  std::optional<nlohmann::json> equals;  ///< measured == equals (booleans and strings)
  std::string why;                       ///< the measurement and mechanism behind the bound

  /// "FILE:LINE: bound #N (scene, engine, [settings], metric)" for messages.
  std::string Name() const;
  /// "max 1.2e-3", "min 35" or "equals true".
  std::string Describe() const;
};

/// Bounds that share a comparison: the same scene, engine, settings and reference settings.
struct BoundGroup {
  std::string scene;
  std::filesystem::path scene_path;
  std::string engine;
  std::vector<std::string> settings;
  std::vector<std::string> reference_settings;
  std::vector<Bound> bounds;  ///< in file order

  /// A gtest-safe name: scene stem, engine and the settings, e.g.
  /// "thesis_free_rocking_bullet" or "harmonic_reference_vs_model_rtol_1e_12".
  std::string TestName() const;
};

/// An invalid tolerance file: the message names the file, the entry and what was expected.
struct ToleranceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Engines a bound may name: "reference" and every engine of engines/CMakeLists.txt, built or
/// left out. Groups of an engine this build left out (see AvailableEngines) are
/// skipped, not failed.
const std::vector<std::string>& KnownEngines();

/// Parses and checks tolerance-file text: only [[bound]] tables; in each, only the keys above;
/// scene, engine, metric and a non-empty why required; exactly one of max, min, equals; the
/// scene file exists in `scenes_dir` and loads with the settings; the metric is a key of the
/// comparison JSON for that scene (theta2..thetaN only for N blocks) and its kind matches the
/// bound
/// (numbers: max/min, booleans and strings: equals); no entry repeats another's bound. Throws
/// ToleranceError naming `file`, the line and the entry.
std::vector<Bound> ParseTolerances(std::string_view text, const std::string& file,
                                   const std::filesystem::path& scenes_dir);

/// Reads and parses a tolerance file (see ParseTolerances). Throws ToleranceError.
std::vector<Bound> LoadTolerances(const std::filesystem::path& file,
                                  const std::filesystem::path& scenes_dir);

/// Groups bounds by comparison, in order of first appearance; test names are made unique.
std::vector<BoundGroup> GroupBounds(const std::vector<Bound>& bounds);

/// Runs a group's comparison in process (an engine's: RunCompare, as `rockbench compare`; the
/// reference against itself: reference::Simulate -> RunEngine -> CompareWithReference) and
/// returns AgreementJson of it: the object comparison.json holds under engines.<engine>. Throws
/// SceneError on bad settings of the reference against itself.
nlohmann::json RunComparison(const BoundGroup& group);

/// The outcome of one bound against a measured agreement.
struct Verdict {
  bool pass = false;
  std::string measured;  ///< the measured value as text ("6.03e-04", "true", "null")
  std::string message;   ///< one line: metric, measured, bound, margin or failure, why
};

/// Checks one bound against AgreementJson output. A missing key, a null or a value of the wrong
/// kind fails with a message saying so.
Verdict CheckBound(const Bound& bound, const nlohmann::json& agreement);

/// Scene files (*.toml, sorted by name) in `scenes_dir` and its 3-D folder three_d/ (named
/// "three_d/NAME.toml").
std::vector<std::string> SceneFiles(const std::filesystem::path& scenes_dir);

/// "scene: engine" for every scene of `scenes_dir` that has no bound for an engine of
/// KnownEngines() other than the reference (reference-against-itself bounds are extras); for a
/// 3-D scene, the built engines that build its body (the planar ones say why they cannot).
std::vector<std::string> UnguardedScenes(const std::vector<Bound>& bounds,
                                         const std::filesystem::path& scenes_dir);

}  // namespace rockbench::agreement
