#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "scene/body_kind.h"
#include "scene/limits.h"
#include "scene/scene.h"
#include "scene/scene_rules.h"
#include "util/format.h"

namespace rockbench {
namespace {

using namespace scene_rules;  // NOLINT: the rules are this file's vocabulary

std::string Quote(std::string_view text) {
  std::string out = "\"";
  out += Excerpt(text);
  out += '"';
  return out;
}

// Describes a TOML node that has the wrong type, for "got ..." in messages.
std::string Describe(const toml::node& node) {
  if (auto s = node.as_string()) return Quote(s->get());
  if (auto b = node.as_boolean()) return b->get() ? "true" : "false";
  if (auto i = node.as_integer()) return std::to_string(i->get());
  if (auto f = node.as_floating_point()) return ShortestText(f->get());
  if (node.is_array()) return "an array";
  if (node.is_table()) return "a table";
  return "a date/time";
}

// A TOML number as a double: a float, or an integer; nullopt for any other value.
std::optional<double> AsNumber(const toml::node& node) {
  if (auto f = node.as_floating_point()) return f->get();
  if (auto i = node.as_integer()) return static_cast<double>(i->get());
  return std::nullopt;
}

// The keys only kind = "kanai_tajimi" reads (ReadSynthetic): a record file and every other kind
// refuse them.
constexpr std::array<const char*, 12> kSyntheticOnlyKeys = {
    "intensity",      "ground_frequency_hz", "ground_damping", "filter_frequency_hz",
    "filter_damping", "high_pass_hz",        "zero_residuals", "envelope",
    "rise_s",         "strong_end_s",        "decay_per_s",    "seed"};

// Allowed keys of every table; a key listed with `true` is a sub-table.
using KeyList = std::vector<std::pair<std::string_view, bool>>;
const std::map<std::string, KeyList, std::less<>>& Schema() {
  static const KeyList kBlock = {{"width", false}, {"height", false},  {"density", false},
                                 {"mass", false},  {"depth", false},   {"friction", false},
                                 {"shape", false}, {"diameter", false}};
  static const KeyList kMotion = {{"file", false},
                                  {"kind", false},
                                  {"samples", false},
                                  {"resolution", false},
                                  {"units", false},
                                  {"scale", false},
                                  {"dt", false},
                                  {"amplitude_g", false},
                                  {"frequency_hz", false},
                                  {"duration_s", false},
                                  {"start_s", false},
                                  {"phase_deg", false},
                                  // kind = "kanai_tajimi"
                                  {"intensity", false},
                                  {"ground_frequency_hz", false},
                                  {"ground_damping", false},
                                  {"filter_frequency_hz", false},
                                  {"filter_damping", false},
                                  {"high_pass_hz", false},
                                  {"zero_residuals", false},
                                  {"envelope", false},
                                  {"rise_s", false},
                                  {"strong_end_s", false},
                                  {"decay_per_s", false},
                                  {"seed", false}};
  static const std::map<std::string, KeyList, std::less<>> kSchema = {
      {"",
       {{"title", false},
        {"block1", true},
        {"block2", true},
        {"block", true},  // [[block]]: an array of tables, bottom first
        {"initial", true},
        {"base", true},
        {"run", true},
        {"model", true},
        {"compare", true},
        {"external", true}}},
      {"block1", kBlock},
      {"block2", kBlock},
      // [initial] takes theta, omega and thetaK, omegaK for any K (ParseInitialKey).
      {"initial", {}},
      {"base", {{"horizontal", true}, {"transverse", true}, {"vertical", true}}},
      {"base.horizontal", kMotion},
      {"base.transverse", kMotion},
      {"base.vertical", kMotion},
      {"run", {{"duration", false}, {"output_interval", false}, {"gravity", false}}},
      {"model",
       {{"integrator", false},
        {"rtol", false},
        {"atol", false},
        {"step", false},
        {"events", false},
        {"equations", false},
        {"overturn_angle", false},
        {"rest_rate", false},  // removed: an error naming rest_rate_rel
        {"rest_rate_rel", false},
        {"check_transitions", false},
        {"formulation", false},
        {"landing_clearance_rel", false}}},
      {"compare",
       {{"tolerance", false},
        {"members", false},
        {"engine_members", false},
        {"amplitude_rel", false},
        {"sample_precision", false},
        {"initial_rel", false},
        {"seed", false}}},
  };
  return kSchema;
}

std::string Join(const std::string& prefix, std::string_view name) {
  return prefix.empty() ? std::string(name) : prefix + "." + std::string(name);
}

// "blockK" (K = 1, 2, ...; no leading zero) -> K; 0 for any other name.
int BlockIndexOf(std::string_view name) {
  if (name.size() < 6 || name.substr(0, 5) != "block" || name[5] == '0') return 0;
  int k = 0;
  for (const char c : name.substr(5)) {
    if (c < '0' || c > '9' || k > 100000) return 0;
    k = 10 * k + (c - '0');
  }
  return k;
}

// A cylinder's [initial] arrays (one entry per body), with their units.
constexpr std::array<std::pair<std::string_view, std::string_view>, 5> kCylinderInitial = {{
    {"tilt", "rad"},
    {"azimuth", "rad"},
    {"tilt_rate", "rad/s"},
    {"azimuth_rate", "rad/s"},
    {"spin_rate", "rad/s"},
}};

// The keys of [initial]: "theta" and "omega" (arrays, one entry per block) and "thetaK",
// "omegaK" (K = 1..kMaxBlocks, no leading zero), and a cylinder's arrays (kCylinderInitial).
// *quantity is the quantity, *block K (0 for an array).
bool ParseInitialKey(std::string_view name, std::string_view* quantity, int* block) {
  for (const auto& [q, unit] : kCylinderInitial) {
    if (name != q) continue;
    *quantity = q;
    *block = 0;
    return true;
  }
  for (const std::string_view q : {std::string_view("theta"), std::string_view("omega")}) {
    if (name.substr(0, q.size()) != q) continue;
    const std::string_view digits = name.substr(q.size());
    int k = 0;
    if (!digits.empty()) {
      if (digits[0] == '0' || digits.size() > 3) return false;
      for (const char c : digits) {
        if (c < '0' || c > '9') return false;
        k = 10 * k + (c - '0');
      }
      if (k > kMaxBlocks) return false;
    }
    *quantity = q;
    *block = k;
    return true;
  }
  return false;
}

// "theta1, theta2, omega1, omega2, theta, omega" for up to two blocks; the ranges beyond; a
// cylinder's arrays.
std::string InitialKeyList(int blocks, bool cylinder) {
  if (cylinder) {
    std::string out;
    for (const auto& [q, unit] : kCylinderInitial)
      out += (out.empty() ? "" : ", ") + std::string(q);
    return out;
  }
  if (blocks <= 2) return "theta1, theta2, omega1, omega2, theta, omega";
  const std::string n = std::to_string(blocks);
  return "theta1 to theta" + n + ", omega1 to omega" + n + ", theta, omega";
}

std::string Trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

// Reads the TOML tree into a Scene, with messages "FILE:LINE: KEY: expected ..., got ...".
class Reader {
 public:
  Reader(std::string file, std::map<std::string, std::string> overrides)
      : file_(std::move(file)), overrides_(std::move(overrides)) {}

  std::string Loc(const std::string& key, const toml::node* node) const {
    if (auto it = overrides_.find(key); it != overrides_.end()) {
      return file_ + ": override " + Quote(it->second);
    }
    if (node != nullptr && node->source().begin.line > 0) {
      return file_ + ":" + std::to_string(node->source().begin.line);
    }
    return file_;
  }

  [[noreturn]] void Fail(const std::string& key, const toml::node* node,
                         const std::string& msg) const {
    throw SceneError(Loc(key, node) + ": " + key + ": " + msg);
  }

  // Rejects keys that the schema does not list for `prefix`. At the top level, a table the
  // schema does not list is an engine's settings table (checked by the engine).
  // [initial]'s list: InitialKeyList(blocks_); a [[block]] table (prefix "blockK") has a
  // [block1]'s keys.
  void CheckKeys(const toml::table& table, const std::string& prefix) const {
    const bool initial = prefix == "initial";
    const KeyList& allowed = Schema().at(BlockIndexOf(prefix) > 0 ? std::string("block1") : prefix);
    for (auto&& [k, v] : table) {
      bool known = false;
      for (const auto& [name, is_table] : allowed) known = known || name == k.str();
      std::string_view quantity;
      int block = 0;
      if (initial) {
        known = ParseInitialKey(k.str(), &quantity, &block) &&
                (quantity == "theta" || quantity == "omega") != cylinder_;
      }
      if (known || (prefix.empty() && v.is_table())) continue;
      std::string list;
      for (const auto& [name, is_table] : allowed) {
        list += (list.empty() ? "" : ", ") + std::string(name);
      }
      if (initial) list = InitialKeyList(blocks_, cylinder_);
      const std::string key = Excerpt(Join(prefix, k.str()));
      std::string loc = file_;
      if (k.source().begin.line > 0) loc += ":" + std::to_string(k.source().begin.line);
      throw SceneError(loc + ": " + key + ": unknown key (expected one of: " + list + ")");
    }
  }

  // A sub-table, or nullptr when absent.
  const toml::table* Table(const toml::table& parent, const std::string& prefix,
                           std::string_view name) const {
    const toml::node* node = parent.get(name);
    if (node == nullptr) return nullptr;
    const std::string key = Join(prefix, name);
    if (!node->is_table())
      Fail(key, node, "expected a table [" + key + "], got " + Describe(*node));
    CheckKeys(*node->as_table(), key);
    return node->as_table();
  }

  std::optional<double> Number(const toml::table& t, const std::string& prefix,
                               std::string_view name, Rule rule, std::string_view unit,
                               const Limit* limit = nullptr) const {
    const toml::node* node = t.get(name);
    if (node == nullptr) return std::nullopt;
    const std::string key = Join(prefix, name);
    const std::optional<double> number = AsNumber(*node);
    if (!number)
      Fail(key, node, "expected " + Expectation(rule, unit) + ", got " + Describe(*node));
    const double v = *number;
    if (!Satisfies(v, rule)) {
      Fail(key, node, "expected " + Expectation(rule, unit) + ", got " + ShortestText(v));
    }
    if (limit != nullptr && !Within(v, *limit)) {
      Fail(key, node,
           "expected " + Expectation(rule, unit) + LimitText(*limit) + ", got " + ShortestText(v));
    }
    return v;
  }

  double RequiredNumber(const toml::table& t, const std::string& prefix, std::string_view name,
                        Rule rule, std::string_view unit, const Limit* limit = nullptr) const {
    auto v = Number(t, prefix, name, rule, unit, limit);
    if (!v) Fail(Join(prefix, name), &t, "missing; expected " + Expectation(rule, unit));
    return *v;
  }

  std::optional<std::string> String(const toml::table& t, const std::string& prefix,
                                    std::string_view name, std::string_view expected) const {
    const toml::node* node = t.get(name);
    if (node == nullptr) return std::nullopt;
    auto s = node->as_string();
    if (s == nullptr) {
      Fail(Join(prefix, name), node,
           "expected " + std::string(expected) + ", got " + Describe(*node));
    }
    return s->get();
  }

  std::optional<bool> Bool(const toml::table& t, const std::string& prefix,
                           std::string_view name) const {
    const toml::node* node = t.get(name);
    if (node == nullptr) return std::nullopt;
    auto b = node->as_boolean();
    if (b == nullptr)
      Fail(Join(prefix, name), node, "expected true or false, got " + Describe(*node));
    return b->get();
  }

  std::optional<int64_t> PositiveInteger(const toml::table& t, const std::string& prefix,
                                         std::string_view name) const {
    const toml::node* node = t.get(name);
    if (node == nullptr) return std::nullopt;
    auto i = node->as_integer();
    if (i == nullptr || i->get() <= 0) {
      Fail(Join(prefix, name), node, "expected a positive integer, got " + Describe(*node));
    }
    return i->get();
  }

  std::optional<int64_t> NonNegativeInteger(const toml::table& t, const std::string& prefix,
                                            std::string_view name, int64_t max) const {
    const toml::node* node = t.get(name);
    if (node == nullptr) return std::nullopt;
    auto i = node->as_integer();
    if (i == nullptr || i->get() < 0 || i->get() > max) {
      Fail(Join(prefix, name), node,
           "expected an integer from 0 to " + std::to_string(max) + ", got " + Describe(*node));
    }
    return i->get();
  }

  template <typename E>
  std::optional<E> Enum(const toml::table& t, const std::string& prefix, std::string_view name,
                        const Choices<E>& choices) const {
    const std::string expected = ChoiceList(choices);
    auto s = String(t, prefix, name, expected);
    if (!s) return std::nullopt;
    for (const auto& [text, value] : choices) {
      if (text == *s) return value;
    }
    Fail(Join(prefix, name), t.get(name), "expected " + expected + ", got " + Quote(*s));
  }

  // A key that must not be there (message says why).
  void Forbid(const toml::table& t, const std::string& prefix, std::string_view name,
              const std::string& why) const {
    if (const toml::node* node = t.get(name)) Fail(Join(prefix, name), node, why);
  }

  // Keeps every top-level table the schema does not list as an engine's table, as written.
  void ReadEngineTables(const toml::table& root, Scene* s) const {
    for (auto&& [k, v] : root) {
      const std::string name(k.str());
      if (Schema().at("").end() != std::find_if(Schema().at("").begin(), Schema().at("").end(),
                                                [&](const auto& e) { return e.first == name; })) {
        continue;
      }
      RawEngineTable& t = s->engine_tables[name];
      t.where = Loc(name, &v);
      for (auto&& [key, node] : *v.as_table()) {
        const std::string dotted = name + "." + std::string(key.str());
        SettingValue value;
        if (auto f = node.as_floating_point()) {
          value = f->get();
        } else if (auto i = node.as_integer()) {
          value = i->get();
        } else if (auto b = node.as_boolean()) {
          value = b->get();
        } else if (auto str = node.as_string()) {
          value = str->get();
        } else {
          Fail(dotted, &node,
               "expected a number, an integer, true/false or a string, got " + Describe(node));
        }
        t.values[std::string(key.str())] = RawSetting{std::move(value), Loc(dotted, &node)};
      }
    }
  }

  // [external.<name>] tables: each names a manifest or a command (ExternalEngineRef).
  std::vector<ExternalEngineRef> ReadExternalEngines(const toml::table& ext,
                                                     const std::filesystem::path& path) const {
    std::vector<ExternalEngineRef> out;
    const std::filesystem::path base =
        path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    for (auto&& [k, v] : ext) {
      const std::string name(k.str());
      const std::string prefix = "external." + name;
      const toml::table* t = v.as_table();
      if (t == nullptr) {
        Fail(prefix, &v,
             "expected a table [external.<name>] with manifest = \"FILE\" or command = "
             "[\"PROGRAM\", ...], got " +
                 Describe(v));
      }
      if (!IsEngineName(name)) {
        Fail(prefix, &v,
             "expected an engine name of lower-case letters, digits and '_', starting with a "
             "letter");
      }
      for (auto&& [key, node] : *t) {
        if (key.str() != "manifest" && key.str() != "command") {
          Fail(prefix + "." + std::string(key.str()), &node,
               "unknown key (expected manifest or command)");
        }
      }
      ExternalEngineRef ref;
      ref.name = name;
      ref.where = Loc(prefix, &v);
      ref.base_dir = base;
      if (auto m = String(*t, prefix, "manifest", "a file name")) {
        if (t->get("command") != nullptr) {
          Fail(prefix + ".command", t->get("command"),
               "give either manifest or command, not both (a manifest states the command)");
        }
        ref.manifest =
            std::filesystem::path(*m).is_absolute() ? std::filesystem::path(*m) : base / *m;
      } else if (const toml::node* c = t->get("command")) {
        const toml::array* a = c->as_array();
        if (a == nullptr || a->empty()) {
          Fail(prefix + ".command", c,
               "expected a non-empty array of strings [\"PROGRAM\", \"ARG\", ...], got " +
                   Describe(*c));
        }
        for (auto&& arg : *a) {
          auto str = arg.as_string();
          if (str == nullptr || str->get().empty()) {
            Fail(prefix + ".command", &arg, "expected non-empty strings, got " + Describe(arg));
          }
          ref.command.push_back(str->get());
        }
      } else {
        Fail(prefix, &v, "expected manifest = \"FILE\" or command = [\"PROGRAM\", ...]");
      }
      out.push_back(std::move(ref));
    }
    return out;
  }

  static bool IsEngineName(const std::string& name) {
    if (name.empty() || name[0] < 'a' || name[0] > 'z') return false;
    for (char c : name) {
      if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    }
    return true;
  }

 public:
  // A registry file: [external.<name>] tables and nothing else.
  std::vector<ExternalEngineRef> ReadRegistry(const toml::table& root,
                                              const std::filesystem::path& path) const {
    for (auto&& [k, v] : root) {
      if (k.str() != "external") {
        Fail(std::string(k.str()), &v,
             "unknown table or key: a registry of external engines holds [external.<name>] "
             "tables only");
      }
    }
    const toml::node* ext = root.get("external");
    if (ext == nullptr) return {};
    if (!ext->is_table()) Fail("external", ext, "expected tables [external.<name>]");
    return ReadExternalEngines(*ext->as_table(), path);
  }

  BlockDef ReadBlock(const toml::table& t, const std::string& prefix) const {
    BlockDef b;
    if (auto shape = String(t, prefix, "shape", "a body kind's name")) {
      if (FindBodyKind(*shape) == nullptr) {
        Fail(Join(prefix, "shape"), t.get("shape"),
             "expected a body kind (" + QuotedList(BodyShapes()) + "), got " + Quote(*shape));
      }
      b.shape = *shape;
    }
    const bool cylinder = b.shape == kCylinderShape;
    if (cylinder) {
      // A cylinder's size is its diameter and height; its width and depth are the diameter.
      for (const char* name : {"width", "depth"}) {
        Forbid(t, prefix, name, "not used by shape = \"cylinder\" (give its diameter)");
      }
      b.diameter_m = RequiredNumber(t, prefix, "diameter", Rule::kPositive, "m", &kLengthLimit);
      b.width_m = b.depth_m = b.diameter_m;
    } else {
      Forbid(t, prefix, "diameter",
             "only for shape = \"cylinder\" (a block's size is its width, height and depth)");
      b.width_m = RequiredNumber(t, prefix, "width", Rule::kPositive, "m", &kLengthLimit);
    }
    b.height_m = RequiredNumber(t, prefix, "height", Rule::kPositive, "m", &kLengthLimit);
    if (!cylinder) {
      b.depth_m = Number(t, prefix, "depth", Rule::kPositive, "m", &kLengthLimit).value_or(1.0);
    }
    b.friction = Number(t, prefix, "friction", Rule::kNonNegativeOrInfinite, "")
                     .value_or(std::numeric_limits<double>::infinity());
    if (std::isfinite(b.friction) && b.friction > kMaxFiniteFriction) {
      Fail(Join(prefix, "friction"), t.get("friction"),
           std::string("expected ") + kFrictionRange + ", got " + ShortestText(b.friction));
    }
    auto density = Number(t, prefix, "density", Rule::kPositive, "kg/m^3", &kDensityLimit);
    auto mass = Number(t, prefix, "mass", Rule::kPositive, "kg", &kMassLimit);
    if (density && mass) {
      Fail(prefix + ".mass", t.get("mass"), "give either density or mass, not both");
    }
    if (!density && !mass) {
      Fail(prefix, &t, "missing density (kg/m^3) or mass (kg)");
    }
    if (density) {
      b.density_kgpm3 = *density;
      // A block's mass as it always was (density * width * height * depth, in that order: the
      // same bits); a cylinder's from its volume.
      b.mass_kg =
          cylinder ? *density * BodyVolume_m3(b) : *density * b.width_m * b.height_m * b.depth_m;
      if (!Within(b.mass_kg, kMassLimit)) {
        Fail(prefix + ".density", t.get("density"),
             std::string(cylinder ? "density * pi diameter^2 height / 4"
                                  : "density * width * height * depth") +
                 " = " + ShortestText(b.mass_kg) + " kg; expected a mass" + LimitText(kMassLimit));
      }
    } else {
      b.density_kgpm3 = 0.0;
      b.mass_kg = *mass;
    }
    return b;
  }

  // kind = "kanai_tajimi": the filtered white noise, its envelope, sampling and seed.
  void ReadSynthetic(const toml::table& t, const std::string& prefix, MotionDef* m) const {
    SyntheticMotionDef& d = m->synthetic;
    const auto intensity = Number(t, prefix, "intensity", Rule::kPositive, "m^2/s^3");
    const auto peak = Number(t, prefix, "amplitude_g", Rule::kPositive, "g", &kAccelLimit);
    if (intensity && peak) {
      Fail(prefix, &t,
           "give intensity (the white noise's PSD, m^2/s^3) or amplitude_g (the record's peak, "
           "g), not both");
    }
    if (!intensity && !peak) {
      Fail(prefix, &t,
           "missing intensity = ... (the white noise's two-sided PSD, m^2/s^3) or amplitude_g = "
           "... (the peak the record is scaled to, g)");
    }
    d.intensity_m2ps3 = intensity.value_or(0.0);
    m->amplitude_g = peak.value_or(0.0);
    Forbid(t, prefix, "frequency_hz",
           "not used by kind = \"kanai_tajimi\" (ground_frequency_hz is the soil's)");
    d.ground_frequency_hz = RequiredNumber(t, prefix, "ground_frequency_hz", Rule::kPositive, "Hz");
    d.ground_damping = RequiredNumber(t, prefix, "ground_damping", Rule::kPositive, "");
    d.filter_frequency_hz =
        Number(t, prefix, "filter_frequency_hz", Rule::kNonNegative, "Hz").value_or(0.0);
    if (d.filter_frequency_hz > 0.0) {
      d.filter_damping = RequiredNumber(t, prefix, "filter_damping", Rule::kPositive, "");
    } else {
      Forbid(t, prefix, "filter_damping", "only with filter_frequency_hz > 0");
    }
    d.high_pass_hz =
        Number(t, prefix, "high_pass_hz", Rule::kNonNegative, "Hz").value_or(d.high_pass_hz);
    d.zero_residuals = Bool(t, prefix, "zero_residuals").value_or(d.zero_residuals);
    d.envelope = Enum(t, prefix, "envelope", kEnvelopes).value_or(SyntheticEnvelope::kJennings);
    if (d.envelope == SyntheticEnvelope::kJennings) {
      d.rise_s = RequiredNumber(t, prefix, "rise_s", Rule::kPositive, "s");
      d.strong_end_s = RequiredNumber(t, prefix, "strong_end_s", Rule::kPositive, "s");
      d.decay_per_s = RequiredNumber(t, prefix, "decay_per_s", Rule::kPositive, "1/s");
    } else {
      for (const char* key : {"rise_s", "strong_end_s", "decay_per_s"}) {
        Forbid(t, prefix, key, "only for envelope = \"jennings\"");
      }
    }
    d.dt_s = Number(t, prefix, "dt", Rule::kPositive, "s", &kSampleIntervalLimit).value_or(d.dt_s);
    d.duration_s = RequiredNumber(t, prefix, "duration_s", Rule::kPositive, "s", &kDurationLimit);
    m->duration_s = d.duration_s;
    if (const auto seed = NonNegativeInteger(t, prefix, "seed", INT64_MAX)) {
      d.seed = static_cast<std::uint64_t>(*seed);
    }
    const std::string problem = SyntheticMotionProblem(m->SyntheticProcess());
    if (!problem.empty()) Fail(prefix, &t, problem);
  }

  // samples = [...]: a record given by its values, with its units and dt (kind kFile, no file);
  // each value a finite number within the acceleration limit after units and scale.
  void ReadSamples(const toml::table& t, const std::string& prefix, const toml::node& node,
                   MotionDef* m) const {
    m->kind = MotionKind::kFile;
    const std::string key = prefix + ".samples";
    const toml::array* values = node.as_array();
    if (values == nullptr) {
      Fail(key, &node,
           "expected an array of numbers (the acceleration in units, one every dt), got " +
               Describe(node));
    }
    for (const char* name : {"amplitude_g", "frequency_hz", "duration_s"}) {
      Forbid(t, prefix, name, "only for analytic kinds (kind = ...), not for samples");
    }
    for (const char* name : kSyntheticOnlyKeys) {
      Forbid(t, prefix, name, "only for kind = \"kanai_tajimi\", not for samples");
    }
    if (auto u = Enum(t, prefix, "units", kUnits)) {
      m->units = *u;
      m->units_given = true;
    } else {
      Fail(prefix + ".units", &t, "missing; samples must state their units: " + ChoiceList(kUnits));
    }
    if (t.get("dt") == nullptr) {
      Fail(prefix + ".dt", &t, "missing; samples need their sample interval: dt = ... (s)");
    }
    m->dt_s = *Number(t, prefix, "dt", Rule::kPositive, "s", &kSampleIntervalLimit);
    m->samples_resolution =
        Number(t, prefix, "resolution", Rule::kNonNegative, "in the samples' units");
    m->samples.reserve(values->size());
    for (size_t i = 0; i < values->size(); ++i) {
      const toml::node& v = *values->get(i);
      // An override's value has no line of the scene: Loc names the override by its key.
      const auto fail = [&](const std::string& msg) {
        throw SceneError(Loc(key, &v) + ": " + key + "[" + std::to_string(i) + "]" + msg);
      };
      const std::optional<double> number = AsNumber(v);
      if (!number) fail(": expected a finite number, got " + Describe(v));
      const double a = *number;
      if (!std::isfinite(a)) fail(": expected a finite number, got " + ShortestText(a));
      if (const std::string problem = SampleAccelProblem(*m, m->units, a); !problem.empty()) {
        fail(problem);
      }
      m->samples.push_back(a);
    }
    if (m->samples.size() < 2) {
      Fail(key, &node,
           "expected at least 2 samples (a record lasts from its first sample to its last), got " +
               std::to_string(m->samples.size()));
    }
  }

  MotionDef ReadMotion(const toml::table& t, const std::string& prefix,
                       const std::filesystem::path& scene_path) const {
    MotionDef m;
    m.key = prefix;
    auto file = String(t, prefix, "file", "a file path");
    const std::string kinds = ChoiceList(kKinds);
    const toml::node* kind_node = t.get("kind");
    const toml::node* samples_node = t.get("samples");
    if (file && kind_node != nullptr) {
      Fail(prefix, &t, "give either file or kind, not both");
    }
    if (samples_node != nullptr && (file || kind_node != nullptr)) {
      Fail(prefix, &t,
           std::string("give one of file, kind or samples, not several (") +
               (file ? "file" : "kind") + " and samples)");
    }
    if (!file && kind_node == nullptr && samples_node == nullptr) {
      Fail(prefix, &t, "missing file = \"...\", samples = [...] or kind = " + kinds);
    }
    m.scale = Number(t, prefix, "scale", Rule::kFinite, "").value_or(1.0);
    if (t.get("phase_deg") != nullptr && (kind_node == nullptr || !kind_node->is_string() ||
                                          kind_node->as_string()->get() != "harmonic")) {
      Fail(prefix + ".phase_deg", t.get("phase_deg"), "only for kind = \"harmonic\"");
    }
    m.phase_deg = Number(t, prefix, "phase_deg", Rule::kFinite, "degrees").value_or(0.0);
    m.start_s =
        Number(t, prefix, "start_s", Rule::kNonNegative, "s", &kDurationLimit).value_or(0.0);
    if (samples_node != nullptr) {
      ReadSamples(t, prefix, *samples_node, &m);
      return m;
    }
    if (file) {
      m.kind = MotionKind::kFile;
      if (file->empty()) Fail(prefix + ".file", t.get("file"), "expected a file path, got \"\"");
      m.file_as_written = *file;
      std::filesystem::path p(*file);
      m.file = p.is_absolute() ? p : (scene_path.parent_path() / p).lexically_normal();
      if (const std::string problem = InputFileProblem(m.file, "record file"); !problem.empty()) {
        Fail(prefix + ".file", t.get("file"), problem);
      }
      const std::string why = "only for analytic kinds (kind = ...), not for a record file";
      Forbid(t, prefix, "resolution",
             "only for samples = [...]: a file's samples are known to their printed digits");
      Forbid(t, prefix, "amplitude_g", why);
      Forbid(t, prefix, "frequency_hz", why);
      Forbid(t, prefix, "duration_s", why);
      for (const char* key : kSyntheticOnlyKeys) {
        Forbid(t, prefix, key, "only for kind = \"kanai_tajimi\", not for a record file");
      }
      const bool at2 = IsAt2File(m.file);
      if (auto u = Enum(t, prefix, "units", kUnits)) {
        m.units = *u;
        m.units_given = true;
      } else if (!at2) {
        Fail(prefix + ".units", &t,
             "missing; a plain record file must state its units: " + ChoiceList(kUnits));
      }
      if (at2) {
        Forbid(t, prefix, "dt", "not allowed for an AT2 file (DT is read from its header)");
      } else {
        m.dt_s = Number(t, prefix, "dt", Rule::kPositive, "s", &kSampleIntervalLimit).value_or(0.0);
      }
      return m;
    }
    m.kind = *Enum(t, prefix, "kind", kKinds);
    const std::string kind_name(MotionKindName(m.kind));
    Forbid(t, prefix, "units", "not used by kind = \"" + kind_name + "\" (amplitude_g is in g)");
    Forbid(t, prefix, "resolution",
           "only for samples = [...], not for kind = \"" + kind_name + "\"");
    if (m.kind == MotionKind::kKanaiTajimi) {
      ReadSynthetic(t, prefix, &m);
      return m;
    }
    const std::string only_synthetic = "only for kind = \"kanai_tajimi\"";
    for (const char* key : kSyntheticOnlyKeys) {
      Forbid(t, prefix, key, only_synthetic);
    }
    Forbid(t, prefix, "dt", "only for one-column record files and kind = \"kanai_tajimi\"");
    m.amplitude_g = RequiredNumber(t, prefix, "amplitude_g", Rule::kFinite, "g", &kAccelLimit);
    if (!Within(m.amplitude_g * m.scale, kAccelLimit)) {
      Fail(prefix + (t.get("scale") != nullptr ? ".scale" : ".amplitude_g"),
           t.get(t.get("scale") != nullptr ? "scale" : "amplitude_g"),
           "amplitude_g * scale = " + GText(m.amplitude_g * m.scale) +
               " g; expected an acceleration (g)" + LimitText(kAccelLimit));
    }
    if (m.kind == MotionKind::kRectangularPulse) {
      Forbid(t, prefix, "frequency_hz", "not used by kind = \"rectangular_pulse\"");
      m.duration_s = RequiredNumber(t, prefix, "duration_s", Rule::kPositive, "s", &kDurationLimit);
    } else {
      m.frequency_hz =
          RequiredNumber(t, prefix, "frequency_hz", Rule::kPositive, "Hz", &kFrequencyLimit);
      if (m.kind == MotionKind::kHarmonic) {
        m.duration_s = Number(t, prefix, "duration_s", Rule::kPositive, "s", &kDurationLimit)
                           .value_or(std::numeric_limits<double>::infinity());
      } else {
        Forbid(t, prefix, "duration_s",
               "not used by kind = \"" + kind_name + "\" (its length follows from frequency_hz)");
      }
    }
    return m;
  }

  // The blocks: [[block]] tables, bottom first (named block1, block2, ... in messages), or
  // [block1] and an optional [block2]; not both.
  void ReadBlocks(const toml::table& root, Scene* s) const {
    const toml::node* array = root.get("block");
    if (array == nullptr) {
      const toml::table* b1 = Table(root, "", "block1");
      if (b1 == nullptr) {
        throw SceneError(file_ +
                         ": block1: missing table [block1] (the lower block: width, height, "
                         "density or mass)");
      }
      s->blocks.push_back(ReadBlock(*b1, "block1"));
      if (const toml::table* b2 = Table(root, "", "block2")) {
        s->blocks.push_back(ReadBlock(*b2, "block2"));
      }
      return;
    }
    const toml::array* tables = array->as_array();
    if (tables == nullptr || (!tables->empty() && !tables->is_array_of_tables())) {
      Fail("block", array,
           "expected [[block]] tables (one per block, bottom first), got " + Describe(*array));
    }
    for (const char* legacy : {"block1", "block2"}) {
      if (const toml::node* node = root.get(legacy)) {
        Fail(legacy, node,
             std::string("a [") + legacy +
                 "] table beside [[block]] tables: give the blocks either as [[block]] tables "
                 "(bottom first) or as [block1] and [block2], not both");
      }
    }
    if (tables->empty()) Fail("block", array, "expected at least one [[block]] table, got none");
    const size_t count = tables->size();
    if (count > static_cast<size_t>(kMaxBlocks)) {
      Fail("block", &(*tables)[kMaxBlocks],
           "expected at most " + std::to_string(kMaxBlocks) +
               " [[block]] tables (the most blocks a stack may have), got " +
               std::to_string(count));
    }
    for (size_t k = 0; k < count; ++k) {
      const std::string prefix = "block" + std::to_string(k + 1);
      const toml::table& t = *(*tables)[k].as_table();
      CheckKeys(t, prefix);
      s->blocks.push_back(ReadBlock(t, prefix));
      if (s->blocks.back().shape != s->blocks.front().shape) {
        Fail(Join(prefix, "shape"), t.get("shape"),
             "every body of a stack is of one kind: block1 is \"" + s->blocks.front().shape +
                 "\", expected the same, got \"" + s->blocks.back().shape + "\"");
      }
      if (k == 1 && s->blocks.front().shape == kCylinderShape) {
        Fail(prefix, &t,
             "a cylinder stands alone: the 3-D model is one cylinder on its base "
             "(docs/three-d.md), got a second body");
      }
    }
  }

  // Block k's table (k = 1..N), either style; nullptr when there is none.
  static const toml::table* BlockTable(const toml::table& root, int k) {
    if (const toml::array* tables = root.get_as<toml::array>("block")) {
      if (k < 1 || static_cast<size_t>(k) > tables->size()) return nullptr;
      return (*tables)[static_cast<size_t>(k - 1)].as_table();
    }
    return k <= 2 ? root.get_as<toml::table>("block" + std::to_string(k)) : nullptr;
  }

  // One number of an [initial] array (entry k - 1 of initial.<quantity>), reported as
  // initial.<quantity>k.
  double InitialEntry(const toml::array& array, const toml::node* where, std::string_view quantity,
                      int k) const {
    const std::string key = "initial." + std::string(quantity) + std::to_string(k);
    const bool rate = quantity == "omega";
    const std::string unit = rate ? "rad/s" : "rad";
    const toml::node& node = array[static_cast<size_t>(k - 1)];
    const auto fail = [&](const std::string& got) {
      throw SceneError(Loc("initial." + std::string(quantity), where) + ": " + key + ": expected " +
                       Expectation(Rule::kFinite, unit) + (rate ? LimitText(kRateLimit) : "") +
                       " (entry " + std::to_string(k) + " of initial." + std::string(quantity) +
                       "), got " + got);
    };
    const std::optional<double> number = AsNumber(node);
    if (!number) fail(Describe(node));
    const double v = *number;
    if (!Satisfies(v, Rule::kFinite) || (rate && !Within(v, kRateLimit))) fail(ShortestText(v));
    return v;
  }

  // [initial]: the angles and rates at t = 0, one per block: arrays theta = [...] and
  // omega = [...] (one entry per block), or thetaK and omegaK (K = 1..N); not both ways for one
  // quantity. No key of a block the scene does not have.
  void ReadInitial(const toml::table& in, Scene* s) const {
    if (cylinder_) {
      ReadCylinderInitial(in, s);
      return;
    }
    const int n = s->block_count();
    const toml::array* arrays[2] = {nullptr, nullptr};
    for (int q = 0; q < 2; ++q) {
      const std::string_view quantity = q == 0 ? "theta" : "omega";
      const std::string key = "initial." + std::string(quantity);
      const toml::node* node = in.get(quantity);
      if (node == nullptr) continue;
      const std::string what = "an array of " + std::to_string(n) + " numbers (" +
                               (q == 0 ? "rad" : "rad/s") + ", one per block, bottom first)";
      arrays[q] = node->as_array();
      if (arrays[q] == nullptr) Fail(key, node, "expected " + what + ", got " + Describe(*node));
      if (arrays[q]->size() != static_cast<size_t>(n)) {
        Fail(key, node,
             "expected " + what + ": the scene has " + std::to_string(n) +
                 (n == 1 ? " block" : " blocks") + ", got " + std::to_string(arrays[q]->size()) +
                 (arrays[q]->size() == 1 ? " entry" : " entries"));
      }
      for (int k = 1; k <= n; ++k) {
        (q == 0 ? s->initial.theta_rad : s->initial.omega_radps)[k - 1] =
            InitialEntry(*arrays[q], node, quantity, k);
      }
    }
    for (int k = 1; k <= n; ++k) {
      for (int q = 0; q < 2; ++q) {
        const std::string name = (q == 0 ? "theta" : "omega") + std::to_string(k);
        if (arrays[q] != nullptr) {
          Forbid(in, "initial", name,
                 std::string("give either initial.") + (q == 0 ? "theta" : "omega") +
                     " (an array, one entry per block) or initial." + name + ", not both");
          continue;
        }
        const std::optional<double> v =
            q == 0 ? Number(in, "initial", name, Rule::kFinite, "rad")
                   : Number(in, "initial", name, Rule::kFinite, "rad/s", &kRateLimit);
        (q == 0 ? s->initial.theta_rad : s->initial.omega_radps)[k - 1] = v.value_or(0.0);
      }
      if (k == 1) ForbidBeyond(in, n);
    }
  }

  // A cylinder's [initial]: arrays tilt, azimuth, tilt_rate, azimuth_rate, spin_rate (one entry
  // per body), each optional (0); the tilt is a magnitude (>= 0), the azimuth its direction.
  void ReadCylinderInitial(const toml::table& in, Scene* s) const {
    const int n = s->block_count();
    InitialState& init = s->initial;
    const std::array<std::array<double, kMaxBlocks>*, 5> into = {
        &init.tilt_rad, &init.azimuth_rad, &init.tilt_rate_radps, &init.azimuth_rate_radps,
        &init.spin_rate_radps};
    for (size_t q = 0; q < kCylinderInitial.size(); ++q) {
      const auto& [quantity, unit] = kCylinderInitial[q];
      const std::string key = "initial." + std::string(quantity);
      const toml::node* node = in.get(quantity);
      if (node == nullptr) continue;
      const std::string what =
          "an array of " + std::to_string(n) + " numbers (" + std::string(unit) + ", one per body)";
      const toml::array* array = node->as_array();
      if (array == nullptr) Fail(key, node, "expected " + what + ", got " + Describe(*node));
      if (array->size() != static_cast<size_t>(n)) {
        Fail(key, node,
             "expected " + what + ", got " + std::to_string(array->size()) +
                 (array->size() == 1 ? " entry" : " entries"));
      }
      for (int k = 1; k <= n; ++k) {
        const toml::node& entry = (*array)[static_cast<size_t>(k - 1)];
        const std::optional<double> v = AsNumber(entry);
        const bool rate = unit == "rad/s";
        const bool ok = v && std::isfinite(*v) && (!rate || Within(*v, kRateLimit)) &&
                        (quantity != "tilt" || *v >= 0.0);
        if (!ok) {
          const std::string expected = quantity == "tilt"
                                           ? "a tilt >= 0 (rad; the azimuth gives its direction)"
                                           : Expectation(Rule::kFinite, unit) +
                                                 (rate ? LimitText(kRateLimit) : std::string());
          Fail(key, node,
               "entry " + std::to_string(k) + ": expected " + expected + ", got " +
                   (v ? ShortestText(*v) : Describe(entry)));
        }
        (*into[q])[static_cast<size_t>(k - 1)] = *v;
      }
    }
  }

  // thetaK, omegaK for a block K beyond the scene's N.
  void ForbidBeyond(const toml::table& in, int n) const {
    for (int k = n + 1; k <= kMaxBlocks; ++k) {
      for (const char* quantity : {"theta", "omega"}) {
        const std::string name = quantity + std::to_string(k);
        if (n == 1 && k == 2) {
          Forbid(in, "initial", name, "not allowed in a single-block scene (there is no [block2])");
        }
        Forbid(in, "initial", name,
               "not allowed: the scene has " + std::to_string(n) + (n == 1 ? " block" : " blocks") +
                   " (no block " + std::to_string(k) + ")");
      }
    }
  }

  // [run]: duration, output interval, gravity.
  RunConfig ReadRun(const toml::table& run) const {
    RunConfig r;
    r.duration_s = Number(run, "run", "duration", Rule::kPositive, "s", &kDurationLimit)
                       .value_or(r.duration_s);
    r.output_interval_s =
        Number(run, "run", "output_interval", Rule::kPositive, "s").value_or(r.output_interval_s);
    r.gravity_mps2 = Number(run, "run", "gravity", Rule::kPositive, "m/s^2", &kGravityLimit)
                         .value_or(r.gravity_mps2);
    if (r.output_interval_s > r.duration_s) {
      if (const toml::node* node = run.get("output_interval")) {
        Fail("run.output_interval", node,
             "must not exceed run.duration (" + ShortestText(r.duration_s) + " s), got " +
                 ShortestText(r.output_interval_s));
      }
      Fail("run.duration", run.get("duration"),
           "must be at least run.output_interval (" + ShortestText(r.output_interval_s) +
               " s, the default), got " + ShortestText(r.duration_s));
    }
    return r;
  }

  // [model]: the reference's integrator, events and rules.
  ModelConfig ReadModel(const toml::table& model) const {
    ModelConfig m;
    m.integrator = Enum(model, "model", "integrator",
                        Choices<Integrator>{{"dopri5", Integrator::kDopri5},
                                            {"dop853", Integrator::kDop853},
                                            {"rk4", Integrator::kRk4}})
                       .value_or(m.integrator);
    m.rtol = Number(model, "model", "rtol", Rule::kPositive, "", &kRtolLimit).value_or(m.rtol);
    m.atol =
        Number(model, "model", "atol", Rule::kPositive, "rad, rad/s", &kAtolLimit).value_or(m.atol);
    m.step_s = Number(model, "model", "step", Rule::kPositive, "s").value_or(m.step_s);
    m.events = Enum(model, "model", "events",
                    Choices<EventScheme>{{"located", EventScheme::kLocated},
                                         {"thesis", EventScheme::kThesis}})
                   .value_or(m.events);
    m.equations = Enum(model, "model", "equations",
                       Choices<Equations>{{"nonlinear", Equations::kNonlinear},
                                          {"linearized", Equations::kLinearized}})
                      .value_or(m.equations);
    m.overturn_rad =
        Number(model, "model", "overturn_angle", Rule::kPositive, "rad", &kOverturnLimit)
            .value_or(m.overturn_rad);
    Forbid(model, "model", "rest_rate",
           "removed: the rest rule is dimensionless now; use model.rest_rate_rel (the rate "
           "relative to sqrt(g / R), default " +
               ShortestText(ModelConfig{}.rest_rate_rel) + "; README \"Coming to rest\")");
    m.rest_rate_rel =
        Number(model, "model", "rest_rate_rel", Rule::kNonNegative, "").value_or(m.rest_rate_rel);
    m.check_transitions = Bool(model, "model", "check_transitions").value_or(m.check_transitions);
    if (const toml::node* node = model.get("landing_clearance_rel")) {
      if (!cylinder_) {
        Fail("model.landing_clearance_rel", node,
             "only for a cylinder (shape = \"cylinder\"): a block lands at theta = 0");
      }
      m.landing_clearance_rel =
          *Number(model, "model", "landing_clearance_rel", Rule::kNonNegative, "");
      if (m.landing_clearance_rel > 0.5) {
        Fail("model.landing_clearance_rel", node,
             "expected a clearance relative to the diameter from 0 to 0.5, got " +
                 ShortestText(m.landing_clearance_rel));
      }
    }
    m.formulation = Enum(model, "model", "formulation",
                         Choices<Formulation>{{"thesis", Formulation::kThesis},
                                              {"chain", Formulation::kChain},
                                              {"unilateral", Formulation::kUnilateral}})
                        .value_or(m.formulation);
    return m;
  }

  // [compare]: the verdict's tolerance and ensembles.
  CompareConfig ReadCompare(const toml::table& cmp) const {
    CompareConfig c;
    c.tolerance_rad = Number(cmp, "compare", "tolerance", Rule::kPositive, "rad", &kToleranceLimit);
    c.members =
        static_cast<int>(NonNegativeInteger(cmp, "compare", "members", 100000).value_or(c.members));
    c.engine_members = static_cast<int>(
        NonNegativeInteger(cmp, "compare", "engine_members", 100000).value_or(c.engine_members));
    c.amplitude_rel =
        Number(cmp, "compare", "amplitude_rel", Rule::kUnitInterval, "").value_or(c.amplitude_rel);
    c.sample_precision =
        Number(cmp, "compare", "sample_precision", Rule::kNonNegative, "", &kSamplePrecisionLimit)
            .value_or(c.sample_precision);
    c.initial_rel =
        Number(cmp, "compare", "initial_rel", Rule::kUnitInterval, "").value_or(c.initial_rel);
    if (const auto seed = NonNegativeInteger(cmp, "compare", "seed", INT64_MAX)) {
      c.seed = static_cast<uint64_t>(*seed);
    }
    return c;
  }

  // The rules that involve several keys, one for every engine and the reference: every block
  // no wider than the one below it, and every initial angle short of model.overturn_angle.
  void CheckStackRules(const toml::table& root, const Scene& s) const {
    for (int k = 2; k <= s.block_count(); ++k) {
      if (s.blocks[k - 1].width_m <= s.blocks[k - 2].width_m) continue;
      const toml::table* t = BlockTable(root, k);
      const std::string key = "block" + std::to_string(k) + ".width";
      Fail(key, t != nullptr ? t->get("width") : nullptr, WiderThanBelow(s, k));
    }
    const toml::node* in = root.get("initial");
    const toml::table* it = in != nullptr ? in->as_table() : nullptr;
    if (cylinder_ && s.initial.tilt_rad[0] >= s.model.overturn_rad) {
      Fail("initial.tilt", it != nullptr ? it->get("tilt") : nullptr,
           "expected a tilt below model.overturn_angle (" + ShortestText(s.model.overturn_rad) +
               " rad; the cylinder would have overturned), got " +
               ShortestText(s.initial.tilt_rad[0]));
    }
    for (int k = 1; k <= s.block_count(); ++k) {
      const double v = s.initial.theta_rad[k - 1];
      if (std::abs(v) < s.model.overturn_rad) continue;
      const std::string name = "theta" + std::to_string(k);
      const toml::node* node = nullptr;
      if (it != nullptr) node = it->get("theta") != nullptr ? it->get("theta") : it->get(name);
      Fail("initial." + name, node,
           "expected |" + name + "| below model.overturn_angle (" +
               ShortestText(s.model.overturn_rad) + " rad; the block would have overturned), got " +
               ShortestText(v));
    }
  }

  Scene Read(const toml::table& root, const std::filesystem::path& path) {
    Scene s;
    s.path = path;
    CheckKeys(root, "");
    // [block3] and beyond are not engine tables: more than two blocks are [[block]] tables.
    for (auto&& [k, v] : root) {
      if (BlockIndexOf(k.str()) > 2) {
        Fail(std::string(k.str()), &v,
             "unknown table: [block1] and [block2] give one or two blocks; a stack of more is "
             "given as [[block]] tables, bottom first");
      }
    }
    ReadEngineTables(root, &s);
    if (const toml::node* ext = root.get("external")) {
      if (!ext->is_table()) Fail("external", ext, "expected tables [external.<name>]");
      s.external_engines = ReadExternalEngines(*ext->as_table(), path);
    }
    s.title = String(root, "", "title", "a string").value_or("");

    ReadBlocks(root, &s);
    blocks_ = s.block_count();
    cylinder_ = s.three_dimensional();

    if (const toml::table* in = Table(root, "", "initial")) ReadInitial(*in, &s);

    if (const toml::table* base = Table(root, "", "base")) {
      if (const toml::table* h = Table(*base, "base", "horizontal")) {
        s.horizontal = ReadMotion(*h, "base.horizontal", path);
      }
      if (const toml::table* y = Table(*base, "base", "transverse")) {
        if (!cylinder_) {
          Fail("base.transverse", base->get("transverse"),
               "only for bodies rocking in 3-D (shape = \"cylinder\"): a block rocks in the "
               "x-z plane under [base.horizontal] and [base.vertical]");
        }
        s.transverse = ReadMotion(*y, "base.transverse", path);
      }
      if (const toml::table* v = Table(*base, "base", "vertical")) {
        s.vertical = ReadMotion(*v, "base.vertical", path);
      }
    }

    if (const toml::table* run = Table(root, "", "run")) s.run = ReadRun(*run);

    if (const toml::table* model = Table(root, "", "model")) s.model = ReadModel(*model);
    CheckStackRules(root, s);

    if (const toml::table* cmp = Table(root, "", "compare")) s.compare = ReadCompare(*cmp);
    return s;
  }

 private:
  std::string file_;
  std::map<std::string, std::string> overrides_;  // dotted key -> override text
  int blocks_ = 0;                                // the scene's blocks, once read
  bool cylinder_ = false;                         // a cylinder scene, once its blocks are read
};

// Applies "key=value" overrides to the parsed tree; returns dotted key -> override text.
std::map<std::string, std::string> ApplyOverrides(toml::table& root,
                                                  const std::vector<std::string>& overrides,
                                                  const std::string& file) {
  std::map<std::string, std::string> applied;
  for (const std::string& text : overrides) {
    const auto fail = [&](const std::string& msg) {
      throw SceneError(file + ": override " + Quote(text) + ": " + msg);
    };
    const auto eq = text.find('=');
    if (eq == std::string::npos) fail("expected key=value");
    const std::string key = Trim(std::string_view(text).substr(0, eq));
    const std::string value = Trim(std::string_view(text).substr(eq + 1));
    // Split the dotted key and check every part against the schema.
    std::vector<std::string> parts;
    std::string prefix;
    for (size_t start = 0;;) {
      const auto dot = key.find('.', start);
      parts.push_back(
          key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    if (parts[0] == "block") {
      fail("block: [[block]] tables are set by their index: blockK.key (block1.width=...)");
    }
    // blockK.key of a [[block]] scene, or of a block beyond [block2]: the K-th block's table.
    toml::array* block_tables = root.get_as<toml::array>("block");
    const int block_k = BlockIndexOf(parts[0]);
    toml::table* block_table = nullptr;
    if (block_k > 2 || (block_k > 0 && block_tables != nullptr)) {
      if (parts.size() == 1) {
        fail(parts[0] + " is a table; set its keys one by one (" + parts[0] + ".x=...)");
      }
      bool known = false;
      for (const auto& [name, tbl] : Schema().at("block1")) known = known || name == parts[1];
      if (!known) fail("unknown key " + Excerpt(parts[0] + "." + parts[1]));
      if (parts.size() > 2) fail(parts[0] + "." + parts[1] + " is not a table");
      int n = 0;
      if (block_tables != nullptr) {
        n = static_cast<int>(block_tables->size());
      } else {
        n = root.get("block2") != nullptr ? 2 : root.get("block1") != nullptr ? 1 : 0;
      }
      if (block_k > n) {
        fail(Excerpt(key) + ": no block " + std::to_string(block_k) + " (the scene has " +
             std::to_string(n) + (n == 1 ? " block)" : " blocks)"));
      }
      if (block_tables == nullptr || !(*block_tables)[block_k - 1].is_table()) {
        fail("block in the scene is not an array of tables");
      }
      block_table = (*block_tables)[block_k - 1].as_table();
    }
    bool engine_table = false;
    for (size_t i = 0; i < parts.size() && block_table == nullptr; ++i) {
      auto it = Schema().find(prefix);
      bool found = false, is_table = false;
      if (it != Schema().end()) {
        for (const auto& [name, tbl] : it->second) {
          if (name == parts[i]) found = true, is_table = tbl;
        }
      }
      std::string_view quantity;
      int initial_block = 0;
      if (prefix == "initial" && ParseInitialKey(parts[i], &quantity, &initial_block)) {
        found = true;
      }
      const std::string here = Join(prefix, parts[i]);
      // engine.key: an engine's table and its key, checked by the engine.
      if (!found && parts.size() == 2 && (i == 0 || engine_table)) {
        engine_table = true;
        found = true, is_table = i == 0;
      }
      if (!found) fail("unknown key " + Excerpt(here));
      const bool last = i + 1 == parts.size();
      if (last && is_table)
        fail(here + " is a table; set its keys one by one (" + here + ".x=...)");
      if (!last && !is_table) fail(here + " is not a table");
      prefix = here;
    }
    // The value: TOML if it parses, otherwise the bare text as a string.
    toml::table parsed;
    bool is_toml = true;
    try {
      const std::string doc = "v = " + value;
      parsed = toml::parse(std::string_view(doc), std::string_view("override"));
    } catch (const toml::parse_error&) {
      is_toml = false;
    }
    toml::table* t = block_table != nullptr ? block_table : &root;
    for (size_t i = 0; i + 1 < parts.size() && block_table == nullptr; ++i) {
      toml::node* n = t->get(parts[i]);
      if (n == nullptr) {
        t->insert(parts[i], toml::table{});
        n = t->get(parts[i]);
      }
      if (!n->is_table()) fail(parts[i] + " in the scene is not a table");
      t = n->as_table();
    }
    const toml::node* v = is_toml ? parsed.get("v") : nullptr;
    if (is_toml && v != nullptr && parsed.size() == 1) {
      v->visit([&](const auto& node) { t->insert_or_assign(parts.back(), node); });
    } else {
      t->insert_or_assign(parts.back(), value);
    }
    applied[key] = text;
  }
  return applied;
}

}  // namespace

Scene ParseScene(std::string_view toml_text, const std::filesystem::path& path,
                 const std::vector<std::string>& overrides) {
  const std::string file = FileLabel(path);
  toml::table root;
  try {
    root = toml::parse(toml_text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(file + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) +
                     ": TOML syntax error: " + std::string(e.description()));
  }
  auto applied = ApplyOverrides(root, overrides, file);
  Scene scene = Reader(file, std::move(applied)).Read(root, path);
  ValidateScene(scene);
  return scene;
}

Scene LoadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  // A scene is a few kB; 16 MiB leaves room for comments and keeps the TOML tree small.
  constexpr double kMaxSceneFile_bytes = 16.0 * 1024 * 1024;
  if (const std::string problem = InputFileProblem(path, "scene file", kMaxSceneFile_bytes);
      !problem.empty()) {
    throw SceneError(problem);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path.string() + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path.string() + ": cannot read the scene file");
  return ParseScene(text.str(), path, overrides);
}

std::vector<ExternalEngineRef> LoadExternalEngineRegistry(const std::filesystem::path& path) {
  constexpr double kMaxRegistryFile_bytes = 1024.0 * 1024;
  if (const std::string problem =
          InputFileProblem(path, "registry of external engines", kMaxRegistryFile_bytes);
      !problem.empty()) {
    throw SceneError(problem);
  }
  const std::string file = FileLabel(path);
  toml::table root;
  try {
    root = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw SceneError(file + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) +
                     ": TOML syntax error: " + std::string(e.description()));
  }
  return Reader(file, {}).ReadRegistry(root, path);
}

}  // namespace rockbench
