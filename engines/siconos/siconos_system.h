#pragma once
/// The Siconos kernel part of the Siconos engine, behind a header that includes neither Siconos
/// nor the harness: Siconos 4.4's headers do not compile as C++20 (Boost.uBLAS's
/// symmetric_matrix of shared_ptr, in NSLawMatrix.hpp, calls std::allocator::construct, removed
/// in C++20), so siconos_system.cc alone is compiled as C++17 and everything else talks to it
/// through these plain types.
///
/// The model: each block a LagrangianLinearTIDS with q = (x, y, phi) of its centre, mass matrix
/// diag(m, m, I) and a constant external force set per step; one Interaction per bottom corner
/// of a block against the face below it (the ground's top face, or the top face of the block
/// below: only neighbours meet), with a
/// Lagrangian scleronomous relation h = (normal gap, tangential coordinate) and a
/// NewtonImpactFrictionNSL(e, 0, mu, 2); a TimeStepping simulation with a MoreauJeanOSI and a
/// 2-D FrictionContact problem. With the kinematic drive the ground is a third dynamical system
/// whose velocity is prescribed (BoundaryCondition) and whose position is set each step.
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rockbench::siconos_engine {

/// Siconos numerics solvers of the 2-D frictional contact problem offered here.
enum class SiconosSolver {
  kLemke,  ///< SICONOS_FRICTION_2D_LEMKE: the problem as an LCP, Lemke's pivoting (exact)
  kNsgs,   ///< SICONOS_FRICTION_2D_NSGS: non-smooth Gauss-Seidel (iterative)
  kEnum,   ///< SICONOS_FRICTION_2D_ENUM: enumeration of the LCP's complementary bases
};

/// One rigid block: half width b, half height h (m), mass (kg), moment of inertia about its
/// centre (kg m^2), and its initial planar state (centre, CCW angle, their rates).
struct SiconosBlock {
  double b_m = 0.0, h_m = 0.0, mass_kg = 0.0, inertia_kgm2 = 0.0;
  double x_m = 0.0, y_m = 0.0, phi_rad = 0.0, vx_mps = 0.0, vy_mps = 0.0, w_radps = 0.0;
  /// Coulomb mu of its base corners' contacts with its support (finite); NaN: the config's
  /// friction.
  double friction = std::numeric_limits<double>::quiet_NaN();
};

struct SiconosSystemConfig {
  std::vector<SiconosBlock> blocks;  ///< block 1 (on the ground), then block k on block k - 1
  double time_step_s = 1e-4;
  double theta = 0.5;        ///< Moreau-Jean theta
  double restitution = 0.0;  ///< Newton's normal restitution e
  double friction = 10.0;    ///< Coulomb mu (finite) of every block without its own
  SiconosSolver solver = SiconosSolver::kLemke;
  double solver_tolerance = 1e-6;
  int solver_max_iterations = 10000;
  /// Whether a step whose iterative solver (NSGS) did not converge is solved again by Lemke.
  bool lemke_fallback = true;
  bool newton_linear = true;  ///< SICONOS_TS_LINEAR (else SICONOS_TS_NONLINEAR, the default)
  /// MoreauJeanOSI's constraint activation threshold, m (Siconos's default 0).
  double activation_threshold_m = 0.0;
  /// The ground a moving body (kinematic drive): its initial position and velocity (m, m/s).
  bool moving_ground = false;
  double ground_x_m = 0.0, ground_y_m = 0.0, ground_vx_mps = 0.0, ground_vy_mps = 0.0;
};

/// A block's state as the simulation holds it.
struct SiconosBodyState {
  double x_m = 0.0, y_m = 0.0, phi_rad = 0.0, vx_mps = 0.0, vy_mps = 0.0, w_radps = 0.0;
};

/// Counts since construction.
struct SiconosCounters {
  std::int64_t steps = 0;
  std::int64_t solver_failures = 0;    ///< steps whose numerics solver reported no solution
  std::int64_t fallback_solves = 0;    ///< of those, solved again by Lemke
  std::int64_t fallback_failures = 0;  ///< Lemke failed too (its result is kept)
  std::int64_t newton_iterations = 0;  ///< cumulative Newton iterations of TimeStepping
  std::int64_t max_newton_iterations = 0;
  std::int64_t max_active_contacts = 0;  ///< largest index set 1 (contacts in the problem)
  std::int64_t solves = 0;               ///< steps with a contact problem to solve
  std::int64_t solver_iterations = 0;    ///< numerics solver iterations, all solves
  std::int64_t max_solver_iterations = 0;
};

/// "lemke", "nsgs", "enum".
const char* SiconosSolverName(SiconosSolver s);

/// "Siconos 4.4.0" (the kernel's version as built against).
std::string SiconosVersionString();

class SiconosSystem {
 public:
  /// Builds the simulation. Throws std::invalid_argument for a configuration Siconos cannot
  /// take, std::runtime_error when Siconos fails to set it up.
  explicit SiconosSystem(const SiconosSystemConfig& config);
  ~SiconosSystem();
  SiconosSystem(const SiconosSystem&) = delete;
  SiconosSystem& operator=(const SiconosSystem&) = delete;

  /// The external force on block i for the next step (N, N, N m).
  void SetForce(int block, double fx_n, double fy_n, double torque_nm);
  /// Moving ground only: its position at the step's start and its velocity during the step.
  void SetGround(double x_m, double y_m, double vx_mps, double vy_mps);
  /// One step of the time-stepping scheme. Returns false when Siconos threw (the state is then
  /// the one before the step's update, or partly updated).
  bool Step();
  SiconosBodyState Body(int block) const;
  const SiconosCounters& Counters() const;
  /// The last Siconos exception's text, empty when none.
  const std::string& LastError() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::siconos_engine
