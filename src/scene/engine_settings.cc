#include "scene/engine_settings.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "scene/limits.h"
#include "scene/scene.h"

namespace rockbench {
namespace {

std::string NumberText(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string RangeText(SettingRange range) {
  switch (range) {
    case SettingRange::kFinite:
      return "a finite number";
    case SettingRange::kPositive:
      return "a positive number";
    case SettingRange::kNonNegative:
      return "a number >= 0";
    case SettingRange::kNonNegativeOrInfinite:
      return "a number >= 0, or inf";
    case SettingRange::kFraction:
      return "a number in (0, 1]";
    case SettingRange::kUnitInterval:
      return "a number in [0, 1]";
  }
  return "a number";
}

// A bound as it reads best in a message: "2", "0.5", "1e-9" (not "1e-09").
std::string BoundText(double v) {
  std::string t = NumberText(v);
  const size_t e = t.find('e');
  if (e == std::string::npos) return t;
  size_t digits = e + 1;
  if (digits < t.size() && (t[digits] == '-' || t[digits] == '+')) ++digits;
  while (digits + 1 < t.size() && t[digits] == '0') t.erase(digits, 1);
  if (t[e + 1] == '+') t.erase(e + 1, 1);
  return t;
}

// The range with its narrower bounds, for messages: "a number in (0, 2)", "a number >= 1e-9",
// "a number in [0.5, 1]".
std::string RangeText(SettingRange range, const NumberBounds& bounds) {
  if (!bounds.any()) return RangeText(range);
  // The range as an interval, then the tighter end of each side.
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool lo_open = false, hi_open = false;
  switch (range) {
    case SettingRange::kFinite:
      break;
    case SettingRange::kPositive:
      lo = 0.0, lo_open = true;
      break;
    case SettingRange::kNonNegative:
    case SettingRange::kNonNegativeOrInfinite:
      lo = 0.0;
      break;
    case SettingRange::kFraction:
      lo = 0.0, lo_open = true, hi = 1.0;
      break;
    case SettingRange::kUnitInterval:
      lo = 0.0, hi = 1.0;
      break;
  }
  if (bounds.min > lo || (bounds.min == lo && bounds.min_open)) {
    lo = bounds.min, lo_open = bounds.min_open;
  }
  if (bounds.max < hi || (bounds.max == hi && bounds.max_open)) {
    hi = bounds.max, hi_open = bounds.max_open;
  }
  std::string text;
  if (lo > -HUGE_VAL && hi < HUGE_VAL) {
    text = std::string("a number in ")
               .append(lo_open ? "(" : "[")
               .append(BoundText(lo))
               .append(", ")
               .append(BoundText(hi))
               .append(hi_open ? ")" : "]");
  } else if (lo > -HUGE_VAL) {
    text = std::string("a number ").append(lo_open ? "> " : ">= ").append(BoundText(lo));
  } else {
    text = std::string("a number ").append(hi_open ? "< " : "<= ").append(BoundText(hi));
  }
  if (range == SettingRange::kNonNegativeOrInfinite && hi == HUGE_VAL) text.append(", or inf");
  return text;
}

bool InBounds(double v, const NumberBounds& b) {
  if (v == HUGE_VAL && b.max == HUGE_VAL) return true;  // the range says whether inf is allowed
  const bool above = b.min_open ? v > b.min : v >= b.min;
  const bool below = b.max_open ? v < b.max : v <= b.max;
  return above && below;
}

// Every engine number: at most 1e6 in magnitude and not subnormal (docs/limits.md). No engine
// setting means anything past it (MuJoCo's impratio = 1e300 made every step non-finite), and a
// subnormal value only makes arithmetic slow.
constexpr double kMaxSettingMagnitude = 1e6;

bool InRange(double v, SettingRange range) {
  if (range == SettingRange::kNonNegativeOrInfinite && v == HUGE_VAL) return true;
  if (!std::isfinite(v)) return false;
  if (std::abs(v) > kMaxSettingMagnitude) return false;
  if (v != 0.0 && std::abs(v) < std::numeric_limits<double>::min()) return false;
  switch (range) {
    case SettingRange::kFinite:
      return true;
    case SettingRange::kPositive:
      return v > 0.0;
    case SettingRange::kNonNegative:
    case SettingRange::kNonNegativeOrInfinite:
      return v >= 0.0;
    case SettingRange::kFraction:
      return v > 0.0 && v <= 1.0;
    case SettingRange::kUnitInterval:
      return v >= 0.0 && v <= 1.0;
  }
  return false;
}

// What a definition expects, for messages: "a positive number (s)", "\"double\" or \"float\"".
std::string Expected(const SettingDef& d) {
  return std::visit(
      [&](const auto& def) -> std::string {
        using T = std::decay_t<decltype(def)>;
        if constexpr (std::is_same_v<T, double>) {
          return RangeText(d.range, d.bounds) + (d.unit.empty() ? "" : " (" + d.unit + ")") +
                 ", with magnitude at most 1e6 and not subnormal (docs/limits.md)";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          return "an integer from " + std::to_string(d.min_integer) + " to " +
                 std::to_string(d.max_integer);
        } else if constexpr (std::is_same_v<T, bool>) {
          return "true or false";
        } else {
          std::string out;
          for (size_t i = 0; i < d.choices.size(); ++i) {
            if (i > 0) out += i + 1 == d.choices.size() ? " or " : ", ";
            out += "\"" + d.choices[i] + "\"";
          }
          return out;
        }
      },
      d.default_value);
}

// The value a raw setting gives for a definition; throws SceneError when it does not fit.
SettingValue Checked(const SettingDef& d, const RawSetting& raw, const std::string& engine) {
  const auto fail = [&]() {
    throw SceneError(raw.where + ": " + engine + "." + d.key + ": expected " + Expected(d) +
                     ", got " + Excerpt(SettingText(raw.value)));
  };
  return std::visit(
      [&](const auto& def) -> SettingValue {
        using T = std::decay_t<decltype(def)>;
        if constexpr (std::is_same_v<T, double>) {
          double v = 0.0;
          if (const double* f = std::get_if<double>(&raw.value)) {
            v = *f;
          } else if (const std::int64_t* i = std::get_if<std::int64_t>(&raw.value)) {
            v = static_cast<double>(*i);
          } else {
            fail();
          }
          if (!InRange(v, d.range) || !InBounds(v, d.bounds)) fail();
          return v;
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          const std::int64_t* i = std::get_if<std::int64_t>(&raw.value);
          if (i == nullptr || *i < d.min_integer || *i > d.max_integer) fail();
          return *i;
        } else if constexpr (std::is_same_v<T, bool>) {
          const bool* b = std::get_if<bool>(&raw.value);
          if (b == nullptr) fail();
          return *b;
        } else {
          const std::string* s = std::get_if<std::string>(&raw.value);
          if (s == nullptr) fail();
          for (const std::string& c : d.choices) {
            if (c == *s) return *s;
          }
          fail();
          return std::string();
        }
      },
      d.default_value);
}

}  // namespace

const SettingDef* EngineSettingsSchema::Find(std::string_view key) const {
  for (const SettingDef& d : settings) {
    if (d.key == key) return &d;
  }
  return nullptr;
}

EngineSettingsSchema& EngineSettingsSchema::Number(std::string key, double value,
                                                   SettingRange range, std::string unit,
                                                   std::string engine_default, std::string doc,
                                                   NumberBounds bounds) {
  SettingDef d;
  d.key = std::move(key), d.default_value = value, d.range = range, d.unit = std::move(unit);
  d.bounds = bounds;
  d.engine_default = std::move(engine_default), d.doc = std::move(doc);
  settings.push_back(std::move(d));
  return *this;
}

EngineSettingsSchema& EngineSettingsSchema::Integer(std::string key, std::int64_t value,
                                                    std::int64_t min_value, std::int64_t max_value,
                                                    std::string engine_default, std::string doc) {
  SettingDef d;
  d.key = std::move(key), d.default_value = value;
  d.min_integer = min_value, d.max_integer = max_value;
  d.engine_default = std::move(engine_default), d.doc = std::move(doc);
  settings.push_back(std::move(d));
  return *this;
}

EngineSettingsSchema& EngineSettingsSchema::Flag(std::string key, bool value,
                                                 std::string engine_default, std::string doc) {
  SettingDef d;
  d.key = std::move(key), d.default_value = value;
  d.engine_default = std::move(engine_default), d.doc = std::move(doc);
  settings.push_back(std::move(d));
  return *this;
}

EngineSettingsSchema& EngineSettingsSchema::Choice(std::string key, std::string value,
                                                   std::vector<std::string> choices,
                                                   std::string engine_default, std::string doc) {
  SettingDef d;
  d.key = std::move(key), d.default_value = std::move(value), d.choices = std::move(choices);
  d.engine_default = std::move(engine_default), d.doc = std::move(doc);
  settings.push_back(std::move(d));
  return *this;
}

const SettingValue& EngineSettings::Get(std::string_view key) const {
  for (const auto& [k, v] : values) {
    if (k == key) return v;
  }
  throw std::logic_error("engine setting '" + std::string(key) + "' is not in the schema");
}

double EngineSettings::Number(std::string_view key) const {
  return std::get<double>(Get(key));
}

std::int64_t EngineSettings::Integer(std::string_view key) const {
  return std::get<std::int64_t>(Get(key));
}

bool EngineSettings::Flag(std::string_view key) const {
  return std::get<bool>(Get(key));
}

const std::string& EngineSettings::Choice(std::string_view key) const {
  return std::get<std::string>(Get(key));
}

nlohmann::json EngineSettings::ToJson() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& entry : values) {
    // Not a structured binding: clang 14 (the fuzz build, scripts/fuzz.sh) cannot capture one.
    std::visit([&](const auto& x) { j[entry.first] = x; }, entry.second);
  }
  return j;
}

std::string SettingText(const SettingValue& value) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, double>) {
          return NumberText(x);
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          return std::to_string(x);
        } else if constexpr (std::is_same_v<T, bool>) {
          return x ? "true" : "false";
        } else {
          return "\"" + x + "\"";
        }
      },
      value);
}

EngineSettings ResolveEngineSettings(const Scene& scene, const EngineSettingsSchema& schema) {
  EngineSettings out;
  const auto table = scene.engine_tables.find(schema.engine);
  if (table != scene.engine_tables.end()) {
    for (const auto& [key, raw] : table->second.values) {
      if (schema.Find(key) != nullptr) continue;
      std::string known;
      for (const SettingDef& d : schema.settings) known += (known.empty() ? "" : ", ") + d.key;
      throw SceneError(raw.where + ": " + schema.engine + "." + key +
                       ": unknown key (expected one of: " + known + ")");
    }
  }
  for (const SettingDef& d : schema.settings) {
    SettingValue v = d.default_value;
    if (table != scene.engine_tables.end()) {
      if (auto it = table->second.values.find(d.key); it != table->second.values.end()) {
        v = Checked(d, it->second, schema.engine);
      }
    }
    out.values.emplace_back(d.key, std::move(v));
  }
  return out;
}

void SetEngineSetting(Scene& scene, const std::string& engine, const std::string& key,
                      SettingValue value) {
  RawEngineTable& t = scene.engine_tables[engine];
  if (t.where.empty()) t.where = scene.path.empty() ? "scene" : scene.path.string();
  const std::string where = (scene.path.empty() ? std::string("scene") : scene.path.string()) +
                            ": set " + engine + "." + key + "=" + SettingText(value);
  t.values[key] = RawSetting{std::move(value), where};
}

}  // namespace rockbench
