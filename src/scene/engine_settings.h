#pragma once
/// An engine's settings: the table [<engine>] of a scene. The scene keeps what the file (and the
/// --set overrides) wrote there, with where each value came from; the engine declares its keys,
/// their types, ranges and defaults in a schema; ResolveEngineSettings checks the one against
/// the other and fills in the defaults. The scene reader knows no engine: an engine's table is
/// checked when that engine is resolved (harness CheckEngineTables does it for every table as
/// soon as a scene is loaded).
#include <cstdint>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace rockbench {

struct Scene;

/// A setting's value: a number, an integer, a flag or a choice (a string).
using SettingValue = std::variant<double, std::int64_t, bool, std::string>;

/// What a number setting must be.
enum class SettingRange {
  kFinite,
  kPositive,
  kNonNegative,
  kNonNegativeOrInfinite,  ///< >= 0, or inf ("no bound"; JSON writes it as null)
  kFraction,               ///< (0, 1]
  kUnitInterval,           ///< [0, 1]
};

/// Bounds of a number setting narrower than its SettingRange says, for what an engine cannot
/// take: ODE's SOR factor in (0, 2), Moreau-Jean's theta from 0.5, DART's cfm from its floor
/// 1e-9. Checked with the range (the tighter end wins), and named in the error message.
struct NumberBounds {
  double min = -std::numeric_limits<double>::infinity();  ///< lower bound, in the unit
  bool min_open = false;                                  ///< true: min itself excluded
  double max = std::numeric_limits<double>::infinity();   ///< upper bound, in the unit
  bool max_open = false;                                  ///< true: max itself excluded
  bool any() const {
    return min != -std::numeric_limits<double>::infinity() ||
           max != std::numeric_limits<double>::infinity();
  }
};

/// One key of an engine's table.
struct SettingDef {
  std::string key;                             ///< "time_step"
  SettingValue default_value;                  ///< ours; its alternative is the setting's type
  SettingRange range = SettingRange::kFinite;  ///< numbers
  NumberBounds bounds;                         ///< numbers: narrower than `range`, if set
  std::int64_t min_integer = 1;                ///< integers: the allowed range
  std::int64_t max_integer = std::numeric_limits<std::int64_t>::max();
  std::vector<std::string> choices;  ///< strings: the allowed values
  std::string unit;                  ///< "s", "m", "m/s", "" (shown in messages and docs)
  std::string engine_default;        ///< the engine's own default, as text ("1/60 s")
  std::string doc;                   ///< one line: what it sets, and why ours differs
};

/// The keys of one engine's table, in the order the docs list them.
struct EngineSettingsSchema {
  std::string engine;  ///< the table's name: "bullet"
  std::vector<SettingDef> settings;

  /// The definition of `key`, or nullptr.
  const SettingDef* Find(std::string_view key) const;

  // Adding keys, in the docs' order: the key, our default, what is allowed, the engine's own
  // default as text ("1/60 s", "-" when it has none) and one line of doc. A number may have
  // bounds narrower than its range: every range check of a setting is said here, once.
  EngineSettingsSchema& Number(std::string key, double value, SettingRange range, std::string unit,
                               std::string engine_default, std::string doc,
                               NumberBounds bounds = {});
  EngineSettingsSchema& Integer(std::string key, std::int64_t value, std::int64_t min_value,
                                std::int64_t max_value, std::string engine_default,
                                std::string doc);
  EngineSettingsSchema& Flag(std::string key, bool value, std::string engine_default,
                             std::string doc);
  EngineSettingsSchema& Choice(std::string key, std::string value, std::vector<std::string> choices,
                               std::string engine_default, std::string doc);
};

/// One value a scene gave, and where: "FILE:LINE" or "FILE: override \"k=v\"".
struct RawSetting {
  SettingValue value;
  std::string where;
};

/// An engine's table as the scene gave it (not yet checked against the engine's schema).
struct RawEngineTable {
  std::string where;  ///< "FILE:LINE" of the table header
  std::map<std::string, RawSetting, std::less<>> values;
};

/// An engine's settings, checked, defaults filled in.
class EngineSettings {
 public:
  double Number(std::string_view key) const;
  std::int64_t Integer(std::string_view key) const;
  bool Flag(std::string_view key) const;
  const std::string& Choice(std::string_view key) const;
  /// {"key": value, ...} in schema order (summary.json "settings").
  nlohmann::json ToJson() const;

  /// (key, value) in schema order.
  std::vector<std::pair<std::string, SettingValue>> values;

 private:
  const SettingValue& Get(std::string_view key) const;
};

/// Checks the scene's [schema.engine] table (absent: all defaults) against the schema and fills
/// in the defaults. Throws SceneError "WHERE: engine.key: ..." for an unknown key (naming the
/// known ones), a value of the wrong type or out of range.
EngineSettings ResolveEngineSettings(const Scene& scene, const EngineSettingsSchema& schema);

/// Sets `engine`.`key` in a scene (sweeps and the stress catalogue set engine settings this
/// way, as --set would). The value is checked when the engine is resolved.
void SetEngineSetting(Scene& scene, const std::string& engine, const std::string& key,
                      SettingValue value);

/// The value as TOML would write it: 1e-4, 50, true, "double".
std::string SettingText(const SettingValue& value);

}  // namespace rockbench
