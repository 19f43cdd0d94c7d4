#pragma once
/// One rectangular rigid block in the plane: its mass properties, the motion of its mass
/// centre, and its mechanical energy. The vocabulary the reference model (reference/) and the
/// engines' monitor (engines/common/monitor.h) share, so that both measure a block alike.
/// Lengths in m, masses in kg, inertias in kg m^2; the base frame (translating with the
/// ground), x right, y up.

#include "scene/vec2.h"

namespace rockbench {

/// Properties of one rectangular block.
struct BlockProps {
  double b = 0.0;        ///< half width, m
  double h = 0.0;        ///< half height, m
  double m = 0.0;        ///< mass, kg
  double r = 0.0;        ///< corner to mass centre, sqrt(b^2 + h^2), m
  double theta_c = 0.0;  ///< slenderness angle atan(b / h), rad
  double I_G = 0.0;      ///< central moment of inertia m (b^2 + h^2) / 3, kg m^2
  double I_O = 0.0;      ///< about a base corner, (4/3) m r^2, kg m^2
};

/// The properties of one block from its full width B and height H (m) and mass m (kg).
BlockProps MakeBlockProps(double B, double H, double m);

/// The motion of one rigid block in the base frame: mass centre G (m), its velocity (m/s), and
/// the counter-clockwise angular velocity (rad/s; -omega in the thesis's convention).
struct BodyMotion {
  Vec2 G;
  Vec2 vG;
  double w_radps = 0.0;
};

/// Kinetic energy in the base frame plus gravitational potential energy m g y_G of one block,
/// J: (1/2) m |vG|^2 + (1/2) I_G w^2 + m g y_G, with I_G = m (b^2 + h^2) / 3. A block at rest on
/// its face has m g h (h its half height).
double BlockEnergy_j(const BlockProps& block, double g_mps2, const BodyMotion& body);

}  // namespace rockbench
