#include "engines/dart/dart_cylinder_world.h"

#include <algorithm>
#include <cmath>
#include <dart/config.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/CylinderShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/TranslationalJoint.hpp>
#include <dart/simulation/World.hpp>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engines/dart/dart_solver.h"

namespace rockbench::dart_engine {
namespace {

Eigen::Vector3d Eig(const Vec3d& v) {
  return {v[0], v[1], v[2]};
}

// The shape's coefficients: friction (DART takes the smaller of a contact's two shapes') and
// restitution (DART multiplies them).
void SetContactCoefficients(dart::dynamics::ShapeNode* node, double mu, double restitution) {
  node->getDynamicsAspect()->setFrictionCoeff(mu);
  node->getDynamicsAspect()->setRestitutionCoeff(restitution);
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
  std::int64_t steps = 0;
  DartLcpCounts lcp;
  std::size_t max_contacts_seen = 0;

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
  // The settings' ranges are the [dart] schema's (dart_settings.cc), checked when the table
  // was resolved; the step is the input's, checked by MakeEngineInput.
  m.dt = m.in.time_step_s;
  m.kinematic = m.in.drive_kind == DriveKind::kKinematic;
  const size_t samples = static_cast<size_t>(m.in.steps) + 1;
  if (m.kinematic && (m.in.drive.ux_m.size() < samples || m.in.drive.uy_m.size() < samples)) {
    throw std::invalid_argument("dart: kinematic drive without ground displacement samples");
  }
  m.mu = InterfaceFriction(m.in, 0, m.s.friction);
  m.world = dart::simulation::World::create("rockbench_cylinder");
  m.world->setTimeStep(m.dt);
  m.world->setGravity(Eigen::Vector3d(0.0, 0.0, -m.in.run.gravity_mps2));
  ConfigureDartSolver(*m.world, m.s, &m.lcp);
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
  ++m.steps;
  m.max_contacts_seen =
      std::max(m.max_contacts_seen, m.world->getLastCollisionResult().getNumContacts());
}

CylinderPose DartCylinderWorld::ReadPose() const {
  const Impl& m = *impl_;
  CylinderPose p;
  const Eigen::Matrix3d r = m.cylinder->getWorldTransform().linear();
  const Eigen::Vector3d c = m.cylinder->getCOM();
  const Eigen::Vector3d v = m.cylinder->getCOMLinearVelocity();
  const Eigen::Vector3d w = m.cylinder->getAngularVelocity();
  const Vec3d u = m.kinematic ? CylinderBaseDisplacement(m.in, m.steps) : Vec3d{0, 0, 0};
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
  const Impl& m = *impl_;
  nlohmann::json j;
  j["steps"] = m.steps;
  j["max_contacts"] = m.max_contacts_seen;
  j["lcp_solves"] = m.lcp.primary_calls;
  j["lcp_primary_failures"] = m.lcp.primary_failures;
  j["lcp_fallback_solves"] = m.lcp.fallback_calls;
  j["lcp_fallback_failures"] = m.lcp.fallback_failures;
  return j;
}

nlohmann::json DartCylinderWorld::Settings() const {
  const Impl& m = *impl_;
  nlohmann::json j;
  j["dart_version"] = DART_VERSION;
  j["drive"] = m.kinematic ? "kinematic" : "inertial";
  j["time_step_s"] = m.dt;
  j["output_interval_s"] = m.in.run.output_interval_s;
  j["collision"] = DartCollisionName(m.s.collision);
  j["collision_detector"] = m.world->getConstraintSolver()->getCollisionDetector()->getType();
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
  j["lcp_solver"] = DartLcpSolverName(m.s.lcp_solver);
  j["pgs_fallback"] = m.s.lcp_solver == DartLcpSolver::kDantzig && m.s.pgs_fallback;
  j["pgs_iterations"] = m.s.pgs_iterations;
  j["restitution"] = m.s.restitution;
  j["restitution_combined"] = m.s.restitution * m.s.restitution;  // DART: product
  j["friction"] = m.s.friction;
  j["friction_combined"] = m.mu;  // the scene's where finite; DART: the smaller (both equal)
  DartContactParams::Write(&j);
  j["max_contacts"] = m.s.max_contacts;
  j["ground_depth_m"] = m.s.ground_depth_m;
  j["kinematic_highpass_hz"] = m.in.kinematic_highpass_hz;
  j["joint"] = "FreeJoint";
  j["integrator"] = "semi-implicit Euler (DART World::step)";
  return j;
}

}  // namespace rockbench::dart_engine
