// Compiled as C++17 (engines/siconos/CMakeLists.txt): Siconos 4.4's headers do not compile as
// C++20. Includes no harness header.
#include "engines/siconos/siconos_cylinder_system.h"

#include <Friction_cst.h>
#include <SolverOptions.h>

#include <SiconosKernel.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace rockbench::siconos_engine {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The rotation body -> world (row-major) of the unit quaternion (w, x, y, z) that Siconos
// applies as v_world = q v q^-1 (NewtonEuler1DR::computeh), normalised here.
std::array<double, 9> RotationOf(double w, double x, double y, double z) {
  const double n = w * w + x * x + y * y + z * z;
  const double s = n > 0.0 ? 2.0 / n : 0.0;
  return {1.0 - s * (y * y + z * z), s * (x * y - w * z),       s * (x * z + w * y),
          s * (x * y + w * z),       1.0 - s * (x * x + z * z), s * (y * z - w * x),
          s * (x * z - w * y),       s * (y * z + w * x),       1.0 - s * (x * x + y * y)};
}

// The unit quaternion (w, x, y, z) of a rotation matrix (row-major), Shepperd's method: the
// largest of the four squared components first (no cancellation).
std::array<double, 4> QuaternionOf(const std::array<double, 9>& r) {
  const double tr = r[0] + r[4] + r[8];
  std::array<double, 4> q{};
  if (tr >= r[0] && tr >= r[4] && tr >= r[8]) {
    const double s = 2.0 * std::sqrt(1.0 + tr);
    q = {0.25 * s, (r[7] - r[5]) / s, (r[2] - r[6]) / s, (r[3] - r[1]) / s};
  } else if (r[0] >= r[4] && r[0] >= r[8]) {
    const double s = 2.0 * std::sqrt(1.0 + r[0] - r[4] - r[8]);
    q = {(r[7] - r[5]) / s, 0.25 * s, (r[1] + r[3]) / s, (r[2] + r[6]) / s};
  } else if (r[4] >= r[8]) {
    const double s = 2.0 * std::sqrt(1.0 + r[4] - r[0] - r[8]);
    q = {(r[2] - r[6]) / s, (r[1] + r[3]) / s, 0.25 * s, (r[5] + r[7]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + r[8] - r[0] - r[4]);
    q = {(r[3] - r[1]) / s, (r[2] + r[6]) / s, (r[5] + r[7]) / s, 0.25 * s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

// The azimuth of the rim's contact frame, shared by the rim's relations: the direction of the
// tilt while the tilt is above SiconosCylinderSystem::kUprightTilt_rad, else the last one.
struct RimFrame {
  double azimuth_rad = 0.0;
};

// One rim contact of the cylinder (ds1) with the ground (the plane z = 0, or ds2's z when the
// ground moves): the bottom rim's point at the angle `slot_rad` from the lowest rim point,
// recomputed from the orientation at each evaluation of h. With k the axis (body z in the world)
// and a = (cos phi, sin phi, 0) the frame's azimuth, e1 = (a - (a.k) k) / |...| is the face's
// direction down the slope (toward the lowest rim point; for phi the tilt's azimuth it is
// (k_z k_x, k_z k_y, -(k_x^2 + k_y^2)) / sin(tilt), cylinder-3d.md section 1), e2 = k x e1, and
// the point is P = G - h k + R (cos slot e1 + sin slot e2). h = (P_z - ground_z, 0, 0), normal
// +z. NewtonEuler3DR builds the contact Jacobian (normal and two tangents, the lever arm P - G,
// the body-frame angular velocity) from P and the normal.
class RimPointR final : public NewtonEuler3DR {
 public:
  RimPointR(std::shared_ptr<RimFrame> frame, double slot_rad, double radius_m, double half_height_m)
      : frame_(std::move(frame)),
        cos_slot_(std::cos(slot_rad)),
        sin_slot_(std::sin(slot_rad)),
        r_(radius_m),
        h_(half_height_m) {}

  void computeh(double /*time*/, const BlockVector& q0, SiconosVector& y) override {
    const double* q = q0.vector(0)->getArray();
    const double ground_z = q0.numberOfBlocks() > 1 ? q0.vector(1)->getValue(2) : 0.0;
    const std::array<double, 9> rot = RotationOf(q[3], q[4], q[5], q[6]);
    const double k[3] = {rot[2], rot[5], rot[8]};
    const double sin_tilt = std::hypot(k[0], k[1]);
    if (sin_tilt > SiconosCylinderSystem::kUprightTilt_rad) {
      frame_->azimuth_rad = std::atan2(k[1], k[0]);
    }
    const double a[3] = {std::cos(frame_->azimuth_rad), std::sin(frame_->azimuth_rad), 0.0};
    const double ak = a[0] * k[0] + a[1] * k[1];
    double e1[3] = {a[0] - ak * k[0], a[1] - ak * k[1], -ak * k[2]};
    const double n1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (double& c : e1) c /= n1;
    const double e2[3] = {k[1] * e1[2] - k[2] * e1[1], k[2] * e1[0] - k[0] * e1[2],
                          k[0] * e1[1] - k[1] * e1[0]};
    double p[3];
    for (int i = 0; i < 3; ++i) {
      p[i] = q[i] - h_ * k[i] + r_ * (cos_slot_ * e1[i] + sin_slot_ * e2[i]);
    }
    y.setValue(0, p[2] - ground_z);
    if (y.size() > 1) {
      y.setValue(1, 0.0);
      y.setValue(2, 0.0);
    }
    for (int i = 0; i < 3; ++i) {
      _Pc1->setValue(i, p[i]);
      _Nc->setValue(i, i == 2 ? 1.0 : 0.0);
    }
    _Pc2->setValue(0, p[0]);
    _Pc2->setValue(1, p[1]);
    _Pc2->setValue(2, ground_z);
  }

 private:
  std::shared_ptr<RimFrame> frame_;
  double cos_slot_, sin_slot_, r_, h_;
};

// As siconos_system.cc: OpenBLAS's thread pool off (weak, so that another BLAS needs nothing).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

// What the solver hook needs of the system stepping on this thread (as siconos_system.cc's,
// whose hook and context are private to that file).
struct CylinderHookContext {
  SiconosCounters* counters = nullptr;
  FrictionContact* osnspb = nullptr;
  SolverOptions* fallback = nullptr;  // the nonsmooth Newton solver's options; null: none
};
thread_local CylinderHookContext t_cylinder_hook;

// TimeStepping's hook on the numerics solver's return code: counts a failure and, with the
// fallback, solves the step's problem again with the fallback's options swapped in.
void OnCylinderSolverOutput(int info, Simulation* sim) {
  CylinderHookContext& h = t_cylinder_hook;
  if (info == 0 || h.counters == nullptr) return;
  ++h.counters->solver_failures;
  if (h.fallback == nullptr) return;
  SolverOptions& current = *h.osnspb->numericsSolverOptions();
  std::swap(current, *h.fallback);
  const int again = h.osnspb->compute(sim->nextTime());
  std::swap(current, *h.fallback);
  ++h.counters->fallback_solves;
  if (again != 0) ++h.counters->fallback_failures;
}

}  // namespace

struct SiconosCylinderSystem::Impl {
  SiconosCylinderConfig cfg;
  SP::NonSmoothDynamicalSystem nsds;
  SP::NewtonEulerDS cylinder;
  SP::SiconosVector force;
  SP::NewtonEulerDS ground;
  SP::SiconosVector ground_velocity;  // the prescribed twist
  SP::TimeStepping sim;
  SP::MoreauJeanOSI osi;
  SP::FrictionContact osnspb;
  SP::SolverOptions fallback;
  SiconosCounters counters;
  std::string last_error;

  // Siconos's shared-pointer cycles broken, as siconos_system.cc's Impl does.
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
};

SiconosCylinderSystem::SiconosCylinderSystem(const SiconosCylinderConfig& config)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.cfg = config;
  const SiconosCylinderConfig& c = m.cfg;
  if (!(std::isfinite(c.friction) && c.friction >= 0.0)) {
    throw std::invalid_argument("siconos: friction must be finite in the contact problem");
  }
  if (c.solver != SiconosSolver::kNsgs) {
    throw std::invalid_argument(
        std::string("siconos.solver: \"") + SiconosSolverName(c.solver) +
        "\" solves the planar (2-D) frictional contact as an LCP; the cylinder's 3-D Coulomb "
        "cone has no LCP form: \"nsgs\" (FrictionContact 3-D NSGS) builds it");
  }
  if (!(c.radius_m > 0.0 && c.half_height_m > 0.0 && c.mass_kg > 0.0)) {
    throw std::invalid_argument("siconos: the cylinder needs a positive size and mass");
  }
  if (openblas_set_num_threads != nullptr) openblas_set_num_threads(1);
  try {
    m.nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, 1e12);
    // The cylinder: centre and quaternion; the twist's angular part in the body frame.
    const std::array<double, 4> quat = QuaternionOf(c.rotation);
    auto q = std::make_shared<SiconosVector>(7);
    auto v = std::make_shared<SiconosVector>(6);
    const std::array<double, 9>& r = c.rotation;
    for (int i = 0; i < 3; ++i) {
      q->setValue(i, c.centre_m[i]);
      v->setValue(i, c.velocity_mps[i]);
      // omega_body = R^T omega_world.
      v->setValue(3 + i, r[i] * c.omega_radps[0] + r[3 + i] * c.omega_radps[1] +
                             r[6 + i] * c.omega_radps[2]);
    }
    for (int i = 0; i < 4; ++i) q->setValue(3 + i, quat[i]);
    auto inertia = std::make_shared<SimpleMatrix>(3, 3);
    inertia->zero();
    inertia->setValue(0, 0, c.inertia_transverse_kgm2);
    inertia->setValue(1, 1, c.inertia_transverse_kgm2);
    inertia->setValue(2, 2, c.inertia_axial_kgm2);
    m.cylinder = std::make_shared<NewtonEulerDS>(q, v, c.mass_kg, inertia);
    m.force = std::make_shared<SiconosVector>(3);
    m.force->zero();
    m.cylinder->setFExtPtr(m.force);
    m.nsds->insertDynamicalSystem(m.cylinder);
    if (c.moving_ground) {
      // The ground: a body whose whole twist is prescribed (its mass plays no part).
      auto gq = std::make_shared<SiconosVector>(7);
      auto gv = std::make_shared<SiconosVector>(6);
      gq->zero();
      gv->zero();
      gq->setValue(3, 1.0);
      for (int i = 0; i < 3; ++i) {
        gq->setValue(i, c.ground_m[i]);
        gv->setValue(i, c.ground_velocity_mps[i]);
      }
      auto unit = std::make_shared<SimpleMatrix>(3, 3);
      unit->eye();
      m.ground = std::make_shared<NewtonEulerDS>(gq, gv, 1.0, unit);
      auto indices = std::make_shared<std::vector<unsigned int>>(6);
      for (unsigned i = 0; i < 6; ++i) (*indices)[i] = i;
      m.ground_velocity = std::make_shared<SiconosVector>(*gv);
      m.ground->setBoundaryConditions(
          std::make_shared<BoundaryCondition>(indices, m.ground_velocity));
      m.nsds->insertDynamicalSystem(m.ground);
    }
    auto law = std::make_shared<NewtonImpactFrictionNSL>(c.restitution, 0.0, c.friction, 3);
    auto frame = std::make_shared<RimFrame>();
    frame->azimuth_rad = c.upright_azimuth_rad;
    for (int j = 0; j < kRimContacts; ++j) {
      const double slot = 2.0 * kPi * j / kRimContacts;
      auto inter = std::make_shared<Interaction>(
          law, std::make_shared<RimPointR>(frame, slot, c.radius_m, c.half_height_m));
      if (c.moving_ground) {
        m.nsds->link(inter, m.cylinder, m.ground);
      } else {
        m.nsds->link(inter, m.cylinder);
      }
    }
    auto td = std::make_shared<TimeDiscretisation>(0.0, c.time_step_s);
    m.osi = std::make_shared<MoreauJeanOSI>(c.theta);
    m.osi->setConstraintActivationThreshold(c.activation_threshold_m);
    m.osnspb = std::make_shared<FrictionContact>(3, SICONOS_FRICTION_3D_NSGS);
    m.osnspb->numericsSolverOptions()->iparam[SICONOS_IPARAM_MAX_ITER] = c.solver_max_iterations;
    m.osnspb->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = c.solver_tolerance;
    m.sim = std::make_shared<TimeStepping>(m.nsds, td, m.osi, m.osnspb);
    m.sim->setNewtonOptions(c.newton_linear ? SICONOS_TS_LINEAR : SICONOS_TS_NONLINEAR);
    m.sim->setWarnOnNonConvergence(false);
    m.sim->setCheckSolverFunction(&OnCylinderSolverOutput);
    if (c.newton_fallback) {
      // solver_options_delete frees the contents only (siconos_system.cc says so).
      m.fallback.reset(solver_options_create(SICONOS_FRICTION_3D_NSN_AC), [](SolverOptions* o) {
        solver_options_delete(o);
        std::free(o);
      });
      m.fallback->iparam[SICONOS_IPARAM_MAX_ITER] = c.solver_max_iterations;
      m.fallback->dparam[SICONOS_DPARAM_TOL] = c.solver_tolerance;
    }
    m.sim->initialize();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("siconos: setting up the cylinder failed: ") + e.what());
  } catch (...) {
    throw std::runtime_error("siconos: setting up the cylinder failed (Siconos exception)");
  }
}

SiconosCylinderSystem::~SiconosCylinderSystem() = default;

void SiconosCylinderSystem::SetForce(const std::array<double, 3>& force_n) {
  Impl& m = *impl_;
  SiconosVector& wrench_old =
      const_cast<SiconosMemory&>(m.cylinder->forcesMemory()).getSiconosVectorMutable(0);
  for (int i = 0; i < 3; ++i) {
    m.force->setValue(i, force_n[i]);
    // The start of the step takes this step's force too (the stored wrench's force part is
    // the previous step's external force: no internal force here).
    wrench_old.setValue(i, force_n[i]);
  }
}

void SiconosCylinderSystem::SetGround(const std::array<double, 3>& position_m,
                                      const std::array<double, 3>& velocity_mps) {
  Impl& m = *impl_;
  if (!m.ground) throw std::logic_error("siconos: SetGround without a moving ground");
  // As SiconosSystem::SetGround: q, twist and their memories, so that Moreau-Jean's
  // q_{n+1} = q_n + h (theta v_{n+1} + (1 - theta) v_n) lands on u + h v exactly.
  NewtonEulerDS& g = *m.ground;
  for (int i = 0; i < 3; ++i) {
    g.q()->setValue(i, position_m[i]);
    g.twist()->setValue(i, velocity_mps[i]);
    g.twist()->setValue(3 + i, 0.0);
    m.ground_velocity->setValue(i, velocity_mps[i]);
    m.ground_velocity->setValue(3 + i, 0.0);
  }
  g.q()->setValue(3, 1.0);
  for (int i = 4; i < 7; ++i) g.q()->setValue(i, 0.0);
  SiconosVector& q_old = const_cast<SiconosMemory&>(g.qMemory()).getSiconosVectorMutable(0);
  SiconosVector& v_old = const_cast<SiconosMemory&>(g.twistMemory()).getSiconosVectorMutable(0);
  q_old = *g.q();
  v_old = *g.twist();
}

bool SiconosCylinderSystem::Step() {
  Impl& m = *impl_;
  t_cylinder_hook = {&m.counters, m.osnspb.get(), m.fallback.get()};
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
  t_cylinder_hook = {};
  ++m.counters.steps;
  return ok;
}

SiconosCylinderState SiconosCylinderSystem::State() const {
  const NewtonEulerDS& d = *impl_->cylinder;
  const double* q = d.q()->getArray();
  const double* v = d.twist()->getArray();
  SiconosCylinderState s;
  s.rotation = RotationOf(q[3], q[4], q[5], q[6]);
  const std::array<double, 9>& r = s.rotation;
  for (int i = 0; i < 3; ++i) {
    s.centre_m[i] = q[i];
    s.velocity_mps[i] = v[i];
    // omega_world = R omega_body.
    s.omega_radps[i] = r[3 * i] * v[3] + r[3 * i + 1] * v[4] + r[3 * i + 2] * v[5];
  }
  return s;
}

const SiconosCounters& SiconosCylinderSystem::Counters() const {
  return impl_->counters;
}

const std::string& SiconosCylinderSystem::LastError() const {
  return impl_->last_error;
}

}  // namespace rockbench::siconos_engine
