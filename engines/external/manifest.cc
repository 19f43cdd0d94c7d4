#include "engines/external/manifest.h"

#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "engines/common/engine_input.h"
#include "util/relayed_text.h"
#include "util/subprocess.h"

namespace rockbench::external {
namespace {

// A message with the manifest's text in it, as a terminal shows it safely: each control byte
// (an escape sequence's ESC, a NUL, a newline inside a quoted key) escaped as every text from
// outside rockbench is (util/relayed_text.h), not cut (the reader's own excerpts are short).
std::string Printable(const std::string& text) {
  return EscapedText(text, text.size());
}

// Reads one manifest file, with messages "FILE:LINE: KEY: expected ..., got ...".
class ManifestReader {
 public:
  ManifestReader(std::string file, std::string engine)
      : file_(std::move(file)), engine_(std::move(engine)) {}

  [[noreturn]] void Fail(const std::string& key, const toml::node* node,
                         const std::string& msg) const {
    std::string loc = file_;
    if (node != nullptr && node->source().begin.line > 0) {
      loc += ":" + std::to_string(node->source().begin.line);
    }
    throw SceneError(Printable(loc + ": " + key + ": " + msg) +
                     " (the manifest of external engine " + engine_ + ")");
  }

  static std::string Describe(const toml::node& n) {
    if (n.is_string()) return "a string";
    if (n.is_integer()) return "an integer";
    if (n.is_floating_point()) return "a number";
    if (n.is_boolean()) return "true/false";
    if (n.is_array()) return "an array";
    if (n.is_table()) return "a table";
    return "a date or time";
  }

  std::string String(const toml::table& t, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return {};
    if (!n->is_string()) Fail(key, n, "expected a string, got " + Describe(*n));
    return n->as_string()->get();
  }

  double Number(const toml::table& t, const std::string& prefix, const std::string& key,
                double fallback, bool positive) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    std::optional<double> v = n->value<double>();
    if (!v || !std::isfinite(*v) || (positive && *v <= 0.0)) {
      Fail(prefix + key, n,
           std::string("expected a ") + (positive ? "positive" : "finite") + " number, got " +
               Describe(*n));
    }
    return *v;
  }

  // A table or array of `count` items where at most `cap` are allowed.
  void CheckCount(const std::string& key, const toml::node* node, size_t count, std::int64_t cap,
                  const char* what) const {
    if (static_cast<std::int64_t>(count) > cap) {
      Fail(key, node,
           std::to_string(count) + " " + what + ", more than the " + std::to_string(cap) +
               " a manifest may have (docs/limits.md)");
    }
  }

  std::vector<std::string> Strings(const toml::table& t, const std::string& key) const {
    std::vector<std::string> out;
    const toml::node* n = t.get(key);
    if (n == nullptr) return out;
    const toml::array* a = n->as_array();
    if (a == nullptr) Fail(key, n, "expected an array of strings, got " + Describe(*n));
    CheckCount(key, n, a->size(), kMaxManifestArray, "entries");
    for (auto&& e : *a) {
      if (!e.is_string() || e.as_string()->get().empty()) {
        Fail(key, &e, "expected non-empty strings, got " + Describe(e));
      }
      out.push_back(e.as_string()->get());
    }
    return out;
  }

  std::vector<double> Steps(const toml::table& t, const std::string& key,
                            std::vector<double> fallback) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    const toml::array* a = n->as_array();
    if (a == nullptr || a->empty()) {
      Fail("sweep." + key, n, "expected a non-empty array of time steps in s");
    }
    CheckCount("sweep." + key, n, a->size(), kMaxManifestArray, "entries");
    std::vector<double> out;
    for (auto&& e : *a) {
      std::optional<double> v = e.value<double>();
      if (!v || !std::isfinite(*v) || *v <= 0.0) {
        Fail("sweep." + key, &e, "expected positive time steps in s, got " + Describe(e));
      }
      out.push_back(*v);
    }
    return out;
  }

  // A value given for setting `key` of the schema (a family's settings), checked for its type.
  SettingValue Value(const std::string& where_key, const toml::node& n,
                     const SettingValue& like) const {
    if (std::holds_alternative<double>(like)) {
      if (auto v = n.value<double>()) return *v;
    } else if (std::holds_alternative<std::int64_t>(like)) {
      if (auto v = n.as_integer()) return v->get();
    } else if (std::holds_alternative<bool>(like)) {
      if (auto v = n.as_boolean()) return v->get();
    } else if (auto v = n.as_string()) {
      return v->get();
    }
    const char* want = std::holds_alternative<double>(like)         ? "a number"
                       : std::holds_alternative<std::int64_t>(like) ? "an integer"
                       : std::holds_alternative<bool>(like)         ? "true/false"
                                                                    : "a string";
    Fail(where_key, &n, std::string("expected ") + want + ", got " + Describe(n));
  }

  // `standard`: the keys every external engine's table has (a TOML table's keys are unique, so
  // the manifest's own keys need no check against each other).
  void Setting(const std::string& key, const toml::table& t,
               const std::unordered_set<std::string>& standard,
               EngineSettingsSchema* schema) const {
    const std::string prefix = "settings." + key + ".";
    static const std::vector<std::string> kKeys = {
        "type", "default", "min", "max", "range", "choices", "unit", "engine_default", "doc"};
    for (auto&& [k, v] : t) {
      if (std::find(kKeys.begin(), kKeys.end(), std::string(k.str())) == kKeys.end()) {
        Fail(prefix + std::string(k.str()), &v,
             "unknown key (expected type, default, min, max, range, choices, unit, "
             "engine_default, doc)");
      }
    }
    if (standard.count(key) != 0) {
      Fail("settings." + key, &t,
           "a standard key of every external engine's table (docs/external-engines.md); "
           "give it another name");
    }
    const std::string type = String(t, "type");
    const toml::node* def = t.get("default");
    if (def == nullptr) Fail(prefix + "default", &t, "expected the setting's default value");
    const std::string engine_default =
        t.get("engine_default") != nullptr ? String(t, "engine_default") : std::string("-");
    const std::string doc = String(t, "doc");
    if (type == "number") {
      static const std::map<std::string, SettingRange> kRanges = {
          {"finite", SettingRange::kFinite},
          {"positive", SettingRange::kPositive},
          {"non_negative", SettingRange::kNonNegative},
          {"non_negative_or_infinite", SettingRange::kNonNegativeOrInfinite},
          {"fraction", SettingRange::kFraction},
          {"unit_interval", SettingRange::kUnitInterval}};
      const std::string range_text = t.get("range") != nullptr ? String(t, "range") : "finite";
      auto range = kRanges.find(range_text);
      if (range == kRanges.end()) {
        Fail(prefix + "range", t.get("range"),
             "expected finite, positive, non_negative, non_negative_or_infinite, fraction or "
             "unit_interval, got '" +
                 range_text + "'");
      }
      NumberBounds bounds;
      bounds.min = Number(t, prefix, "min", bounds.min, false);
      bounds.max = Number(t, prefix, "max", bounds.max, false);
      std::optional<double> v = def->value<double>();
      if (!v) Fail(prefix + "default", def, "expected a number, got " + Describe(*def));
      schema->Number(key, *v, range->second, String(t, "unit"), engine_default, doc, bounds);
    } else if (type == "integer") {
      auto v = def->as_integer();
      if (v == nullptr) Fail(prefix + "default", def, "expected an integer, got " + Describe(*def));
      auto bound = [&](const char* k, std::int64_t fallback) {
        const toml::node* n = t.get(k);
        if (n == nullptr) return fallback;
        if (!n->is_integer()) Fail(prefix + k, n, "expected an integer, got " + Describe(*n));
        return n->as_integer()->get();
      };
      schema->Integer(key, v->get(), bound("min", std::numeric_limits<std::int64_t>::min()),
                      bound("max", std::numeric_limits<std::int64_t>::max()), engine_default, doc);
    } else if (type == "flag") {
      auto v = def->as_boolean();
      if (v == nullptr) Fail(prefix + "default", def, "expected true/false, got " + Describe(*def));
      schema->Flag(key, v->get(), engine_default, doc);
    } else if (type == "choice") {
      auto v = def->as_string();
      std::vector<std::string> choices = Strings(t, "choices");
      if (choices.empty()) Fail(prefix + "choices", &t, "expected the allowed values");
      if (v == nullptr || std::find(choices.begin(), choices.end(), v->get()) == choices.end()) {
        Fail(prefix + "default", def, "expected one of the choices");
      }
      schema->Choice(key, v->get(), std::move(choices), engine_default, doc);
    } else {
      Fail(prefix + "type", t.get("type") != nullptr ? t.get("type") : &t,
           "expected number, integer, flag or choice, got '" + type + "'");
    }
    // The default must satisfy its own range: resolving an empty table checks it.
  }

  ExternalManifest Read(const toml::table& root, const ExternalEngineRef& ref) const {
    static const std::vector<std::string> kKeys = {
        "protocol",     "version",      "command",          "max_blocks", "drives", "requires",
        "install_hint", "wall_limit_s", "memory_limit_mib", "settings",   "sweep"};
    for (auto&& [k, v] : root) {
      if (std::find(kKeys.begin(), kKeys.end(), std::string(k.str())) == kKeys.end()) {
        Fail(std::string(k.str()), &v,
             "unknown key (expected protocol, version, command, max_blocks, drives, requires, "
             "install_hint, wall_limit_s, memory_limit_mib, [settings.<key>], [sweep])");
      }
    }
    ExternalManifest m;
    m.name = ref.name;
    m.where = ref.where;
    m.file = ref.manifest;
    const toml::node* protocol = root.get("protocol");
    if (protocol == nullptr || !protocol->is_integer() ||
        protocol->as_integer()->get() != kProtocolVersion) {
      Fail("protocol", protocol,
           "expected protocol = " + std::to_string(kProtocolVersion) +
               " (the version of the external-engine protocol this rockbench speaks)");
    }
    m.version = String(root, "version");
    if (m.version.empty()) m.version = "external engine " + ref.name;
    m.command = Strings(root, "command");
    if (m.command.empty()) Fail("command", root.get("command"), "expected [\"PROGRAM\", ...]");
    if (const toml::node* n = root.get("max_blocks")) {
      if (!n->is_integer() || n->as_integer()->get() < 1) {
        Fail("max_blocks", n, "expected a positive integer");
      }
      m.max_blocks = static_cast<int>(std::min<std::int64_t>(n->as_integer()->get(), kMaxBlocks));
    }
    if (root.get("drives") != nullptr) {
      m.drives = Strings(root, "drives");
      for (const std::string& d : m.drives) {
        if (d != "inertial" && d != "kinematic") {
          Fail("drives", root.get("drives"),
               "expected \"inertial\" and/or \"kinematic\", got '" + d + "'");
        }
      }
      if (m.drives.empty()) Fail("drives", root.get("drives"), "expected at least one drive");
    }
    for (const std::string& r : Strings(root, "requires")) m.requires_files.push_back(r);
    m.install_hint = String(root, "install_hint");
    m.schema.engine = ref.name;
    AddProtocolSettings(m.schema, m.drives, Number(root, "", "wall_limit_s", 600.0, true),
                        Number(root, "", "memory_limit_mib", 4096.0, true));
    if (const toml::node* s = root.get("settings")) {
      if (!s->is_table()) Fail("settings", s, "expected tables [settings.<key>]");
      CheckCount("settings", s, s->as_table()->size(), kMaxManifestSettings, "settings");
      std::unordered_set<std::string> standard;
      for (const SettingDef& d : m.schema.settings) standard.insert(d.key);
      for (auto&& [k, v] : *s->as_table()) {
        if (!v.is_table()) Fail("settings." + std::string(k.str()), &v, "expected a table");
        Setting(std::string(k.str()), *v.as_table(), standard, &m.schema);
      }
    }
    // The table's keys, looked up once each below.
    std::unordered_map<std::string, const SettingDef*> keys;
    for (const SettingDef& d : m.schema.settings) keys.emplace(d.key, &d);
    if (const toml::node* sw = root.get("sweep")) {
      const toml::table* t = sw->as_table();
      if (t == nullptr) Fail("sweep", sw, "expected a table [sweep]");
      for (auto&& [k, v] : *t) {
        const std::string key(k.str());
        if (key != "steps_s" && key != "quick_steps_s" && key != "stress_steps_s" &&
            key != "family") {
          Fail("sweep." + key, &v,
               "unknown key (expected steps_s, quick_steps_s, stress_steps_s, [[sweep.family]])");
        }
      }
      m.sweep_steps_s = Steps(*t, "steps_s", m.sweep_steps_s);
      m.quick_steps_s = Steps(*t, "quick_steps_s", m.quick_steps_s);
      m.stress_steps_s = Steps(*t, "stress_steps_s", m.stress_steps_s);
      if (const toml::node* f = t->get("family")) {
        const toml::array* a = f->as_array();
        if (a == nullptr) Fail("sweep.family", f, "expected [[sweep.family]] tables");
        CheckCount("sweep.family", f, a->size(), kMaxManifestFamilies, "families");
        for (auto&& e : *a) {
          const toml::table* ft = e.as_table();
          if (ft == nullptr) Fail("sweep.family", &e, "expected a table");
          ExternalFamily fam;
          fam.name = String(*ft, "name");
          fam.id = String(*ft, "id");
          if (fam.name.empty() || fam.name.find(',') != std::string::npos) {
            Fail("sweep.family.name", &e, "expected a name without commas (a field of sweep.csv)");
          }
          if (fam.id.empty() || fam.id.find_first_of("/ ,") != std::string::npos) {
            Fail("sweep.family.id", &e, "expected an id without '/', ',' or spaces");
          }
          if (const toml::node* st = ft->get("settings")) {
            if (!st->is_table()) Fail("sweep.family.settings", st, "expected a table");
            for (auto&& [k, v] : *st->as_table()) {
              const std::string key(k.str());
              const auto found = keys.find(key);
              const SettingDef* d = found == keys.end() ? nullptr : found->second;
              if (d == nullptr || key == "time_step") {
                Fail("sweep.family.settings." + key, &v,
                     "not a key of the engine's table (the step is the sweep's own)");
              }
              fam.settings.emplace_back(key,
                                        Value("sweep.family.settings." + key, v, d->default_value));
            }
          }
          m.families.push_back(std::move(fam));
        }
      }
    }
    if (m.families.empty()) m.families.push_back({ref.name, "ours", {}});
    return m;
  }

 private:
  std::string file_, engine_;
};

// Makes a relative program or file argument absolute against `dir` when it names a file
// there; a bare program name stays as it is (looked up in PATH).
std::vector<std::string> ResolveCommand(std::vector<std::string> command,
                                        const std::filesystem::path& dir) {
  for (size_t i = 0; i < command.size(); ++i) {
    const std::filesystem::path p(command[i]);
    if (p.is_absolute() || command[i].rfind('-', 0) == 0) continue;
    if (i == 0 && command[i].find('/') == std::string::npos) continue;
    std::error_code ec;
    const std::filesystem::path candidate = dir / p;
    if (std::filesystem::exists(candidate, ec)) {
      command[i] = std::filesystem::absolute(candidate, ec).lexically_normal().string();
    }
  }
  return command;
}

std::string MissingReason(const ExternalManifest& m, const std::filesystem::path& dir) {
  if (!FindProgram(m.command[0])) {
    return "its program '" + m.command[0] + "' is not installed" +
           (m.install_hint.empty() ? "" : " (" + m.install_hint + ")");
  }
  for (const std::filesystem::path& r : m.requires_files) {
    std::error_code ec;
    if (!std::filesystem::exists(dir / r, ec)) {
      return (dir / r).lexically_normal().string() + " is missing" +
             (m.install_hint.empty() ? "" : " (" + m.install_hint + ")");
    }
  }
  return {};
}

}  // namespace

// The standard keys rockbench reads itself (ReadProtocolSettings).
constexpr char kOutputEveryKey[] = "output_every_steps";
constexpr char kWallLimitKey[] = "wall_limit_s";
constexpr char kMemoryLimitKey[] = "memory_limit_mib";

void AddProtocolSettings(EngineSettingsSchema& schema, const std::vector<std::string>& drives,
                         double wall_limit_s, double memory_limit_mib) {
  AddTimeStepSetting(schema, "-", "the engine's fixed step (input time_step_s)");
  if (drives.size() == 2) {
    AddDriveSetting(schema);
  } else {
    AddDriveSetting(schema, drives,
                    "how the base motion reaches the blocks (the manifest's drives)");
  }
  if (drives.size() == 2 || drives.front() == "kinematic") AddKinematicHighpassSetting(schema);
  schema.Integer(kOutputEveryKey, 1, 1, 1000000, "-",
                 "poses written every this many steps; the monitor reads impacts from them, so "
                 "1 (every step) unless the run is too long to write");
  schema.Number(kWallLimitKey, wall_limit_s, SettingRange::kPositive, "s", "-",
                "the run is killed past this wall-clock time (a hang is a failed run, not a lost "
                "study)");
  schema.Number(kMemoryLimitKey, memory_limit_mib, SettingRange::kPositive, "MiB", "-",
                "the run is killed once its resident memory exceeds this");
}

ProtocolSettings ReadProtocolSettings(const EngineSettings& settings) {
  ProtocolSettings p;
  p.output_every_steps = settings.Integer(kOutputEveryKey);
  p.wall_limit_s = settings.Number(kWallLimitKey);
  p.memory_limit_mib = settings.Number(kMemoryLimitKey);
  return p;
}

ExternalManifest LoadManifest(const ExternalEngineRef& ref) {
  ExternalManifest m;
  std::filesystem::path dir = ref.base_dir;
  if (!ref.manifest.empty()) {
    std::error_code ec;
    const auto status = std::filesystem::status(ref.manifest, ec);
    if (!std::filesystem::is_regular_file(status)) {
      throw SceneError(
          ref.where + ": external." + ref.name + ".manifest: " +
          (std::filesystem::exists(status) ? "not a regular file: " : "no manifest file ") +
          ref.manifest.string());
    }
    // At most the cap and one piece more is read: a file that grows after the check above (or
    // was swapped for a device) cannot make the read unbounded.
    std::string text;
    {
      std::ifstream in(ref.manifest, std::ios::binary);
      if (!in) {
        throw SceneError(ref.manifest.string() + ": cannot read the manifest of external engine " +
                         ref.name);
      }
      // In pieces: a manifest of a few kB allocates a few kB.
      char piece[16384];
      while (in && static_cast<std::int64_t>(text.size()) <= kMaxManifestBytes) {
        in.read(piece, sizeof piece);
        text.append(piece, static_cast<size_t>(in.gcount()));
      }
      if (in.bad()) {
        throw SceneError(ref.manifest.string() + ": cannot read the manifest of external engine " +
                         ref.name);
      }
    }
    if (static_cast<std::int64_t>(text.size()) > kMaxManifestBytes) {
      const auto size = std::filesystem::file_size(ref.manifest, ec);
      throw SceneError(
          ref.manifest.string() + ": " +
          (ec ? std::string("more than ") : std::to_string(size) + " bytes, more than ") + "the " +
          std::to_string(kMaxManifestBytes) +
          " a manifest may have (docs/limits.md; the manifest of external engine " + ref.name +
          ")");
    }
    toml::table root;
    try {
      root = toml::parse(text, ref.manifest.string());
    } catch (const toml::parse_error& e) {
      throw SceneError(Printable(ref.manifest.string() + ":" +
                                 std::to_string(e.source().begin.line) +
                                 ": TOML syntax error: " + std::string(e.description())) +
                       " (the manifest of external engine " + ref.name + ")");
    }
    m = ManifestReader(ref.manifest.string(), ref.name).Read(root, ref);
    dir = ref.manifest.has_parent_path() ? ref.manifest.parent_path() : ".";
  } else {
    m.name = ref.name;
    m.where = ref.where;
    m.command = ref.command;
    m.version = "external command: " + ref.command[0];
    m.schema.engine = ref.name;
    AddProtocolSettings(m.schema, m.drives, 600.0, 4096.0);
    m.families.push_back({ref.name, "ours", {}});
  }
  m.command = ResolveCommand(m.command, dir);
  m.missing_reason = MissingReason(m, dir);
  return m;
}

}  // namespace rockbench::external
