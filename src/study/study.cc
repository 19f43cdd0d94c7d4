// Reading a study file and building its members' scenes.
#include "study/study.h"

#include <fnmatch.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "run/engine_registry.h"
#include "run/resource_estimate.h"
#include "scene/body_kind.h"
#include "scene/limits.h"

namespace rockbench {
namespace {

// Longest path and file name the system opens (Linux's PATH_MAX and NAME_MAX).
constexpr size_t kMaxPathBytes = 4095;
constexpr size_t kMaxNameBytes = 255;
// A study file is a few kB; a million values take about 10 MB.
constexpr double kMaxStudyFile_bytes = 64.0 * 1024 * 1024;

// A path for messages: as it is when short and printable, else an excerpt.
std::string Shown(const std::string& text) {
  const bool plain = text.size() <= 200 && std::none_of(text.begin(), text.end(), [](char c) {
                       return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
                     });
  return plain ? text : Excerpt(text, 200);
}

std::string Where(const std::filesystem::path& file, int line) {
  return Shown(file.string()) + ":" + std::to_string(line);
}

std::string Where(const std::filesystem::path& file, const toml::node& node) {
  return Where(file, static_cast<int>(node.source().begin.line));
}

// A string of the study that names a key, an engine, a value or a file: printable (a NUL
// would cut every message that quotes it, and no key or file name holds a control character).
void CheckText(const std::string& text, const std::string& where, const std::string& key) {
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      throw SceneError(where + ": " + key + ": \"" + Excerpt(text) + "\" holds a control " +
                       "character (byte " + std::to_string(i) + "); expected printable text");
    }
  }
}

// A file name of the study (the scene, a record, a glob): printable, and a path the system can
// open (at most 4095 bytes, each name at most 255).
void CheckPathText(const std::string& text, const std::string& where, const std::string& key) {
  CheckText(text, where, key);
  if (text.empty()) throw SceneError(where + ": " + key + ": expected a file name, got \"\"");
  if (text.size() > kMaxPathBytes) {
    throw SceneError(where + ": " + key + ": \"" + Excerpt(text) + "\" is a path of " +
                     std::to_string(text.size()) + " bytes, more than the " +
                     std::to_string(kMaxPathBytes) + " a path may have");
  }
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find('/', start), text.size());
    if (end - start > kMaxNameBytes) {
      throw SceneError(where + ": " + key + ": \"" + Excerpt(text) + "\" holds a name of " +
                       std::to_string(end - start) + " bytes, more than the " +
                       std::to_string(kMaxNameBytes) + " a file name may have");
    }
    start = end + 1;
  }
}

const std::vector<std::string>& DerivedKeys() {
  static const std::vector<std::string> keys = {
      "size_factor",           "pulse.frequency_ratio",   "pulse.amplitude_ratio",
      "base.horizontal.pga_g", "base.horizontal.pgv_mps", "base.pga_resultant_g"};
  return keys;
}

bool IsDerived(const std::string& key) {
  const auto& d = DerivedKeys();
  return std::find(d.begin(), d.end(), key) != d.end();
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A TOML string with its quotes and escapes.
std::string Quoted(const std::string& s) {
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}

// The files a glob (relative to `dir`) names, sorted by their relative text.
std::vector<std::string> ExpandGlob(const std::filesystem::path& dir, const std::string& pattern) {
  const std::filesystem::path rel(pattern);
  const std::filesystem::path folder = rel.parent_path();
  const std::string name = rel.filename().string();
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir / folder, ec)) {
    if (!entry.is_regular_file()) continue;
    const std::string f = entry.path().filename().string();
    if (::fnmatch(name.c_str(), f.c_str(), 0) == 0) files.push_back((folder / f).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

AxisValue ValueOf(const toml::node& v, const std::string& key, const std::filesystem::path& file,
                  const std::filesystem::path& dir) {
  AxisValue a;
  if (auto d = v.value_exact<double>()) {
    a.number = *d;
    a.is_number = true;
  } else if (auto i = v.value_exact<int64_t>()) {
    a.number = static_cast<double>(*i);
    a.is_number = true;
  } else if (auto s = v.value_exact<std::string>()) {
    const bool is_file = EndsWith(key, ".file");
    if (is_file) {
      CheckPathText(*s, Where(file, v), "axis " + key);
    } else {
      CheckText(*s, Where(file, v), "axis " + key);
    }
    a.text = *s;
    // A record file is relative to the study file, as the scene's is to the scene.
    a.toml = Quoted(is_file ? std::filesystem::absolute(dir / *s).lexically_normal().string() : *s);
    return a;
  } else if (auto b = v.value_exact<bool>()) {
    a.text = a.toml = *b ? "true" : "false";
    return a;
  } else {
    throw SceneError(Where(file, v) + ": axis " + key +
                     ": values: expected numbers, strings or booleans");
  }
  if (!std::isfinite(a.number)) {
    throw SceneError(Where(file, v) + ": axis " + key + ": values: expected finite numbers");
  }
  a.text = a.toml = ShortestText(a.number);
  return a;
}

// `earlier`: the axes read before this one (the axis `zip_with` names is one of them).
StudyAxis ReadAxis(const toml::table& t, const std::filesystem::path& file,
                   const std::filesystem::path& dir, const std::vector<StudyAxis>& earlier) {
  const std::string where = Where(file, t);
  for (const auto& [k, v] : t) {
    const std::string name(k.str());
    if (name != "key" && name != "values" && name != "glob" && name != "zip_with") {
      throw SceneError(Where(file, v) + ": [[axis]] " + Excerpt(name) +
                       ": unknown key (expected one of: key, values, glob, zip_with)");
    }
  }
  StudyAxis axis;
  axis.line = static_cast<int>(t.source().begin.line);
  const auto key = t["key"].value<std::string>();
  constexpr size_t kMaxKeyChars = 200;
  if (!key || key->empty() || key->size() > kMaxKeyChars) {
    throw SceneError(where +
                     ": [[axis]] key: expected a scene key (as --set takes it) or one of: "
                     "size_factor, pulse.frequency_ratio, pulse.amplitude_ratio, "
                     "base.horizontal.pga_g, base.horizontal.pgv_mps, base.pga_resultant_g" +
                     (key && !key->empty() ? ", got \"" + Excerpt(*key) + "\"" : std::string()));
  }
  CheckText(*key, where, "[[axis]] key");
  axis.key = *key;
  axis.derived = IsDerived(axis.key);
  // zip_with: an earlier axis of its own (not itself paired with another).
  if (const toml::node* z = t.get("zip_with")) {
    const auto name = z->value<std::string>();
    const auto it = name ? std::find_if(earlier.begin(), earlier.end(),
                                        [&](const StudyAxis& a) { return a.key == *name; })
                         : earlier.end();
    if (it == earlier.end() || it->zip_with >= 0) {
      std::string keys;
      for (const StudyAxis& a : earlier) {
        if (a.zip_with < 0) keys += (keys.empty() ? "" : ", ") + a.key;
      }
      throw SceneError(Where(file, *z) + ": axis " + axis.key +
                       ": zip_with: expected the key of an earlier axis that is not itself "
                       "zipped (" +
                       (keys.empty() ? std::string("none") : Excerpt(keys, 300)) + ")" +
                       (name ? ", got \"" + Excerpt(*name) + "\"" : std::string()));
    }
    axis.zip_with = static_cast<int>(it - earlier.begin());
  }
  const toml::array* values = t["values"].as_array();
  const auto glob = t["glob"].value<std::string>();
  if ((values != nullptr) == glob.has_value()) {
    throw SceneError(where + ": axis " + axis.key + ": expected values = [...] or glob = \"...\"");
  }
  const auto too_many = [&](size_t n) {
    return SceneError(where + ": axis " + axis.key + ": " + std::to_string(n) +
                      " values, more than a study's " + std::to_string(kMaxStudyMembers) +
                      " members (docs/ensemble.md, \"Limits\")");
  };
  if (glob) {
    if (!EndsWith(axis.key, ".file")) {
      throw SceneError(where + ": axis " + axis.key +
                       ": glob is for a record file key (base.horizontal.file)");
    }
    CheckPathText(*glob, where, "axis " + axis.key + ": glob");
    const std::vector<std::string> files = ExpandGlob(dir, *glob);
    if (files.size() > static_cast<size_t>(kMaxStudyMembers)) throw too_many(files.size());
    for (const std::string& f : files) {
      axis.values.push_back(ValueOf(toml::value<std::string>(f), axis.key, file, dir));
    }
    if (axis.values.empty()) {
      throw SceneError(where + ": axis " + axis.key + ": glob \"" + Excerpt(*glob) +
                       "\" matches no file in " +
                       Shown((dir / std::filesystem::path(*glob).parent_path()).string()));
    }
    return axis;
  }
  if (values->size() > static_cast<size_t>(kMaxStudyMembers)) throw too_many(values->size());
  for (const toml::node& v : *values) axis.values.push_back(ValueOf(v, axis.key, file, dir));
  if (axis.values.empty()) throw SceneError(where + ": axis " + axis.key + ": values is empty");
  for (const AxisValue& v : axis.values) {
    if (axis.derived && (!v.is_number || !(v.number > 0.0))) {
      throw SceneError(where + ": axis " + axis.key + ": values: expected positive numbers, got " +
                       Excerpt(v.text));
    }
  }
  return axis;
}

std::vector<std::string> ReadStringList(const toml::node& node, const std::string& key,
                                        const std::filesystem::path& file) {
  const toml::array* a = node.as_array();
  std::vector<std::string> out;
  if (a != nullptr) {
    for (const toml::node& v : *a) {
      auto s = v.value_exact<std::string>();
      if (!s) break;
      out.push_back(*s);
    }
  }
  if (a == nullptr || out.size() != a->size()) {
    throw SceneError(Where(file, node) + ": " + key + ": expected a list of strings");
  }
  for (const std::string& entry : out) CheckText(entry, Where(file, node), key);
  return out;
}

double ReadPositive(const toml::node& node, const std::string& key,
                    const std::filesystem::path& file) {
  const auto v = node.value<double>();
  if (!v || !(*v > 0.0) || !std::isfinite(*v)) {
    throw SceneError(Where(file, node) + ": " + key + ": expected a positive number");
  }
  return *v;
}

// wall_limit_s: the range --wall-limit takes (a millisecond to 16 weeks).
double ReadWallLimit(const toml::node& node, const std::filesystem::path& file) {
  constexpr double kMin_s = 1e-3, kMax_s = 1e7;
  const double v = ReadPositive(node, "wall_limit_s", file);
  if (v < kMin_s || v > kMax_s) {
    throw SceneError(Where(file, node) + ": wall_limit_s: expected " + ShortestText(kMin_s) +
                     " to " + ShortestText(kMax_s) + " s, got " + ShortestText(v));
  }
  return v;
}

void CheckEngines(const StudyDef& s, const toml::node& node) {
  // The external engines the study's scene names ([external.<name>]) are registered (their
  // tables are checked) but run only when a registry file the user owns names them too. A scene
  // that cannot be read is said later, with its member's context.
  std::optional<Scene> scene;
  if (!s.scene_path.empty()) {
    try {
      scene = LoadScene(s.scene_path);
      RegisterExternalEngines(*scene);
    } catch (const SceneError&) {
      scene.reset();
    }
  }
  std::vector<std::string> seen;
  for (const std::string& e : s.engines) {
    if (std::find(seen.begin(), seen.end(), e) != seen.end()) {
      throw SceneError(Where(s.path, node) + ": engines: \"" + Excerpt(e) + "\" listed twice");
    }
    seen.push_back(e);
    // One engine name per entry, the reference or an engine of the build or of a registry file
    // the user owns: "all", a comma-joined list and an engine the study's scene brings are
    // refused here, not row by row.
    try {
      CheckEngineName(e);
    } catch (const SceneError& err) {
      throw SceneError(Where(s.path, node) + ": engines: " + err.what());
    }
    // An engine that does not build the scene's body (a planar engine facing a cylinder) is
    // refused here, before any member is built or run.
    const Engine* engine = scene ? FindEngine(e) : nullptr;
    if (engine != nullptr && !scene->blocks.empty()) {
      const std::string& shape = scene->blocks.front().shape;
      const std::vector<std::string> builds = engine->body_shapes();
      if (std::find(builds.begin(), builds.end(), shape) == builds.end()) {
        std::string list;
        for (const std::string& b : builds) list += (list.empty() ? "\"" : ", \"") + b + "\"";
        throw SceneError(Where(s.path, node) + ": engines: \"" + e + "\" builds bodies of shape " +
                         list + ", not the " + shape + " of the study's scene " +
                         Shown(s.scene_path.string()) +
                         (shape == kCylinderShape
                              ? " (a cylinder rocks in three dimensions; this engine simulates "
                                "bodies in the x-z plane only): a cylinder study runs the "
                                "reference and the 3-D engines (bullet, ode, mujoco, dart, "
                                "siconos)"
                              : ""));
      }
    }
  }
  if (s.engines.empty()) {
    throw SceneError(Where(s.path, node) + ": engines: expected \"reference\" and/or engine names");
  }
}

void ReadTop(const toml::table& root, StudyDef* s) {
  const std::filesystem::path dir = s->path.parent_path();
  const toml::node* engines_node = nullptr;
  for (const auto& [k, v] : root) {
    const std::string name(k.str());
    if (name == "title") {
      s->title = v.value<std::string>().value_or("");
    } else if (name == "scene") {
      const auto p = v.value<std::string>();
      if (!p) throw SceneError(Where(s->path, v) + ": scene: expected a file name");
      CheckPathText(*p, Where(s->path, v), "scene");
      s->scene_path = (dir / *p).lexically_normal();
      s->scene_line = static_cast<int>(v.source().begin.line);
    } else if (name == "engines") {
      s->engines = ReadStringList(v, "engines", s->path);
      engines_node = &v;
    } else if (name == "set") {
      s->overrides = ReadStringList(v, "set", s->path);
      s->set_line = static_cast<int>(v.source().begin.line);
    } else if (name == "combine") {
      const std::string c = v.value<std::string>().value_or("");
      if (c != "product" && c != "zip") {
        throw SceneError(Where(s->path, v) + ": combine: expected \"product\" or \"zip\"");
      }
      s->combine = c == "zip" ? StudyCombine::kZip : StudyCombine::kProduct;
    } else if (name == "wall_limit_s") {
      s->wall_limit_s = ReadWallLimit(v, s->path);
    } else if (name == "min_impact_rate") {
      s->min_impact_rate_radps = ReadPositive(v, name, s->path);
    } else if (name == "axis") {
      const toml::array* axes = v.as_array();
      if (axes == nullptr) throw SceneError(Where(s->path, v) + ": axis: expected [[axis]] tables");
      for (const toml::node& a : *axes) {
        if (!a.is_table()) throw SceneError(Where(s->path, a) + ": axis: expected [[axis]] tables");
        s->axes.push_back(ReadAxis(*a.as_table(), s->path, dir, s->axes));
      }
    } else {
      throw SceneError(Where(s->path, v) + ": " + Excerpt(name) +
                       ": unknown key (expected one of: title, scene, engines, set, combine, "
                       "wall_limit_s, min_impact_rate, axis)");
    }
  }
  // Once the scene is known: its external engines are the study's too.
  if (engines_node != nullptr) CheckEngines(*s, *engines_node);
}

// Block 1's p = sqrt(3 g / (4 R)) (rad/s) and tan(alpha1).
void Block1Parameters(const Scene& scene, double* p_radps, double* tan_alpha) {
  const double b = scene.blocks.at(0).width_m / 2.0, h = scene.blocks.at(0).height_m / 2.0;
  *p_radps = std::sqrt(3.0 * scene.run.gravity_mps2 / (4.0 * std::hypot(b, h)));
  *tan_alpha = b / h;
}

void ApplyDerived(const std::string& key, double v, Scene* scene) {
  if (key == "size_factor") {
    for (BlockDef& b : scene->blocks) {
      b.width_m *= v;
      b.height_m *= v;
      b.depth_m *= v;
      b.diameter_m *= v;  // a cylinder's (0 for a block)
      b.mass_kg *= v * v * v;
    }
    return;
  }
  if (key == "base.pga_resultant_g") {
    // Both horizontal components by one factor: the resultant's peak scales with it exactly.
    std::optional<MotionComponent> x, y;
    if (scene->horizontal) x = MotionComponent::FromDef(*scene->horizontal);
    if (scene->transverse) y = MotionComponent::FromDef(*scene->transverse);
    if (!x && !y) {
      throw SceneError(scene->path.string() + ": axis " + key +
                       ": the scene has no [base.horizontal] or [base.transverse]");
    }
    const double now =
        MeasureResultantPga(x, y, scene->run.duration_s).pga_mps2 / kStandardGravity_mps2;
    if (!(now > 0.0)) {
      throw SceneError(scene->path.string() + ": axis " + key +
                       ": the horizontal motion is zero; it cannot be scaled to a target");
    }
    if (scene->horizontal) scene->horizontal->scale *= v / now;
    if (scene->transverse) scene->transverse->scale *= v / now;
    return;
  }
  if (!scene->horizontal) {
    throw SceneError(scene->path.string() + ": axis " + key +
                     ": the scene has no [base.horizontal]");
  }
  MotionDef& h = *scene->horizontal;
  double p = 0.0, tan_alpha = 0.0;
  Block1Parameters(*scene, &p, &tan_alpha);
  if (key == "pulse.frequency_ratio") {
    h.frequency_hz = v * p / (2.0 * M_PI);
  } else if (key == "pulse.amplitude_ratio") {
    h.amplitude_g = v * scene->run.gravity_mps2 * tan_alpha / kStandardGravity_mps2;
  } else {
    const IntensityMeasures im =
        MeasureIntensity(MotionComponent::FromDef(h), scene->run.duration_s);
    const bool pga = key == "base.horizontal.pga_g";
    const double now = pga ? im.pga_mps2 / kStandardGravity_mps2 : im.pgv_mps;
    if (!(now > 0.0)) {
      throw SceneError(scene->path.string() + ": axis " + key +
                       ": the horizontal motion is zero; it cannot be scaled to a target");
    }
    h.scale *= v / now;
  }
}

}  // namespace

int64_t StudyDef::member_count() const {
  if (axes.empty()) return 1;
  if (combine == StudyCombine::kZip) return static_cast<int64_t>(axes.front().values.size());
  int64_t n = 1;
  for (const StudyAxis& a : axes) {
    if (a.zip_with < 0) n *= static_cast<int64_t>(a.values.size());
  }
  return n;
}

std::vector<int> StudyDef::ValueIndices(int64_t member) const {
  std::vector<int> idx(axes.size(), 0);
  if (combine == StudyCombine::kZip) {
    std::fill(idx.begin(), idx.end(), static_cast<int>(member));
    return idx;
  }
  for (size_t k = axes.size(); k-- > 0;) {
    if (axes[k].zip_with >= 0) continue;
    const auto n = static_cast<int64_t>(axes[k].values.size());
    idx[k] = static_cast<int>(member % n);
    member /= n;
  }
  // A zipped axis takes its partner's index (an earlier axis, not itself zipped).
  for (size_t k = 0; k < axes.size(); ++k) {
    if (axes[k].zip_with >= 0) idx[k] = idx[static_cast<size_t>(axes[k].zip_with)];
  }
  return idx;
}

namespace {

// The scene of a member with the first `set_entries` of the study's `set` and its first
// `axis_count` axes applied (MemberScene: all of them).
Scene BuildScene(const StudyDef& study, const std::vector<int>& idx, size_t set_entries,
                 size_t axis_count) {
  std::vector<std::string> overrides(study.overrides.begin(),
                                     study.overrides.begin() + static_cast<long>(set_entries));
  for (size_t k = 0; k < axis_count; ++k) {
    const StudyAxis& a = study.axes[k];
    if (!a.derived) overrides.push_back(a.key + "=" + a.values[idx[k]].toml);
  }
  Scene scene = LoadScene(study.scene_path, overrides);
  // Derived axes in their fixed order: geometry first, then what depends on it.
  for (const std::string& key : DerivedKeys()) {
    for (size_t k = 0; k < axis_count; ++k) {
      if (study.axes[k].key == key) ApplyDerived(key, study.axes[k].values[idx[k]].number, &scene);
    }
  }
  ValidateScene(scene);
  CheckEngineTables(scene);
  // The memory of each of the member's runs (the reference, or the reference and an engine),
  // estimated before anything runs, against this process's budget (--memory-budget). Its time
  // is bounded by the study's wall_limit_s, not by an estimate.
  ResourceBudget budget = ProcessBudget();
  budget.wall_s = std::numeric_limits<double>::infinity();
  for (const std::string& engine : study.engines) {
    CheckRunEstimate(EstimateRun(scene, {engine}, 0, 0, 1), budget, Shown(scene.path.string()));
  }
  return scene;
}

// The message of an exception from building a scene: a SceneError's text, a file system
// error's path cut to an excerpt, any other's what().
std::string SceneMessage(const std::exception& e) {
  if (const auto* fe = dynamic_cast<const std::filesystem::filesystem_error*>(&e)) {
    return Excerpt(fe->path1().string()) + ": " + fe->code().message();
  }
  return e.what();
}

// Whether building the scene with these parts throws; its message in *why.
bool Fails(const StudyDef& study, const std::vector<int>& idx, size_t set_entries,
           size_t axis_count, std::string* why) {
  try {
    BuildScene(study, idx, set_entries, axis_count);
    return false;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    *why = SceneMessage(e);
    return true;
  }
}

// The error of member `member`'s scene (message `why`), blamed on what made it: the base scene
// itself, a `set` entry or an axis. The scene is built again with the base alone, then the
// `set` entries, then the axes added one at a time; the first of these builds that fails with
// the member's own message names the culprit (a build failing otherwise - a base scene whose
// placeholder record every member replaces - is not it).
std::string Blame(const StudyDef& study, int64_t member, const std::vector<int>& idx,
                  const std::string& why) {
  std::string message;
  if (Fails(study, idx, 0, 0, &message) && message == why) {
    return Where(study.path, study.scene_line) + ": scene \"" + Shown(study.scene_path.string()) +
           "\": " + why;
  }
  for (size_t j = 1; j <= study.overrides.size(); ++j) {
    if (Fails(study, idx, j, 0, &message) && message == why) {
      return Where(study.path, study.set_line) + ": set \"" + Excerpt(study.overrides[j - 1]) +
             "\": " + why;
    }
  }
  for (size_t k = 1; k <= study.axes.size(); ++k) {
    if (k == study.axes.size() ||
        (Fails(study, idx, study.overrides.size(), k, &message) && message == why)) {
      const StudyAxis& a = study.axes[k - 1];
      return Where(study.path, a.line) + ": axis " + a.key + " = " +
             Excerpt(a.values[idx[k - 1]].text) + " (" + MemberText(study, member) + "): " + why;
    }
  }
  // No axis: the set entries and the base scene together.
  return Shown(study.path.string()) + ": " + MemberText(study, member) + ": " + why;
}

}  // namespace

std::string MemberText(const StudyDef& study, int64_t member) {
  const std::vector<int> idx = study.ValueIndices(member);
  std::string text = "member " + std::to_string(member);
  for (size_t k = 0; k < study.axes.size(); ++k) {
    text += (k == 0 ? ": " : ", ") + study.axes[k].key + " = " +
            Excerpt(study.axes[k].values[idx[k]].text);
  }
  return text;
}

StudyDef LoadStudy(const std::filesystem::path& path, StudyCheck check) {
  const std::string problem = InputFileProblem(path, "study file", kMaxStudyFile_bytes);
  if (!problem.empty()) throw SceneError(problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(Shown(path.string()) + ": cannot open the study file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseStudy(text.str(), path, check);
}

StudyDef ParseStudy(const std::string& text, const std::filesystem::path& path, StudyCheck check) {
  StudyDef s;
  s.path = path;
  s.engines = {"reference"};
  const std::string name = Shown(path.string());
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    throw SceneError(name + ":" + std::to_string(e.source().begin.line) + ": " +
                     Excerpt(e.description(), 200));
  }
  ReadTop(root, &s);
  if (s.scene_path.empty()) throw SceneError(name + ": scene: required (the base scene)");
  if (s.combine == StudyCombine::kZip) {
    for (const StudyAxis& a : s.axes) {
      if (a.values.size() != s.axes.front().values.size()) {
        throw SceneError(name + ": combine = \"zip\": axis " + a.key + " has " +
                         std::to_string(a.values.size()) + " values, axis " + s.axes.front().key +
                         " " + std::to_string(s.axes.front().values.size()) + " (expected equal)");
      }
    }
  }
  for (size_t i = 0; i < s.axes.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (s.axes[i].key == s.axes[j].key) {
        throw SceneError(Where(path, s.axes[i].line) + ": axis " + s.axes[i].key + " given twice");
      }
    }
  }
  // zip_with pairs the values of two axes of a product, one to one.
  for (const StudyAxis& a : s.axes) {
    if (a.zip_with < 0) continue;
    const StudyAxis& partner = s.axes[static_cast<size_t>(a.zip_with)];
    if (s.combine == StudyCombine::kZip) {
      throw SceneError(Where(path, a.line) + ": axis " + a.key +
                       ": zip_with: every axis of combine = \"zip\" is zipped already");
    }
    if (a.values.size() != partner.values.size()) {
      throw SceneError(Where(path, a.line) + ": axis " + a.key + ": zip_with = \"" + partner.key +
                       "\": " + std::to_string(a.values.size()) + " values, axis " + partner.key +
                       " " + std::to_string(partner.values.size()) + " (expected equal)");
    }
  }
  // The resultant's scaling sets the x component's scale too: one of the two only.
  for (const StudyAxis& a : s.axes) {
    if (a.key != "base.pga_resultant_g") continue;
    for (const StudyAxis& b : s.axes) {
      if (b.key == "base.horizontal.pga_g" || b.key == "base.horizontal.pgv_mps") {
        throw SceneError(Where(path, a.line) + ": axis base.pga_resultant_g scales " +
                         "[base.horizontal] too: not with axis " + b.key + " (line " +
                         std::to_string(b.line) + ")");
      }
    }
  }
  // The study's size, before member_count() multiplies the axes' lengths (in doubles: no
  // overflow).
  double members = 1.0;
  std::string sizes;
  for (const StudyAxis& a : s.axes) {
    if ((s.combine == StudyCombine::kProduct && a.zip_with < 0) || &a == &s.axes.front()) {
      members *= static_cast<double>(a.values.size());
    }
    sizes += (sizes.empty()                     ? ""
              : s.combine == StudyCombine::kZip ? ", "
                                                : " x ") +
             a.key + " (" + std::to_string(a.values.size()) + ")";
  }
  const double runs = members * static_cast<double>(s.engines.size());
  if (runs > static_cast<double>(kMaxStudyRuns)) {
    throw SceneError(name + ": " + ShortestText(members) + " members x " +
                     std::to_string(s.engines.size()) + " runs = " + ShortestText(runs) +
                     " runs (axes: " + Excerpt(sizes, 300) + "), more than the limit of " +
                     std::to_string(kMaxStudyRuns) +
                     " runs a study may have (docs/ensemble.md, \"Limits\"): split it into "
                     "several studies along an axis");
  }
  // Every axis key, and with kEveryValue every value, is checked by building the members that
  // hold them: member 0, and the members that differ from it on one axis (zip: every member).
  {
    const Scene first = MemberScene(s, 0);
    s.blocks = first.block_count();
    s.cylinder = first.three_dimensional();
  }
  if (check == StudyCheck::kEveryValue) {
    if (s.combine == StudyCombine::kZip) {
      for (int64_t m = 1; m < s.member_count(); ++m) MemberScene(s, m);
    } else {
      int64_t stride = 1;
      for (size_t k = s.axes.size(); k-- > 0;) {
        if (s.axes[k].zip_with >= 0) continue;  // its values go with its partner's
        const auto n = static_cast<int64_t>(s.axes[k].values.size());
        for (int64_t j = 1; j < n; ++j) MemberScene(s, j * stride);
        stride *= n;
      }
    }
  }
  return s;
}

Scene MemberScene(const StudyDef& study, int64_t member) {
  const std::vector<int> idx = study.ValueIndices(member);
  try {
    return BuildScene(study, idx, study.overrides.size(), study.axes.size());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(Blame(study, member, idx, SceneMessage(e)));
  }
}

}  // namespace rockbench
