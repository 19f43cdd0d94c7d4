#include "engines/dart/dart_cylinder_world.h"

#include <algorithm>
#include <cmath>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/CylinderShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/TranslationalJoint.hpp>
#include <dart/simulation/World.hpp>
#include <numbers>
#include <string>

#include "engines/dart/dart_solver.h"

namespace rockbench::dart_engine {
namespace {

Eigen::Vector3d Eig(const Vec3d& v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

struct DartCylinderWorld::Impl {
  const EngineInput& in;
  const DartSettings s;
  const CylinderBodyDef body_def;
  double dt = 0.0;
  bool kinematic = false;
  double mu = 0.0;  // the contact's friction coefficient (the scene's or the settings')
  dart::simulation::WorldPtr world;
  dart::dynamics::SkeletonPtr ground_skel, cylinder_skel;
  dart::dynamics::BodyNode* ground = nullptr;
  dart::dynamics::BodyNode* cylinder = nullptr;
  // The ground's velocity during the last step (kinematic drive), world, m/s.
  Eigen::Vector3d ground_velocity = Eigen::Vector3d::Zero();
  std::unique_ptr<DartContactParams> params;
  // Diagnostics.
  DartStepCounts counts;

  Impl(const EngineInput& input, const DartSettings& settings)
      : in(input), s(settings), body_def(CylinderBodyOf(input)) {}

  void MakeGround();
  void MakeCylinder();
  bool Prism() const { return s.collision == DartCollision::kDart; }
  int Sides() const { return Prism() ? kDartCylinderPrismSides : kDartFclCylinderSlices; }
};

// Ground: a box whose top face is z = 0 in the base frame, much wider than the cylinder; an
// immobile skeleton (never integrated, never pushed by contacts) on a 3-D translational joint
// whose coordinates and rates the kinematic drive sets each step; contacts see its velocity.
void DartCylinderWorld::Impl::MakeGround() {
  using namespace dart::dynamics;
  ground_skel = Skeleton::create("ground");
  TranslationalJoint::Properties jp;
  jp.mName = "ground_xyz";
  auto [joint, body] = ground_skel->createJointAndBodyNodePair<TranslationalJoint>(nullptr, jp);
  const double size = std::max({0.5, body_def.radius_m, body_def.half_height_m});
  auto shape =
      std::make_shared<BoxShape>(Eigen::Vector3d(80.0 * size, 80.0 * size, s.ground_depth_m));
  ShapeNode* node =
      body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape, "ground_shape");
  SetContactCoefficients(node, mu, s.restitution);
  // The box's centre is half its thickness below the body frame, the ground's reference point.
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.translation() = Eigen::Vector3d(0.0, 0.0, -0.5 * s.ground_depth_m);
  node->setRelativeTransform(offset);
  ground_skel->setMobile(false);
  ground = body;
  if (kinematic) {
    ground_velocity = Eig(CylinderBaseVelocityBefore(in));
    joint->setPositions(Eig(CylinderBaseDisplacement(in, 0)));
    joint->setVelocities(ground_velocity);
  }
  world->addSkeleton(ground_skel);
}

// The cylinder: a free body whose frame is its centre with z its axis, its mass and inertia
// CylinderBodyOf's, its collision shape the prism of thin boxes (DART's detector) or DART's
// cylinder (FCL), placed at CylinderStartPose shifted with the ground.
void DartCylinderWorld::Impl::MakeCylinder() {
  using namespace dart::dynamics;
  cylinder_skel = Skeleton::create("cylinder");
  FreeJoint::Properties jp;
  jp.mName = "cylinder_free";
  auto [joint, body] = cylinder_skel->createJointAndBodyNodePair<FreeJoint>(nullptr, jp);
  const double r = body_def.radius_m, h = body_def.half_height_m;
  if (Prism()) {
    // Box k spans the diameters through vertices 2k and 2k + 1 (and the opposite two): half
    // sizes R cos(pi/N) and R sin(pi/N), turned by (2k + 1/2) 2 pi / N about the axis, so its
    // corners are at angles 2k (2 pi / N) and (2k + 1) (2 pi / N) (+ pi) on the circle of radius
    // R, at z = -+h. N / 4 boxes give the N vertices of each face.
    const int n = kDartCylinderPrismSides;
    const double half = std::numbers::pi / n;
    auto shape = std::make_shared<BoxShape>(
        Eigen::Vector3d(2.0 * r * std::cos(half), 2.0 * r * std::sin(half), 2.0 * h));
    for (int k = 0; k < n / 4; ++k) {
      ShapeNode* node = body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(
          shape, "cylinder_prism_" + std::to_string(k));
      Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
      turn.linear() =
          Eigen::AngleAxisd((4 * k + 1) * half, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      node->setRelativeTransform(turn);
      SetContactCoefficients(node, mu, s.restitution);
    }
  } else {
    auto shape = std::make_shared<CylinderShape>(r, 2.0 * h);
    ShapeNode* node =
        body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape, "cylinder_shape");
    SetContactCoefficients(node, mu, s.restitution);
  }
  // Mass and inertia exactly CylinderBodyOf's, about the centre, principal along the body axes.
  const Eigen::Vector3d moments(body_def.inertia_transverse_kgm2, body_def.inertia_transverse_kgm2,
                                body_def.inertia_axial_kgm2);
  body->setInertia(
      Inertia(body_def.mass_kg, Eigen::Vector3d::Zero(), moments.asDiagonal().toDenseMatrix()));
  // No damping: FreeJoint's defaults are zero.
  const CylinderPose start = CylinderStartPose(in);
  const Vec3d u0 = kinematic ? CylinderBaseDisplacement(in, 0) : Vec3d{0, 0, 0};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      pose.linear()(i, j) = start.rotation[static_cast<size_t>(3 * i + j)];
  }
  pose.translation() = Eig(start.centre_m) + Eig(u0);
  joint->setTransform(pose);
  joint->setAngularVelocity(Eig(start.omega_radps));
  joint->setLinearVelocity(Eig(start.velocity_mps) + ground_velocity);
  world->addSkeleton(cylinder_skel);
  cylinder = body;
}

DartCylinderWorld::DartCylinderWorld(const EngineInput& input, const DartSettings& settings)
    : impl_(std::make_unique<Impl>(input, settings)) {
  Impl& m = *impl_;
  CheckDartInput(m.in);
  m.dt = m.in.time_step_s;
  m.kinematic = m.in.drive_kind == DriveKind::kKinematic;
  m.mu = InterfaceFriction(m.in, 0, m.s.friction);
  m.world =
      MakeDartWorld("rockbench_cylinder", m.in, Eigen::Vector3d(0.0, 0.0, -m.in.run.gravity_mps2),
                    m.s, &m.counts.lcp, nullptr);
  m.MakeGround();
  m.MakeCylinder();
  m.params = std::make_unique<DartContactParams>(m.s);
}

DartCylinderWorld::~DartCylinderWorld() = default;

void DartCylinderWorld::ApplyDrive(std::int64_t n) {
  Impl& m = *impl_;
  if (!m.kinematic) {
    // The exact equivalent of a translating base: effective gravity in the base frame.
    const Vec3d a = CylinderDriveAccel(m.in, n);
    m.world->setGravity(Eigen::Vector3d(-a[0], -a[1], -(m.in.run.gravity_mps2 + a[2])));
    return;
  }
  // Kinematic: collision detection sees the ground at u_n, the contact LCP its velocity
  // (u_{n+1} - u_n) / dt (the ground is immobile: World::step leaves both alone).
  const Eigen::Vector3d u0 = Eig(CylinderBaseDisplacement(m.in, n));
  const Eigen::Vector3d u1 = Eig(CylinderBaseDisplacement(m.in, n + 1));
  m.ground_velocity = (u1 - u0) / m.dt;
  auto* joint = m.ground->getParentJoint();
  joint->setPositions(u0);
  joint->setVelocities(m.ground_velocity);
}

void DartCylinderWorld::Step() {
  Impl& m = *impl_;
  m.world->step();
  m.counts.Count(*m.world);
}

CylinderPose DartCylinderWorld::ReadPose() const {
  const Impl& m = *impl_;
  CylinderPose p;
  const Eigen::Matrix3d r = m.cylinder->getWorldTransform().linear();
  const Eigen::Vector3d c = m.cylinder->getCOM();
  const Eigen::Vector3d v = m.cylinder->getCOMLinearVelocity();
  const Eigen::Vector3d w = m.cylinder->getAngularVelocity();
  const Vec3d u = m.kinematic ? CylinderBaseDisplacement(m.in, m.counts.steps) : Vec3d{0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    p.centre_m[k] = c[i] - u[k];
    p.velocity_mps[k] = v[i] - m.ground_velocity[i];
    p.omega_radps[k] = w[i];
    for (int j = 0; j < 3; ++j) p.rotation[static_cast<size_t>(3 * i + j)] = r(i, j);
  }
  return p;
}

nlohmann::json DartCylinderWorld::Diagnostics() const {
  return impl_->counts.Diagnostics();
}

nlohmann::json DartCylinderWorld::Settings() const {
  const Impl& m = *impl_;
  nlohmann::json j = CommonSettings(m.in, m.s, *m.world);
  j["cylinder_shape"] = m.Prism() ? "prism of " + std::to_string(kDartCylinderPrismSides) +
                                        " sides inscribed in " + "the rim (" +
                                        std::to_string(kDartCylinderPrismSides / 4) +
                                        " boxes through the axis; DART's box-box contacts)"
                                  : std::string("CylinderShape (FCL meshes it with ") +
                                        std::to_string(kDartFclCylinderSlices) + " slices)";
  j["cylinder_sides"] = m.Sides();
  // The largest gap between the rim and the polygon's edges, m.
  j["cylinder_rim_gap_m"] = m.body_def.radius_m * (1.0 - std::cos(std::numbers::pi / m.Sides()));
  j["mass_kg"] = m.body_def.mass_kg;
  j["inertia_kgm2"] = {m.body_def.inertia_transverse_kgm2, m.body_def.inertia_transverse_kgm2,
                       m.body_def.inertia_axial_kgm2};
  j["friction_combined"] = m.mu;  // the scene's where finite; DART: the smaller (both equal)
  j["joint"] = "FreeJoint";
  return j;
}

}  // namespace rockbench::dart_engine
