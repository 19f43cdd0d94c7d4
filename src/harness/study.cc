// Reading a study file and building its members' scenes.
#include "harness/study.h"

#include <fnmatch.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "harness/engine_registry.h"
#include "scene/ground_motion.h"
#include "scene/intensity.h"

namespace rockbench {
namespace {

std::string Where(const std::filesystem::path& file, const toml::node& node) {
  return file.string() + ":" + std::to_string(node.source().begin.line);
}

const std::vector<std::string>& DerivedKeys() {
  static const std::vector<std::string> keys = {"size_factor", "pulse.frequency_ratio",
                                                "pulse.amplitude_ratio", "base.horizontal.pga_g",
                                                "base.horizontal.pgv_mps"};
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
    a.text = *s;
    // A record file is relative to the study file, as the scene's is to the scene.
    const bool is_file = EndsWith(key, ".file");
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

StudyAxis ReadAxis(const toml::table& t, const std::filesystem::path& file,
                   const std::filesystem::path& dir) {
  const std::string where = Where(file, t);
  for (const auto& [k, v] : t) {
    const std::string name(k.str());
    if (name != "key" && name != "values" && name != "glob") {
      throw SceneError(Where(file, v) + ": [[axis]] " + name +
                       ": unknown key (expected one of: key, values, glob)");
    }
  }
  StudyAxis axis;
  const auto key = t["key"].value<std::string>();
  if (!key || key->empty()) {
    throw SceneError(where +
                     ": [[axis]] key: expected a scene key (as --set takes it) or one of: "
                     "size_factor, pulse.frequency_ratio, pulse.amplitude_ratio, "
                     "base.horizontal.pga_g, base.horizontal.pgv_mps");
  }
  axis.key = *key;
  axis.derived = IsDerived(axis.key);
  const toml::array* values = t["values"].as_array();
  const auto glob = t["glob"].value<std::string>();
  if ((values != nullptr) == glob.has_value()) {
    throw SceneError(where + ": axis " + axis.key + ": expected values = [...] or glob = \"...\"");
  }
  if (glob) {
    if (!EndsWith(axis.key, ".file")) {
      throw SceneError(where + ": axis " + axis.key +
                       ": glob is for a record file key (base.horizontal.file)");
    }
    for (const std::string& f : ExpandGlob(dir, *glob)) {
      axis.values.push_back(ValueOf(toml::value<std::string>(f), axis.key, file, dir));
    }
    if (axis.values.empty()) {
      throw SceneError(where + ": axis " + axis.key + ": glob \"" + *glob +
                       "\" matches no file in " +
                       (dir / std::filesystem::path(*glob).parent_path()).string());
    }
    return axis;
  }
  for (const toml::node& v : *values) axis.values.push_back(ValueOf(v, axis.key, file, dir));
  if (axis.values.empty()) throw SceneError(where + ": axis " + axis.key + ": values is empty");
  for (const AxisValue& v : axis.values) {
    if (axis.derived && (!v.is_number || !(v.number > 0.0))) {
      throw SceneError(where + ": axis " + axis.key + ": values: expected positive numbers");
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

void CheckEngines(const StudyDef& s, const toml::node& node) {
  std::vector<std::string> seen;
  for (const std::string& e : s.engines) {
    if (std::find(seen.begin(), seen.end(), e) != seen.end()) {
      throw SceneError(Where(s.path, node) + ": engines: \"" + e + "\" listed twice");
    }
    seen.push_back(e);
    if (e == "reference") continue;
    try {
      ParseEngineList(e);
    } catch (const SceneError& err) {
      throw SceneError(Where(s.path, node) + ": engines: " + err.what());
    }
  }
  if (s.engines.empty()) {
    throw SceneError(Where(s.path, node) + ": engines: expected \"reference\" and/or engine names");
  }
}

void ReadTop(const toml::table& root, StudyDef* s) {
  const std::filesystem::path dir = s->path.parent_path();
  for (const auto& [k, v] : root) {
    const std::string name(k.str());
    if (name == "title") {
      s->title = v.value<std::string>().value_or("");
    } else if (name == "scene") {
      const auto p = v.value<std::string>();
      if (!p) throw SceneError(Where(s->path, v) + ": scene: expected a file name");
      s->scene_path = (dir / *p).lexically_normal();
    } else if (name == "engines") {
      s->engines = ReadStringList(v, "engines", s->path);
      CheckEngines(*s, v);
    } else if (name == "set") {
      s->overrides = ReadStringList(v, "set", s->path);
    } else if (name == "combine") {
      const std::string c = v.value<std::string>().value_or("");
      if (c != "product" && c != "zip") {
        throw SceneError(Where(s->path, v) + ": combine: expected \"product\" or \"zip\"");
      }
      s->combine = c == "zip" ? StudyCombine::kZip : StudyCombine::kProduct;
    } else if (name == "wall_limit_s") {
      s->wall_limit_s = ReadPositive(v, name, s->path);
    } else if (name == "min_impact_rate") {
      s->min_impact_rate_radps = ReadPositive(v, name, s->path);
    } else if (name == "axis") {
      const toml::array* axes = v.as_array();
      if (axes == nullptr) throw SceneError(Where(s->path, v) + ": axis: expected [[axis]] tables");
      for (const toml::node& a : *axes) {
        if (!a.is_table()) throw SceneError(Where(s->path, a) + ": axis: expected [[axis]] tables");
        s->axes.push_back(ReadAxis(*a.as_table(), s->path, dir));
      }
    } else {
      throw SceneError(Where(s->path, v) + ": " + name +
                       ": unknown key (expected one of: title, scene, engines, set, combine, "
                       "wall_limit_s, min_impact_rate, axis)");
    }
  }
}

// Block 1's p = sqrt(3 g / (4 R)) (rad/s) and tan(alpha1).
void Block1Parameters(const Scene& scene, double* p_radps, double* tan_alpha) {
  const double b = scene.block1.width_m / 2.0, h = scene.block1.height_m / 2.0;
  *p_radps = std::sqrt(3.0 * scene.run.gravity_mps2 / (4.0 * std::hypot(b, h)));
  *tan_alpha = b / h;
}

void ApplyDerived(const std::string& key, double v, Scene* scene) {
  if (key == "size_factor") {
    for (BlockDef* b : {&scene->block1, scene->block2 ? &*scene->block2 : nullptr}) {
      if (b == nullptr) continue;
      b->width_m *= v;
      b->height_m *= v;
      b->depth_m *= v;
      b->mass_kg *= v * v * v;
    }
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
  for (const StudyAxis& a : axes) n *= static_cast<int64_t>(a.values.size());
  return n;
}

std::vector<int> StudyDef::ValueIndices(int64_t member) const {
  std::vector<int> idx(axes.size(), 0);
  if (combine == StudyCombine::kZip) {
    std::fill(idx.begin(), idx.end(), static_cast<int>(member));
    return idx;
  }
  for (size_t k = axes.size(); k-- > 0;) {
    const auto n = static_cast<int64_t>(axes[k].values.size());
    idx[k] = static_cast<int>(member % n);
    member /= n;
  }
  return idx;
}

StudyDef LoadStudy(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path.string() + ": cannot open the study file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseStudy(text.str(), path);
}

StudyDef ParseStudy(const std::string& text, const std::filesystem::path& path) {
  StudyDef s;
  s.path = path;
  s.engines = {"reference"};
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    throw SceneError(path.string() + ":" + std::to_string(e.source().begin.line) + ": " +
                     std::string(e.description()));
  }
  ReadTop(root, &s);
  if (s.scene_path.empty()) throw SceneError(path.string() + ": scene: required (the base scene)");
  if (s.combine == StudyCombine::kZip) {
    for (const StudyAxis& a : s.axes) {
      if (a.values.size() != s.axes.front().values.size()) {
        throw SceneError(path.string() + ": combine = \"zip\": axis " + a.key + " has " +
                         std::to_string(a.values.size()) + " values, axis " + s.axes.front().key +
                         " " + std::to_string(s.axes.front().values.size()) + " (expected equal)");
      }
    }
  }
  for (size_t i = 0; i < s.axes.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (s.axes[i].key == s.axes[j].key) {
        throw SceneError(path.string() + ": axis " + s.axes[i].key + " given twice");
      }
    }
  }
  // Every axis key is checked by reading member 0's scene.
  MemberScene(s, 0);
  return s;
}

Scene MemberScene(const StudyDef& study, int64_t member) {
  const std::vector<int> idx = study.ValueIndices(member);
  std::vector<std::string> overrides = study.overrides;
  for (size_t k = 0; k < study.axes.size(); ++k) {
    const StudyAxis& a = study.axes[k];
    if (!a.derived) overrides.push_back(a.key + "=" + a.values[idx[k]].toml);
  }
  Scene scene = LoadScene(study.scene_path, overrides);
  // Derived axes in their fixed order: geometry first, then what depends on it.
  for (const std::string& key : DerivedKeys()) {
    for (size_t k = 0; k < study.axes.size(); ++k) {
      if (study.axes[k].key == key) ApplyDerived(key, study.axes[k].values[idx[k]].number, &scene);
    }
  }
  ValidateScene(scene);
  CheckEngineTables(scene);
  return scene;
}

}  // namespace rockbench
