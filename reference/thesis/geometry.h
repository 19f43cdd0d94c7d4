#pragma once
/// Geometry and mass properties of two stacked rectangular blocks (Roussis 1999, 4.2 and
/// docs/model-notes). Block 2 sits centred on block 1.
#include "scene/rigid_block.h"
#include "scene/scene.h"

namespace rockbench::reference {

// One block's mass properties are the scene's (scene/rigid_block.h).
using ::rockbench::BlockProps;
using ::rockbench::MakeBlockProps;

/// Sine and cosine of a constant angle.
struct SinCos {
  double sin = 0.0, cos = 1.0;
};

struct Geometry {
  bool two_blocks = true;
  double g = 9.81;  ///< gravity, m/s^2
  BlockProps block1;
  BlockProps block2;  ///< zero when there is no block 2
  /// Block 2's pivots seen from block 1's pivot: xi = b1 - b2 (same side), xi' = b1 + b2.
  double xi = 0.0, xi_p = 0.0;
  /// l = sqrt(xi^2 + 4 h1^2), beta = atan(xi / (2 h1)); primes for the opposite side.
  double l = 0.0, beta = 0.0, l_p = 0.0, beta_p = 0.0;
  /// The stack (mode 3): total mass, mass-centre height, corner distance, slenderness, inertia
  /// about a base corner of block 1. For one block these are block 1's.
  double M = 0.0, h_stack = 0.0, R = 0.0, theta_c = 0.0, I_O = 0.0;
  /// d = sqrt((2 h1 + h2)^2 + b1^2), omega = atan((2 h1 + h2) / b1) (transition criteria).
  double d = 0.0, omega_d = 0.0;
  /// Sines and cosines of the constant angles of the equations of motion (modes.cc), taken
  /// once: block 1's and block 2's slenderness, beta, beta', the stack's slenderness, and the
  /// offsets of gamma1 (theta_c2 - beta) and gamma2 (theta_c2 + beta').
  SinCos trig_c1, trig_c2, trig_beta, trig_beta_p, trig_c_stack, trig_gamma1, trig_gamma2;
};

/// Builds the geometry of a scene. Throws SceneError when block 2 is wider than block 1 (its
/// pivots would not be on block 1: outside the thesis's model).
Geometry MakeGeometry(const Scene& scene);
/// Builds the geometry from full widths and heights (m) and masses (kg); B2 = 0: one block.
Geometry MakeGeometry(double B1, double H1, double m1, double B2, double H2, double m2,
                      double g = 9.81);

}  // namespace rockbench::reference
