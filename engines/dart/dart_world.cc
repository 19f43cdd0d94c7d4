#include "engines/dart/dart_world.h"

#include <algorithm>
#include <cmath>
#include <dart/collision/CollisionFilter.hpp>
#include <dart/collision/CollisionObject.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/PlanarJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/TranslationalJoint2D.hpp>
#include <dart/simulation/World.hpp>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "engines/dart/dart_solver.h"
#include "scene/stack_pose.h"

namespace rockbench::dart_engine {

const char* DartCollisionName(DartCollision c) {
  return c == DartCollision::kFcl ? "fcl" : "dart";
}

const char* DartLcpSolverName(DartLcpSolver s) {
  return s == DartLcpSolver::kPgs ? "pgs" : "dantzig";
}

namespace {

// Friction from the scene. DART 6.12 has no coefficient per pair of shapes: a contact takes the
// smaller of its two shapes' coefficients (ContactConstraint). Each interface k (block k + 1 on
// its support) must get mu[k]; a block meets its support with its base and the block above with
// its top. One shape per block gets there unless an interface's coefficient is below both its
// neighbours' (then no single value of the block below it can be the smaller at both of its
// faces): that block below is given a second shape, its top, with its own coefficient.
struct ShapeFrictions {
  double ground = 0.0;
  std::vector<double> base;  // per block: its (only, or base) shape's coefficient
  std::vector<double> top;   // per block: its top shape's coefficient; NaN: no top shape
};

// Coefficients for the shapes such that min(ground, base[0]) = mu[0] and, for k >= 1,
// min(upper face of block k, base[k]) = mu[k], the upper face being top[k - 1] when block k has a
// top shape and base[k - 1] otherwise. Equal coefficients everywhere give every shape that value.
ShapeFrictions AssignShapeFrictions(const std::vector<double>& mu) {
  const size_t n = mu.size();
  ShapeFrictions f;
  f.ground = mu[0];
  f.base.assign(n, 0.0);
  f.top.assign(n, std::numeric_limits<double>::quiet_NaN());
  double below = f.ground;  // the support's upper face; at least mu[k] at each k
  for (size_t k = 0; k < n; ++k) {
    // One shape: at least both its interfaces' coefficients, and the smaller at this one.
    const double one = k + 1 < n ? std::max(mu[k], mu[k + 1]) : mu[k];
    if (below == mu[k] || one == mu[k]) {
      f.base[k] = one;
      below = one;
    } else {
      f.base[k] = mu[k];
      f.top[k] = mu[k + 1];
      below = mu[k + 1];
    }
  }
  return f;
}

// The world's collision filter, then only the listed pairs of shapes (a block's base with its
// support's upper face): with a block's top shape, its base and top must each meet one
// neighbour only.
class ShapePairFilter final : public dart::collision::CollisionFilter {
 public:
  explicit ShapePairFilter(std::shared_ptr<dart::collision::CollisionFilter> inner)
      : inner_(std::move(inner)) {}
  void Allow(const dart::dynamics::ShapeFrame* a, const dart::dynamics::ShapeFrame* b) {
    allowed_.insert(Key(a, b));
  }
  bool ignoresCollision(const dart::collision::CollisionObject* a,
                        const dart::collision::CollisionObject* b) const override {
    if (inner_ && inner_->ignoresCollision(a, b)) return true;
    return allowed_.count(Key(a->getShapeFrame(), b->getShapeFrame())) == 0;
  }

 private:
  using Pair = std::pair<const void*, const void*>;
  static Pair Key(const void* a, const void* b) {
    return std::less<const void*>()(a, b) ? Pair(a, b) : Pair(b, a);
  }
  std::shared_ptr<dart::collision::CollisionFilter> inner_;
  std::set<Pair> allowed_;
};

double OutOfPlaneRotation(const Eigen::Matrix3d& r) {
  return std::max({std::abs(r(2, 0)), std::abs(r(2, 1)), std::abs(r(0, 2)), std::abs(r(1, 2))});
}

void ReadBody(const dart::dynamics::BodyNode& body, BodyReadout* out) {
  const Eigen::Isometry3d& t = body.getWorldTransform();
  const Eigen::Vector3d com = body.getCOM();
  const Eigen::Vector3d v = body.getCOMLinearVelocity();
  const Eigen::Vector3d w = body.getAngularVelocity();
  out->x_m = com.x();
  out->y_m = com.y();
  out->cos_phi = t.linear()(0, 0);
  out->sin_phi = t.linear()(1, 0);
  out->vx_mps = v.x();
  out->vy_mps = v.y();
  out->w_radps = w.z();
}

}  // namespace

struct DartWorld::Impl {
  const EngineInput& in;
  DartSettings s;
  double dt = 0.0;
  bool kinematic = false;
  dart::simulation::WorldPtr world;
  dart::dynamics::SkeletonPtr ground_skel;
  dart::dynamics::BodyNode* ground = nullptr;
  // Per block, bottom first: its skeleton, its body and its initial out-of-plane position.
  std::vector<dart::dynamics::SkeletonPtr> skels;
  std::vector<dart::dynamics::BodyNode*> blocks;
  std::vector<double> z;
  // The ground's shape; per block, its base shape and its top shape (null: the base is its top
  // too; ShapeFrictions).
  dart::dynamics::ShapeNode* ground_shape = nullptr;
  std::vector<dart::dynamics::ShapeNode*> base_shapes, top_shapes;
  // The process-wide contact parameters, taken once the world is built.
  std::unique_ptr<DartContactParams> params;
  // Diagnostics.
  DartStepCounts counts;

  Impl(const EngineInput& input, const DartSettings& settings) : in(input), s(settings) {}

  // The world with the settings' LCP solvers (counted) and collision detector; its solver.
  dart::constraint::BoxedLcpConstraintSolver* MakeWorld();
  // Ground: a box whose top face is y = 0 in the base frame, much wider than the stack (`size`
  // the largest half size of a block, `depth` its largest depth, m). An immobile skeleton
  // (never integrated, never pushed by contacts) on a 2-D translational joint whose coordinates
  // and rates the kinematic drive sets each step; contacts see its velocity.
  void MakeGround(double ground_mu, double size, double depth);
  // Blocks, placed by the pivot chain in the base frame then shifted with the ground, with
  // their shapes' friction coefficients (ShapeFrictions).
  void MakeBlocks(const std::vector<double>& base_mu, const std::vector<double>& top_mu);
  // Which pairs may touch: neighbours only, and a block's base only its support's upper face.
  void FilterContacts(dart::constraint::BoxedLcpConstraintSolver* solver);
  // Block `name` (its skeleton into *skel) with its base shape of friction `base_mu` and, when
  // top_mu is a number, a top shape of friction top_mu (the same box).
  dart::dynamics::BodyNode* MakeBlock(const std::string& name, const BlockDef& def,
                                      const PlanarPose& pose, double ux0, double uy0, double gvx,
                                      double gvy, double base_mu, double top_mu,
                                      dart::dynamics::SkeletonPtr* skel);
};

dart::dynamics::BodyNode* DartWorld::Impl::MakeBlock(const std::string& name, const BlockDef& def,
                                                     const PlanarPose& pose, double ux0, double uy0,
                                                     double gvx, double gvy, double base_mu,
                                                     double top_mu,
                                                     dart::dynamics::SkeletonPtr* skel) {
  using namespace dart::dynamics;
  *skel = Skeleton::create(name);
  PlanarJoint::Properties jp;
  jp.mName = name + "_planar";
  auto [joint, body] = (*skel)->createJointAndBodyNodePair<PlanarJoint>(nullptr, jp);
  joint->setXYPlane();
  auto shape = std::make_shared<BoxShape>(Eigen::Vector3d(def.width_m, def.height_m, def.depth_m));
  ShapeNode* node =
      body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape, name + "_shape");
  SetContactCoefficients(node, base_mu, s.restitution);
  base_shapes.push_back(node);
  ShapeNode* top = nullptr;
  if (!std::isnan(top_mu)) {
    top = body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape, name + "_top_shape");
    SetContactCoefficients(top, top_mu, s.restitution);
  }
  top_shapes.push_back(top);
  body->setInertia(
      Inertia(def.mass_kg, Eigen::Vector3d::Zero(), shape->computeInertia(def.mass_kg)));
  // No damping, no spring: PlanarJoint's defaults are zero; the coordinates are (x, y, phi) of
  // the body frame (the box centre) in the world's x-y plane, their rates the world velocities.
  joint->setPositions(Eigen::Vector3d(pose.x_m + ux0, pose.y_m + uy0, pose.phi_rad));
  joint->setVelocities(Eigen::Vector3d(pose.vx_mps + gvx, pose.vy_mps + gvy, pose.w_radps));
  world->addSkeleton(*skel);
  return body;
}

dart::constraint::BoxedLcpConstraintSolver* DartWorld::Impl::MakeWorld() {
  dart::constraint::BoxedLcpConstraintSolver* solver = nullptr;
  world = MakeDartWorld("rockbench", in, Eigen::Vector3d(0.0, -in.run.gravity_mps2, 0.0), s,
                        &counts.lcp, &solver);
  return solver;
}

void DartWorld::Impl::MakeGround(double ground_mu, double size, double depth) {
  using namespace dart::dynamics;
  ground_skel = Skeleton::create("ground");
  TranslationalJoint2D::Properties jp;
  jp.mName = "ground_xy";
  auto [joint, body] = ground_skel->createJointAndBodyNodePair<TranslationalJoint2D>(nullptr, jp);
  joint->setXYPlane();
  auto shape = std::make_shared<BoxShape>(
      Eigen::Vector3d(80.0 * size, s.ground_depth_m, 2.0 * (depth + 1.0)));
  ShapeNode* node =
      body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape, "ground_shape");
  SetContactCoefficients(node, ground_mu, s.restitution);
  ground_shape = node;
  // The box's centre is half its thickness below the body frame, the ground's reference point.
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.translation() = Eigen::Vector3d(0.0, -0.5 * s.ground_depth_m, 0.0);
  node->setRelativeTransform(offset);
  ground_skel->setMobile(false);
  ground = body;
  if (kinematic) {
    joint->setPositions(Eigen::Vector2d(in.drive.ux_m.front(), in.drive.uy_m.front()));
    joint->setVelocities(Eigen::Vector2d(in.drive.ux0_mps, in.drive.uy0_mps));
  }
  world->addSkeleton(ground_skel);
}

void DartWorld::Impl::MakeBlocks(const std::vector<double>& base_mu,
                                 const std::vector<double>& top_mu) {
  const int n = in.block_count();
  const StackPlacement place = PlaceStack(in.blocks, in.initial);
  const double ux0 = kinematic ? in.drive.ux_m.front() : 0.0;
  const double uy0 = kinematic ? in.drive.uy_m.front() : 0.0;
  const double gvx = kinematic ? in.drive.ux0_mps : 0.0;
  const double gvy = kinematic ? in.drive.uy0_mps : 0.0;
  skels.resize(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    blocks.push_back(MakeBlock(std::string("block") + std::to_string(k + 1), in.blocks[k],
                               place.blocks[k], ux0, uy0, gvx, gvy, base_mu[k], top_mu[k],
                               &skels[k]));
    z.push_back(blocks[k]->getCOM().z());
  }
}

void DartWorld::Impl::FilterContacts(dart::constraint::BoxedLcpConstraintSolver* solver) {
  const int n = in.block_count();
  if (n >= 3) {
    // Three or more blocks: contacts between neighbours only (block 1 and the ground, block k
    // and block k - 1), as the model: every other pair on the collision filter's blacklist. (Two
    // blocks keep block 2 and the ground, as before issue 23.)
    auto& option = solver->getCollisionOption();
    auto filter =
        std::dynamic_pointer_cast<dart::collision::BodyNodeCollisionFilter>(option.collisionFilter);
    if (!filter) {
      filter = std::make_shared<dart::collision::BodyNodeCollisionFilter>();
      option.collisionFilter = filter;
    }
    for (int k = 1; k < n; ++k) filter->addBodyNodePairToBlackList(ground, blocks[k]);
    for (int i = 0; i < n; ++i) {
      for (int j = i + 2; j < n; ++j) filter->addBodyNodePairToBlackList(blocks[i], blocks[j]);
    }
  }
  if (std::any_of(top_shapes.begin(), top_shapes.end(), [](auto* p) { return p != nullptr; })) {
    // A block with a top shape: each block's base meets its support's upper face only (a top
    // shape needs three or more blocks, whose other pairs the blacklist above leaves out).
    auto& option = solver->getCollisionOption();
    auto filter = std::make_shared<ShapePairFilter>(option.collisionFilter);
    filter->Allow(ground_shape, base_shapes[0]);
    for (int k = 1; k < n; ++k) {
      filter->Allow(top_shapes[k - 1] ? top_shapes[k - 1] : base_shapes[k - 1], base_shapes[k]);
    }
    option.collisionFilter = filter;
  }
}

DartWorld::DartWorld(const EngineInput& input, const DartSettings& settings)
    : impl_(std::make_unique<Impl>(input, settings)) {
  Impl& m = *impl_;
  CheckDartInput(m.in);
  m.dt = m.in.time_step_s;
  m.kinematic = m.in.drive_kind == DriveKind::kKinematic;
  dart::constraint::BoxedLcpConstraintSolver* solver = m.MakeWorld();

  // Friction from the scene: each interface's coefficient (the block's where finite, else the
  // settings'), given by the shapes' coefficients under DART's rule (ShapeFrictions).
  const int n = m.in.block_count();
  std::vector<double> mu(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) mu[k] = InterfaceFriction(m.in, k, m.s.friction);
  const ShapeFrictions friction = AssignShapeFrictions(mu);
  double size = 0.5, depth = 0.0;  // the largest half size and depth of a block
  for (const BlockDef& def : m.in.blocks) {
    size = std::max({size, 0.5 * def.width_m, 0.5 * def.height_m});
    depth = std::max(depth, def.depth_m);
  }

  m.MakeGround(friction.ground, size, depth);
  m.MakeBlocks(friction.base, friction.top);
  m.FilterContacts(solver);

  m.params = std::make_unique<DartContactParams>(m.s);
}

DartWorld::~DartWorld() = default;

void DartWorld::ApplyDrive(std::int64_t n) {
  Impl& m = *impl_;
  const size_t i = static_cast<size_t>(n);
  if (!m.kinematic) {
    const double ax = m.in.drive.ax_mps2.empty() ? 0.0 : m.in.drive.ax_mps2[i];
    const double ay = m.in.drive.ay_mps2.empty() ? 0.0 : m.in.drive.ay_mps2[i];
    // The exact equivalent of a translating base: effective gravity in the base frame.
    m.world->setGravity(Eigen::Vector3d(-ax, -(m.in.run.gravity_mps2 + ay), 0.0));
    return;
  }
  // Kinematic: collision detection sees the ground at u_n, the contact LCP its velocity
  // (u_{n+1} - u_n) / dt (the ground is immobile: World::step leaves both alone).
  const auto& ux = m.in.drive.ux_m;
  const auto& uy = m.in.drive.uy_m;
  auto* joint = m.ground->getParentJoint();
  joint->setPositions(Eigen::Vector2d(ux[i], uy[i]));
  joint->setVelocities(Eigen::Vector2d((ux[i + 1] - ux[i]) / m.dt, (uy[i + 1] - uy[i]) / m.dt));
}

void DartWorld::Step() {
  Impl& m = *impl_;
  m.world->step();
  m.counts.Count(*m.world);
}

StepReadout DartWorld::Read(std::int64_t n) const {
  const Impl& m = *impl_;
  StepReadout s(m.in.block_count());
  s.t_s = static_cast<double>(n) * m.dt;
  double oop_m = 0.0, oop_rad = 0.0;
  for (size_t k = 0; k < m.blocks.size(); ++k) {
    ReadBody(*m.blocks[k], &s.blocks[k]);
    const double dz = std::abs(m.blocks[k]->getCOM().z() - m.z[k]);
    const double tilt = OutOfPlaneRotation(m.blocks[k]->getWorldTransform().linear());
    oop_m = k == 0 ? dz : std::max(oop_m, dz);  // block 1's own value first, as before
    oop_rad = k == 0 ? tilt : std::max(oop_rad, tilt);
  }
  s.out_of_plane_m = oop_m;
  s.out_of_plane_rad = oop_rad;
  ReadBaseMotion(m.in, n, &s);
  return s;
}

std::size_t DartWorld::LastContactCount() const {
  return impl_->world->getLastCollisionResult().getNumContacts();
}

nlohmann::json DartWorld::Diagnostics() const {
  return impl_->counts.Diagnostics();
}

nlohmann::json DartWorld::Settings() const {
  const Impl& m = *impl_;
  nlohmann::json j = CommonSettings(m.in, m.s, *m.world);
  j["substeps_per_sample"] = std::max(1.0, std::round(m.in.run.output_interval_s / m.dt));
  j["friction_combined"] = m.s.friction;  // DART: the smaller of the two
  j["joint"] = "PlanarJoint (x-y plane) per block";
  // Three or more blocks: contacts between neighbours only (two: block 2 and the ground too).
  if (m.blocks.size() >= 3) j["collision_pairs"] = "neighbours";
  // Friction from the scene: each interface's coefficient as DART combines the shapes' values
  // in force (the smaller), block 1 on the ground first.
  if (HasFiniteFriction(m.in)) {
    auto mu_of = [](const dart::dynamics::ShapeNode* node) {
      return node->getDynamicsAspect()->getFrictionCoeff();
    };
    nlohmann::json mu = nlohmann::json::array();
    for (size_t k = 0; k < m.blocks.size(); ++k) {
      const dart::dynamics::ShapeNode* face =
          k == 0 ? m.ground_shape
                 : (m.top_shapes[k - 1] ? m.top_shapes[k - 1] : m.base_shapes[k - 1]);
      mu.push_back(std::min(mu_of(face), mu_of(m.base_shapes[k])));
    }
    j["interface_friction"] = mu;
  }
  return j;
}

}  // namespace rockbench::dart_engine
