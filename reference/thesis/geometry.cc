#include "reference/thesis/geometry.h"

#include <cmath>
#include <sstream>

namespace rockbench::reference {
namespace {
SinCos SinCosOf(double angle_rad) {
  return {std::sin(angle_rad), std::cos(angle_rad)};
}
}  // namespace

Geometry MakeGeometry(double B1, double H1, double m1, double B2, double H2, double m2, double g) {
  Geometry geo;
  geo.g = g;
  geo.block1 = MakeBlockProps(B1, H1, m1);
  geo.two_blocks = B2 > 0.0;
  const BlockProps& p1 = geo.block1;
  if (!geo.two_blocks) {
    geo.M = p1.m;
    geo.h_stack = p1.h;
    geo.R = p1.r;
    geo.theta_c = p1.theta_c;
    geo.I_O = p1.I_O;
    geo.trig_c1 = geo.trig_c_stack = SinCosOf(p1.theta_c);
    return geo;
  }
  geo.block2 = MakeBlockProps(B2, H2, m2);
  const BlockProps& p2 = geo.block2;
  geo.xi = p1.b - p2.b;
  geo.xi_p = p1.b + p2.b;
  geo.l = std::hypot(geo.xi, 2.0 * p1.h);
  geo.beta = std::atan2(geo.xi, 2.0 * p1.h);
  geo.l_p = std::hypot(geo.xi_p, 2.0 * p1.h);
  geo.beta_p = std::atan2(geo.xi_p, 2.0 * p1.h);
  geo.M = p1.m + p2.m;
  const double y2 = 2.0 * p1.h + p2.h;  // height of block 2's mass centre at rest
  geo.h_stack = (p1.m * p1.h + p2.m * y2) / geo.M;
  geo.R = std::hypot(p1.b, geo.h_stack);
  geo.theta_c = std::atan2(p1.b, geo.h_stack);
  geo.I_O = p1.I_O + p2.I_G + p2.m * (p1.b * p1.b + y2 * y2);
  geo.d = std::hypot(y2, p1.b);
  geo.omega_d = std::atan2(y2, p1.b);
  geo.trig_c1 = SinCosOf(p1.theta_c);
  geo.trig_c2 = SinCosOf(p2.theta_c);
  geo.trig_beta = SinCosOf(geo.beta);
  geo.trig_beta_p = SinCosOf(geo.beta_p);
  geo.trig_c_stack = SinCosOf(geo.theta_c);
  geo.trig_gamma1 = SinCosOf(p2.theta_c - geo.beta);
  geo.trig_gamma2 = SinCosOf(p2.theta_c + geo.beta_p);
  return geo;
}

Geometry MakeGeometry(const Scene& scene) {
  RequireAtMostTwoBlocks(scene, "reference model geometry");
  if (scene.blocks.empty()) throw SceneError(scene.path.string() + ": block1: missing");
  const BlockDef& b1 = scene.blocks[0];
  const bool two = scene.block_count() == 2;
  const double B2 = two ? scene.blocks[1].width_m : 0.0;
  const double H2 = two ? scene.blocks[1].height_m : 0.0;
  const double m2 = two ? scene.blocks[1].mass_kg : 0.0;
  if (two && B2 > b1.width_m) {
    std::ostringstream os;
    os << scene.path.string() << ": block2.width (" << B2 << " m) exceeds block1.width ("
       << b1.width_m
       << " m): block 2 would pivot outside block 1's top face, which the thesis's model "
          "does not describe";
    throw SceneError(os.str());
  }
  return MakeGeometry(b1.width_m, b1.height_m, b1.mass_kg, B2, H2, m2, scene.run.gravity_mps2);
}

}  // namespace rockbench::reference
