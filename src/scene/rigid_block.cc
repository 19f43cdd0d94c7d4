#include "scene/rigid_block.h"

#include <cmath>

namespace rockbench {

BlockProps MakeBlockProps(double B, double H, double m) {
  BlockProps p;
  p.b = 0.5 * B;
  p.h = 0.5 * H;
  p.m = m;
  p.r = std::hypot(p.b, p.h);
  p.theta_c = std::atan2(p.b, p.h);
  p.I_G = m * (p.b * p.b + p.h * p.h) / 3.0;
  p.I_O = p.I_G + m * p.r * p.r;
  return p;
}

double BlockEnergy_j(const BlockProps& block, double g_mps2, const BodyMotion& body) {
  return 0.5 * block.m * Dot(body.vG, body.vG) + 0.5 * block.I_G * body.w_radps * body.w_radps +
         block.m * g_mps2 * body.G.y;
}

}  // namespace rockbench
