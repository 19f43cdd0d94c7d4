#include "engines/common/cylinder_world.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/body_kind.h"

namespace rockbench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kCylinderFlags[4] = {"sliding", "uplift", "penetration", "blow_up"};
enum { kSliding, kUplift, kPenetration, kBlowUp };

double At(const std::vector<double>& v, std::int64_t n) {
  return v.empty() ? 0.0
                   : v[static_cast<size_t>(
                         std::min<std::int64_t>(n, static_cast<std::int64_t>(v.size()) - 1))];
}

Vec3d Cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool Finite(const CylinderPose& p) {
  for (const Vec3d* v : {&p.centre_m, &p.velocity_mps, &p.omega_radps}) {
    for (double x : *v) {
      if (!std::isfinite(x)) return false;
    }
  }
  for (double x : p.rotation) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

}  // namespace

CylinderBodyDef CylinderBodyOf(const EngineInput& input) {
  const BlockDef& b = input.blocks.at(0);
  CylinderBodyDef c;
  c.radius_m = 0.5 * b.diameter_m;
  c.half_height_m = 0.5 * b.height_m;
  c.mass_kg = b.mass_kg;
  c.inertia_transverse_kgm2 =
      b.mass_kg * (3.0 * c.radius_m * c.radius_m + b.height_m * b.height_m) / 12.0;
  c.inertia_axial_kgm2 = 0.5 * b.mass_kg * c.radius_m * c.radius_m;
  c.friction = b.friction;
  return c;
}

CylinderPose CylinderStartPose(const EngineInput& input) {
  const CylinderBodyDef body = CylinderBodyOf(input);
  CylinderState s;
  s.tilt_rad = input.initial.tilt_rad[0];
  s.azimuth_rad = input.initial.azimuth_rad[0];
  s.tilt_rate_radps = input.initial.tilt_rate_radps[0];
  s.azimuth_rate_radps = input.initial.azimuth_rate_radps[0];
  s.spin_rate_radps = input.initial.spin_rate_radps[0];
  CylinderPose p;
  p.centre_m = CylinderCentre(s, body.radius_m, body.half_height_m);
  p.rotation = CylinderRotation(s);
  p.velocity_mps = CylinderCentreVelocity(s, body.radius_m, body.half_height_m);
  p.omega_radps = CylinderAngularVelocity(s);
  return p;
}

Vec3d CylinderDriveAccel(const EngineInput& input, std::int64_t n) {
  const DriveSamples& d = input.drive;
  return {At(d.ax_mps2, n), At(d.at_mps2, n), At(d.ay_mps2, n)};
}

Vec3d CylinderBaseDisplacement(const EngineInput& input, std::int64_t n) {
  const DriveSamples& d = input.drive;
  return {At(d.ux_m, n), At(d.ut_m, n), At(d.uy_m, n)};
}

Vec3d CylinderBaseVelocityBefore(const EngineInput& input) {
  const DriveSamples& d = input.drive;
  return {d.ux0_mps, d.ut0_mps, d.uy0_mps};
}

Vec3d CylinderBaseVelocityAfter(const EngineInput& input, std::int64_t n) {
  if (n < 1) return CylinderBaseVelocityBefore(input);
  const Vec3d u = CylinderBaseDisplacement(input, n),
              before = CylinderBaseDisplacement(input, n - 1);
  Vec3d v;
  for (int i = 0; i < 3; ++i) v[i] = (u[i] - before[i]) / input.time_step_s;
  return v;
}

CylinderMonitor::CylinderMonitor(const EngineInput& input, CylinderMonitorConfig config)
    : input_(input),
      config_(config),
      body_(CylinderBodyOf(input)),
      alpha_rad_(std::atan2(body_.radius_m, body_.half_height_m)) {
  history_.blocks = 1;
  history_.shape = std::string(kCylinderShape);
  const double out = input.run.output_interval_s / input.time_step_s;
  steps_per_output_ = std::max<std::int64_t>(1, std::llround(out));
  std::fill(std::begin(flag_t_), std::end(flag_t_), kNaN);
  std::fill(std::begin(significant_t_), std::end(significant_t_), kNaN);
}

Sample CylinderMonitor::Row(double t, const CylinderState& s) const {
  Sample row(1, CylinderKind());
  row.t_s = t;
  const double values[8] = {s.tilt_rad,           s.azimuth_rad,    s.spin_rad,
                            s.tilt_x_rad(),       s.tilt_y_rad(),   s.tilt_rate_radps,
                            s.azimuth_rate_radps, s.spin_rate_radps};
  for (size_t q = 0; q < 8; ++q) row.state[q][0] = values[q];
  row.mode.set(0, on_rim_ ? Contact::kRight : Contact::kFace);
  return row;
}

void CylinderMonitor::Flag(int flag, double t, double size) {
  if (std::isnan(flag_t_[flag])) flag_t_[flag] = t;
  const double significant =
      config_.significant_critical_fraction * alpha_rad_ * 2.0 * body_.radius_m;
  if (std::isnan(significant_t_[flag]) && (flag == kBlowUp || size > significant)) {
    significant_t_[flag] = t;
  }
}

void CylinderMonitor::Start(const CylinderPose& pose) {
  last_ = CylinderStateOf(pose.rotation, pose.omega_radps);
  // The scene's azimuth, also for a cylinder that stands upright.
  if (last_.tilt_rad < 1e-12) last_.azimuth_rad = input_.initial.azimuth_rad[0];
  on_rim_ = last_.tilt_rad > config_.tilt_enter_rad;
  peak_tilt_rad_ = last_.tilt_rad;
  history_.samples.push_back(Row(0.0, last_));
}

bool CylinderMonitor::Step(std::int64_t n, const CylinderPose& pose) {
  const double t = static_cast<double>(n) * input_.time_step_s;
  if (!pose.engine_fault.empty() || !Finite(pose)) {
    status_ = RunStatus::kNonFinite;
    status_detail_ =
        !pose.engine_fault.empty()
            ? pose.engine_fault + " (at t = " + std::to_string(t) + " s)"
            : "the cylinder's pose or velocity stopped being finite at t = " + std::to_string(t) +
                  " s";
    Flag(kBlowUp, t, 0.0);
    return false;
  }
  const double dt = input_.time_step_s;
  const CylinderState s = CylinderStateOf(pose.rotation, pose.omega_radps, &last_);
  // On the rim or on the face (hysteresis).
  if (!on_rim_ && s.tilt_rad > config_.tilt_enter_rad) on_rim_ = true;
  if (on_rim_ && s.tilt_rad < config_.tilt_leave_rad) on_rim_ = false;
  if (s.tilt_rad > peak_tilt_rad_) {
    peak_tilt_rad_ = s.tilt_rad;
    peak_tilt_t_s_ = t;
  }
  // A pass near upright: the tilt turns from falling to rising low down.
  // A pass near upright: the tilt vector turns through it (a landing in planar rocking, whose
  // crossing step may end on the face), or the tilt turns from falling to rising low down on the
  // rim (a roll round it).
  // (Above the noise of a cylinder resting on its face: one of the two tilts beyond the rim's.)
  const bool flipped =
      s.tilt_x_rad() * last_.tilt_x_rad() + s.tilt_y_rad() * last_.tilt_y_rad() < 0.0 &&
      std::max(s.tilt_rad, last_.tilt_rad) > config_.tilt_enter_rad;
  if (flipped || (on_rim_ && prev_tilt_rate_ < 0.0 && s.tilt_rate_radps >= 0.0 &&
                  s.tilt_rad > config_.tilt_enter_rad && s.tilt_rad < 0.01 * alpha_rad_)) {
    ++passes_;
  }
  prev_tilt_rate_ = s.tilt_rate_radps;
  // The rim: the lowest point's height, and its material velocity along the base.
  if (on_rim_ && s.tilt_rad > 1e-9) {
    const Mat3d& q = pose.rotation;
    const Vec3d k{q[2], q[5], q[8]};
    const double sk = std::hypot(k[0], k[1]);
    // Down the slope in the bottom face: (k_z k_x, k_z k_y, -(k_x^2 + k_y^2)) / sin(tilt).
    const Vec3d e1{k[2] * k[0] / sk, k[2] * k[1] / sk, -sk};
    Vec3d lever;  // from the centre to the lowest rim point
    for (int i = 0; i < 3; ++i) lever[i] = -body_.half_height_m * k[i] + body_.radius_m * e1[i];
    const double z = pose.centre_m[2] + lever[2];
    if (z > config_.uplift_tol_m) {
      max_uplift_m_ = std::max(max_uplift_m_, z);
      Flag(kUplift, t, z);
    }
    if (-z > config_.penetration_flag_m) {
      max_penetration_m_ = std::max(max_penetration_m_, -z);
      Flag(kPenetration, t, -z);
    }
    const Vec3d w_cross = Cross(pose.omega_radps, lever);
    const double vx = pose.velocity_mps[0] + w_cross[0], vy = pose.velocity_mps[1] + w_cross[1];
    // The net displacement of the contact relative to the base beyond rolling (a vector sum:
    // the contact's noise and the step's lag along a turning rim cancel, a sliding does not).
    slip_x_m_ += vx * dt;
    slip_y_m_ += vy * dt;
    slip_m_ = std::max(slip_m_, std::hypot(slip_x_m_, slip_y_m_));
    if (slip_m_ > config_.slip_flag_rel * 2.0 * body_.radius_m) Flag(kSliding, t, slip_m_);
  }
  const double fastest = std::max({std::abs(pose.omega_radps[0]), std::abs(pose.omega_radps[1]),
                                   std::abs(pose.omega_radps[2])});
  if (fastest > config_.blow_up_rate_radps) {
    Flag(kBlowUp, t, fastest);
    status_ = RunStatus::kBlowUp;
    status_detail_ = "a rate above " + std::to_string(config_.blow_up_rate_radps) + " rad/s";
    history_.samples.push_back(Row(t, s));
    last_ = s;
    last_t_s_ = t;
    return false;
  }
  // Overturn: the tilt reaches the model's overturn angle, the time interpolated in the step.
  if (s.tilt_rad >= input_.overturn_rad) {
    const double frac = (input_.overturn_rad - last_.tilt_rad) / (s.tilt_rad - last_.tilt_rad);
    overturn_t_s_ = t - dt + std::clamp(frac, 0.0, 1.0) * dt;
    overturn_azimuth_rad_ = WrappedAzimuth_rad(s.azimuth_rad);
    status_ = RunStatus::kOverturned;
    history_.samples.push_back(Row(t, s));
    last_ = s;
    last_t_s_ = t;
    return false;
  }
  last_ = s;
  last_t_s_ = t;
  if (n % steps_per_output_ == 0) history_.samples.push_back(Row(t, s));
  return true;
}

void CylinderMonitor::Finish() {
  if (history_.samples.empty() || history_.samples.back().t_s != last_t_s_) {
    history_.samples.push_back(Row(last_t_s_, last_));
  }
}

RunOutcome CylinderMonitor::Outcome() const {
  RunOutcome o(1);
  o.status = status_;
  o.end_t_s = last_t_s_;
  o.peak_theta_rad[0] = peak_tilt_rad_;
  o.peak_theta_t_s[0] = peak_tilt_t_s_;
  o.impacts_at[0] = passes_;
  if (status_ == RunStatus::kOverturned) {
    o.overturned_block = 1;
    o.overturn_t_s = overturn_t_s_;
  }
  for (int f = 0; f < 4; ++f) {
    if (!std::isnan(flag_t_[f])) {
      o.violations.push_back(kCylinderFlags[f]);
      o.violation_onsets_t_s.push_back(flag_t_[f]);
    }
    if (!std::isnan(significant_t_[f])) {
      o.significant_violations.push_back(kCylinderFlags[f]);
      o.significant_onsets_t_s.push_back(significant_t_[f]);
    }
  }
  return o;
}

nlohmann::json CylinderMonitor::Summary() const {
  const RunOutcome o = Outcome();
  nlohmann::json j;
  j["status"] = StatusText(status_);
  if (!status_detail_.empty()) j["status_detail"] = status_detail_;
  j["model_kind"] = "cylinder";
  j["peaks"]["tilt1"] = {{"abs_rad", peak_tilt_rad_}, {"t_s", peak_tilt_t_s_}};
  j["passes_near_upright"] = passes_;
  if (status_ == RunStatus::kOverturned) {
    j["overturn"] = {{"block", 1}, {"t_s", overturn_t_s_}, {"azimuth_rad", overturn_azimuth_rad_}};
  } else {
    j["overturn"] = nullptr;
  }
  j["monitor"] = {{"slip_m", slip_m_},
                  {"max_uplift_m", max_uplift_m_},
                  {"max_penetration_m", max_penetration_m_}};
  j["violations"] = o.violations;
  j["significant_violations"] = o.significant_violations;
  return j;
}

}  // namespace rockbench
