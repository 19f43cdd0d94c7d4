#include "engines/dart/dart_solver.h"

#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/collision/fcl/FCLCollisionDetector.hpp>
#include <dart/constraint/ContactConstraint.hpp>
#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
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

}  // namespace rockbench::dart_engine
