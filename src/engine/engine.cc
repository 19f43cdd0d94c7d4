#include "engine/engine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {

std::string TimeStepLabel(double dt_s) {
  char buf[40];
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    std::snprintf(buf, sizeof buf, "%.3g", dt_s);
    return buf;
  }
  // Up to three significant digits, as "2.5e-3" (not "2.5e-03" or "0.0025").
  for (int digits = 0; digits <= 2; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*e", digits, dt_s);
    if (std::fabs(std::strtod(buf, nullptr) - dt_s) > 1e-9 * dt_s) continue;
    const std::string e = buf;
    const size_t pos = e.find('e');
    const char sign = e[pos + 1];
    std::string exponent = e.substr(pos + 2);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    if (exponent == "0") return e.substr(0, pos);
    return e.substr(0, pos) + "e" + (sign == '-' ? "-" : "") + exponent;
  }
  // A frame rate's step, as "1/60".
  const double per_s = 1.0 / dt_s;
  if (std::fabs(per_s - std::round(per_s)) < 1e-6 * per_s) {
    std::snprintf(buf, sizeof buf, "1/%.0f", std::round(per_s));
    return buf;
  }
  std::snprintf(buf, sizeof buf, "%.3g", dt_s);
  return buf;
}

SweepSetting TwoFamilyGrid::Point(bool engine_defaults, double dt_s) const {
  SweepSetting s;
  s.family = engine_defaults ? defaults_family : ours_family;
  s.label = TimeStepLabel(dt_s);
  s.time_step_s = dt_s;
  s.settings = {{"time_step", dt_s}};
  if (engine_defaults) {
    s.settings.insert(s.settings.end(), defaults_settings.begin(), defaults_settings.end());
  }
  return s;
}

std::vector<SweepSetting> TwoFamilyGrid::Sweep(const std::vector<double>& steps_s) const {
  std::vector<SweepSetting> grid;
  for (const bool engine_defaults : {false, true}) {
    for (double dt : steps_s) grid.push_back(Point(engine_defaults, dt));
  }
  return grid;
}

std::vector<SweepSetting> TwoFamilyGrid::Stress(const std::vector<double>& steps_s,
                                                const std::function<bool(double)>& quick) const {
  std::vector<SweepSetting> grid = Sweep(steps_s);
  for (SweepSetting& s : grid) {
    s.id = (s.family == defaults_family ? defaults_id : ours_id) + "/dt=" + s.label;
    s.quick = quick(s.time_step_s);
  }
  return grid;
}

std::vector<SweepSetting> TwoFamilyGrid::StandardSweep(bool quick, double coarsest_s) const {
  return Sweep(quick ? std::vector<double>{1e-3, 1e-4}
                     : std::vector<double>{coarsest_s, 1e-3, 5e-4, 1e-4, 5e-5, 1e-5});
}

std::vector<SweepSetting> TwoFamilyGrid::StandardStress() const {
  return Stress({1.0 / 60.0, 1e-3, 1e-4, 1e-5}, [](double dt) { return dt > 0.01; });
}

Scene Engine::SceneForSetting(const Scene& base, const SweepSetting& setting) const {
  Scene s = base;
  for (const auto& [key, value] : setting.settings) SetEngineSetting(s, name(), key, value);
  return s;
}

std::string Engine::SummaryPointer() const {
  // A name's '~' and '/' escaped as a JSON pointer's (RFC 6901).
  std::string key;
  for (const char c : name()) key += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return "/engines/" + key;
}

std::string Engine::SummaryLine(const EngineResult& r) const {
  const RunOutcome& o = r.outcome;
  std::string flags;
  for (const std::string& f : o.violations) {
    if (!flags.empty()) flags += ',';
    flags += f;
  }
  char line[320];
  // A cylinder's peak is of its tilt, and its monitor counts passes near upright, not impacts.
  const bool cylinder = r.history.shape == kCylinderShape;
  std::snprintf(line, sizeof line,
                cylinder ? "%s (%s): %s, peak tilt1 %.4g rad at %.3f s, %d passes near upright, "
                           "flags: %s, %.3g ms"
                         : "%s (%s): %s, peak |theta1| %.4g rad at %.3f s, %d impacts, flags: %s, "
                           "%.3g ms",
                name().c_str(), r.settings_line.c_str(), StatusText(o.status),
                o.peak_theta_rad.empty() ? 0.0 : o.peak_theta_rad[0],
                o.peak_theta_t_s.empty() ? 0.0 : o.peak_theta_t_s[0], o.impacts(),
                flags.empty() ? "none" : flags.c_str(), r.wall_s * 1e3);
  return line;
}

std::vector<std::string> Engine::body_shapes() const {
  return {PlanarBlockKind().shape};
}

void CheckBuildsBodies(const Engine& engine, const Scene& scene) {
  if (scene.blocks.empty()) return;
  const std::string& shape = scene.blocks.front().shape;
  const std::vector<std::string> builds = engine.body_shapes();
  if (std::find(builds.begin(), builds.end(), shape) != builds.end()) return;
  // A planar engine facing a body that rocks in 3-D says so.
  const bool three_d =
      std::find(builds.begin(), builds.end(), std::string(kCylinderShape)) != builds.end();
  const std::string why = shape == kCylinderShape && !three_d
                              ? " (a cylinder rocks in three dimensions; this engine simulates "
                                "bodies in the x-z plane only)"
                              : "";
  throw SceneError((scene.path.empty() ? std::string("scene") : scene.path.string()) +
                   ": block1.shape: the engine '" + engine.name() + "' builds bodies of shape " +
                   QuotedList(builds) + ", not \"" + shape + "\"" + why);
}

}  // namespace rockbench
