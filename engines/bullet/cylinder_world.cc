#include "engines/bullet/cylinder_world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engines/bullet/bullet_cylinder.h"
#include "engines/bullet/bullet_engine.h"

namespace rockbench::bullet {
namespace {

// The ground plane z = 0 with a bounded box (+-kHalfSize_m across, +-1 m in z) in place of
// btStaticPlaneShape's infinite one: Bullet takes a moving (kinematic) body with a box beyond
// 1e6 m out of the simulation ("Overflow in AABB"). Its shape type is still the static plane's,
// so the cylinder meets it through the convex-plane algorithm.
class BoundedPlaneShape final : public btStaticPlaneShape {
 public:
  static constexpr double kHalfSize_m = 1e4;
  BoundedPlaneShape() : btStaticPlaneShape(btVector3(0, 0, 1), 0) {}
  void getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const override {
    const btVector3 half{btScalar(kHalfSize_m), btScalar(kHalfSize_m), btScalar(1)};
    btTransformAabb(-half, half, 0, t, aabb_min, aabb_max);
  }
};

Vec3d Minus(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

btVector3 Bt(const Vec3d& v) {
  return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
}

}  // namespace

BulletCylinderWorld::BulletCylinderWorld(const BulletInput& input)
    : in_(input),
      body_(CylinderBodyOf(input)),
      dynamics_(input, btVector3(0, 0, btScalar(-input.run.gravity_mps2))),
      world_(dynamics_.world()) {
  const BulletConfig& c = in_.config;
  dt_ = in_.time_step_s;
  kinematic_ = in_.drive_kind == DriveKind::kKinematic;

  // Friction: Bullet's contact coefficient is the product of the two bodies' values (clamped at
  // 10). The scene's finite coefficient goes on the cylinder over a ground of 1, so that the
  // product is that coefficient exactly; otherwise both take the table's value, as the blocks.
  const bool scene_friction = std::isfinite(body_.friction);
  cylinder_friction_ = scene_friction ? body_.friction : c.friction;
  ground_friction_ = scene_friction ? 1.0 : c.friction;

  // Ground: the plane z = 0 at the base's displacement (kinematic drive) or at rest.
  ground_shape_ = std::make_unique<BoundedPlaneShape>();
  const Vec3d u0 = kinematic_ ? CylinderBaseDisplacement(in_, 0) : Vec3d{};
  ground_ = MakeGround(in_, ground_shape_.get(), GroundTransform(u0), ground_friction_);
  world_->addRigidBody(ground_.get());

  // The cylinder: exact radius and half-height (no margin unless the table sets one), the mass
  // and central inertia of CylinderBodyOf, the start pose shifted with the ground.
  shape_ = std::make_unique<btCylinderShapeZ>(
      btVector3(btScalar(body_.radius_m), btScalar(body_.radius_m), btScalar(body_.half_height_m)));
  shape_->setMargin(btScalar(c.margin_m));
  const btVector3 inertia(btScalar(body_.inertia_transverse_kgm2),
                          btScalar(body_.inertia_transverse_kgm2),
                          btScalar(body_.inertia_axial_kgm2));
  const CylinderPose start = CylinderStartPose(in_);
  const Vec3d v0 = kinematic_ ? CylinderBaseVelocityBefore(in_) : Vec3d{};
  btTransform pose;
  const Mat3d& q = start.rotation;
  pose.setBasis(btMatrix3x3(btScalar(q[0]), btScalar(q[1]), btScalar(q[2]), btScalar(q[3]),
                            btScalar(q[4]), btScalar(q[5]), btScalar(q[6]), btScalar(q[7]),
                            btScalar(q[8])));
  pose.setOrigin(Bt(start.centre_m) + Bt(u0));
  cylinder_ = std::make_unique<btRigidBody>(
      BodyInfo(c, body_.mass_kg, shape_.get(), inertia, pose, cylinder_friction_));
  // Bullet's default gyroscopic term (implicit, body frame), named here because the wobble
  // depends on it.
  cylinder_->setFlags(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
  cylinder_->setActivationState(DISABLE_DEACTIVATION);
  cylinder_->setLinearVelocity(Bt(start.velocity_mps) + Bt(v0));
  cylinder_->setAngularVelocity(Bt(start.omega_radps));
  world_->addRigidBody(cylinder_.get());
}

BulletCylinderWorld::~BulletCylinderWorld() {
  if (cylinder_) world_->removeRigidBody(cylinder_.get());
  if (ground_) world_->removeRigidBody(ground_.get());
}

btTransform BulletCylinderWorld::GroundTransform(const Vec3d& u_m) const {
  btTransform t;
  t.setIdentity();
  t.setOrigin(Bt(u_m));
  return t;
}

void BulletCylinderWorld::ApplyDrive(std::int64_t n) {
  next_step_ = n;
  if (!kinematic_) {
    // The exact equivalent of a translating base: effective gravity in the base frame.
    const Vec3d a = CylinderDriveAccel(in_, n);
    world_->setGravity(
        btVector3(btScalar(-a[0]), btScalar(-a[1]), btScalar(-(in_.run.gravity_mps2 + a[2]))));
    return;
  }
  // Kinematic: the ground at u_n moving with (u_{n+1} - u_n) / dt (PlaceKinematicGround).
  const Vec3d u = CylinderBaseDisplacement(in_, n), next = CylinderBaseDisplacement(in_, n + 1);
  PlaceKinematicGround(
      ground_.get(), GroundTransform(u),
      GroundTransform({2.0 * u[0] - next[0], 2.0 * u[1] - next[1], 2.0 * u[2] - next[2]}));
}

void BulletCylinderWorld::Step() {
  world_->stepSimulation(btScalar(dt_), 0);
  steps_done_ = next_step_ + 1;
}

CylinderPose BulletCylinderWorld::ReadPose() const {
  const btTransform& t = cylinder_->getCenterOfMassTransform();
  const btMatrix3x3& r = t.getBasis();
  CylinderPose p;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) p.rotation[3 * i + j] = double(r[i][j]);
    p.centre_m[i] = double(t.getOrigin()[i]);
    p.velocity_mps[i] = double(cylinder_->getLinearVelocity()[i]);
    p.omega_radps[i] = double(cylinder_->getAngularVelocity()[i]);
  }
  if (kinematic_) {
    // The base after steps_done_ steps: at u_n, moving as in the step that ended there.
    const std::int64_t n = steps_done_;
    const Vec3d u = CylinderBaseDisplacement(in_, n);
    const Vec3d v = CylinderBaseVelocityAfter(in_, n);
    p.centre_m = Minus(p.centre_m, u);
    p.velocity_mps = Minus(p.velocity_mps, v);
  }
  return p;
}

nlohmann::json BulletCylinderWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, *world_);
  j["cylinder_friction"] = cylinder_friction_;
  j["ground_friction"] = ground_friction_;
  // Bullet multiplies the two bodies' values and clamps the product at 10.
  j["friction_combined"] = std::min(10.0, cylinder_friction_ * ground_friction_);
  j["shape"] = "btCylinderShapeZ";
  j["ground"] = "btStaticPlaneShape z = 0";
  j["contact"] = "convex-plane: the cylinder's support point (exact rim), one a step";
  j["mass_kg"] = body_.mass_kg;
  j["inertia_kgm2"] = {body_.inertia_transverse_kgm2, body_.inertia_transverse_kgm2,
                       body_.inertia_axial_kgm2};
  j["gyroscopic"] = "implicit (body)";
  return j;
}

EngineResult SimulateCylinder(const BulletInput& input) {
  if (input.config.precision != BulletPrecision::kDouble ||
      std::string(CompiledPrecision()) != "double") {
    throw std::invalid_argument("bullet: the cylinder is built in double precision only");
  }
  BulletCylinderWorld world(input);
  static_assert(CylinderWorld<BulletCylinderWorld>);
  return RunCylinderWorld("bullet", input, world);
}

}  // namespace rockbench::bullet
