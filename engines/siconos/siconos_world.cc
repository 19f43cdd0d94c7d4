#include "engines/siconos/siconos_world.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/siconos/siconos_system.h"
#include "engines/siconos/siconos_world_parts.h"
#include "scene/stack_pose.h"

namespace rockbench::siconos_engine {

namespace {

SiconosBlock Block(const BlockDef& def, const PlanarPose& pose, double ux0, double uy0, double gvx,
                   double gvy) {
  SiconosBlock b;
  b.b_m = 0.5 * def.width_m;
  b.h_m = 0.5 * def.height_m;
  b.mass_kg = def.mass_kg;
  b.inertia_kgm2 = def.mass_kg * (def.width_m * def.width_m + def.height_m * def.height_m) / 12.0;
  b.x_m = pose.x_m + ux0;
  b.y_m = pose.y_m + uy0;
  b.phi_rad = pose.phi_rad;
  b.vx_mps = pose.vx_mps + gvx;
  b.vy_mps = pose.vy_mps + gvy;
  b.w_radps = pose.w_radps;
  return b;
}

void ReadBody(const SiconosBodyState& st, BodyReadout* out) {
  out->x_m = st.x_m;
  out->y_m = st.y_m;
  out->cos_phi = std::cos(st.phi_rad);
  out->sin_phi = std::sin(st.phi_rad);
  out->vx_mps = st.vx_mps;
  out->vy_mps = st.vy_mps;
  out->w_radps = st.w_radps;
}

}  // namespace

SiconosWorld::SiconosWorld(const EngineInput& input, const SiconosSettings& settings)
    : WorldBase(input, settings) {
  // The settings' ranges are the [siconos] schema's (siconos_settings.cc), checked when the
  // table was resolved; the step is the input's, checked by MakeEngineInput.
  const size_t samples = static_cast<size_t>(in_.steps) + 1;
  if (kinematic_ && (in_.drive.ux_m.size() < samples || in_.drive.uy_m.size() < samples)) {
    throw std::invalid_argument("siconos: kinematic drive without ground displacement samples");
  }
  const StackPlacement place = PlaceStack(in_.blocks, in_.initial);
  const double ux0 = kinematic_ ? in_.drive.ux_m.front() : 0.0;
  const double uy0 = kinematic_ ? in_.drive.uy_m.front() : 0.0;
  const double gvx = kinematic_ ? in_.drive.ux0_mps : 0.0;
  const double gvy = kinematic_ ? in_.drive.uy0_mps : 0.0;

  SiconosSystemConfig c;
  for (int k = 0; k < in_.block_count(); ++k) {
    c.blocks.push_back(Block(in_.blocks[k], place.blocks[k], ux0, uy0, gvx, gvy));
    // Friction from the scene: the law of block k's base contacts has its coefficient.
    if (std::isfinite(in_.blocks[k].friction)) c.blocks.back().friction = in_.blocks[k].friction;
  }
  SetTimeStepping(in_, s_, kinematic_, &c);
  c.friction = s_.friction;
  c.lemke_fallback = s_.lemke_fallback;
  c.ground_x_m = ux0;
  c.ground_y_m = uy0;
  c.ground_vx_mps = gvx;
  c.ground_vy_mps = gvy;
  sys_ = std::make_unique<SiconosSystem>(c);
}

SiconosWorld::~SiconosWorld() = default;

void SiconosWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  const double g = in_.run.gravity_mps2;
  double ax = 0.0, ay = 0.0;
  if (kinematic_) {
    const auto& ux = in_.drive.ux_m;
    const auto& uy = in_.drive.uy_m;
    const double dt = in_.time_step_s;
    sys_->SetGround(ux[i], uy[i], (ux[i + 1] - ux[i]) / dt, (uy[i + 1] - uy[i]) / dt);
  } else {
    ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
    ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
  }
  // The exact equivalent of a translating base: each block's weight in the tilted gravity.
  for (int k = 0; k < in_.block_count(); ++k) {
    const double m = in_.blocks[k].mass_kg;
    sys_->SetForce(k, -m * ax, -m * (g + ay), 0.0);
  }
}

void SiconosWorld::Step() {
  if (failed_) return;
  if (!sys_->Step()) failed_ = true;
}

StepReadout SiconosWorld::Read(std::int64_t n) const {
  StepReadout s(in_.block_count());
  s.t_s = static_cast<double>(n) * in_.time_step_s;
  for (int k = 0; k < in_.block_count(); ++k) ReadBody(sys_->Body(k), &s.blocks[k]);
  if (failed_) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (BodyReadout& b : s.blocks) b.x_m = b.y_m = nan;
  }
  // Planar by construction: the dynamical systems have no out-of-plane coordinates.
  s.out_of_plane_m = 0.0;
  s.out_of_plane_rad = 0.0;
  ReadBaseMotion(in_, n, &s);
  return s;
}

nlohmann::json SiconosWorld::Diagnostics() const {
  return CountersJson(sys_->Counters(), sys_->LastError());
}

nlohmann::json SiconosWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, s_, kinematic_);
  j["solver"] = SiconosSolverName(s_.solver);
  j["lemke_fallback"] = s_.lemke_fallback && s_.solver != SiconosSolver::kLemke;
  j["contact"] = "FrictionContact (2-D), NewtonImpactFrictionNSL per bottom corner";
  // Friction from the scene: each interface's coefficient (its contacts' law), block 1 on the
  // ground first.
  if (HasFiniteFriction(in_)) {
    nlohmann::json mu = nlohmann::json::array();
    for (int k = 0; k < in_.block_count(); ++k)
      mu.push_back(InterfaceFriction(in_, k, s_.friction));
    j["interface_friction"] = mu;
  }
  return j;
}

}  // namespace rockbench::siconos_engine
