#include "engines/siconos/siconos_cylinder_world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/siconos/siconos_cylinder_system.h"
#include "engines/siconos/siconos_system.h"
#include "engines/siconos/siconos_world_parts.h"

namespace rockbench::siconos_engine {
namespace {

std::array<double, 3> Arr(const Vec3d& v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

SiconosCylinderWorld::SiconosCylinderWorld(const EngineInput& input,
                                           const SiconosSettings& settings)
    : WorldBase(input, settings), body_(CylinderBodyOf(input)) {
  friction_ = std::isfinite(body_.friction) ? body_.friction : s_.friction;
  const CylinderPose start = CylinderStartPose(in_);
  // The kinematic drive: the ground and the cylinder start at the base's displacement, moving
  // with its velocity before step 0.
  const Vec3d u0 = kinematic_ ? CylinderBaseDisplacement(in_, 0) : Vec3d{};
  const Vec3d v0 = kinematic_ ? CylinderBaseVelocityBefore(in_) : Vec3d{};

  SiconosCylinderConfig c;
  c.radius_m = body_.radius_m;
  c.half_height_m = body_.half_height_m;
  c.mass_kg = body_.mass_kg;
  c.inertia_transverse_kgm2 = body_.inertia_transverse_kgm2;
  c.inertia_axial_kgm2 = body_.inertia_axial_kgm2;
  for (int i = 0; i < 3; ++i) {
    c.centre_m[i] = start.centre_m[i] + u0[i];
    c.velocity_mps[i] = start.velocity_mps[i] + v0[i];
    c.omega_radps[i] = start.omega_radps[i];
  }
  std::copy(start.rotation.begin(), start.rotation.end(), c.rotation.begin());
  c.upright_azimuth_rad = in_.initial.azimuth_rad[0];
  SetTimeStepping(in_, s_, kinematic_, &c);
  c.friction = friction_;
  c.newton_fallback = s_.lemke_fallback;
  c.ground_m = Arr(u0);
  c.ground_velocity_mps = Arr(v0);
  sys_ = std::make_unique<SiconosCylinderSystem>(c);
}

SiconosCylinderWorld::~SiconosCylinderWorld() = default;

void SiconosCylinderWorld::ApplyDrive(std::int64_t n) {
  next_step_ = n;
  const double m = body_.mass_kg, g = in_.run.gravity_mps2;
  if (kinematic_) {
    const Vec3d u = CylinderBaseDisplacement(in_, n), next = CylinderBaseDisplacement(in_, n + 1);
    const double dt = in_.time_step_s;
    sys_->SetGround(Arr(u), {(next[0] - u[0]) / dt, (next[1] - u[1]) / dt, (next[2] - u[2]) / dt});
    sys_->SetForce({0.0, 0.0, -m * g});
    return;
  }
  // The exact equivalent of a translating base: the weight in the effective gravity.
  const Vec3d a = CylinderDriveAccel(in_, n);
  sys_->SetForce({-m * a[0], -m * a[1], -m * (g + a[2])});
}

void SiconosCylinderWorld::Step() {
  if (!failed_ && !sys_->Step()) failed_ = true;
  steps_done_ = next_step_ + 1;
}

CylinderPose SiconosCylinderWorld::ReadPose() const {
  const SiconosCylinderState s = sys_->State();
  CylinderPose p;
  for (int i = 0; i < 3; ++i) {
    p.centre_m[i] = s.centre_m[i];
    p.velocity_mps[i] = s.velocity_mps[i];
    p.omega_radps[i] = s.omega_radps[i];
  }
  std::copy(s.rotation.begin(), s.rotation.end(), p.rotation.begin());
  if (kinematic_) {
    // The base after steps_done_ steps: at u_n, moving as in the step that ended there.
    const std::int64_t n = steps_done_;
    const Vec3d u = CylinderBaseDisplacement(in_, n);
    const Vec3d v = CylinderBaseVelocityAfter(in_, n);
    for (int i = 0; i < 3; ++i) {
      p.centre_m[i] -= u[i];
      p.velocity_mps[i] -= v[i];
    }
  }
  if (failed_) p.centre_m[0] = std::numeric_limits<double>::quiet_NaN();
  return p;
}

nlohmann::json SiconosCylinderWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, s_, kinematic_);
  j["cylinder_friction"] = friction_;
  j["solver"] = std::string(SiconosSolverName(s_.solver)) + " (SICONOS_FRICTION_3D_NSGS)";
  j["lemke_fallback"] = s_.lemke_fallback;
  if (s_.lemke_fallback) {
    j["fallback_solver"] = "SICONOS_FRICTION_3D_NSN_AC (no Lemke in 3-D)";
  }
  j["activation_threshold_m"] = s_.activation_threshold_m;
  j["body"] = "NewtonEulerDS (quaternion), gyroscopic term on";
  j["mass_kg"] = body_.mass_kg;
  j["inertia_kgm2"] = {body_.inertia_transverse_kgm2, body_.inertia_transverse_kgm2,
                       body_.inertia_axial_kgm2};
  j["contact"] = "FrictionContact (3-D), NewtonImpactFrictionNSL on " +
                 std::to_string(kRimContacts) +
                 " exact bottom-rim points (NewtonEuler3DR): the lowest and the rest equally "
                 "spaced from it, recomputed from the orientation";
  j["ground"] = "plane z = 0";
  return j;
}

nlohmann::json SiconosCylinderWorld::Diagnostics() const {
  return CountersJson(sys_->Counters(), sys_->LastError());
}

EngineResult SimulateCylinder(const std::string& scene_path, const EngineInput& input,
                              const SiconosSettings& settings) {
  static_assert(CylinderWorld<SiconosCylinderWorld>);
  return SimulateCylinderWorld<SiconosCylinderWorld>("siconos", scene_path, input, settings);
}

}  // namespace rockbench::siconos_engine
