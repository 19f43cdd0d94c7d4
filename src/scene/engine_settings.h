#pragma once
/// An engine's settings: the table [<engine>] of a scene. The scene keeps what the file (and the
/// --set overrides) wrote there, with where each value came from; the engine declares its keys,
/// their types, ranges and defaults in a schema; ResolveEngineSettings checks the one against
/// the other and fills in the defaults. The scene reader knows no engine: an engine's table is
/// checked when that engine is resolved (harness CheckEngineTables does it for every table as
/// soon as a scene is loaded).
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
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

/// An engine's schema that also reads its resolved table into the engine's settings struct `S`,
/// so that each key is written once: a key is bound to the member of S it sets, and the member's
/// default (S{}.*member) is the schema's default. Keys that are not S's (the time step and the
/// drive, which MakeEngineInput reads) go into `unbound()`. The messages for a bad value are the
/// schema's (ResolveEngineSettings): this only adds the reading.
template <class S>
class SettingsTable {
 public:
  explicit SettingsTable(std::string engine) { schema_.engine = std::move(engine); }

  /// The schema: what ResolveEngineSettings checks against, the docs list and summary.json writes.
  const EngineSettingsSchema& schema() const { return schema_; }
  /// The schema, to add keys that S does not hold (read by another function).
  EngineSettingsSchema& unbound() { return schema_; }

  /// A number key setting `member` (unit as in EngineSettingsSchema::Number).
  SettingsTable& Number(std::string key, double S::*member, SettingRange range, std::string unit,
                        std::string engine_default, std::string doc, NumberBounds bounds = {}) {
    schema_.Number(std::move(key), S{}.*member, range, std::move(unit), std::move(engine_default),
                   std::move(doc), bounds);
    return Bind([member](const SettingValue& v, S& s) { s.*member = std::get<double>(v); });
  }
  /// An integer key from min_value to max_value (within int) setting `member`.
  SettingsTable& Integer(std::string key, int S::*member, std::int64_t min_value,
                         std::int64_t max_value, std::string engine_default, std::string doc) {
    schema_.Integer(std::move(key), S{}.*member, min_value, max_value, std::move(engine_default),
                    std::move(doc));
    return Bind([member](const SettingValue& v, S& s) {
      s.*member = static_cast<int>(std::get<std::int64_t>(v));
    });
  }
  /// A flag setting `member`.
  SettingsTable& Flag(std::string key, bool S::*member, std::string engine_default,
                      std::string doc) {
    schema_.Flag(std::move(key), S{}.*member, std::move(engine_default), std::move(doc));
    return Bind([member](const SettingValue& v, S& s) { s.*member = std::get<bool>(v); });
  }
  /// A choice among `values`, each written as name_of(value) (the choices in this order);
  /// sets `member` to the value chosen.
  template <class T, class NameOf>
  SettingsTable& Choice(std::string key, T S::*member, std::vector<T> values, NameOf name_of,
                        std::string engine_default, std::string doc) {
    std::vector<std::string> names;
    for (const T& value : values) names.emplace_back(name_of(value));
    schema_.Choice(std::move(key), std::string(name_of(S{}.*member)), names,
                   std::move(engine_default), std::move(doc));
    return Bind([member, values, names](const SettingValue& v, S& s) {
      const std::string& chosen = std::get<std::string>(v);
      for (size_t i = 0; i < names.size(); ++i) {
        if (names[i] == chosen) s.*member = values[i];
      }
    });
  }

  /// S{} with the value of every bound key, from `settings` resolved against schema().
  S Read(const EngineSettings& settings) const {
    if (settings.values.size() != schema_.settings.size()) {
      throw std::logic_error("settings of " + schema_.engine + " not resolved by its schema");
    }
    S s{};
    for (const auto& [index, set] : setters_) set(settings.values[index].second, s);
    return s;
  }

 private:
  using Setter = std::function<void(const SettingValue&, S&)>;
  // The setter of the key just added to the schema.
  SettingsTable& Bind(Setter set) {
    setters_.emplace_back(schema_.settings.size() - 1, std::move(set));
    return *this;
  }

  EngineSettingsSchema schema_;
  std::vector<std::pair<size_t, Setter>> setters_;  ///< (index in schema_.settings, setter)
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
