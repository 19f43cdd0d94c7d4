#include "reference/chain/stack_chain.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockbench::reference {
namespace {

// Rotation by the counter-clockwise angle phi = -theta, from theta's sine and cosine.
Vec2 RotateBack(double sin_theta, double cos_theta, Vec2 v) {
  return {cos_theta * v.x + sin_theta * v.y, -sin_theta * v.x + cos_theta * v.y};
}

double SideSign(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

}  // namespace

StackGeometry MakeStackGeometry(const std::vector<BlockSize>& blocks, double g_mps2) {
  StackGeometry geo;
  geo.g = g_mps2;
  geo.blocks.reserve(blocks.size());
  for (const BlockSize& b : blocks) {
    geo.blocks.push_back(MakeBlockProps(b.width_m, b.height_m, b.mass_kg));
  }
  return geo;
}

StackChain::StackChain(StackGeometry geometry) : geo_(std::move(geometry)), n_(geo_.size()) {
  if (n_ < 1 || n_ > kMaxBlocks) {
    throw std::invalid_argument("StackChain: " + std::to_string(n_) + " blocks (1 to " +
                                std::to_string(kMaxBlocks) + ")");
  }
  const size_t n = static_cast<size_t>(n_);
  sin_.assign(n, 0.0);
  cos_.assign(n, 1.0);
  pivot_.assign(n, Vec2{});
  G_.assign(n, Vec2{});
  for (auto* v : {&S_, &v_, &c_, &pA_, &a_, &U_, &force_, &momenta_}) v->assign(n, Spatial{});
  theta_.assign(n, 0.0);
  zero_.assign(n, 0.0);
  IA_.assign(n, Inertia{});
  D_.assign(n, 0.0);
  u_.assign(n, 0.0);
  qd_.assign(n, 0.0);
  config_ = Configuration(n_);
}

StackChain::Spatial StackChain::Times(const Inertia& I, const Spatial& v) {
  return {I.ww * v.w + I.wx * v.x + I.wy * v.y, I.wx * v.w + I.xx * v.x + I.xy * v.y,
          I.wy * v.w + I.xy * v.x + I.yy * v.y};
}

void StackChain::Place(const Configuration& c, const double* theta_rad, const double* omega_radps) {
  config_ = c;
  double theta_below = 0.0, omega_below = 0.0, side_below = 1.0;
  Spatial v_below{};
  for (int k = 0; k < n_; ++k) {
    const BlockProps& p = geo_.blocks[k];
    const bool open = c[k] != Contact::kFace;
    const double theta = open ? theta_rad[k] : theta_below;
    const double omega = open ? omega_radps[k] : omega_below;
    // A closed face turns about any of its corners alike: take the side of the one below.
    const double side = open ? SideSign(c[k]) : side_below;
    sin_[k] = open ? std::sin(theta) : (k == 0 ? 0.0 : sin_[k - 1]);
    cos_[k] = open ? std::cos(theta) : (k == 0 ? 1.0 : cos_[k - 1]);
    // The model's own pivot chain (its equations' terms), not a placement: engines and renders
    // use scene/stack_pose.h.
    if (k == 0) {
      pivot_[k] = {side * p.b, 0.0};
    } else {
      const BlockProps& below = geo_.blocks[k - 1];
      pivot_[k] =
          pivot_[k - 1] + RotateBack(sin_[k - 1], cos_[k - 1],
                                     Vec2{side * p.b - side_below * below.b, 2.0 * below.h});
    }
    G_[k] = pivot_[k] + RotateBack(sin_[k], cos_[k], Vec2{-side * p.b, p.h});
    // Joint axis: a unit clockwise turn (theta's sense) about the pivot.
    S_[k] = {-1.0, -pivot_[k].y, pivot_[k].x};
    qd_[k] = open ? omega - omega_below : 0.0;
    const Spatial vJ{S_[k].w * qd_[k], S_[k].x * qd_[k], S_[k].y * qd_[k]};
    v_[k] = {v_below.w + vJ.w, v_below.x + vJ.x, v_below.y + vJ.y};
    // Velocity-product acceleration of the joint, v x vJ (zero for a weld).
    c_[k] = {0.0, -v_[k].w * vJ.y + vJ.w * v_[k].y, v_[k].w * vJ.x - vJ.w * v_[k].x};
    theta_[k] = theta;
    theta_below = theta;
    omega_below = omega;
    side_below = side;
    v_below = v_[k];
  }
}

void StackChain::Recursion(const Spatial& base_accel, bool with_velocities, const Spatial* applied,
                           double* rel_acc) {
  // Inward: articulated inertia and bias of each subtree, handed to the body below through its
  // joint (projected out along an open joint's axis, whole through a weld).
  Inertia carry_I{};
  Spatial carry_p{};
  for (int k = n_ - 1; k >= 0; --k) {
    const BlockProps& p = geo_.blocks[k];
    const Vec2 G = G_[k];
    Inertia& IA = IA_[k];
    IA.ww = p.I_G + p.m * Dot(G, G) + carry_I.ww;
    IA.wx = -p.m * G.y + carry_I.wx;
    IA.wy = p.m * G.x + carry_I.wy;
    IA.xx = p.m + carry_I.xx;
    IA.xy = carry_I.xy;
    IA.yy = p.m + carry_I.yy;
    Spatial& pA = pA_[k];
    pA = carry_p;
    if (with_velocities) {
      // v x* (I v), I the block's own inertia.
      const Spatial v = v_[k];
      const Spatial h{(p.I_G + p.m * Dot(G, G)) * v.w + p.m * (G.x * v.y - G.y * v.x),
                      p.m * (v.x - v.w * G.y), p.m * (v.y + v.w * G.x)};
      pA.w += v.x * h.y - v.y * h.x;
      pA.x += -v.w * h.y;
      pA.y += v.w * h.x;
    }
    if (applied != nullptr) {
      pA.w -= applied[k].w;
      pA.x -= applied[k].x;
      pA.y -= applied[k].y;
    }
    const Spatial c = with_velocities ? c_[k] : Spatial{};
    if (config_[k] != Contact::kFace) {
      const Spatial S = S_[k];
      const Spatial U = Times(IA, S);
      const double D = S.w * U.w + S.x * U.x + S.y * U.y;
      const double u = -(S.w * pA.w + S.x * pA.x + S.y * pA.y);
      U_[k] = U;
      D_[k] = D;
      u_[k] = u;
      carry_I = {IA.ww - U.w * U.w / D, IA.wx - U.w * U.x / D, IA.wy - U.w * U.y / D,
                 IA.xx - U.x * U.x / D, IA.xy - U.x * U.y / D, IA.yy - U.y * U.y / D};
      const Spatial Ic = Times(carry_I, c);
      const double uD = u / D;
      carry_p = {pA.w + Ic.w + U.w * uD, pA.x + Ic.x + U.x * uD, pA.y + Ic.y + U.y * uD};
    } else {
      carry_I = IA;
      const Spatial Ic = Times(IA, c);
      carry_p = {pA.w + Ic.w, pA.x + Ic.x, pA.y + Ic.y};
    }
  }
  // Outward: the joints' accelerations and each body's spatial acceleration.
  Spatial a_below = base_accel;
  for (int k = 0; k < n_; ++k) {
    if (config_[k] != Contact::kFace) {
      const Spatial c = with_velocities ? c_[k] : Spatial{};
      const Spatial ap{a_below.w + c.w, a_below.x + c.x, a_below.y + c.y};
      const Spatial U = U_[k];
      const double qdd = (u_[k] - (U.w * ap.w + U.x * ap.x + U.y * ap.y)) / D_[k];
      a_[k] = {ap.w + S_[k].w * qdd, ap.x + S_[k].x * qdd, ap.y + S_[k].y * qdd};
      if (rel_acc != nullptr) rel_acc[k] = qdd;
    } else {
      a_[k] = a_below;
      if (rel_acc != nullptr) rel_acc[k] = 0.0;
    }
    a_below = a_[k];
  }
}

void StackChain::Accelerations(double xg_mps2, double yg_mps2, double* theta_dd,
                               InterfaceLoad* loads) {
  // Gravity and the base's acceleration as an acceleration of the base the other way
  // (Featherstone's trick): every body then accelerates by -g_eff more than it does, and the
  // forces across the joints are the real contact forces.
  const Spatial base{0.0, xg_mps2, geo_.g + yg_mps2};
  Recursion(base, true, nullptr, nullptr);
  for (int k = 0; k < n_; ++k) theta_dd[k] = -a_[k].w;
  if (loads == nullptr) return;
  for (int k = 0; k < n_; ++k) {
    const Spatial f = Times(IA_[k], a_[k]);
    force_[k] = {f.w + pA_[k].w, f.x + pA_[k].x, f.y + pA_[k].y};
  }
  Resolve(loads);
}

void StackChain::Resolve(InterfaceLoad* loads) const {
  // force_[k]: the force system (moment about the origin, force) of the support on the blocks
  // from k up, in the support's top-face frame; a closed face carries it on block k's two base
  // corners.
  for (int k = 0; k < n_; ++k) {
    InterfaceLoad& L = loads[k];
    const Spatial F = force_[k];
    const double sn = k == 0 ? 0.0 : sin_[k - 1], cs = k == 0 ? 1.0 : cos_[k - 1];
    L.normal_n = F.x * sn + F.y * cs;
    L.tangential_n = F.x * cs - F.y * sn;
    if (config_[k] != Contact::kFace) {
      L.left_n = L.right_n = 0.0;
      continue;
    }
    const BlockProps& p = geo_.blocks[k];
    // Block k's base centre, the middle of the face: the moment about it is b (N_R - N_L).
    const Vec2 mid = G_[k] - p.h * Vec2{sin_[k], cos_[k]};
    const double moment_mid = F.w - (mid.x * F.y - mid.y * F.x);
    const double diff = moment_mid / p.b;
    L.right_n = 0.5 * (L.normal_n + diff);
    L.left_n = 0.5 * (L.normal_n - diff);
  }
}

void StackChain::LoadsFor(const Vec2* aG, const double* alpha, Vec2 g_eff, InterfaceLoad* loads) {
  // From the top: the force and the moment about the origin that the blocks from k up need.
  Vec2 F{};
  double M = 0.0;
  for (int k = n_ - 1; k >= 0; --k) {
    const BlockProps& p = geo_.blocks[k];
    const Vec2 f = p.m * (aG[k] - g_eff);
    F = F + f;
    M += p.I_G * alpha[k] + Cross(G_[k], f);
    force_[k] = {M, F.x, F.y};
  }
  Resolve(loads);
}

BodyMotion StackChain::Body(int i) const {
  const Spatial v = v_[i];
  const Vec2 G = G_[i];
  return {G, Vec2{v.x - v.w * G.y, v.y + v.w * G.x}, v.w};
}

double StackChain::Energy(double* per_block_j) const {
  double total = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double e = BlockEnergy_j(geo_.blocks[i], geo_.g, Body(i));
    if (per_block_j != nullptr) per_block_j[i] = e;
    total += e;
  }
  return total;
}

void StackChain::ImpactRates(const Configuration& after, double* omega_plus,
                             InterfaceLoad* impulses) {
  // The blocks' spatial momenta about the origin before the impact, applied as impulses to the
  // stack at rest in `after`: the recursion's "accelerations" are then the velocities after.
  for (int k = 0; k < n_; ++k) {
    const BlockProps& p = geo_.blocks[k];
    const Vec2 G = G_[k];
    const Spatial v = v_[k];
    momenta_[k] = {(p.I_G + p.m * Dot(G, G)) * v.w + p.m * (G.x * v.y - G.y * v.x),
                   p.m * (v.x - v.w * G.y), p.m * (v.y + v.w * G.x)};
  }
  // The same angles (an impact changes rates, not positions), `after`'s pivots.
  Place(after, theta_.data(), zero_.data());
  Recursion(Spatial{}, false, momenta_.data(), nullptr);
  for (int k = 0; k < n_; ++k) omega_plus[k] = -a_[k].w;
  if (impulses != nullptr) {
    // The impulse across each interface: the jump of the momentum of the blocks above it.
    for (int k = 0; k < n_; ++k) {
      const Spatial f = Times(IA_[k], a_[k]);
      force_[k] = {f.w + pA_[k].w, f.x + pA_[k].x, f.y + pA_[k].y};
    }
    Resolve(impulses);
  }
  Place(after, theta_.data(), omega_plus);
}

}  // namespace rockbench::reference
