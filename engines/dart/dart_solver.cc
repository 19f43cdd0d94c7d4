#include "engines/dart/dart_solver.h"

#include <algorithm>
#include <cmath>
#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/collision/fcl/FCLCollisionDetector.hpp>
#include <dart/config.hpp>
#include <dart/constraint/ContactConstraint.hpp>
#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockbench::dart_engine {
namespace {

// DART's contact parameters are static members of ContactConstraint: one set per process.
// Worlds alive at the same time must agree on them (checked under this lock); while any world
// lives, nobody changes them, so the steps read them without a lock.
struct ContactParams {
  double erp = 0.0, allowance = 0.0, max_erv = 0.0, cfm = 0.0;
  bool operator==(const ContactParams&) const = default;
};
std::mutex g_contact_mutex;
int g_live_worlds = 0;
ContactParams g_live_params;

// Forwards to a boxed LCP solver and counts its calls and failures (a failure of the primary
// solver is when DART hands the problem to the fallback).
class CountingLcpSolver final : public dart::constraint::BoxedLcpSolver {
 public:
  CountingLcpSolver(std::shared_ptr<dart::constraint::BoxedLcpSolver> inner, std::int64_t* calls,
                    std::int64_t* failures)
      : inner_(std::move(inner)), calls_(calls), failures_(failures) {}

  const std::string& getType() const override {
    static const std::string type = "rockbench::CountingLcpSolver";
    return type;
  }
  bool solve(int n, double* A, double* x, double* b, int nub, double* lo, double* hi, int* findex,
             bool earlyTermination) override {
    ++*calls_;
    const bool ok = inner_->solve(n, A, x, b, nub, lo, hi, findex, earlyTermination);
    if (!ok) ++*failures_;
    return ok;
  }
  // Debian's libdart 6.12 is built without NDEBUG: its BoxedLcpSolver has the debug-only
  // virtual canSolve, which its asserts call. Declared whatever our NDEBUG says, so that this
  // class's vtable has the slot the library expects.
#ifndef NDEBUG
  bool canSolve(int n, const double* A) override {
    return inner_->canSolve(n, A);
  }
#else
  virtual bool canSolve(int /*n*/, const double* /*A*/) {
    return true;
  }
#endif

 private:
  std::shared_ptr<dart::constraint::BoxedLcpSolver> inner_;
  std::int64_t* calls_;
  std::int64_t* failures_;
};

}  // namespace

dart::constraint::BoxedLcpConstraintSolver* ConfigureDartSolver(dart::simulation::World& world,
                                                                const DartSettings& s,
                                                                DartLcpCounts* counts) {
  auto* solver =
      dynamic_cast<dart::constraint::BoxedLcpConstraintSolver*>(world.getConstraintSolver());
  if (solver == nullptr) throw std::logic_error("dart: the world's solver is not a boxed LCP");
  dart::constraint::PgsBoxedLcpSolver::Option pgs_option;
  pgs_option.mMaxIteration = s.pgs_iterations;
  auto make_pgs = [&] {
    auto pgs = std::make_shared<dart::constraint::PgsBoxedLcpSolver>();
    pgs->setOption(pgs_option);
    return pgs;
  };
  std::shared_ptr<dart::constraint::BoxedLcpSolver> primary;
  if (s.lcp_solver == DartLcpSolver::kPgs) {
    primary = make_pgs();
  } else {
    primary = std::make_shared<dart::constraint::DantzigBoxedLcpSolver>();
  }
  solver->setBoxedLcpSolver(std::make_shared<CountingLcpSolver>(primary, &counts->primary_calls,
                                                                &counts->primary_failures));
  if (s.lcp_solver == DartLcpSolver::kDantzig && s.pgs_fallback) {
    solver->setSecondaryBoxedLcpSolver(std::make_shared<CountingLcpSolver>(
        make_pgs(), &counts->fallback_calls, &counts->fallback_failures));
  } else {
    solver->setSecondaryBoxedLcpSolver(nullptr);
  }
  if (s.collision == DartCollision::kFcl) {
    auto fcl = dart::collision::FCLCollisionDetector::create();
    fcl->setPrimitiveShapeType(dart::collision::FCLCollisionDetector::PRIMITIVE);
    fcl->setContactPointComputationMethod(dart::collision::FCLCollisionDetector::DART);
    solver->setCollisionDetector(fcl);
  } else {
    solver->setCollisionDetector(dart::collision::DARTCollisionDetector::create());
  }
  solver->getCollisionOption().maxNumContacts = static_cast<std::size_t>(s.max_contacts);
  return solver;
}

DartContactParams::DartContactParams(const DartSettings& s) {
  const ContactParams p{s.erp, s.error_allowance_m, s.max_erv_mps, s.cfm};
  std::lock_guard<std::mutex> lock(g_contact_mutex);
  if (g_live_worlds > 0 && !(p == g_live_params)) {
    throw std::invalid_argument(
        "dart: contact erp, error allowance, max erv and cfm are process-wide in DART 6 "
        "(ContactConstraint statics); another DART world alive in this process uses other "
        "values");
  }
  if (g_live_worlds == 0) {
    using dart::constraint::ContactConstraint;
    ContactConstraint::setErrorReductionParameter(p.erp);
    ContactConstraint::setErrorAllowance(p.allowance);
    ContactConstraint::setMaxErrorReductionVelocity(p.max_erv);
    ContactConstraint::setConstraintForceMixing(p.cfm);
    g_live_params = p;
  }
  ++g_live_worlds;
}

DartContactParams::~DartContactParams() {
  std::lock_guard<std::mutex> lock(g_contact_mutex);
  --g_live_worlds;
}

void DartContactParams::Write(nlohmann::json* j) {
  using dart::constraint::ContactConstraint;
  (*j)["erp"] = ContactConstraint::getErrorReductionParameter();
  (*j)["error_allowance_m"] = ContactConstraint::getErrorAllowance();
  (*j)["max_erv_mps"] = ContactConstraint::getMaxErrorReductionVelocity();
  (*j)["cfm"] = ContactConstraint::getConstraintForceMixing();
}

dart::simulation::WorldPtr MakeDartWorld(const std::string& name, const EngineInput& input,
                                         const Eigen::Vector3d& gravity_mps2,
                                         const DartSettings& settings, DartLcpCounts* counts,
                                         dart::constraint::BoxedLcpConstraintSolver** solver) {
  dart::simulation::WorldPtr world = dart::simulation::World::create(name);
  world->setTimeStep(input.time_step_s);
  world->setGravity(gravity_mps2);
  dart::constraint::BoxedLcpConstraintSolver* s = ConfigureDartSolver(*world, settings, counts);
  if (solver != nullptr) *solver = s;
  return world;
}

void CheckDartInput(const EngineInput& input) {
  const size_t samples = static_cast<size_t>(input.steps) + 1;
  if (input.drive_kind == DriveKind::kKinematic &&
      (input.drive.ux_m.size() < samples || input.drive.uy_m.size() < samples)) {
    throw std::invalid_argument("dart: kinematic drive without ground displacement samples");
  }
}

void SetContactCoefficients(dart::dynamics::ShapeNode* node, double mu, double restitution) {
  node->getDynamicsAspect()->setFrictionCoeff(mu);
  node->getDynamicsAspect()->setRestitutionCoeff(restitution);
}

void DartStepCounts::Count(const dart::simulation::World& world) {
  ++steps;
  max_contacts = std::max(max_contacts, world.getLastCollisionResult().getNumContacts());
}

nlohmann::json DartStepCounts::Diagnostics() const {
  nlohmann::json j;
  j["steps"] = steps;
  j["max_contacts"] = max_contacts;
  j["lcp_solves"] = lcp.primary_calls;
  j["lcp_primary_failures"] = lcp.primary_failures;
  j["lcp_fallback_solves"] = lcp.fallback_calls;
  j["lcp_fallback_failures"] = lcp.fallback_failures;
  return j;
}

nlohmann::json CommonSettings(const EngineInput& input, const DartSettings& s,
                              const dart::simulation::World& world) {
  nlohmann::json j;
  j["dart_version"] = DART_VERSION;
  j["drive"] = input.drive_kind == DriveKind::kKinematic ? "kinematic" : "inertial";
  j["time_step_s"] = input.time_step_s;
  j["output_interval_s"] = input.run.output_interval_s;
  j["collision"] = DartCollisionName(s.collision);
  j["collision_detector"] = world.getConstraintSolver()->getCollisionDetector()->getType();
  j["lcp_solver"] = DartLcpSolverName(s.lcp_solver);
  j["pgs_fallback"] = s.lcp_solver == DartLcpSolver::kDantzig && s.pgs_fallback;
  j["pgs_iterations"] = s.pgs_iterations;
  j["restitution"] = s.restitution;
  j["restitution_combined"] = s.restitution * s.restitution;  // DART: product
  j["friction"] = s.friction;
  DartContactParams::Write(&j);
  j["max_contacts"] = s.max_contacts;
  j["ground_depth_m"] = s.ground_depth_m;
  j["kinematic_highpass_hz"] = input.kinematic_highpass_hz;
  j["integrator"] = "semi-implicit Euler (DART World::step)";
  return j;
}

}  // namespace rockbench::dart_engine
