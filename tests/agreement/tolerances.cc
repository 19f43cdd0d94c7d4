#include "tolerances.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "compare/agreement.h"
#include "compare/compare_run.h"
#include "engine/engine.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "scene/scene.h"

namespace rockbench::agreement {
namespace {

constexpr const char* kKeys[] = {"scene", "metric", "engine", "settings", "reference_settings",
                                 "max",   "min",    "equals", "why"};

std::string Join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

std::string Num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// What a TOML node is, for messages.
std::string Kind(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date/time";
  }
}

// The value at a dotted path, or nullptr. A walk that meets a null before the path's end
// returns that null: a part whose shape only a run knows (such as "violations", null in
// AgreementJson of an empty agreement).
const nlohmann::json* Resolve(const nlohmann::json& j, const std::string& path) {
  const nlohmann::json* node = &j;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '.')) {
    if (node->is_null()) return node;
    if (!node->is_object() || part.empty() || !node->contains(part)) return nullptr;
    node = &(*node)[part];
  }
  return node;
}

// The keys AgreementJson writes, for "expected one of" messages: leaves only, dotted.
void Leaves(const nlohmann::json& j, const std::string& prefix, std::vector<std::string>* out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object()) {
      Leaves(*it, key, out);
    } else if (!it->is_array()) {
      out->push_back(key);
    }
  }
}

// A scene loaded with overrides, or a ToleranceError naming the entry.
Scene LoadFor(const Bound& b, const std::vector<std::string>& settings, const char* which) {
  try {
    Scene scene = LoadScene(b.scene_path, settings);
    CheckEngineTables(scene);
    return scene;
  } catch (const SceneError& e) {
    throw ToleranceError(b.Name() + ": " + which + " do not load: " + e.what());
  }
}

std::string Sanitize(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (ok) {
      out += c;
    } else if (!out.empty() && out.back() != '_') {
      out += '_';
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

// The comparison a bound belongs to.
std::string GroupKey(const std::string& scene, const std::string& engine,
                     const std::vector<std::string>& settings,
                     const std::vector<std::string>& reference_settings) {
  return scene + "\n" + engine + "\n" + Join(settings, "\t") + "\n" +
         Join(reference_settings, "\t");
}

}  // namespace

const std::vector<std::string>& KnownEngines() {
  static const std::vector<std::string> kEngines = [] {
    std::vector<std::string> names = {"reference"};
    for (const RegisteredEngine& e : EngineRegistry()) names.push_back(e.name);
    return names;
  }();
  return kEngines;
}

std::string Bound::Name() const {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  s += ": bound #" + std::to_string(index);
  if (!scene.empty()) {
    s += " (" + scene + ", " + engine + ", [" + Join(settings) + "]";
    if (!reference_settings.empty()) s += ", reference [" + Join(reference_settings) + "]";
    s += ", " + metric + ")";
  }
  return s;
}

std::string Bound::Describe() const {
  if (max) return "max " + Num(*max);
  if (min) return "min " + Num(*min);
  if (equals) return "equals " + equals->dump();
  return "(no bound)";
}

std::string BoundGroup::TestName() const {
  std::string name = Sanitize(std::filesystem::path(scene).stem().string()) + "_" + engine;
  if (!settings.empty()) name += "_" + Sanitize(Join(settings, "_"));
  if (!reference_settings.empty()) name += "_vs_" + Sanitize(Join(reference_settings, "_"));
  return name;
}

std::vector<Bound> ParseTolerances(std::string_view text, const std::string& file,
                                   const std::filesystem::path& scenes_dir) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    throw ToleranceError(file + ":" + std::to_string(e.source().begin.line) + ":" +
                         std::to_string(e.source().begin.column) + ": " +
                         std::string(e.description()));
  }
  for (auto&& [k, v] : root) {
    if (k.str() != "bound") {
      throw ToleranceError(file + ":" + std::to_string(k.source().begin.line) + ": " +
                           std::string(k.str()) + ": unknown key (expected only [[bound]] tables)");
    }
  }
  std::vector<Bound> bounds;
  const toml::node* list = root.get("bound");
  if (list == nullptr) return bounds;
  if (!list->is_array_of_tables()) {
    throw ToleranceError(file + ":" + std::to_string(list->source().begin.line) +
                         ": bound: expected [[bound]] tables, got " + Kind(*list));
  }
  // Scenes loaded once per (scene, settings): the loads check the settings.
  std::map<std::string, int> block_count;
  std::set<std::string> seen;
  int index = 0;
  for (const toml::node& node : *list->as_array()) {
    const toml::table& t = *node.as_table();
    Bound b;
    b.file = file;
    b.index = ++index;
    b.line = static_cast<int>(t.source().begin.line);
    for (auto&& [k, v] : t) {
      if (b.line == 0 || static_cast<int>(k.source().begin.line) < b.line) {
        b.line = static_cast<int>(k.source().begin.line);
      }
    }
    auto fail = [&b](const std::string& key, const std::string& msg) -> ToleranceError {
      return ToleranceError(b.Name() + ": " + key + ": " + msg);
    };
    for (auto&& [k, v] : t) {
      if (std::find(std::begin(kKeys), std::end(kKeys), k.str()) == std::end(kKeys)) {
        throw fail(std::string(k.str()),
                   "unknown key (expected scene, engine, settings, reference_settings, metric, "
                   "one of max/min/equals, why)");
      }
    }
    auto string = [&](const char* key, bool required) -> std::string {
      const toml::node* n = t.get(key);
      if (n == nullptr) {
        if (required) throw fail(key, "missing (expected a string)");
        return "";
      }
      if (!n->is_string()) throw fail(key, "expected a string, got " + Kind(*n));
      return n->as_string()->get();
    };
    auto strings = [&](const char* key) {
      std::vector<std::string> out;
      const toml::node* n = t.get(key);
      if (n == nullptr) return out;
      if (!n->is_array()) throw fail(key, "expected an array of \"key=value\" strings");
      for (const toml::node& e : *n->as_array()) {
        if (!e.is_string()) {
          throw fail(key, "expected an array of \"key=value\" strings, got " + Kind(e));
        }
        const std::string s = e.as_string()->get();
        if (s.find('=') == std::string::npos) {
          throw fail(key, "\"" + s + "\": expected key=value");
        }
        out.push_back(s);
      }
      return out;
    };
    // Identity first, so that later messages can name the entry in full.
    b.scene = string("scene", true);
    b.engine = string("engine", true);
    b.metric = string("metric", true);
    b.settings = strings("settings");
    b.reference_settings = strings("reference_settings");
    b.why = string("why", false);
    if (b.why.find_first_not_of(" \t\r\n") == std::string::npos) {
      throw fail("why",
                 "missing or blank (expected the measured value and the mechanism behind "
                 "the bound)");
    }
    const auto& known = KnownEngines();
    if (std::find(known.begin(), known.end(), b.engine) == known.end()) {
      throw fail("engine",
                 "unknown engine '" + b.engine + "' (expected one of: " + Join(known) + ")");
    }
    // The comparison applies reference_settings only where the engine is the reference
    // (RunComparison): on another engine's row they would be silently ignored.
    if (b.engine != "reference" && !b.reference_settings.empty()) {
      throw fail("reference_settings",
                 "only with engine = \"reference\" (an engine's comparison runs the reference "
                 "at the row's settings; it would ignore these)");
    }
    if (b.engine == "reference" && b.reference_settings.empty()) {
      throw fail("reference_settings",
                 "required with engine = \"reference\" (the reference against itself with the "
                 "same settings agrees exactly: the bound could not fail)");
    }
    b.scene_path = scenes_dir / b.scene;
    if (b.scene.empty() || !std::filesystem::is_regular_file(b.scene_path)) {
      throw fail("scene", "no such scene file: " + b.scene_path.string());
    }
    // Exactly one bound.
    const toml::node* max = t.get("max");
    const toml::node* min = t.get("min");
    const toml::node* equals = t.get("equals");
    const int n_bounds = (max != nullptr) + (min != nullptr) + (equals != nullptr);
    if (n_bounds != 1) {
      throw fail(n_bounds == 0 ? "max" : "max/min/equals",
                 n_bounds == 0
                     ? "missing: expected exactly one of max, min (numbers) or equals "
                       "(boolean or string)"
                     : "expected exactly one of max, min, equals, got " + std::to_string(n_bounds));
    }
    for (auto [key, n, out] : {std::tuple{"max", max, &b.max}, std::tuple{"min", min, &b.min}}) {
      if (n == nullptr) continue;
      if (!n->is_number()) throw fail(key, "expected a number, got " + Kind(*n));
      const double x = n->value<double>().value();
      if (!std::isfinite(x)) throw fail(key, "expected a finite number");
      *out = x;
    }
    if (equals != nullptr) {
      if (equals->is_boolean()) {
        b.equals = nlohmann::json(equals->as_boolean()->get());
      } else if (equals->is_string()) {
        b.equals = nlohmann::json(equals->as_string()->get());
      } else {
        throw fail("equals", "expected a boolean or a string, got " + Kind(*equals) +
                                 " (use max or min for numbers)");
      }
    }
    // Metric: key or abs(key).
    b.metric_path = b.metric;
    if (b.metric.rfind("abs(", 0) == 0) {
      if (b.metric.back() != ')') throw fail("metric", "expected abs(KEY)");
      b.metric_abs = true;
      b.metric_path = b.metric.substr(4, b.metric.size() - 5);
    }
    // The settings must load, and the metric must be a key of this scene's comparison JSON.
    std::vector<std::string> ref_settings = b.settings;
    ref_settings.insert(ref_settings.end(), b.reference_settings.begin(),
                        b.reference_settings.end());
    const std::string load_key = b.scene + "\n" + Join(b.settings, "\t");
    if (!block_count.count(load_key)) {
      const Scene loaded = LoadFor(b, b.settings, "settings");
      // A 3-D scene (a cylinder) is marked by a negative count: its keys are tilt_x1, tilt_y1.
      block_count[load_key] = loaded.three_dimensional() ? -1 : loaded.block_count();
    }
    if (!b.reference_settings.empty()) LoadFor(b, ref_settings, "reference_settings");
    // The keys of this scene's comparison: theta1..thetaN and their final errors.
    const bool cylinder = block_count[load_key] < 0;
    const int blocks = std::abs(block_count[load_key]);
    EngineAgreement shape;
    shape.bodies.resize(static_cast<size_t>(blocks));
    if (cylinder) {
      // The keys of a cylinder's comparison (compare/cylinder_compare.h).
      shape.bodies[0].angle.quantity = "tilt_x";
      AngleAgreement tilt_y;
      tilt_y.quantity = "tilt_y";
      tilt_y.name = "tilt_y1";
      shape.bodies[0].more_angles.push_back(tilt_y);
      shape.overturn_azimuth_reference_rad = 0.0;
      shape.overturn_azimuth_engine_rad = 0.0;
    }
    shape.verdict_kind = "agrees";  // the verdict's keys are written when a verdict is made
    nlohmann::json shape_json = AgreementJson(shape);
    shape_json["statistics"] = nullptr;  // its shape depends on the run (null: any key below)
    const nlohmann::json* leaf = Resolve(shape_json, b.metric_path);
    if (leaf == nullptr || leaf->is_object() || leaf->is_array()) {
      std::vector<std::string> keys;
      Leaves(shape_json, "", &keys);
      throw fail("metric", "unknown metric '" + b.metric_path + "' for this scene (" +
                               (cylinder      ? std::string("a cylinder")
                                : blocks == 1 ? std::string("one block")
                                              : std::to_string(blocks) + " blocks") +
                               "); expected one of: " + Join(keys));
    }
    // Wall times depend on the machine: they belong in benchmarks, not in a test's bounds.
    if (b.metric_path == "wall_s") {
      throw fail("metric",
                 "wall_s is a timing: timings are not bounded in tests (benchmarks "
                 "and docs only)");
    }
    // Kinds: known from the shape unless the key is null there (filled in by a run).
    const bool numeric = leaf->is_number(), boolean = leaf->is_boolean(),
               text_kind = leaf->is_string();
    if (!leaf->is_null()) {
      if ((b.max || b.min) && (boolean || text_kind)) {
        throw fail("metric", "'" + b.metric_path + "' is a " +
                                 (boolean ? std::string("boolean") : std::string("string")) +
                                 ": bound it with equals, not max/min");
      }
      if (b.equals && numeric) {
        throw fail("metric", "'" + b.metric_path + "' is a number: bound it with max or min");
      }
    }
    if (b.metric_abs && (boolean || text_kind || b.equals)) {
      throw fail("metric", "abs() applies to numbers only");
    }
    // One bound of each kind per metric and comparison.
    const std::string id = GroupKey(b.scene, b.engine, b.settings, b.reference_settings) + "\n" +
                           b.metric + "\n" +
                           (b.max   ? "max"
                            : b.min ? "min"
                                    : "equals");
    if (!seen.insert(id).second) {
      throw fail("metric", "repeats an earlier entry's " +
                               std::string(b.max   ? "max"
                                           : b.min ? "min"
                                                   : "equals") +
                               " bound on the same comparison and metric");
    }
    bounds.push_back(std::move(b));
  }
  return bounds;
}

std::vector<Bound> LoadTolerances(const std::filesystem::path& file,
                                  const std::filesystem::path& scenes_dir) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ToleranceError(file.string() + ": cannot read the tolerance file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseTolerances(ss.str(), file.string(), scenes_dir);
}

std::vector<BoundGroup> GroupBounds(const std::vector<Bound>& bounds) {
  std::vector<BoundGroup> groups;
  std::map<std::string, size_t> where;
  for (const Bound& b : bounds) {
    const std::string key = GroupKey(b.scene, b.engine, b.settings, b.reference_settings);
    auto it = where.find(key);
    if (it == where.end()) {
      BoundGroup g;
      g.scene = b.scene;
      g.scene_path = b.scene_path;
      g.engine = b.engine;
      g.settings = b.settings;
      g.reference_settings = b.reference_settings;
      it = where.emplace(key, groups.size()).first;
      groups.push_back(std::move(g));
    }
    groups[it->second].bounds.push_back(b);
  }
  // Unique test names (two settings lists could sanitize alike).
  std::map<std::string, int> uses;
  for (const BoundGroup& g : groups) ++uses[g.TestName()];
  for (const auto& [name, n] : uses) {
    if (n > 1) {
      throw ToleranceError("two comparisons would both be named " + name +
                           ": change one's settings spelling");
    }
  }
  return groups;
}

nlohmann::json RunComparison(const BoundGroup& group) {
  std::vector<std::string> ref_settings = group.settings;
  ref_settings.insert(ref_settings.end(), group.reference_settings.begin(),
                      group.reference_settings.end());
  const Scene scene = LoadScene(group.scene_path, group.settings);
  const Scene ref_scene = LoadScene(group.scene_path, ref_settings);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  if (group.engine != "reference") {
    // The comparison `rockbench compare` makes: witness, ensembles, statistics, verdict.
    const CompareRun run = RunCompare(scene, motion, {group.engine});
    return run.comparison["engines"][group.engine];
  }
  const reference::Result reference = reference::Simulate(ref_scene, motion);
  const EngineRun run = RunEngine(group.engine, scene, motion, {.check_convergence = false});
  return AgreementJson(CompareWithReference(scene, reference, run));
}

Verdict CheckBound(const Bound& b, const nlohmann::json& agreement) {
  Verdict v;
  const nlohmann::json* x = Resolve(agreement, b.metric_path);
  const std::string head = b.metric + " (" + b.Describe() + ")";
  const std::string tail = "\n    why: " + b.why + "\n    at " + b.Name();
  if (x == nullptr || x->is_null()) {
    v.measured = x == nullptr ? "missing" : "null";
    v.message = head + ": FAILED, the comparison has " +
                (x == nullptr ? std::string("no such key") : std::string("null there")) + tail;
    return v;
  }
  if (b.equals) {
    v.measured = x->dump();
    v.pass = *x == *b.equals;
    v.message = head + ": measured " + v.measured + (v.pass ? ": ok" : ": FAILED") + tail;
    return v;
  }
  if (!x->is_number()) {
    v.measured = x->dump();
    v.message = head + ": FAILED, measured " + v.measured + " is not a number" + tail;
    return v;
  }
  double value = x->get<double>();
  if (b.metric_abs) value = std::abs(value);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", value);
  v.measured = buf;
  v.pass = b.max ? value <= *b.max : value >= *b.min;
  std::string margin;
  if (v.pass) {
    // How far the measurement is from the bound, as a ratio (bound / measured for max).
    const double ratio =
        b.max ? (value > 0 ? *b.max / value : INFINITY) : (*b.min > 0 ? value / *b.min : INFINITY);
    std::snprintf(buf, sizeof buf, ": ok (margin %.2fx)", ratio);
    margin = buf;
  } else {
    margin = ": FAILED";
  }
  v.message = head + ": measured " + v.measured + margin + tail;
  return v;
}

std::vector<std::string> SceneFiles(const std::filesystem::path& scenes_dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir)) {
    if (e.is_regular_file() && e.path().extension() == ".toml") {
      out.push_back(e.path().filename().string());
    }
  }
  // The 3-D scenes (scenes/three_d/), named relative to the scenes folder.
  if (std::filesystem::is_directory(scenes_dir / "three_d")) {
    for (const auto& e : std::filesystem::directory_iterator(scenes_dir / "three_d")) {
      if (e.is_regular_file() && e.path().extension() == ".toml") {
        out.push_back("three_d/" + e.path().filename().string());
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> UnguardedScenes(const std::vector<Bound>& bounds,
                                         const std::filesystem::path& scenes_dir) {
  std::vector<std::string> out;
  for (const std::string& scene : SceneFiles(scenes_dir)) {
    // A 3-D scene needs the engines that build its body (a planar engine cannot: it says so
    // when named); an engine this build left out cannot tell, so it is not asked for there.
    const Scene loaded = LoadScene(scenes_dir / scene);
    for (const std::string& engine : KnownEngines()) {
      if (engine == "reference") continue;
      if (loaded.three_dimensional()) {
        const Engine* built = FindEngine(engine);
        if (built == nullptr) continue;
        try {
          CheckBuildsBodies(*built, loaded);
        } catch (const SceneError&) {
          continue;
        }
      }
      const bool guarded = std::any_of(bounds.begin(), bounds.end(), [&](const Bound& b) {
        return b.scene == scene && b.engine == engine;
      });
      if (!guarded) out.push_back(scene + ": " + engine);
    }
  }
  return out;
}

}  // namespace rockbench::agreement
