#include "engines/common/engine_input.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "engine/engine.h"

namespace rockbench {
namespace {

// Upper bound on the number of steps of one run (about a day of CPU at 1 us per step).
constexpr std::int64_t kMaxSteps = 2'000'000'000;

// The keys this file defines and reads (and kTimeStepKey, engine_input.h).
constexpr char kDriveKey[] = "drive";
constexpr char kKinematicHighpassKey[] = "kinematic_highpass_hz";

}  // namespace

void AddTimeStepSetting(EngineSettingsSchema& schema, std::string engine_default, std::string doc) {
  schema.Number(kTimeStepKey, kDefaultTimeStep_s, SettingRange::kPositive, "s",
                std::move(engine_default), std::move(doc));
}

void AddDriveSetting(EngineSettingsSchema& schema, const std::vector<std::string>& drives,
                     std::string doc) {
  schema.Choice(kDriveKey, drives.front(), drives, "-", std::move(doc));
}

void AddKinematicHighpassSetting(EngineSettingsSchema& schema) {
  schema.Number(kKinematicHighpassKey, 0.0, SettingRange::kNonNegative, "Hz", "-",
                "kinematic drive's baseline-correction corner; 0: none (docs/bullet.md)");
}

EngineInput MakeEngineInput(const Scene& scene, const GroundMotion& motion,
                            const std::string& engine, const EngineSettings& settings,
                            double stop_at_rest_after_s) {
  const auto has = [&](std::string_view key) {
    return std::any_of(settings.values.begin(), settings.values.end(),
                       [&](const auto& kv) { return kv.first == key; });
  };
  const DriveKind drive =
      has(kDriveKey) && settings.Choice(kDriveKey) == DriveKindName(DriveKind::kKinematic)
          ? DriveKind::kKinematic
          : DriveKind::kInertial;
  EngineInput in =
      MakeEngineInput(scene, motion, engine, settings.Number(kTimeStepKey), drive,
                      has(kKinematicHighpassKey) ? settings.Number(kKinematicHighpassKey) : 0.0);
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

bool HasFiniteFriction(const EngineInput& input) {
  return std::any_of(input.blocks.begin(), input.blocks.end(),
                     [](const BlockDef& b) { return std::isfinite(b.friction); });
}

double InterfaceFriction(const EngineInput& input, int k, double engine_mu) {
  const double mu = input.blocks.at(static_cast<size_t>(k)).friction;
  return std::isfinite(mu) ? mu : engine_mu;
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
    throw SceneError(where + ": " + engine + "." + kTimeStepKey +
                     ": expected a positive time step in s");
  }
  if (std::ceil(scene.run.duration_s / dt - 1e-9) > static_cast<double>(kMaxSteps)) {
    throw SceneError(where + ": " + engine + "." + kTimeStepKey +
                     ": expected at most 2e9 steps over run.duration (time step too small)");
  }
  EngineInput in;
  in.blocks = scene.blocks;
  in.initial = scene.initial;
  in.run = scene.run;
  in.time_step_s = dt;
  in.drive_kind = drive;
  in.kinematic_highpass_hz = kinematic_highpass_hz;
  in.overturn_rad = scene.model.overturn_rad;
  in.steps = StepCount(scene.run.duration_s, dt);
  in.motion_end_s = motion.empty() ? 0.0 : motion.end_s();
  in.slip_and_lift = scene.tracks_slip_and_lift();

  const size_t n = static_cast<size_t>(in.steps);
  DriveSamples& d = in.drive;
  if (!motion.empty()) SampleGroundAcceleration(motion, dt, n, &d.ax_mps2, &d.ay_mps2);
  if (motion.has_transverse()) {
    d.at_mps2.resize(n);
    for (size_t i = 0; i < n; ++i) d.at_mps2[i] = motion.transverse_mps2(static_cast<double>(i) * dt);
  }
  if (drive == DriveKind::kKinematic) {
    const std::vector<double> zeros(d.ax_mps2.empty() ? n : 0, 0.0);
    const std::vector<double>& ax = d.ax_mps2.empty() ? zeros : d.ax_mps2;
    const std::vector<double>& ay = d.ay_mps2.empty() ? zeros : d.ay_mps2;
    const double fc = kinematic_highpass_hz;
    // The ground path every kinematic-drive engine follows, and the animations draw
    // (scene/ground_displacement.h).
    GroundPath px = IntegrateGroundPath(ax, dt, fc);
    GroundPath py = IntegrateGroundPath(ay, dt, fc);
    d.ux_m = std::move(px.u_m);
    d.uy_m = std::move(py.u_m);
    d.ux0_mps = px.velocity_before_mps;
    d.uy0_mps = py.velocity_before_mps;
    if (!d.at_mps2.empty()) {
      GroundPath pt = IntegrateGroundPath(d.at_mps2, dt, fc);
      d.ut_m = std::move(pt.u_m);
      d.ut0_mps = pt.velocity_before_mps;
    }
    d.raw_peak_x_m = px.raw_peak_m;
    d.raw_peak_y_m = py.raw_peak_m;
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
