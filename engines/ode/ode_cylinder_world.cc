#include "engines/ode/ode_cylinder_world.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "engines/ode/ode_library.h"

#if !defined(dDOUBLE)
#error "rockbench's ODE engine needs ODE built in double precision (dDOUBLE)"
#endif

namespace rockbench::ode {
namespace {

static_assert(sizeof(dReal) == sizeof(double), "ODE must be double precision");

// As OdeWorld's (ode_world.cc): a step whose bound on |omega| dt exceeds this is not taken
// (ODE aborts on an orientation quaternion it cannot normalise once |omega| dt passes ~1e154).
constexpr double kMaxStepRotation_rad = 1e100;

// |v| of a 3-vector.
double Norm2(const dReal* v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

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
  const bool scene_friction = std::isfinite(body_def_.friction);
  mu_ = scene_friction ? body_def_.friction : s_.friction;
  pyramid_ = scene_friction || s_.friction_pyramid;
  max_contacts_ = std::min(s_.max_contacts, kCylinderPlaneMaxContacts);

  AcquireOde();
  thread_ = std::this_thread::get_id();
  world_ = dWorldCreate();
  // A threading implementation of its own (see OdeWorld's class comment).
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  if (threading_ == nullptr) {
    dWorldDestroy(world_);
    ReleaseOde();
    throw std::runtime_error("ode: dThreadingAllocateSelfThreadedImplementation failed");
  }
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                       threading_);
  dWorldSetGravity(world_, 0, 0, -in_.run.gravity_mps2);
  dWorldSetERP(world_, s_.erp);
  dWorldSetCFM(world_, s_.cfm);
  dWorldSetContactMaxCorrectingVel(world_, s_.contact_max_correcting_vel_mps);
  dWorldSetContactSurfaceLayer(world_, s_.contact_surface_layer_m);
  dWorldSetQuickStepNumIterations(world_, s_.quick_step_iterations);
  dWorldSetQuickStepW(world_, s_.quick_step_w);
  dWorldSetAutoDisableFlag(world_, 0);
  dWorldSetLinearDamping(world_, 0);
  dWorldSetAngularDamping(world_, 0);
  contact_group_ = dJointGroupCreate(0);

  // Ground: the plane z = u_z (n . p = d with n = +z), and for the kinematic drive the body the
  // contacts hold on to, at the base's displacement and velocity.
  const Vec3d u0 = CylinderBaseDisplacement(in_, 0);
  const Vec3d v0 = kinematic_ ? CylinderBaseVelocityBefore(in_) : Vec3d{0, 0, 0};
  const Vec3d shift = kinematic_ ? u0 : Vec3d{0, 0, 0};
  plane_ = dCreatePlane(nullptr, 0, 0, 1, shift[2]);
  if (kinematic_) {
    ground_body_ = dBodyCreate(world_);
    dBodySetKinematic(ground_body_);
    dBodySetPosition(ground_body_, u0[0], u0[1], u0[2]);
    dBodySetLinearVel(ground_body_, v0[0], v0[1], v0[2]);
  }

  // The cylinder: mass and central inertia exactly CylinderBodyOf's (body z the axis).
  const CylinderPose start = CylinderStartPose(in_);
  body_ = dBodyCreate(world_);
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
  dBodySetAutoDisableFlag(body_, 0);
  dBodySetDamping(body_, 0, 0);
  if (s_.finite_rotation) {
    dBodySetFiniteRotationMode(body_, 1);
    dBodySetFiniteRotationAxis(body_, 0, 0, 0);  // full finite rotation
  }
  // dCreateCylinder's axis is its local z, its length the full height.
  geom_ = dCreateCylinder(nullptr, body_def_.radius_m, 2.0 * body_def_.half_height_m);
  dGeomSetBody(geom_, body_);
}

OdeCylinderWorld::~OdeCylinderWorld() {
  if (contact_group_) dJointGroupDestroy(contact_group_);
  if (geom_) dGeomDestroy(geom_);
  if (plane_) dGeomDestroy(plane_);
  if (world_) dWorldDestroy(world_);  // and its bodies
  if (threading_) dThreadingFreeImplementation(threading_);
  ReleaseOde();
}

void OdeCylinderWorld::ApplyDrive(std::int64_t n) {
  if (!kinematic_) {
    // The exact equivalent of a translating base: effective gravity in the base frame.
    const Vec3d a = CylinderDriveAccel(in_, n);
    dWorldSetGravity(world_, -a[0], -a[1], -(in_.run.gravity_mps2 + a[2]));
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
  dWorldGetGravity(world_, g);
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
  if (!fault_.empty()) return;  // the run has ended (see the header)
  if (const double bound = StepRotationBound_rad(); !(bound <= kMaxStepRotation_rad)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "ODE's orientation update would overflow (|omega| dt up to %.3g rad, on "
                  "which ODE aborts): the step was not taken",
                  bound);
    fault_ = buf;
    return;
  }
  if (std::this_thread::get_id() != thread_) {
    AllocateForThisThread();
    thread_ = std::this_thread::get_id();
  }
  dContact contact[kCylinderPlaneMaxContacts];
  contacts_ = Collide(contact);
  const dReal* centre = dBodyGetPosition(body_);
  for (int k = 0; k < contacts_; ++k) {
    dContact& c = contact[k];
    dSurfaceParameters& sp = c.surface;
    sp.mode = dContactSoftERP | dContactSoftCFM;
    sp.mu = mu_;
    sp.soft_erp = s_.contact_erp;
    sp.soft_cfm = s_.contact_cfm;
    if (pyramid_) sp.mode |= dContactApprox1;
    if (s_.restitution > 0.0) {
      sp.mode |= dContactBounce;
      sp.bounce = s_.restitution;
      sp.bounce_vel = 0.0;
    }
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
    dJointID j = dJointCreateContact(world_, contact_group_, &c);
    dJointAttach(j, body_, ground_body_);
  }
  int ok = 0;
  if (s_.stepper == OdeStepper::kQuickStep) {
    // As OdeWorld: this world's own generator state, under the process-wide lock.
    std::lock_guard<std::mutex> lock(QuickStepMutex());
    dRandSetSeed(rand_seed_);
    ok = dWorldQuickStep(world_, dt_);
    rand_seed_ = dRandGetSeed();
  } else {
    ok = dWorldStep(world_, dt_);
  }
  dJointGroupEmpty(contact_group_);
  if (!ok) throw std::runtime_error("ode: the step failed (out of memory)");
  ++steps_;
}

CylinderPose OdeCylinderWorld::ReadPose() const {
  CylinderPose p;
  if (!fault_.empty()) {
    // The step was not taken: no pose to read (the monitor ends the run as non_finite).
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    p.centre_m = {kNaN, kNaN, kNaN};
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
  auto finite_or_null = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  nlohmann::json j;
  j["ode_version"] = dODE_VERSION;
  j["ode_configuration"] = dGetConfiguration();
  j["precision"] = "double";
  j["drive"] = DriveKindName(in_.drive_kind);
  j["time_step_s"] = dt_;
  j["output_interval_s"] = in_.run.output_interval_s;
  j["substeps_per_sample"] = std::max(1.0, std::round(in_.run.output_interval_s / dt_));
  j["stepper"] = OdeStepperName(s_.stepper);
  if (s_.stepper == OdeStepper::kQuickStep) {
    j["quick_step_iterations"] = dWorldGetQuickStepNumIterations(world_);
    j["quick_step_w"] = dWorldGetQuickStepW(world_);
  }
  j["erp"] = dWorldGetERP(world_);
  j["cfm"] = dWorldGetCFM(world_);
  j["contact_erp"] = s_.contact_erp;
  j["contact_cfm"] = s_.contact_cfm;
  j["contact_max_correcting_vel_mps"] = finite_or_null(dWorldGetContactMaxCorrectingVel(world_));
  j["contact_surface_layer_m"] = dWorldGetContactSurfaceLayer(world_);
  j["friction"] = finite_or_null(s_.friction);
  j["friction_model"] =
      pyramid_ ? "pyramid (dContactApprox1: mu times the normal force, first direction along "
                 "the lean)"
               : (std::isfinite(mu_) ? "box (constant bound mu, N)" : "unbounded (never slips)");
  if (std::isfinite(body_def_.friction)) j["interface_friction"] = {body_def_.friction};
  j["restitution"] = s_.restitution;
  j["max_contacts"] = max_contacts_;
  j["finite_rotation"] = s_.finite_rotation;
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
  j["kinematic_highpass_hz"] = in_.kinematic_highpass_hz;
  j["auto_disable"] = false;
  return j;
}

}  // namespace rockbench::ode
