#pragma once
/// The Siconos kernel part of the Siconos engine's cylinder (shape "cylinder", issue 41), behind
/// a header that includes neither Siconos nor the harness (siconos_cylinder_system.cc is compiled
/// as C++17, as siconos_system.cc, for the reason siconos_system.h gives).
///
/// The model: the cylinder a NewtonEulerDS (q = centre and unit quaternion, 7 coordinates; the
/// twist = the centre's velocity in the world and the angular velocity in the body frame, 6),
/// with the mass and the central inertia diag(I_t, I_t, I_a) given, Siconos's gyroscopic term
/// omega x I omega and a constant external force set per step. The ground is the plane z = 0
/// (world axes +x horizontal, +y transverse, +z up). Its contact with the cylinder's bottom rim
/// is kRimContacts Interactions, each a NewtonEuler3DR whose contact point is recomputed from the
/// orientation whenever Siconos evaluates h: slot j is the bottom rim's point at the angle
/// 2 pi j / kRimContacts from the LOWEST rim point (slot 0, exact: the rim point down the slope
/// of the tilted face), normal +z, gap its height above the ground, with a
/// NewtonImpactFrictionNSL(e, 0, mu, 3). Slot 0 carries the rocking and rolling; the others
/// carry the face (a landing lands on slot kRimContacts / 2, the diametrically opposite point,
/// and upright the face stands on the square they make). Stepped by TimeStepping with a
/// MoreauJeanOSI and a 3-D FrictionContact problem. With the kinematic drive the ground is a
/// second NewtonEulerDS whose twist is prescribed (BoundaryCondition on all six) and whose
/// position is set each step.
#include <array>
#include <memory>
#include <string>

#include "engines/siconos/siconos_system.h"

namespace rockbench::siconos_engine {

/// Contacts on the bottom rim, equally spaced from the lowest point (see above). Four, not the
/// lowest point and those at +-120 degrees: a landing then meets the opposite point (slot 2), so
/// that the plastic impact conserves the angular momentum about it (the reference's landing;
/// the free rocking's landings match its e = 0.849 for D = 0.5 m, H = 1.5 m), where +-120
/// degrees would land on the chord at R / 2 first. Upright the face stands on the square they
/// make, turned to the tilt's azimuth: a noise-level tilt leans toward the tipping side, so a
/// field at 45 degrees to the start azimuth still needed 0.97..1.03 of the threshold (D / H) g
/// to tip it (measured at a 1e-4 s step).
inline constexpr int kRimContacts = 4;

struct SiconosCylinderConfig {
  double radius_m = 0.0, half_height_m = 0.0, mass_kg = 0.0;
  double inertia_transverse_kgm2 = 0.0, inertia_axial_kgm2 = 0.0;
  /// Initial pose and velocity in the world: centre (m), rotation body -> world (row-major,
  /// body z the axis), centre velocity (m/s), angular velocity (rad/s, world components).
  std::array<double, 3> centre_m{}, velocity_mps{}, omega_radps{};
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  /// The azimuth of the rim's contact frame (rad) while the cylinder stands upright (its tilt
  /// below kUprightTilt_rad the lowest rim point is not defined): the scene's azimuth.
  double upright_azimuth_rad = 0.0;
  double time_step_s = 1e-4;
  double theta = 0.5;        ///< Moreau-Jean theta
  double restitution = 0.0;  ///< Newton's normal restitution e
  double friction = 10.0;    ///< Coulomb mu (finite) of the rim's contacts
  /// Numerics solver: only SiconosSolver::kNsgs (SICONOS_FRICTION_3D_NSGS); the 2-D Lemke and
  /// enumeration solvers have no 3-D counterpart (the constructor throws std::invalid_argument).
  SiconosSolver solver = SiconosSolver::kNsgs;
  double solver_tolerance = 1e-8;
  int solver_max_iterations = 1000;
  /// Whether a step NSGS did not converge on is solved again by the nonsmooth Newton solver
  /// (SICONOS_FRICTION_3D_NSN_AC, Alart-Curnier), the 3-D problem's direct solver.
  bool newton_fallback = true;
  bool newton_linear = true;            ///< SICONOS_TS_LINEAR (else SICONOS_TS_NONLINEAR)
  double activation_threshold_m = 0.0;  ///< MoreauJeanOSI's constraint activation threshold
  /// The kinematic drive: the ground a moving body, its initial position and velocity.
  bool moving_ground = false;
  std::array<double, 3> ground_m{}, ground_velocity_mps{};
};

/// The cylinder's pose and velocity as the simulation holds them (world, z up).
struct SiconosCylinderState {
  std::array<double, 3> centre_m{}, velocity_mps{}, omega_radps{};
  std::array<double, 9> rotation{};
};

class SiconosCylinderSystem {
 public:
  /// Below this tilt (rad) the rim's contact frame keeps its last azimuth (the lowest point of
  /// a face this close to level is not defined; the rim's heights then differ by at most
  /// 2 R sin(tilt), 5e-10 m on R = 0.25 m).
  static constexpr double kUprightTilt_rad = 1e-9;

  /// Builds the simulation. Throws std::invalid_argument for a configuration it cannot take,
  /// std::runtime_error when Siconos fails to set it up.
  explicit SiconosCylinderSystem(const SiconosCylinderConfig& config);
  ~SiconosCylinderSystem();
  SiconosCylinderSystem(const SiconosCylinderSystem&) = delete;
  SiconosCylinderSystem& operator=(const SiconosCylinderSystem&) = delete;

  /// The external force on the cylinder for the next step (world, N), constant over the step:
  /// both theta-weighted ends of Moreau-Jean's step take it (the force part of the previous
  /// step's stored wrench is replaced, as a LagrangianLinearTIDS's constant F_ext).
  void SetForce(const std::array<double, 3>& force_n);
  /// Moving ground only: its position at the step's start and its velocity during the step.
  void SetGround(const std::array<double, 3>& position_m,
                 const std::array<double, 3>& velocity_mps);
  /// One step. Returns false when Siconos threw.
  bool Step();
  SiconosCylinderState State() const;
  const SiconosCounters& Counters() const;
  const std::string& LastError() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::siconos_engine
