// Compiled as C++17 (engines/siconos/CMakeLists.txt): Siconos 4.4's headers do not compile as
// C++20. Includes no harness header.
#include "engines/siconos/siconos_system.h"

#include <Friction_cst.h>
#include <SolverOptions.h>

#include <SiconosKernel.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>

namespace rockbench::siconos_engine {

const char* SiconosSolverName(SiconosSolver s) {
  switch (s) {
    case SiconosSolver::kNsgs:
      return "nsgs";
    case SiconosSolver::kEnum:
      return "enum";
    case SiconosSolver::kLemke:
      break;
  }
  return "lemke";
}

std::string SiconosVersionString() {
  return "Siconos 4.4 (kernel and numerics)";
}

namespace {

// A bottom corner of an upper body B against the top face of a lower body A (the ground when
// the relation has one dynamical system: A fixed, top face y = 0; else q = (q_A, q_B)).
// h = (gap, s) with d = x_B + R_B p - x_A, n = R_A (0, 1), t = R_A (1, 0): gap = n.d - h_A (the
// corner's height above A's top face), s = t.d (its place along the face). Their derivatives
// are the normal and tangential relative velocities of the corner and the point of A under it
// (d/dt t.d = t.(v_B + w_B z x r - v_A) + w_A n.d, which is t.(v_rel) since
// -t.(w_A z x d) = w_A n.d; likewise for the normal), so H = dh/dq is the contact Jacobian.
// A corner beyond the ends of A's face (|s| > b_A, with a margin) is not in contact: its gap is
// set large. The margin, 1% of b_A: where B is as wide as A (a column of equal drums, a stack
// of equal boxes) its corners stand on A's edges, and without it a corner that drifts a
// rounding error outward (measured: from the first steps) drops its contact, and B falls into
// A (five equal boxes: 6.5 cm of penetration within 0.3 s). There B's corner is carried by A's
// corner, which the face's extension by the margin stands in for; B narrower than A by more
// than the margin (every shipped two-block scene) never comes near it.
class CornerR final : public LagrangianScleronomousR {
 public:
  CornerR(bool two_bodies, double px, double py, double face_half_height, double face_half_width)
      : two_(two_bodies), px_(px), py_(py), ha_(face_half_height), ba_(face_half_width) {}

  void computeh(const BlockVector& q, BlockVector& /*z*/, SiconosVector& y) override {
    Geometry g(*this, q);
    double gap = g.nx * g.dx + g.ny * g.dy - ha_;
    const double s = g.tx * g.dx + g.ty * g.dy;
    if (std::abs(s) > ba_ * (1.0 + kEdgeMargin)) gap = std::max(gap, 0.0) + kOffFace;
    y.setValue(0, gap);
    y.setValue(1, s);
  }

  void computeJachq(const BlockVector& q, BlockVector& /*z*/) override {
    Geometry g(*this, q);
    SimpleMatrix& j = *_jachq;
    const int o = two_ ? 3 : 0;  // B's columns
    // d(d)/d phi_B = z x r_B = (-r_y, r_x).
    j.setValue(0, o + 0, g.nx);
    j.setValue(0, o + 1, g.ny);
    j.setValue(0, o + 2, -g.nx * g.ry + g.ny * g.rx);
    j.setValue(1, o + 0, g.tx);
    j.setValue(1, o + 1, g.ty);
    j.setValue(1, o + 2, -g.tx * g.ry + g.ty * g.rx);
    if (two_) {
      // d n / d phi_A = -t, d t / d phi_A = n; d(d)/d x_A = -identity.
      j.setValue(0, 0, -g.nx);
      j.setValue(0, 1, -g.ny);
      j.setValue(0, 2, -(g.tx * g.dx + g.ty * g.dy));
      j.setValue(1, 0, -g.tx);
      j.setValue(1, 1, -g.ty);
      j.setValue(1, 2, g.nx * g.dx + g.ny * g.dy);
    }
  }

 private:
  static constexpr double kOffFace = 1.0;      // m: far beyond any activation threshold
  static constexpr double kEdgeMargin = 0.01;  // of the face's half width (see above)

  struct Geometry {
    double rx = 0.0, ry = 0.0, dx = 0.0, dy = 0.0;
    double nx = 0.0, ny = 1.0, tx = 1.0, ty = 0.0;
    Geometry(const CornerR& r, const BlockVector& q) {
      // The blocks of q are the bodies' own (x, y, phi) vectors: read them directly
      // (BlockVector::getValue walks the blocks for every entry).
      const double* qb = q.vector(r.two_ ? 1 : 0)->getArray();
      const double xb = qb[0], yb = qb[1], pb = qb[2];
      const double cb = std::cos(pb), sb = std::sin(pb);
      rx = cb * r.px_ - sb * r.py_;
      ry = sb * r.px_ + cb * r.py_;
      double xa = 0.0, ya = 0.0;
      if (r.two_) {
        const double* qa = q.vector(0)->getArray();
        xa = qa[0];
        ya = qa[1];
        const double pa = qa[2];
        const double ca = std::cos(pa), sa = std::sin(pa);
        tx = ca;
        ty = sa;
        nx = -sa;
        ny = ca;
      }
      dx = xb + rx - xa;
      dy = yb + ry - ya;
    }
  };

  bool two_;
  double px_, py_, ha_, ba_;
};

int SolverId(SiconosSolver s) {
  switch (s) {
    case SiconosSolver::kNsgs:
      return SICONOS_FRICTION_2D_NSGS;
    case SiconosSolver::kEnum:
      return SICONOS_FRICTION_2D_ENUM;
    case SiconosSolver::kLemke:
      break;
  }
  return SICONOS_FRICTION_2D_LEMKE;
}

// OpenBLAS (Debian's libblas.so.3 for Siconos numerics is OpenBLAS's pthread build) would run
// the contact problem's tiny matrix products on a thread pool whose workers spin on
// sched_yield: measured 58% of a stack run's time in the kernel's sched_yield. Weak, so that a
// Siconos linked against another BLAS needs nothing.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

// What the solver hook needs of the system stepping on this thread.
struct SolverHookContext {
  SiconosCounters* counters = nullptr;
  FrictionContact* osnspb = nullptr;
  SolverOptions* fallback = nullptr;  // Lemke's options; null: no fallback
};
thread_local SolverHookContext t_hook;

// TimeStepping's hook on the numerics solver's return code (a function pointer without a
// context, called after the problem's compute(), before the state update): counts a failure
// and, with the fallback, solves the step's problem again with Lemke (the options swapped in
// and out: OneStepNSProblem has no setter that keeps both). compute() writes the new impulses
// into the interactions as the first solve did.
void OnSolverOutput(int info, Simulation* sim) {
  if (info == 0 || t_hook.counters == nullptr) return;
  ++t_hook.counters->solver_failures;
  if (t_hook.fallback == nullptr) return;
  SolverOptions& current = *t_hook.osnspb->numericsSolverOptions();
  std::swap(current, *t_hook.fallback);
  const int again = t_hook.osnspb->compute(sim->nextTime());
  std::swap(current, *t_hook.fallback);
  ++t_hook.counters->fallback_solves;
  if (again != 0) ++t_hook.counters->fallback_failures;
}

}  // namespace

struct SiconosSystem::Impl {
  SiconosSystemConfig cfg;
  SP::NonSmoothDynamicalSystem nsds;
  std::vector<SP::LagrangianLinearTIDS> blocks;
  std::vector<SP::SiconosVector> forces;
  SP::LagrangianLinearTIDS ground;
  SP::SiconosVector ground_velocity;  // the prescribed velocity (x, y, phi)
  SP::TimeStepping sim;
  SP::MoreauJeanOSI osi;
  SP::FrictionContact osnspb;
  SP::SolverOptions lemke;  // the fallback's options
  SiconosCounters counters;
  std::string last_error;

  // Siconos's objects hold shared pointers to each other in cycles (its own comment on
  // Simulation::clear: "the memory is never freed" otherwise): the simulation and its
  // integrator and contact problem, and the integrator and the systems graph whose vertices
  // name it. Broken here, as the Model of earlier Siconos versions did in its destructor.
  ~Impl() {
    if (nsds && nsds->topology()) {
      SP::DynamicalSystemsGraph dsg = nsds->topology()->dSG(0);
      DynamicalSystemsGraph::VIterator vi, vend;
      for (std::tie(vi, vend) = dsg->vertices(); vi != vend; ++vi) dsg->properties(*vi).osi.reset();
    }
    if (osi) {
      osi->setSimulationPtr(SP::Simulation());
      osi->setDynamicalSystemsGraph(SP::DynamicalSystemsGraph());
    }
    if (osnspb) osnspb->setSimulationPtr(SP::Simulation());
    if (sim) sim->clear();
  }

  SP::LagrangianLinearTIDS MakeBody(double x, double y, double phi, double vx, double vy, double w,
                                    double m, double inertia) {
    auto q = std::make_shared<SiconosVector>(3);
    auto v = std::make_shared<SiconosVector>(3);
    q->setValue(0, x);
    q->setValue(1, y);
    q->setValue(2, phi);
    v->setValue(0, vx);
    v->setValue(1, vy);
    v->setValue(2, w);
    auto mass = std::make_shared<SimpleMatrix>(3, 3);
    mass->zero();
    mass->setValue(0, 0, m);
    mass->setValue(1, 1, m);
    mass->setValue(2, 2, inertia);
    return std::make_shared<LagrangianLinearTIDS>(q, v, mass);
  }
};

SiconosSystem::SiconosSystem(const SiconosSystemConfig& config) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.cfg = config;
  const SiconosSystemConfig& c = m.cfg;
  if (c.blocks.empty()) throw std::invalid_argument("siconos: no block");
  const auto finite_mu = [](double mu) { return std::isfinite(mu) && mu >= 0.0; };
  if (!finite_mu(c.friction) ||
      !std::all_of(c.blocks.begin(), c.blocks.end(), [&](const SiconosBlock& b) {
        return std::isnan(b.friction) || finite_mu(b.friction);
      })) {
    throw std::invalid_argument("siconos: friction must be finite in the contact problem");
  }
  if (openblas_set_num_threads != nullptr) openblas_set_num_threads(1);
  try {
    m.nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, 1e12);
    for (const SiconosBlock& b : c.blocks) {
      auto ds = m.MakeBody(b.x_m, b.y_m, b.phi_rad, b.vx_mps, b.vy_mps, b.w_radps, b.mass_kg,
                           b.inertia_kgm2);
      auto f = std::make_shared<SiconosVector>(3);
      f->zero();
      ds->setFExtPtr(f);
      m.nsds->insertDynamicalSystem(ds);
      m.blocks.push_back(ds);
      m.forces.push_back(f);
    }
    if (c.moving_ground) {
      // Mass 1 (never used: every velocity is prescribed).
      m.ground = m.MakeBody(c.ground_x_m, c.ground_y_m, 0.0, c.ground_vx_mps, c.ground_vy_mps, 0.0,
                            1.0, 1.0);
      auto indices = std::make_shared<std::vector<unsigned int>>(3);
      for (unsigned i = 0; i < 3; ++i) (*indices)[i] = i;
      m.ground_velocity = std::make_shared<SiconosVector>(3);
      m.ground_velocity->setValue(0, c.ground_vx_mps);
      m.ground_velocity->setValue(1, c.ground_vy_mps);
      m.ground_velocity->setValue(2, 0.0);
      m.ground->setBoundaryConditions(
          std::make_shared<BoundaryCondition>(indices, m.ground_velocity));
      m.nsds->insertDynamicalSystem(m.ground);
    }
    // One law per coefficient: the config's, and each block's own (its base corners' contacts).
    std::map<double, SP::NewtonImpactFrictionNSL> laws;
    laws[c.friction] = std::make_shared<NewtonImpactFrictionNSL>(c.restitution, 0.0, c.friction, 2);
    const auto law_of = [&](double mu) {
      SP::NewtonImpactFrictionNSL& law = laws[mu];
      if (!law) law = std::make_shared<NewtonImpactFrictionNSL>(c.restitution, 0.0, mu, 2);
      return law;
    };
    const double kWide = 1e9;  // the ground's face has no ends
    for (size_t i = 0; i < c.blocks.size(); ++i) {
      const SiconosBlock& b = c.blocks[i];
      const SP::NewtonImpactFrictionNSL nslaw =
          law_of(std::isnan(b.friction) ? c.friction : b.friction);
      for (const double side : {-1.0, 1.0}) {
        SP::Interaction inter;
        if (i == 0) {
          const bool two = c.moving_ground;
          inter = std::make_shared<Interaction>(
              nslaw, std::make_shared<CornerR>(two, side * b.b_m, -b.h_m, 0.0, kWide));
          if (two) {
            m.nsds->link(inter, m.ground, m.blocks[0]);
          } else {
            m.nsds->link(inter, m.blocks[0]);
          }
        } else {
          // Block i + 1's corners on block i's top face (the block below).
          const SiconosBlock& a = c.blocks[i - 1];
          inter = std::make_shared<Interaction>(
              nslaw, std::make_shared<CornerR>(true, side * b.b_m, -b.h_m, a.h_m, a.b_m));
          m.nsds->link(inter, m.blocks[i - 1], m.blocks[i]);
        }
      }
    }
    auto td = std::make_shared<TimeDiscretisation>(0.0, c.time_step_s);
    m.osi = std::make_shared<MoreauJeanOSI>(c.theta);
    const SP::MoreauJeanOSI& osi = m.osi;
    osi->setConstraintActivationThreshold(c.activation_threshold_m);
    m.osnspb = std::make_shared<FrictionContact>(2, SolverId(c.solver));
    m.osnspb->numericsSolverOptions()->iparam[SICONOS_IPARAM_MAX_ITER] = c.solver_max_iterations;
    m.osnspb->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = c.solver_tolerance;
    m.sim = std::make_shared<TimeStepping>(m.nsds, td, osi, m.osnspb);
    m.sim->setNewtonOptions(c.newton_linear ? SICONOS_TS_LINEAR : SICONOS_TS_NONLINEAR);
    m.sim->setWarnOnNonConvergence(false);
    m.sim->setCheckSolverFunction(&OnSolverOutput);
    if (c.lemke_fallback && c.solver != SiconosSolver::kLemke) {
      // Siconos 4.4's solver_options_delete frees the options' contents, not the struct that
      // solver_options_create allocated (measured with valgrind: 120 bytes lost per run).
      m.lemke.reset(solver_options_create(SICONOS_FRICTION_2D_LEMKE), [](SolverOptions* o) {
        solver_options_delete(o);
        std::free(o);
      });
    }
    m.sim->initialize();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("siconos: setting up the simulation failed: ") + e.what());
  } catch (...) {
    throw std::runtime_error("siconos: setting up the simulation failed (Siconos exception)");
  }
}

SiconosSystem::~SiconosSystem() = default;

void SiconosSystem::SetForce(int block, double fx_n, double fy_n, double torque_nm) {
  SiconosVector& f = *impl_->forces.at(static_cast<size_t>(block));
  f.setValue(0, fx_n);
  f.setValue(1, fy_n);
  f.setValue(2, torque_nm);
}

void SiconosSystem::SetGround(double x_m, double y_m, double vx_mps, double vy_mps) {
  Impl& m = *impl_;
  if (!m.ground) throw std::logic_error("siconos: SetGround without a moving ground");
  // The step starts from (x, y) moving with (vx, vy) throughout: q, v and their memories (the
  // step's "old" state) all set, so that Moreau-Jean's q_{n+1} = q_n + h (theta v_{n+1} +
  // (1 - theta) v_n) lands on x + h vx exactly.
  LagrangianDS& g = *m.ground;
  g.q()->setValue(0, x_m);
  g.q()->setValue(1, y_m);
  g.q()->setValue(2, 0.0);
  g.velocity()->setValue(0, vx_mps);
  g.velocity()->setValue(1, vy_mps);
  g.velocity()->setValue(2, 0.0);
  SiconosVector& q_old = const_cast<SiconosMemory&>(g.qMemory()).getSiconosVectorMutable(0);
  SiconosVector& v_old = const_cast<SiconosMemory&>(g.velocityMemory()).getSiconosVectorMutable(0);
  q_old = *g.q();
  v_old = *g.velocity();
  m.ground_velocity->setValue(0, vx_mps);
  m.ground_velocity->setValue(1, vy_mps);
}

bool SiconosSystem::Step() {
  Impl& m = *impl_;
  t_hook = {&m.counters, m.osnspb.get(), m.lemke.get()};
  bool ok = true;
  try {
    m.sim->computeOneStep();
    const std::int64_t it = m.sim->getNewtonNbIterations();
    m.counters.newton_iterations += it;
    m.counters.max_newton_iterations = std::max(m.counters.max_newton_iterations, it);
    const std::int64_t active = static_cast<std::int64_t>(m.sim->indexSet(1)->size());
    m.counters.max_active_contacts = std::max(m.counters.max_active_contacts, active);
    if (active > 0) {
      const std::int64_t iters =
          m.osnspb->numericsSolverOptions()->iparam[SICONOS_IPARAM_ITER_DONE];
      ++m.counters.solves;
      m.counters.solver_iterations += iters;
      m.counters.max_solver_iterations = std::max(m.counters.max_solver_iterations, iters);
    }
    m.sim->nextStep();
  } catch (const std::exception& e) {
    m.last_error = e.what();
    ok = false;
  } catch (...) {
    m.last_error = "Siconos exception";
    ok = false;
  }
  t_hook = {};
  ++m.counters.steps;
  return ok;
}

SiconosBodyState SiconosSystem::Body(int block) const {
  const LagrangianLinearTIDS& d = *impl_->blocks.at(static_cast<size_t>(block));
  SiconosBodyState s;
  s.x_m = d.q()->getValue(0);
  s.y_m = d.q()->getValue(1);
  s.phi_rad = d.q()->getValue(2);
  s.vx_mps = d.velocity()->getValue(0);
  s.vy_mps = d.velocity()->getValue(1);
  s.w_radps = d.velocity()->getValue(2);
  return s;
}

const SiconosCounters& SiconosSystem::Counters() const {
  return impl_->counters;
}

const std::string& SiconosSystem::LastError() const {
  return impl_->last_error;
}

}  // namespace rockbench::siconos_engine
