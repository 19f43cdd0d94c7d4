#include "engines/ode/ode_cylinder_world.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/ode/ode_world_parts.h"

namespace rockbench::ode {
namespace {

void CheckInput(const EngineInput& in) {
  if (in.blocks.size() != 1) {
    throw std::invalid_argument("ode: the cylinder is one body (the scene has " +
                                std::to_string(in.blocks.size()) + ")");
  }
  if (in.drive_kind == DriveKind::kKinematic) {
    const size_t need = static_cast<size_t>(in.steps) + 1;
    if (in.drive.ux_m.size() < need || in.drive.uy_m.size() < need ||
        (!in.drive.ut_m.empty() && in.drive.ut_m.size() < need)) {
      throw std::invalid_argument(
          "ode: kinematic drive needs ux_m, uy_m (and ut_m) at n = 0..steps");
    }
  }
}

}  // namespace

OdeCylinderWorld::OdeCylinderWorld(const EngineInput& input, const OdeSettings& settings)
    : in_(input), s_(settings), body_def_(CylinderBodyOf(input)) {
  CheckInput(in_);
  dt_ = in_.time_step_s;
  kinematic_ = in_.drive_kind == DriveKind::kKinematic;
  // The scene's coefficient wins (Coulomb's pyramid with that mu), as for the blocks.
  const OdeFriction friction = FrictionOf(body_def_.friction, s_);
  mu_ = friction.mu;
  pyramid_ = friction.pyramid;
  max_contacts_ = std::min(s_.max_contacts, kCylinderPlaneMaxContacts);

  core_ = std::make_unique<OdeWorldCore>(s_, 0, 0, -in_.run.gravity_mps2);

  // Ground: the plane z = u_z (n . p = d with n = +z), and for the kinematic drive the body the
  // contacts hold on to, at the base's displacement and velocity.
  const Vec3d u0 = CylinderBaseDisplacement(in_, 0);
  const Vec3d v0 = kinematic_ ? CylinderBaseVelocityBefore(in_) : Vec3d{0, 0, 0};
  const Vec3d shift = kinematic_ ? u0 : Vec3d{0, 0, 0};
  plane_ = dCreatePlane(nullptr, 0, 0, 1, shift[2]);
  if (kinematic_) ground_body_ = MakeKinematicBody(core_->world(), u0.data(), v0.data());

  // The cylinder: mass and central inertia exactly CylinderBodyOf's (body z the axis).
  const CylinderPose start = CylinderStartPose(in_);
  body_ = dBodyCreate(core_->world());
  dMass m;
  dMassSetZero(&m);
  dMassSetParameters(&m, body_def_.mass_kg, 0, 0, 0, body_def_.inertia_transverse_kgm2,
                     body_def_.inertia_transverse_kgm2, body_def_.inertia_axial_kgm2, 0, 0, 0);
  dBodySetMass(body_, &m);
  dBodySetPosition(body_, start.centre_m[0] + shift[0], start.centre_m[1] + shift[1],
                   start.centre_m[2] + shift[2]);
  dMatrix3 r;  // 3x4, row major
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[4 * i + j] = start.rotation[static_cast<size_t>(3 * i + j)];
    r[4 * i + 3] = 0;
  }
  dBodySetRotation(body_, r);
  dBodySetLinearVel(body_, start.velocity_mps[0] + v0[0], start.velocity_mps[1] + v0[1],
                    start.velocity_mps[2] + v0[2]);
  dBodySetAngularVel(body_, start.omega_radps[0], start.omega_radps[1], start.omega_radps[2]);
  SetUndampedBody(body_, s_);
  // dCreateCylinder's axis is its local z, its length the full height.
  geom_ = dCreateCylinder(nullptr, body_def_.radius_m, 2.0 * body_def_.half_height_m);
  dGeomSetBody(geom_, body_);
}

OdeCylinderWorld::~OdeCylinderWorld() {
  if (geom_) dGeomDestroy(geom_);
  if (plane_) dGeomDestroy(plane_);
  // core_ then destroys the contact group and the world with its bodies.
}

const std::string& OdeCylinderWorld::fault() const {
  return core_->fault();
}

void OdeCylinderWorld::ApplyDrive(std::int64_t n) {
  if (!kinematic_) {
    // The exact equivalent of a translating base: effective gravity in the base frame.
    const Vec3d a = CylinderDriveAccel(in_, n);
    dWorldSetGravity(core_->world(), -a[0], -a[1], -(in_.run.gravity_mps2 + a[2]));
    return;
  }
  // Kinematic: the plane at u_n's height (where collision detection sees it), the ground body
  // moving with (u_{n+1} - u_n) / dt; dWorldStep moves it on (reset here every step).
  const Vec3d u = CylinderBaseDisplacement(in_, n), next = CylinderBaseDisplacement(in_, n + 1);
  dGeomPlaneSetParams(plane_, 0, 0, 1, u[2]);
  dBodySetPosition(ground_body_, u[0], u[1], u[2]);
  dBodySetLinearVel(ground_body_, (next[0] - u[0]) / dt_, (next[1] - u[1]) / dt_,
                    (next[2] - u[2]) / dt_);
}

double OdeCylinderWorld::StepRotationBound_rad() const {
  dVector3 g;
  dWorldGetGravity(core_->world(), g);
  double speed = Norm2(g) * dt_;  // m/s gained in the step
  if (kinematic_) speed += Norm2(dBodyGetLinearVel(ground_body_));
  const double corner_m = std::hypot(body_def_.radius_m, body_def_.half_height_m);
  const double fastest =
      Norm2(dBodyGetLinearVel(body_)) + Norm2(dBodyGetAngularVel(body_)) * corner_m;
  return (fastest + speed) / std::min(body_def_.radius_m, body_def_.half_height_m) * dt_;
}

int OdeCylinderWorld::Collide(dContact* contact) const {
  const int n = dCollide(geom_, plane_, max_contacts_, &contact[0].geom, sizeof(dContact));
  if (!s_.cylinder_upright_rim) return n;
  // ODE's test for its face branch (collision_cylinder_plane.cpp), on the axis (body z).
  const dReal* r = dBodyGetRotation(body_);
  const double axis[3] = {r[2], r[6], r[10]};
  dVector4 plane;
  dGeomPlaneGetParams(plane_, plane);
  const double cos_tilt = axis[0] * plane[0] + axis[1] * plane[1] + axis[2] * plane[2];
  const double off = cos_tilt < 0 ? cos_tilt + 1.0 : cos_tilt - 1.0;
  if (!(off < 1e-7 && off > -1e-7)) return n;  // tilted: ODE's exact lowest rim point
  // Down the lower face toward its lowest rim point: axis (axis . n) - n, scaled to R.
  double down[3];
  for (int i = 0; i < 3; ++i) down[i] = axis[i] * cos_tilt - plane[i];
  const double len = std::sqrt(down[0] * down[0] + down[1] * down[1] + down[2] * down[2]);
  if (!(len > 0.0)) return n;  // exactly upright: ODE's four points, all at the face's depth
  const double radius = body_def_.radius_m;
  for (double& d : down) d *= radius / len;
  // The lower face's centre, and the rim's diameter across the lean (axis x down, length R).
  const dReal* pos = dBodyGetPosition(body_);
  const double side_h = cos_tilt >= 0 ? -body_def_.half_height_m : body_def_.half_height_m;
  const double across[3] = {axis[1] * down[2] - axis[2] * down[1],
                            axis[2] * down[0] - axis[0] * down[2],
                            axis[0] * down[1] - axis[1] * down[0]};
  // The lowest point first (on or under the plane, as ODE's tilted branch), then the others
  // under it (as ODE's face branch).
  const double signs[4][2] = {{1, 0}, {0, 1}, {0, -1}, {-1, 0}};
  int count = 0;
  for (int k = 0; k < 4 && count < max_contacts_; ++k) {
    dContactGeom& g = contact[count].geom;
    for (int i = 0; i < 3; ++i) {
      g.pos[i] = pos[i] + side_h * axis[i] + signs[k][0] * down[i] + signs[k][1] * across[i];
    }
    g.pos[3] = 0;
    g.depth = plane[3] - (g.pos[0] * plane[0] + g.pos[1] * plane[1] + g.pos[2] * plane[2]);
    if (k == 0 ? !(g.depth >= 0.0) : !(g.depth > 0.0)) continue;
    for (int i = 0; i < 3; ++i) g.normal[i] = plane[i];
    g.normal[3] = 0;
    g.g1 = geom_;
    g.g2 = plane_;
    g.side1 = g.side2 = -1;
    ++count;
  }
  return count;
}

void OdeCylinderWorld::Step() {
  // Not taken once the run has ended or when it could overflow (see the header).
  if (!core_->fault().empty() || !core_->MayStep(StepRotationBound_rad())) return;
  dContact contact[kCylinderPlaneMaxContacts];
  contacts_ = Collide(contact);
  const dReal* centre = dBodyGetPosition(body_);
  for (int k = 0; k < contacts_; ++k) {
    dContact& c = contact[k];
    dSurfaceParameters& sp = c.surface;
    SetSurface(&sp, s_, {mu_, pyramid_});
    // First friction direction: from the axis toward the contact point, along the base (the
    // lean's direction on the rim): the pyramid is exact Coulomb for a force along the lean,
    // as in planar rocking; across it, it allows up to sqrt(2) mu N.
    const double dx = c.geom.pos[0] - centre[0], dy = c.geom.pos[1] - centre[1];
    const double len = std::hypot(dx, dy);
    if (len > 0.5 * body_def_.radius_m) {
      sp.mode |= dContactFDir1;
      c.fdir1[0] = dx / len;
      c.fdir1[1] = dy / len;
      c.fdir1[2] = 0;
      c.fdir1[3] = 0;
    }
    dJointID j = dJointCreateContact(core_->world(), core_->contacts(), &c);
    dJointAttach(j, body_, ground_body_);
  }
  core_->Advance(dt_);
  ++steps_;
}

CylinderPose OdeCylinderWorld::ReadPose() const {
  CylinderPose p;
  if (!core_->fault().empty()) {
    // The step was not taken: no pose to read; the monitor ends the run as non_finite, saying why.
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    p.centre_m = {kNaN, kNaN, kNaN};
    p.engine_fault = core_->fault();
    return p;
  }
  const dReal* pos = dBodyGetPosition(body_);
  const dReal* r = dBodyGetRotation(body_);  // 3x4, row major
  const dReal* v = dBodyGetLinearVel(body_);
  const dReal* w = dBodyGetAngularVel(body_);
  const Vec3d u = kinematic_ ? CylinderBaseDisplacement(in_, steps_) : Vec3d{0, 0, 0};
  const dReal zero[3] = {0, 0, 0};
  const dReal* vg = kinematic_ ? dBodyGetLinearVel(ground_body_) : zero;
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    p.centre_m[k] = pos[i] - u[k];
    p.velocity_mps[k] = v[i] - vg[i];
    p.omega_radps[k] = w[i];
    for (int j = 0; j < 3; ++j) p.rotation[static_cast<size_t>(3 * i + j)] = r[4 * i + j];
  }
  return p;
}

nlohmann::json OdeCylinderWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, s_, core_->world());
  j["friction_model"] =
      pyramid_ ? "pyramid (dContactApprox1: mu times the normal force, first direction along "
                 "the lean)"
               : (std::isfinite(mu_) ? "box (constant bound mu, N)" : "unbounded (never slips)");
  if (std::isfinite(body_def_.friction)) j["interface_friction"] = {body_def_.friction};
  j["max_contacts"] = max_contacts_;
  j["body"] = "dCreateCylinder (exact), mass and inertia set from the scene";
  j["ground"] = kinematic_ ? "plane (dCreatePlane) following the base, contacts on a kinematic "
                             "body moving with it"
                           : "plane (dCreatePlane)";
  j["collider"] = s_.cylinder_upright_rim
                      ? "dCollideCylinderPlane (tilted: the lowest rim point, exact), completed "
                        "within 4.5e-4 rad of upright by the lowest rim point and the rim points "
                        "90 degrees apart under the plane"
                      : "dCollideCylinderPlane as it is (within 4.5e-4 rad of upright: no contact "
                        "until the face's centre is under the plane)";
  j["cylinder_upright_rim"] = s_.cylinder_upright_rim;
  return j;
}

}  // namespace rockbench::ode
