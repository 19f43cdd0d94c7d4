#include "engines/common/engine_input.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "engines/common/engine.h"

namespace rockbench {
namespace {

// Upper bound on the number of steps of one run (about a day of CPU at 1 us per step).
constexpr std::int64_t kMaxSteps = 2'000'000'000;

// Second-order Butterworth low-pass (bilinear transform with pre-warping), transposed direct
// form II. Runs over x in place; `steady` starts the filter in steady state for x[0].
void LowPassInPlace(std::vector<double>& x, double fc_hz, double dt_s, bool steady, bool reverse) {
  if (x.empty()) return;
  const double k = std::tan(std::numbers::pi * fc_hz * dt_s);
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
  const double b0 = k * k * norm, b1 = 2.0 * b0, b2 = b0;
  const double a1 = 2.0 * (k * k - 1.0) * norm, a2 = (1.0 - std::sqrt(2.0) * k + k * k) * norm;
  const size_t n = x.size();
  const double first = reverse ? x[n - 1] : x[0];
  double z1 = steady ? first * (1.0 - b0) : 0.0;
  double z2 = steady ? first * (b2 - a2) : 0.0;
  for (size_t i = 0; i < n; ++i) {
    double& v = reverse ? x[n - 1 - i] : x[i];
    const double in = v;
    const double out = b0 * in + z1;
    z1 = b1 * in - a1 * out + z2;
    z2 = b2 * in - a2 * out;
    v = out;
  }
}

}  // namespace

std::vector<double> KinematicDisplacement(const std::vector<double>& accel_mps2, double dt_s,
                                          double highpass_hz, double* velocity_before_mps,
                                          double* raw_peak_m) {
  const size_t n = accel_mps2.size();
  std::vector<double> u(n + 1, 0.0);
  // Leapfrog double integration: the ground's second difference is exactly dt^2 a_n, the
  // velocity change the inertial drive gives the blocks in step n.
  double u_prev = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double next = 2.0 * u[i] - u_prev + dt_s * dt_s * accel_mps2[i];
    u_prev = u[i];
    u[i + 1] = next;
  }
  double peak = 0.0;
  for (double v : u) peak = std::max(peak, std::abs(v));
  if (raw_peak_m) *raw_peak_m = peak;
  if (velocity_before_mps) *velocity_before_mps = 0.0;
  if (highpass_hz <= 0.0) return u;

  // Baseline: zero-phase low-pass of u. The 2nd-order Butterworth's envelope decays with time
  // constant 1 / (0.707 * 2 pi fc) = 0.225 / fc; pads of 1.2 / fc (5.3 time constants) let
  // the start-up transients of both passes die out before the data.
  const double pad_d = std::ceil(1.2 / (highpass_hz * dt_s));
  const size_t pad = static_cast<size_t>(std::min(pad_d, 5e7));
  std::vector<double> x(pad + u.size() + pad, 0.0);
  std::copy(u.begin(), u.end(), x.begin() + static_cast<std::ptrdiff_t>(pad));
  const double last = u.back();
  for (size_t k = 1; k <= pad; ++k) {
    // Odd reflection about the last sample (continues the final trend); beyond the record's
    // own length the reflection repeats its first value.
    const size_t mirror = k <= n ? n - k : 0;
    x[pad + n + k] = 2.0 * last - u[mirror];
  }
  LowPassInPlace(x, highpass_hz, dt_s, /*steady=*/false, /*reverse=*/false);
  LowPassInPlace(x, highpass_hz, dt_s, /*steady=*/true, /*reverse=*/true);
  std::vector<double> out(u.size());
  for (size_t i = 0; i < u.size(); ++i) out[i] = u[i] - x[pad + i];
  // u_{-1} = 0 before the record; its baseline value is x[pad - 1].
  const double u_minus1 = pad > 0 ? -x[pad - 1] : 0.0;
  if (velocity_before_mps) *velocity_before_mps = (out[0] - u_minus1) / dt_s;
  return out;
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

void AddDriveSetting(EngineSettingsSchema& schema) {
  schema.Choice("drive", "inertial", {"inertial", "kinematic"}, "-",
                "base motion as tilted gravity (inertial) or a moving ground (kinematic)");
}

void AddKinematicHighpassSetting(EngineSettingsSchema& schema) {
  schema.Number("kinematic_highpass_hz", 0.0, SettingRange::kNonNegative, "Hz", "-",
                "kinematic drive's baseline-correction corner; 0: none (docs/bullet.md)");
}

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

EngineInput MakeEngineInput(const Scene& scene, const GroundMotion& motion,
                            const std::string& engine, const EngineSettings& settings,
                            double stop_at_rest_after_s) {
  const auto has = [&](std::string_view key) {
    return std::any_of(settings.values.begin(), settings.values.end(),
                       [&](const auto& kv) { return kv.first == key; });
  };
  const DriveKind drive = has("drive") && settings.Choice("drive") == "kinematic"
                              ? DriveKind::kKinematic
                              : DriveKind::kInertial;
  EngineInput in = MakeEngineInput(
      scene, motion, engine, settings.Number("time_step"), drive,
      has("kinematic_highpass_hz") ? settings.Number("kinematic_highpass_hz") : 0.0);
  in.stop_at_rest_after_s = stop_at_rest_after_s;
  return in;
}

nlohmann::json KinematicDriveJson(const EngineInput& input) {
  const DriveSamples& d = input.drive;
  nlohmann::json k;
  k["baseline"] = input.kinematic_highpass_hz > 0.0
                      ? "zero-phase Butterworth high-pass (u minus forward-backward 2nd-order "
                        "low-pass of u)"
                      : "none";
  k["highpass_hz"] = input.kinematic_highpass_hz;
  k["raw_peak_displacement_x_m"] = d.raw_peak_x_m;
  k["raw_peak_displacement_y_m"] = d.raw_peak_y_m;
  k["peak_displacement_x_m"] = d.peak_x_m;
  k["peak_displacement_y_m"] = d.peak_y_m;
  k["correction_max_accel_x_mps2"] = d.correction_max_x_mps2;
  k["correction_max_accel_y_mps2"] = d.correction_max_y_mps2;
  return k;
}

const char* DriveKindName(DriveKind kind) {
  return kind == DriveKind::kKinematic ? "kinematic" : "inertial";
}

EngineInput MakeEngineInput(const Scene& scene, const GroundMotion& motion,
                            const std::string& engine, double time_step_s, DriveKind drive,
                            double kinematic_highpass_hz) {
  const double dt = time_step_s;
  const std::string where = scene.path.empty() ? std::string("scene") : scene.path.string();
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw SceneError(where + ": " + engine + ".time_step: expected a positive time step in s");
  }
  if (std::ceil(scene.run.duration_s / dt - 1e-9) > static_cast<double>(kMaxSteps)) {
    throw SceneError(where + ": " + engine +
                     ".time_step: expected at most 2e9 steps over run.duration (time step too "
                     "small)");
  }
  EngineInput in;
  in.block1 = scene.block1;
  in.block2 = scene.block2;
  in.initial = scene.initial;
  in.run = scene.run;
  in.time_step_s = dt;
  in.drive_kind = drive;
  in.kinematic_highpass_hz = kinematic_highpass_hz;
  in.overturn_rad = scene.model.overturn_rad;
  in.steps = static_cast<std::int64_t>(std::max(0.0, std::ceil(scene.run.duration_s / dt - 1e-9)));
  in.motion_end_s = motion.empty() ? 0.0 : motion.end_s();

  const size_t n = static_cast<size_t>(in.steps);
  DriveSamples& d = in.drive;
  if (!motion.empty()) {
    d.ax_mps2.resize(n);
    d.ay_mps2.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) * dt;
      d.ax_mps2[i] = motion.xg_mps2(t);
      d.ay_mps2[i] = motion.yg_mps2(t);
    }
  }
  if (drive == DriveKind::kKinematic) {
    const std::vector<double> zeros(d.ax_mps2.empty() ? n : 0, 0.0);
    const std::vector<double>& ax = d.ax_mps2.empty() ? zeros : d.ax_mps2;
    const std::vector<double>& ay = d.ay_mps2.empty() ? zeros : d.ay_mps2;
    const double fc = kinematic_highpass_hz;
    d.ux_m = KinematicDisplacement(ax, dt, fc, &d.ux0_mps, &d.raw_peak_x_m);
    d.uy_m = KinematicDisplacement(ay, dt, fc, &d.uy0_mps, &d.raw_peak_y_m);
    // What the correction changed: the drive's acceleration against the record's.
    double um1x = d.ux_m[0] - d.ux0_mps * dt, um1y = d.uy_m[0] - d.uy0_mps * dt;
    for (size_t i = 0; i < n; ++i) {
      const double prev_x = i == 0 ? um1x : d.ux_m[i - 1];
      const double prev_y = i == 0 ? um1y : d.uy_m[i - 1];
      const double axe = (d.ux_m[i + 1] - 2.0 * d.ux_m[i] + prev_x) / (dt * dt);
      const double aye = (d.uy_m[i + 1] - 2.0 * d.uy_m[i] + prev_y) / (dt * dt);
      d.correction_max_x_mps2 = std::max(d.correction_max_x_mps2, std::abs(axe - ax[i]));
      d.correction_max_y_mps2 = std::max(d.correction_max_y_mps2, std::abs(aye - ay[i]));
    }
    for (size_t i = 0; i <= n; ++i) {
      d.peak_x_m = std::max(d.peak_x_m, std::abs(d.ux_m[i]));
      d.peak_y_m = std::max(d.peak_y_m, std::abs(d.uy_m[i]));
    }
  }
  return in;
}

}  // namespace rockbench
