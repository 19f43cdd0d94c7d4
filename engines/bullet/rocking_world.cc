#include "engines/bullet/rocking_world.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "scene/stack_pose.h"

namespace rockbench::bullet {
namespace {

btTransform PoseTransform(const PlanarPose& p, double ux, double uy, double z) {
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(btScalar(p.x_m + ux), btScalar(p.y_m + uy), btScalar(z)));
  t.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(p.phi_rad)));
  return t;
}

void ReadBody(const btRigidBody& body, BodyReadout* out) {
  const btTransform& t = body.getCenterOfMassTransform();
  const btMatrix3x3& r = t.getBasis();
  out->x_m = double(t.getOrigin().x());
  out->y_m = double(t.getOrigin().y());
  out->cos_phi = double(r[0][0]);
  out->sin_phi = double(r[1][0]);
  out->vx_mps = double(body.getLinearVelocity().x());
  out->vy_mps = double(body.getLinearVelocity().y());
  out->w_radps = double(body.getAngularVelocity().z());
}

// The broadphase's pair filter of a stack of three or more blocks: the default group and mask
// test, then only neighbours meet. Every body's user index is its place in the stack (the
// ground 0, block k k), so two bodies are neighbours when their indices differ by one.
struct NeighbourFilter : btOverlapFilterCallback {
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override {
    const bool collides = (p0->m_collisionFilterGroup & p1->m_collisionFilterMask) != 0 &&
                          (p1->m_collisionFilterGroup & p0->m_collisionFilterMask) != 0;
    if (!collides) return false;
    const auto* a = static_cast<const btCollisionObject*>(p0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(p1->m_clientObject);
    const int gap = a->getUserIndex() - b->getUserIndex();
    return gap == 1 || gap == -1;
  }
};

// Bullet's contact-added callback (process-wide; Bullet calls it only for a pair with a body
// flagged CF_CUSTOM_MATERIAL_CALLBACK): a contact between two neighbours of the stack (user
// indices differing by one) takes the upper body's base friction, which its user pointer holds
// (RockingWorld::base_friction_), in place of Bullet's product of the two bodies' values.
// Infinite there, or any other pair: Bullet's own combination stays.
bool SetPairFriction(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int,
                     const btCollisionObjectWrapper* w1, int, int) {
  const btCollisionObject* a = w0->getCollisionObject();
  const btCollisionObject* b = w1->getCollisionObject();
  const btCollisionObject* upper = a->getUserIndex() > b->getUserIndex() ? a : b;
  const btCollisionObject* lower = upper == a ? b : a;
  if (upper->getUserIndex() - lower->getUserIndex() != 1) return false;
  const auto* mu = static_cast<const double*>(upper->getUserPointer());
  if (mu != nullptr && std::isfinite(*mu)) cp.m_combinedFriction = btScalar(*mu);
  return false;
}

// Installs SetPairFriction as Bullet's contact-added callback, once per process.
void InstallPairFriction() {
  static std::once_flag once;
  std::call_once(once, [] { gContactAddedCallback = SetPairFriction; });
}

// Largest out-of-plane rotation component of a basis (0 for a rotation about z alone).
double OutOfPlaneRotation(const btMatrix3x3& r) {
  return std::max({std::abs(double(r[2][0])), std::abs(double(r[2][1])), std::abs(double(r[0][2])),
                   std::abs(double(r[1][2]))});
}

}  // namespace

const char* CompiledPrecision() {
  return sizeof(btScalar) == sizeof(double) ? "double" : "float";
}

RockingWorld::RockingWorld(const BulletInput& input)
    : in_(input),
      dynamics_(input, btVector3(0, btScalar(-input.run.gravity_mps2), 0)),
      world_(dynamics_.world()) {
  const BulletConfig& c = in_.config;
  dt_ = in_.time_step_s;
  kinematic_ = in_.drive_kind == DriveKind::kKinematic;

  const int n = in_.block_count();
  if (n >= 3) {
    filter_ = std::make_unique<NeighbourFilter>();
    world_->getPairCache()->setOverlapFilterCallback(filter_.get());
  }

  // The ground's size: much wider than the largest block (one block: as if block 2 were 0).
  double size = 0.5, depth = 0.0;
  for (const BlockDef& def : in_.blocks) {
    size = std::max({size, 0.5 * def.width_m, 0.5 * def.height_m});
    depth = std::max(depth, def.depth_m);
  }

  // Ground: a box whose top face is y = 0 in the base frame, much wider than the stack.
  ground_half_depth_m_ = 0.5 * c.ground_depth_m;
  ground_shape_ = std::make_unique<btBoxShape>(
      btVector3(btScalar(40.0 * size), btScalar(ground_half_depth_m_), btScalar(depth + 1.0)));
  ground_shape_->setMargin(btScalar(c.margin_m));
  const double ux0 = kinematic_ ? in_.drive.ux_m.front() : 0.0;
  const double uy0 = kinematic_ ? in_.drive.uy_m.front() : 0.0;
  ground_ = MakeGround(in_, ground_shape_.get(), GroundTransform(ux0, uy0), c.friction);
  ground_->setUserIndex(0);
  world_->addRigidBody(ground_.get());

  // Blocks, placed by the pivot chain in the base frame then shifted with the ground.
  const StackPlacement place = PlaceStack(in_.blocks, in_.initial);
  const double gvx = kinematic_ ? in_.drive.ux0_mps : 0.0;
  const double gvy = kinematic_ ? in_.drive.uy0_mps : 0.0;
  auto make_block = [&](const BlockDef& def, const PlanarPose& pose, double z, int index,
                        std::unique_ptr<btBoxShape>* shape) {
    *shape = std::make_unique<btBoxShape>(btVector3(
        btScalar(0.5 * def.width_m), btScalar(0.5 * def.height_m), btScalar(0.5 * def.depth_m)));
    (*shape)->setMargin(btScalar(c.margin_m));
    btVector3 inertia(0, 0, 0);
    (*shape)->calculateLocalInertia(btScalar(def.mass_kg), inertia);
    auto body = std::make_unique<btRigidBody>(BodyInfo(
        c, def.mass_kg, shape->get(), inertia, PoseTransform(pose, ux0, uy0, z), c.friction));
    body->setUserIndex(index);  // its place in the stack, for NeighbourFilter
    // Planar motion: translation in x-y, rotation about z only.
    body->setLinearFactor(btVector3(1, 1, 0));
    body->setAngularFactor(btVector3(0, 0, 1));
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setLinearVelocity(btVector3(btScalar(pose.vx_mps + gvx), btScalar(pose.vy_mps + gvy), 0));
    body->setAngularVelocity(btVector3(0, 0, btScalar(pose.w_radps)));
    world_->addRigidBody(body.get());
    return body;
  };
  // Bottom first: the solver's order of bodies, and so of contacts, is the order they are added.
  z_.assign(static_cast<size_t>(n), 0.0);
  shapes_.resize(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    blocks_.push_back(make_block(in_.blocks[k], place.blocks[k], z_[k], k + 1, &shapes_[k]));
  }
  // Friction from the scene: the contacts of a block with a finite friction and its support take
  // that coefficient exactly (SetPairFriction); without one, nothing changes.
  if (HasFiniteFriction(in_)) {
    InstallPairFriction();
    base_friction_.resize(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
      base_friction_[k] = in_.blocks[k].friction;
      btRigidBody& body = *blocks_[k];
      body.setUserPointer(&base_friction_[k]);
      if (std::isfinite(base_friction_[k])) {
        body.setCollisionFlags(body.getCollisionFlags() |
                               btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      }
    }
  }
}

RockingWorld::~RockingWorld() {
  for (auto it = blocks_.rbegin(); it != blocks_.rend(); ++it) world_->removeRigidBody(it->get());
  if (ground_) world_->removeRigidBody(ground_.get());
}

btTransform RockingWorld::GroundTransform(double ux, double uy) const {
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(btScalar(ux), btScalar(uy - ground_half_depth_m_), 0));
  return t;
}

void RockingWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  if (!kinematic_) {
    const double ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
    const double ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
    // The exact equivalent of a translating base: effective gravity in the base frame.
    world_->setGravity(btVector3(btScalar(-ax), btScalar(-(in_.run.gravity_mps2 + ay)), 0));
    return;
  }
  // Kinematic: the ground at u_n moving with (u_{n+1} - u_n) / dt (PlaceKinematicGround).
  const double ux = in_.drive.ux_m[i], uy = in_.drive.uy_m[i];
  const double nx = in_.drive.ux_m[i + 1], ny = in_.drive.uy_m[i + 1];
  PlaceKinematicGround(ground_.get(), GroundTransform(ux, uy),
                       GroundTransform(2.0 * ux - nx, 2.0 * uy - ny));
}

void RockingWorld::Step() {
  world_->stepSimulation(btScalar(dt_), 0);
}

StepReadout RockingWorld::Read(std::int64_t n) const {
  StepReadout s(static_cast<int>(blocks_.size()));
  s.t_s = static_cast<double>(n) * dt_;
  double oop_m = 0.0, oop_rad = 0.0;
  for (size_t k = 0; k < blocks_.size(); ++k) {
    const btRigidBody& body = *blocks_[k];
    ReadBody(body, &s.blocks[k]);
    const btTransform& t = body.getCenterOfMassTransform();
    const double dz = std::abs(double(t.getOrigin().z()) - z_[k]);
    const double tilt = OutOfPlaneRotation(t.getBasis());
    oop_m = k == 0 ? dz : std::max(oop_m, dz);  // block 1's own value first, as before
    oop_rad = k == 0 ? tilt : std::max(oop_rad, tilt);
  }
  s.out_of_plane_m = oop_m;
  s.out_of_plane_rad = oop_rad;
  ReadBaseMotion(in_, n, &s);
  return s;
}

nlohmann::json RockingWorld::Settings() const {
  const BulletConfig& c = in_.config;
  nlohmann::json j = CommonSettings(in_, *world_);
  // Bullet multiplies the two bodies' values; friction products are clamped at 10.
  j["friction_combined"] = std::min(10.0, c.friction * c.friction);
  j["ground_depth_m"] = c.ground_depth_m;
  // Three or more blocks: only neighbours collide (one and two blocks: every pair, as before).
  if (filter_) j["collision_filter"] = "neighbours";
  // Friction from the scene: each interface's coefficient, block 1 on the ground first.
  if (!base_friction_.empty()) {
    nlohmann::json mu = nlohmann::json::array();
    for (int k = 0; k < block_count(); ++k) {
      mu.push_back(InterfaceFriction(in_, k, BulletCombinedFriction(c.friction)));
    }
    j["interface_friction"] = mu;
  }
  return j;
}

}  // namespace rockbench::bullet
