#include "renders/drawn_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "motion/ground_displacement.h"
#include "renders/limits.h"

namespace rockbench::renders {

InitialState StackState(const Sample& s) {
  InitialState out;
  const int n = s.blocks();
  if (n == 0) return out;
  for (int k = 0; k < kMaxBlocks; ++k) {
    const auto from = static_cast<size_t>(std::min(k, n - 1));
    out.theta_rad[k] = s.theta_rad[from];
    out.omega_radps[k] = s.omega_radps[from];
  }
  return out;
}

DrawnStack PoseFor(const Scene& scene, const InitialState& state, Vec2 base) {
  // The engines' chain (scene/stack_pose.h PlaceStack), every block of the scene.
  DrawnStack pose = StackCornersAt(scene, state).blocks;
  // Everything moves with the base.
  for (BlockCorners& q : pose) {
    for (auto& p : q) p = p + base;
  }
  return pose;
}

DrawnStack PoseFor(const Scene& scene, double theta1_rad, double theta2_rad, Vec2 base) {
  InitialState state;
  state.theta_rad[0] = theta1_rad;
  state.theta_rad[1] = theta2_rad;
  return PoseFor(scene, state, base);
}

Sample StateAt(const History& history, double t_s) {
  const auto& s = history.samples;
  if (s.empty()) throw std::invalid_argument("StateAt: the history has no samples");
  // First sample strictly after t (after a pair of samples at an event time: the post-event one).
  auto it = std::upper_bound(s.begin(), s.end(), t_s,
                             [](double t, const Sample& x) { return t < x.t_s; });
  if (it == s.begin()) return s.front();
  if (it == s.end()) return s.back();
  const Sample& a = *(it - 1);
  const Sample& b = *it;
  const double span = b.t_s - a.t_s;
  const double w = span > 0.0 ? (t_s - a.t_s) / span : 0.0;
  Sample out = a;
  out.t_s = t_s;
  for (size_t k = 0; k < out.theta_rad.size() && k < b.theta_rad.size(); ++k) {
    out.theta_rad[k] = a.theta_rad[k] + w * (b.theta_rad[k] - a.theta_rad[k]);
    out.omega_radps[k] = a.omega_radps[k] + w * (b.omega_radps[k] - a.omega_radps[k]);
  }
  return out;
}

BaseDisplacement BaseDisplacement::FromSamples(double t0_s, double dt_s, std::vector<double> x_m,
                                               std::vector<double> y_m) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("BaseDisplacement: dt_s must be > 0");
  if (!y_m.empty() && y_m.size() != x_m.size()) {
    throw std::invalid_argument("BaseDisplacement: x_m and y_m differ in length");
  }
  BaseDisplacement d;
  d.t0_s_ = t0_s;
  d.dt_s_ = dt_s;
  d.x_m_ = std::move(x_m);
  d.y_m_ = std::move(y_m);
  return d;
}

BaseDisplacement BaseDisplacement::FromFunction(Function f) {
  BaseDisplacement d;
  d.function_ = std::move(f);
  return d;
}

Vec2 BaseDisplacement::At(double t_s) const {
  if (function_) return function_(t_s);
  if (x_m_.empty()) return {};
  const double u = (t_s - t0_s_) / dt_s_;
  const size_t n = x_m_.size();
  auto at = [&](const std::vector<double>& v) {
    if (v.empty()) return 0.0;
    if (u <= 0.0) return v.front();
    if (u >= static_cast<double>(n - 1)) return v.back();
    const size_t i = static_cast<size_t>(u);
    const double w = u - static_cast<double>(i);
    return v[i] + w * (v[i + 1] - v[i]);
  };
  return {at(x_m_), at(y_m_)};
}

void BaseDisplacement::SetTransverse(std::vector<double> transverse_m) {
  if (!transverse_m.empty() && transverse_m.size() != x_m_.size()) {
    throw std::invalid_argument("BaseDisplacement: the transverse samples differ in length");
  }
  t_m_ = std::move(transverse_m);
}

void BaseDisplacement::SetTransverse(TransverseFunction f) {
  transverse_function_ = std::move(f);
}

double BaseDisplacement::TransverseAt(double t_s) const {
  if (transverse_function_) return transverse_function_(t_s);
  if (t_m_.empty()) return 0.0;
  const double u = (t_s - t0_s_) / dt_s_;
  if (u <= 0.0) return t_m_.front();
  if (u >= static_cast<double>(t_m_.size() - 1)) return t_m_.back();
  const size_t i = static_cast<size_t>(u);
  const double w = u - static_cast<double>(i);
  return t_m_[i] + w * (t_m_[i + 1] - t_m_[i]);
}

namespace {

// The window the path is integrated over: [0, t_end], and with a high-pass (a zero-phase
// filter looks ahead) at least the run, as the engines integrate it.
double IntegrationWindow_s(double t_end_s, const BaseIntegrationConfig& config) {
  return config.highpass_hz > 0.0 ? std::max(t_end_s, config.run_duration_s) : t_end_s;
}

// One of the filter's pads, samples (as IntegrateGroundPath makes them).
double FilterPad(const BaseIntegrationConfig& config) {
  if (!(config.highpass_hz > 0.0)) return 0.0;
  return std::min(std::ceil(1.2 / (config.highpass_hz * config.dt_s)), 5e7);
}

// A number of an engine's table, as written (a TOML integer is a number too).
std::optional<double> TableNumber(const RawEngineTable& table, std::string_view key) {
  const auto it = table.values.find(key);
  if (it == table.values.end()) return std::nullopt;
  if (const auto* d = std::get_if<double>(&it->second.value)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&it->second.value)) {
    return static_cast<double>(*i);
  }
  return std::nullopt;
}

}  // namespace

BaseIntegrationConfig BaseIntegrationFor(const Scene& scene) {
  BaseIntegrationConfig config;
  config.run_duration_s = scene.run.duration_s;
  for (const auto& [engine, table] : scene.engine_tables) {
    const auto drive = table.values.find("drive");
    if (drive == table.values.end()) continue;
    const auto* kind = std::get_if<std::string>(&drive->second.value);
    if (kind == nullptr || *kind != "kinematic") continue;
    // The engine checks its own table; here only sensible values are taken.
    if (const auto dt = TableNumber(table, "time_step"); dt && std::isfinite(*dt) && *dt > 0.0) {
      config.dt_s = *dt;
    }
    if (const auto fc = TableNumber(table, "kinematic_highpass_hz");
        fc && std::isfinite(*fc) && *fc >= 0.0) {
      config.highpass_hz = *fc;
    }
    break;
  }
  return config;
}

double BaseDisplacementSamples(const GroundMotion& motion, double t_end_s,
                               const BaseIntegrationConfig& config) {
  if (motion.empty() || !(t_end_s > 0.0)) return 0.0;
  const double window_s = IntegrationWindow_s(t_end_s, config);
  return static_cast<double>(StepCount(window_s, config.dt_s)) + 1.0 + 2.0 * FilterPad(config);
}

BaseDisplacement IntegrateBaseDisplacement(const GroundMotion& motion, double t_end_s,
                                           const BaseIntegrationConfig& config) {
  if (motion.empty() || !(t_end_s > 0.0)) return {};
  if (!(config.dt_s > 0.0) || !std::isfinite(config.dt_s)) {
    throw std::invalid_argument("IntegrateBaseDisplacement: dt_s must be a positive time step");
  }
  // The kinematic drive's grid and path (engines/common/engine_input.cc MakeEngineInput does
  // the same): at the engine's step and high-pass, the same numbers the engine moved its
  // ground by.
  const double dt_s = config.dt_s;
  const auto steps = static_cast<size_t>(StepCount(IntegrationWindow_s(t_end_s, config), dt_s));
  std::vector<double> ax, ay;
  SampleGroundAcceleration(motion, dt_s, steps, &ax, &ay);
  std::vector<double> x = IntegrateGroundPath(ax, dt_s, config.highpass_hz).u_m;
  ax = std::vector<double>();  // memory: at most 5 doubles a sample at a time (EstimateExport)
  std::vector<double> y = motion.has_vertical()
                              ? IntegrateGroundPath(ay, dt_s, config.highpass_hz).u_m
                              : std::vector<double>{};
  BaseDisplacement d = BaseDisplacement::FromSamples(0.0, dt_s, std::move(x), std::move(y));
  if (motion.has_transverse()) {
    // A 3-D scene's +y, sampled as MakeEngineInput samples the engines' at_mps2.
    ay = std::vector<double>();
    std::vector<double> at(steps);
    for (size_t i = 0; i < steps; ++i) {
      at[i] = motion.transverse_mps2(static_cast<double>(i) * dt_s);
    }
    d.SetTransverse(IntegrateGroundPath(at, dt_s, config.highpass_hz).u_m);
  }
  return d;
}

Vec2 Camera::ToPixel(Vec2 w) const {
  const double s = px_per_m();
  return {vp_x_px + (w.x - world.x_min_m) * s, vp_y_px + (world.y_max_m - w.y) * s};
}

Box MotionBox(const Scene& scene, const std::vector<const History*>& histories,
              const BaseDisplacement& base, double t_from_s, double t_to_s, double margin_frac) {
  const double inf = std::numeric_limits<double>::infinity();
  Box box{inf, -inf, inf, -inf};
  auto add = [&](Vec2 p) {
    box.x_min_m = std::min(box.x_min_m, p.x);
    box.x_max_m = std::max(box.x_max_m, p.x);
    box.y_min_m = std::min(box.y_min_m, p.y);
    box.y_max_m = std::max(box.y_max_m, p.y);
  };
  auto add_pose = [&](const InitialState& state, double t) {
    const Vec2 b = base.At(t);
    for (const BlockCorners& q : PoseFor(scene, state, b)) {
      for (const auto& p : q) add(p);
    }
    add(b);
  };
  // The rest pose and the poses at the window's ends are always in view.
  add_pose({}, t_from_s);
  for (const History* h : histories) {
    if (!h || h->samples.empty()) continue;
    for (double t : {t_from_s, t_to_s}) add_pose(StackState(StateAt(*h, t)), t);
    for (const Sample& s : h->samples) {
      if (s.t_s < t_from_s || s.t_s > t_to_s) continue;
      add_pose(StackState(s), s.t_s);
    }
  }
  // The base displacement over the whole window (between history samples too).
  if (!base.empty()) {
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const double t = t_from_s + (t_to_s - t_from_s) * i / n;
      const Vec2 b = base.At(t);
      add_pose({}, t);
      add(b);
    }
  }
  // A strip of ground below the lowest ground position.
  double stack_h = 0.0;
  for (const BlockDef& b : scene.blocks) stack_h += b.height_m;
  box.y_min_m -= 0.2 * stack_h;
  const double m = margin_frac * std::max(box.width_m(), box.height_m());
  box.x_min_m -= m;
  box.x_max_m += m;
  box.y_min_m -= m;
  box.y_max_m += m;
  return box;
}

Camera FitCamera(const Box& box, double vp_x_px, double vp_y_px, double vp_w_px, double vp_h_px) {
  Camera cam;
  cam.vp_x_px = vp_x_px;
  cam.vp_y_px = vp_y_px;
  cam.vp_w_px = vp_w_px;
  cam.vp_h_px = vp_h_px;
  cam.world = box;
  const double vp_aspect = vp_w_px / vp_h_px;
  const double box_aspect = box.width_m() / box.height_m();
  if (box_aspect < vp_aspect) {
    // Widen symmetrically.
    const double w = box.height_m() * vp_aspect;
    const double cx = 0.5 * (box.x_min_m + box.x_max_m);
    cam.world.x_min_m = cx - 0.5 * w;
    cam.world.x_max_m = cx + 0.5 * w;
  } else {
    // Heighten upwards: the ground stays at the bottom.
    cam.world.y_max_m = box.y_min_m + box.width_m() / vp_aspect;
  }
  return cam;
}

std::vector<double> FrameTimes(double t_from_s, double t_to_s, double fps, double speed) {
  if (!(fps > 0.0)) throw std::invalid_argument("frame rate must be > 0");
  if (!(speed > 0.0)) throw std::invalid_argument("speed factor must be > 0");
  if (!(t_to_s >= t_from_s)) throw std::invalid_argument("the time window ends before it starts");
  const double count = FrameCount(t_from_s, t_to_s, fps, speed);
  if (!(count <= static_cast<double>(kMaxFrames))) {
    throw std::invalid_argument("the animation would have " + ShortestText(count) +
                                " frames, more than the limit of " + std::to_string(kMaxFrames));
  }
  const double step_s = speed / fps;
  const long n = static_cast<long>(count);
  std::vector<double> times(static_cast<size_t>(n));
  for (long k = 0; k < n; ++k)
    times[static_cast<size_t>(k)] = t_from_s + static_cast<double>(k) * step_s;
  return times;
}

}  // namespace rockbench::renders
