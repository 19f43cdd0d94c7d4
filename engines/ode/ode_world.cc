#include "engines/ode/ode_world.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/ode/ode_world_parts.h"
#include "scene/stack_pose.h"

namespace rockbench::ode {
namespace {

void ReadBody(dBodyID body, BodyReadout* out) {
  const dReal* p = dBodyGetPosition(body);
  const dReal* r = dBodyGetRotation(body);  // 3x4, row major: r[4 * row + col]
  const dReal* v = dBodyGetLinearVel(body);
  const dReal* w = dBodyGetAngularVel(body);
  out->x_m = p[0];
  out->y_m = p[1];
  out->cos_phi = r[0];
  out->sin_phi = r[4];
  out->vx_mps = v[0];
  out->vy_mps = v[1];
  out->w_radps = w[2];
}

// Largest out-of-plane rotation component of a body's rotation (0 for a rotation about z).
double OutOfPlaneRotation(dBodyID body) {
  const dReal* r = dBodyGetRotation(body);
  return std::max({std::abs(r[8]), std::abs(r[9]), std::abs(r[2]), std::abs(r[6])});
}

// The settings' ranges are the [ode] schema's (ode_settings.cc), checked when the table is
// resolved; the input's step by MakeEngineInput. What is left is the input's own consistency.
void CheckInput(const EngineInput& in) {
  if (in.drive_kind == DriveKind::kKinematic) {
    const size_t need = static_cast<size_t>(in.steps) + 1;
    if (in.drive.ux_m.size() < need || in.drive.uy_m.size() < need) {
      throw std::invalid_argument("ode: kinematic drive needs ux_m and uy_m at n = 0..steps");
    }
  }
}

}  // namespace

const char* OdeStepperName(OdeStepper stepper) {
  return stepper == OdeStepper::kQuickStep ? "quick_step" : "world_step";
}

OdeWorld::OdeWorld(const EngineInput& input, const OdeSettings& settings)
    : in_(input), s_(settings) {
  CheckInput(in_);
  dt_ = in_.time_step_s;
  kinematic_ = in_.drive_kind == DriveKind::kKinematic;

  core_ = std::make_unique<OdeWorldCore>(s_, 0, -in_.run.gravity_mps2, 0);

  // Ground: a box whose top face is y = 0 in the base frame, much wider than the stack and
  // deeper (z) than the blocks, so that its z faces never give the separating axis.
  double size = 0.5, depth = 0.0;
  for (const BlockDef& def : in_.blocks) {
    size = std::max({size, 0.5 * def.width_m, 0.5 * def.height_m});
    depth = std::max(depth, def.depth_m);
  }
  ground_half_depth_m_ = 0.5 * s_.ground_depth_m;
  ground_geom_ = dCreateBox(nullptr, 80.0 * size, s_.ground_depth_m, 2.0 * (depth + 1.0));
  const double ux0 = kinematic_ ? in_.drive.ux_m.front() : 0.0;
  const double uy0 = kinematic_ ? in_.drive.uy_m.front() : 0.0;
  if (kinematic_) {
    const double p[3] = {ux0, uy0 - ground_half_depth_m_, 0};
    const double v[3] = {in_.drive.ux0_mps, in_.drive.uy0_mps, 0};
    ground_body_ = MakeKinematicBody(core_->world(), p, v);
    dGeomSetBody(ground_geom_, ground_body_);
  } else {
    dGeomSetPosition(ground_geom_, 0, -ground_half_depth_m_, 0);
  }

  // Blocks, placed by the pivot chain in the base frame then shifted with the ground.
  const StackPlacement place = PlaceStack(in_.blocks, in_.initial);
  const double gvx = kinematic_ ? in_.drive.ux0_mps : 0.0;
  const double gvy = kinematic_ ? in_.drive.uy0_mps : 0.0;
  auto make_block = [&](const BlockDef& def, const PlanarPose& pose, dBodyID* body, dGeomID* geom,
                        dJointID* plane) {
    *body = dBodyCreate(core_->world());
    dMass m;
    // Uniform box: I_zz = m (w^2 + h^2) / 12 about the centre, as the model's.
    dMassSetBoxTotal(&m, def.mass_kg, def.width_m, def.height_m, def.depth_m);
    dBodySetMass(*body, &m);
    dBodySetPosition(*body, pose.x_m + ux0, pose.y_m + uy0, 0);
    dMatrix3 r;
    dRFromAxisAndAngle(r, 0, 0, 1, pose.phi_rad);
    dBodySetRotation(*body, r);
    dBodySetLinearVel(*body, pose.vx_mps + gvx, pose.vy_mps + gvy, 0);
    dBodySetAngularVel(*body, 0, 0, pose.w_radps);
    SetUndampedBody(*body, s_);
    *geom = dCreateBox(nullptr, def.width_m, def.height_m, def.depth_m);
    dGeomSetBody(*geom, *body);
    // Planar motion: v_z = 0 (with ERP back to z = 0), w_x = w_y = 0. Attached to the static
    // environment; the joint's rows do not involve w_z.
    *plane = dJointCreatePlane2D(core_->world(), nullptr);
    dJointAttach(*plane, *body, nullptr);
  };
  // Bottom first.
  const size_t n = in_.blocks.size();
  bodies_.assign(n, nullptr);
  geoms_.assign(n, nullptr);
  planes_.assign(n, nullptr);
  for (size_t k = 0; k < n; ++k) {
    make_block(in_.blocks[k], place.blocks[k], &bodies_[k], &geoms_[k], &planes_[k]);
  }
}

OdeWorld::~OdeWorld() {
  for (auto it = geoms_.rbegin(); it != geoms_.rend(); ++it) {
    if (*it) dGeomDestroy(*it);
  }
  if (ground_geom_) dGeomDestroy(ground_geom_);
  // core_ then destroys the contact group and the world with its bodies and Plane2D joints.
}

void OdeWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  if (!kinematic_) {
    const double ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
    const double ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
    // The exact equivalent of a translating base: effective gravity in the base frame.
    dWorldSetGravity(core_->world(), -ax, -(in_.run.gravity_mps2 + ay), 0);
    return;
  }
  // Kinematic: the ground at u_n (where collision detection sees it, with the blocks) moving
  // with (u_{n+1} - u_n) / dt; dWorldStep moves it on to u_{n+1} (up to rounding, reset here).
  const double ux = in_.drive.ux_m[i], uy = in_.drive.uy_m[i];
  const double nx = in_.drive.ux_m[i + 1], ny = in_.drive.uy_m[i + 1];
  dBodySetPosition(ground_body_, ux, uy - ground_half_depth_m_, 0);
  dBodySetLinearVel(ground_body_, (nx - ux) / dt_, (ny - uy) / dt_, 0);
}

int OdeWorld::Collide(dxGeom* a, dxGeom* b, dxBody* body_a, dxBody* body_b, double scene_mu) {
  // The scene's coefficient wins: Coulomb's law with that mu (the pyramid is exact in the plane).
  const OdeFriction friction = FrictionOf(scene_mu, s_);
  dContact contact[8];
  const int n = dCollide(a, b, s_.max_contacts, &contact[0].geom, sizeof(dContact));
  for (int k = 0; k < n; ++k) {
    dContact& c = contact[k];
    dSurfaceParameters& sp = c.surface;
    SetSurface(&sp, s_, friction);
    // First friction direction: the in-plane tangent, so that the friction pyramid is exact
    // Coulomb in the plane (the second direction, along z, is redundant with Plane2D).
    const double nx = c.geom.normal[0], ny = c.geom.normal[1];
    const double len = std::hypot(nx, ny);
    if (len > 0.5) {
      sp.mode |= dContactFDir1;
      c.fdir1[0] = -ny / len;
      c.fdir1[1] = nx / len;
      c.fdir1[2] = 0;
      c.fdir1[3] = 0;
    }
    dJointID j = dJointCreateContact(core_->world(), core_->contacts(), &c);
    dJointAttach(j, body_a, body_b);
  }
  return n;
}

double OdeWorld::StepRotationBound_rad() const {
  dVector3 g;
  dWorldGetGravity(core_->world(), g);
  double speed = Norm2(g) * dt_;  // m/s gained in the step
  if (kinematic_) speed += Norm2(dBodyGetLinearVel(ground_body_));
  double fastest = 0.0, smallest = std::min(in_.blocks[0].width_m, in_.blocks[0].height_m);
  for (size_t k = 0; k < bodies_.size(); ++k) {
    const double width_m = in_.blocks[k].width_m, height_m = in_.blocks[k].height_m;
    const double half_diagonal = 0.5 * std::hypot(width_m, height_m);
    fastest = std::max(fastest, Norm2(dBodyGetLinearVel(bodies_[k])) +
                                    Norm2(dBodyGetAngularVel(bodies_[k])) * half_diagonal);
    smallest = std::min({smallest, width_m, height_m});
  }
  return (fastest + speed) / (0.5 * smallest) * dt_;
}

void OdeWorld::Step() {
  // Not taken once the run has ended or when it could overflow (see the header).
  if (!core_->fault().empty() || !core_->MayStep(StepRotationBound_rad())) return;
  // Neighbours only, bottom first: block 1 on the ground, block k on block k - 1.
  contacts_ground_ =
      Collide(geoms_[0], ground_geom_, bodies_[0], ground_body_, in_.blocks[0].friction);
  contacts_interface_ = 0;
  contacts_block2_ground_ = 0;
  for (size_t k = 1; k < bodies_.size(); ++k) {
    contacts_interface_ +=
        Collide(geoms_[k], geoms_[k - 1], bodies_[k], bodies_[k - 1], in_.blocks[k].friction);
  }
  if (bodies_.size() == 2) {
    // Two blocks: also block 2 on the ground, once it has fallen off block 1 (as before issue
    // 23, so that their runs keep their bytes; Bullet's two blocks collide every pair too). Not
    // an interface of the model: the settings' friction.
    contacts_block2_ground_ = Collide(geoms_[1], ground_geom_, bodies_[1], ground_body_,
                                      std::numeric_limits<double>::infinity());
  }
  core_->Advance(dt_);
}

StepReadout OdeWorld::Read(std::int64_t n) const {
  StepReadout s(in_.block_count());
  s.t_s = static_cast<double>(n) * dt_;
  double oop_m = 0.0, oop_rad = 0.0;
  for (size_t k = 0; k < bodies_.size(); ++k) {
    ReadBody(bodies_[k], &s.blocks[k]);
    const double dz = std::abs(dBodyGetPosition(bodies_[k])[2]);
    const double tilt = OutOfPlaneRotation(bodies_[k]);
    oop_m = k == 0 ? dz : std::max(oop_m, dz);  // block 1's own value first, as before
    oop_rad = k == 0 ? tilt : std::max(oop_rad, tilt);
  }
  s.out_of_plane_m = oop_m;
  s.out_of_plane_rad = oop_rad;
  ReadBaseMotion(in_, n, &s);
  s.engine_fault = core_->fault();
  return s;
}

nlohmann::json OdeWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, s_, core_->world());
  j["friction_model"] =
      s_.friction_pyramid
          ? "pyramid (dContactApprox1: mu times the normal force)"
          : (std::isfinite(s_.friction) ? "box (constant bound mu, N)" : "unbounded (never slips)");
  // Friction from the scene: each interface's coefficient (Coulomb's pyramid where the scene
  // sets it), block 1 on the ground first.
  if (HasFiniteFriction(in_)) {
    nlohmann::json mu = nlohmann::json::array();
    for (int k = 0; k < in_.block_count(); ++k) {
      mu.push_back(FiniteOrNull(InterfaceFriction(in_, k, s_.friction)));
    }
    j["interface_friction"] = mu;
  }
  j["max_contacts"] = s_.max_contacts;
  j["planar_constraint"] = "Plane2D joint per block";
  j["ground_depth_m"] = s_.ground_depth_m;
  // Three or more blocks: contacts between neighbours only (two: block 2 and the ground too).
  if (bodies_.size() >= 3) j["collision_pairs"] = "neighbours";
  return j;
}

}  // namespace rockbench::ode
