#include "renders/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "renders/limits.h"

namespace rockbench::renders {
namespace {

// Clockwise rotation by theta (thesis sign) of p about pivot.
Vec2 RotateClockwise(Vec2 p, Vec2 pivot, double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  const double dx = p.x_m - pivot.x_m, dy = p.y_m - pivot.y_m;
  return {pivot.x_m + c * dx + s * dy, pivot.y_m - s * dx + c * dy};
}

Quad RestQuad(double half_width_m, double y0_m, double height_m) {
  return {Vec2{-half_width_m, y0_m}, Vec2{half_width_m, y0_m}, Vec2{half_width_m, y0_m + height_m},
          Vec2{-half_width_m, y0_m + height_m}};
}

}  // namespace

StackPose PoseFor(const Scene& scene, double theta1_rad, double theta2_rad, Vec2 base) {
  StackPose pose;
  const double b1 = 0.5 * scene.block1.width_m, h1 = scene.block1.height_m;
  // Block 1 about its right (theta1 > 0) or left (theta1 < 0) base corner.
  const Vec2 pivot1{theta1_rad >= 0.0 ? b1 : -b1, 0.0};
  const Quad rest1 = RestQuad(b1, 0.0, h1);
  for (int i = 0; i < 4; ++i) pose.block1[i] = RotateClockwise(rest1[i], pivot1, theta1_rad);
  if (scene.block2) {
    pose.has_block2 = true;
    const double b2 = 0.5 * scene.block2->width_m;
    // In block 1's rest frame: relative rotation about the contact corner on its top face.
    const double rel_rad = theta2_rad - theta1_rad;
    const double corner = std::min(b1, b2);
    const Vec2 pivot2{rel_rad >= 0.0 ? corner : -corner, h1};
    const Quad rest2 = RestQuad(b2, h1, scene.block2->height_m);
    for (int i = 0; i < 4; ++i) {
      pose.block2[i] =
          RotateClockwise(RotateClockwise(rest2[i], pivot2, rel_rad), pivot1, theta1_rad);
    }
  }
  // Everything moves with the base.
  for (auto& p : pose.block1) p = {p.x_m + base.x_m, p.y_m + base.y_m};
  for (auto& p : pose.block2) p = {p.x_m + base.x_m, p.y_m + base.y_m};
  return pose;
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
  out.theta1_rad = a.theta1_rad + w * (b.theta1_rad - a.theta1_rad);
  out.theta2_rad = a.theta2_rad + w * (b.theta2_rad - a.theta2_rad);
  out.omega1_radps = a.omega1_radps + w * (b.omega1_radps - a.omega1_radps);
  out.omega2_radps = a.omega2_radps + w * (b.omega2_radps - a.omega2_radps);
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

namespace {

// Acceleration samples -> baseline-corrected displacement (see IntegrateBaseDisplacement).
std::vector<double> DoubleIntegrate(const std::vector<double>& a_mps2, double dt_s) {
  const size_t n = a_mps2.size();
  std::vector<double> v(n, 0.0), x(n, 0.0);
  for (size_t i = 1; i < n; ++i) v[i] = v[i - 1] + 0.5 * dt_s * (a_mps2[i - 1] + a_mps2[i]);
  // Least-squares line v ~ c0 + c1 t through the velocity, removed. Trapezoidal weights (half
  // at the ends) make it the continuous L2 fit over [0, t_end], not biased by the end samples.
  if (n >= 2) {
    double sw = 0, st = 0, sv = 0, stt = 0, stv = 0;
    for (size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) * dt_s;
      const double w = (i == 0 || i + 1 == n) ? 0.5 : 1.0;
      sw += w;
      st += w * t;
      sv += w * v[i];
      stt += w * t * t;
      stv += w * t * v[i];
    }
    const double det = sw * stt - st * st;
    const double c1 = det != 0.0 ? (sw * stv - st * sv) / det : 0.0;
    const double c0 = (sv - c1 * st) / sw;
    for (size_t i = 0; i < n; ++i) v[i] -= c0 + c1 * static_cast<double>(i) * dt_s;
  }
  for (size_t i = 1; i < n; ++i) x[i] = x[i - 1] + 0.5 * dt_s * (v[i - 1] + v[i]);
  return x;
}

// The sample interval of the integration: the finest record's, else config.dt_s.
double IntegrationStep_s(const GroundMotion& motion, const BaseIntegrationConfig& config) {
  double dt_s = std::numeric_limits<double>::infinity();
  for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
    if (*c && !(*c)->samples_mps2().empty() && (*c)->dt_s() > 0.0) {
      dt_s = std::min(dt_s, (*c)->dt_s());
    }
  }
  return std::isfinite(dt_s) ? dt_s : config.dt_s;
}

}  // namespace

double BaseDisplacementSamples(const GroundMotion& motion, double t_end_s,
                               const BaseIntegrationConfig& config) {
  if (motion.empty() || !(t_end_s > 0.0)) return 0.0;
  return std::ceil(t_end_s / IntegrationStep_s(motion, config)) + 1.0;
}

BaseDisplacement IntegrateBaseDisplacement(const GroundMotion& motion, double t_end_s,
                                           const BaseIntegrationConfig& config) {
  if (motion.empty() || !(t_end_s > 0.0)) return {};
  // Records are integrated on their own sample grid (they are linear between samples).
  const double dt_s = IntegrationStep_s(motion, config);
  const size_t n = static_cast<size_t>(BaseDisplacementSamples(motion, t_end_s, config));
  std::vector<double> ax(n), ay(n);
  for (size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt_s;
    ax[i] = motion.xg_mps2(t);
    ay[i] = motion.yg_mps2(t);
  }
  std::vector<double> x = DoubleIntegrate(ax, dt_s);
  std::vector<double> y = motion.has_vertical() ? DoubleIntegrate(ay, dt_s) : std::vector<double>{};
  return BaseDisplacement::FromSamples(0.0, dt_s, std::move(x), std::move(y));
}

Vec2 Camera::ToPixel(Vec2 w) const {
  const double s = px_per_m();
  return {vp_x_px + (w.x_m - world.x_min_m) * s, vp_y_px + (world.y_max_m - w.y_m) * s};
}

Box MotionBox(const Scene& scene, const std::vector<const History*>& histories,
              const BaseDisplacement& base, double t_from_s, double t_to_s, double margin_frac) {
  const double inf = std::numeric_limits<double>::infinity();
  Box box{inf, -inf, inf, -inf};
  auto add = [&](Vec2 p) {
    box.x_min_m = std::min(box.x_min_m, p.x_m);
    box.x_max_m = std::max(box.x_max_m, p.x_m);
    box.y_min_m = std::min(box.y_min_m, p.y_m);
    box.y_max_m = std::max(box.y_max_m, p.y_m);
  };
  auto add_pose = [&](double th1, double th2, double t) {
    const Vec2 b = base.At(t);
    const StackPose pose = PoseFor(scene, th1, th2, b);
    for (const auto& p : pose.block1) add(p);
    if (pose.has_block2) {
      for (const auto& p : pose.block2) add(p);
    }
    add({b.x_m, b.y_m});
  };
  // The rest pose and the poses at the window's ends are always in view.
  add_pose(0.0, 0.0, t_from_s);
  for (const History* h : histories) {
    if (!h || h->samples.empty()) continue;
    for (double t : {t_from_s, t_to_s}) {
      const Sample s = StateAt(*h, t);
      add_pose(s.theta1_rad, h->two_blocks ? s.theta2_rad : s.theta1_rad, t);
    }
    for (const Sample& s : h->samples) {
      if (s.t_s < t_from_s || s.t_s > t_to_s) continue;
      add_pose(s.theta1_rad, h->two_blocks ? s.theta2_rad : s.theta1_rad, s.t_s);
    }
  }
  // The base displacement over the whole window (between history samples too).
  if (!base.empty()) {
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const double t = t_from_s + (t_to_s - t_from_s) * i / n;
      const Vec2 b = base.At(t);
      add_pose(0.0, 0.0, t);
      add(b);
    }
  }
  // A strip of ground below the lowest ground position.
  const double stack_h = scene.block1.height_m + (scene.block2 ? scene.block2->height_m : 0.0);
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
