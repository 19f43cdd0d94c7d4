#include "reference/thesis/kinematics.h"

#include <cmath>

namespace rockbench::reference {
namespace {

double SideSign(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

// Rotation by the CCW angle phi = -theta, from theta's sine and cosine (cos phi = cos theta,
// sin phi = -sin theta).
Vec2 RotateBack(double sin_theta, double cos_theta, Vec2 v) {
  return {cos_theta * v.x + sin_theta * v.y, -sin_theta * v.x + cos_theta * v.y};
}

// Positions of the chain points for pivot sides s1 (ground) and s2 (interface). The model's own
// pivots (the thesis's equations), not a placement: engines and renders use scene/stack_pose.h.
struct Points {
  Vec2 P1, Q2, G1, G2;
  double s1, s2;
};

Points Place(const Geometry& geo, Contacts c, const Tilts& tl) {
  const BlockProps& p1 = geo.block1;
  const BlockProps& p2 = geo.block2;
  Points pts;
  pts.s1 = SideSign(c.ground);
  // Locked interface: any corner gives the same motion; take block 1's side.
  pts.s2 = c.interface == Contact::kFace ? pts.s1 : SideSign(c.interface);
  pts.P1 = {pts.s1 * p1.b, 0.0};
  pts.G1 = pts.P1 + RotateBack(tl.sin1, tl.cos1, Vec2{0.0, p1.h} - Vec2{pts.s1 * p1.b, 0.0});
  pts.Q2 = pts.P1 +
           RotateBack(tl.sin1, tl.cos1, Vec2{pts.s2 * p2.b, 2.0 * p1.h} - Vec2{pts.s1 * p1.b, 0.0});
  pts.G2 = pts.Q2 + RotateBack(tl.sin2, tl.cos2, Vec2{0.0, p2.h} - Vec2{pts.s2 * p2.b, 0.0});
  return pts;
}

}  // namespace

Tilts TiltsOf(const State& s) {
  return {std::sin(s.theta1), std::cos(s.theta1), std::sin(s.theta2), std::cos(s.theta2)};
}

int DofCount(Mode mode, bool two_blocks) {
  const Contacts c = ContactsOf(mode);
  if (!two_blocks) return c.ground == Contact::kFace ? 0 : 1;
  return (c.ground != Contact::kFace) + (c.interface != Contact::kFace);
}

Chain EvaluateChain(const Geometry& geo, Mode mode, const State& s) {
  return EvaluateChain(geo, mode, s, TiltsOf(s));
}

Chain EvaluateChain(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts) {
  const Contacts c = ContactsOf(mode);
  const Points pts = Place(geo, c, tilts);
  Chain ch;
  ch.tilts = tilts;
  ch.P1 = pts.P1;
  ch.Q2 = pts.Q2;
  ch.G = {pts.G1, pts.G2};
  // Derivatives in full coordinates (theta1, theta2): rotation about a pivot, dX/dtheta = -perp.
  const Vec2 dG1_dt1 = -1.0 * Perp(pts.G1 - pts.P1);
  const Vec2 dQ2_dt1 = -1.0 * Perp(pts.Q2 - pts.P1);
  const Vec2 dG2_dt2 = -1.0 * Perp(pts.G2 - pts.Q2);
  const bool ground_moves = c.ground != Contact::kFace;
  const bool interface_moves = geo.two_blocks && c.interface != Contact::kFace;
  if (ground_moves && interface_moves) {  // modes 1, 2
    ch.ndof = 2;
    ch.JG[0] = {dG1_dt1, Vec2{}};
    ch.JG[1] = {dQ2_dt1, dG2_dt2};
    ch.Jphi[0] = {-1.0, 0.0};
    ch.Jphi[1] = {0.0, -1.0};
    ch.u = {s.omega1, s.omega2};
  } else if (ground_moves) {  // mode 3 (or one block): theta2 = theta1
    ch.ndof = 1;
    ch.JG[0] = {dG1_dt1, Vec2{}};
    ch.JG[1] = {dQ2_dt1 + dG2_dt2, Vec2{}};
    ch.Jphi[0] = {-1.0, 0.0};
    ch.Jphi[1] = {-1.0, 0.0};
    ch.u = {s.omega1, 0.0};
  } else if (interface_moves) {  // mode 4
    ch.ndof = 1;
    ch.JG[1] = {dG2_dt2, Vec2{}};
    ch.Jphi[1] = {-1.0, 0.0};
    ch.u = {s.omega2, 0.0};
  }
  // Velocity-product accelerations: centripetal terms of the pivot chain.
  const double w1 = ground_moves ? s.omega1 : 0.0;
  const double w2 = interface_moves ? s.omega2 : (ground_moves ? s.omega1 : 0.0);
  ch.a_vp[0] = -(w1 * w1) * (pts.G1 - pts.P1);
  ch.a_vp[1] = -(w1 * w1) * (pts.Q2 - pts.P1) - (w2 * w2) * (pts.G2 - pts.Q2);
  if (!geo.two_blocks) ch.a_vp[1] = {};
  return ch;
}

GeneralizedDynamics AssembleDynamics(const Geometry& geo, Mode mode, const State& s, double xg_mps2,
                                     double yg_mps2) {
  const Chain ch = EvaluateChain(geo, mode, s);
  GeneralizedDynamics gd;
  gd.ndof = ch.ndof;
  const Vec2 g_eff{-xg_mps2, -(geo.g + yg_mps2)};
  const int nbody = geo.two_blocks ? 2 : 1;
  const double m[2] = {geo.block1.m, geo.block2.m};
  const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
  for (int b = 0; b < nbody; ++b) {
    const Vec2 force = m[b] * (g_eff - ch.a_vp[b]);
    for (int i = 0; i < ch.ndof; ++i) {
      gd.f[i] += Dot(ch.JG[b][i], force);
      for (int j = 0; j < ch.ndof; ++j) {
        gd.M[i][j] += m[b] * Dot(ch.JG[b][i], ch.JG[b][j]) + IG[b] * ch.Jphi[b][i] * ch.Jphi[b][j];
      }
    }
  }
  return gd;
}

std::array<double, 2> GenericAccelerations(const Geometry& geo, Mode mode, const State& s,
                                           double xg_mps2, double yg_mps2) {
  const GeneralizedDynamics gd = AssembleDynamics(geo, mode, s, xg_mps2, yg_mps2);
  const Contacts c = ContactsOf(mode);
  if (gd.ndof == 0) return {0.0, 0.0};
  if (gd.ndof == 1) {
    const double a = gd.f[0] / gd.M[0][0];
    if (c.ground == Contact::kFace) return {0.0, a};  // mode 4
    return {a, a};                                    // mode 3 / one block
  }
  const double det = gd.M[0][0] * gd.M[1][1] - gd.M[0][1] * gd.M[1][0];
  return {(gd.f[0] * gd.M[1][1] - gd.M[0][1] * gd.f[1]) / det,
          (gd.M[0][0] * gd.f[1] - gd.M[1][0] * gd.f[0]) / det};
}

namespace {

// Splits a face contact force into the normal forces at its two corners. The face runs through
// corners cL and cR with inward normal n (pointing into the supported body). F is the total
// force on the supported body and Mx its total moment about X (CCW).
void SplitFace(Vec2 cL, Vec2 cR, Vec2 n, Vec2 F, double Mx, Vec2 X, double* NL, double* NR) {
  const Vec2 t = cR - cL;
  const double half = 0.5 * std::sqrt(Dot(t, t));
  const Vec2 tu = (1.0 / (2.0 * half)) * t;
  const Vec2 mid = 0.5 * (cL + cR);
  const double N = Dot(F, n);
  // Moment about the mid point: the tangential force has no arm there.
  const double M_mid = Mx + Cross(X - mid, F);
  // Normal forces NL at mid - half tu, NR at mid + half tu: moment about mid = half (NR - NL)
  // (tu x n) with tu x n = +1 for an upward normal and a rightward tangent.
  const double tn = Cross(tu, n);
  const double diff = M_mid / (half * tn);  // NR - NL
  *NR = 0.5 * (N + diff);
  *NL = 0.5 * (N - diff);
}

}  // namespace

Reactions ComputeReactions(const Geometry& geo, Mode mode, const State& s,
                           const std::array<double, 2>& acc, double xg_mps2, double yg_mps2) {
  return ComputeReactions(geo, mode, s, TiltsOf(s), acc, xg_mps2, yg_mps2);
}

Reactions ComputeReactions(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts,
                           const std::array<double, 2>& acc, double xg_mps2, double yg_mps2) {
  const Contacts c = ContactsOf(mode);
  const Chain ch = EvaluateChain(geo, mode, s, tilts);
  // Generalized accelerations of the mode.
  double ud[2] = {0.0, 0.0};
  if (ch.ndof == 2) {
    ud[0] = acc[0];
    ud[1] = acc[1];
  } else if (ch.ndof == 1) {
    ud[0] = c.ground == Contact::kFace ? acc[1] : acc[0];
  }
  std::array<Vec2, 2> aG;
  std::array<double, 2> alpha;  // CCW angular accelerations
  for (int b = 0; b < 2; ++b) {
    aG[b] = ch.a_vp[b];
    alpha[b] = 0.0;
    for (int k = 0; k < ch.ndof; ++k) {
      aG[b] = aG[b] + ud[k] * ch.JG[b][k];
      alpha[b] += ch.Jphi[b][k] * ud[k];
    }
  }
  return ContactLoads(geo, mode, tilts, aG, alpha, Vec2{-xg_mps2, -(geo.g + yg_mps2)});
}

Reactions ContactLoads(const Geometry& geo, Mode mode, const State& s,
                       const std::array<Vec2, 2>& aG, const std::array<double, 2>& alpha,
                       Vec2 g_eff) {
  return ContactLoads(geo, mode, TiltsOf(s), aG, alpha, g_eff);
}

Reactions ContactLoads(const Geometry& geo, Mode mode, const Tilts& tl,
                       const std::array<Vec2, 2>& aG, const std::array<double, 2>& alpha,
                       Vec2 g_eff) {
  const Contacts c = ContactsOf(mode);
  const Points pts = Place(geo, c, tl);
  const Vec2 G1 = pts.G1, G2 = pts.G2;
  const BlockProps& p1 = geo.block1;
  const BlockProps& p2 = geo.block2;
  Reactions r;
  Vec2 F_int{};                     // force of block 1 on block 2
  double M_int_G1 = 0.0;            // moment of that force system about G1
  const Vec2 n1{tl.sin1, tl.cos1};  // block 1's top-face normal
  const Vec2 t1{tl.cos1, -tl.sin1};
  if (geo.two_blocks) {
    F_int = p2.m * (aG[1] - g_eff);
    // Moment of the interface forces about G2 equals I_G2 alpha2.
    const double M_G2 = p2.I_G * alpha[1];
    M_int_G1 = M_G2 + Cross(G2 - G1, F_int);
    r.N_interface = Dot(F_int, n1);
    r.T_interface = Dot(F_int, t1);
    if (c.interface == Contact::kFace) {
      // Block 2's base corners, on block 1's top face.
      const Vec2 base_c = G2 - p2.h * Vec2{tl.sin2, tl.cos2};
      const Vec2 cL = base_c - p2.b * t1, cR = base_c + p2.b * t1;
      SplitFace(cL, cR, n1, F_int, M_G2, G2, &r.interface_left, &r.interface_right);
    }
  }
  // Ground on block 1: m1 aG1 = F_gnd + m1 g_eff - F_int.
  const Vec2 F_gnd = p1.m * (aG[0] - g_eff) + F_int;
  r.N_ground = F_gnd.y;
  r.T_ground = F_gnd.x;
  if (c.ground == Contact::kFace) {
    const double M_G1 = p1.I_G * alpha[0] + M_int_G1;
    SplitFace(Vec2{-p1.b, 0.0}, Vec2{p1.b, 0.0}, Vec2{0.0, 1.0}, F_gnd, M_G1, G1, &r.ground_left,
              &r.ground_right);
  }
  return r;
}

BodyVelocities Velocities(const Geometry& geo, Mode mode, const State& s) {
  return Velocities(EvaluateChain(geo, mode, s));
}

BodyVelocities Velocities(const Chain& ch) {
  BodyVelocities v;
  for (int b = 0; b < 2; ++b) {
    for (int k = 0; k < ch.ndof; ++k) {
      v.vG[b] = v.vG[b] + ch.u[k] * ch.JG[b][k];
      v.w[b] += ch.Jphi[b][k] * ch.u[k];
    }
  }
  return v;
}

double AngularMomentum(const Geometry& geo, Mode mode, const State& s, Vec2 A, int body) {
  const Chain ch = EvaluateChain(geo, mode, s);
  const BodyVelocities v = Velocities(ch);
  const double m[2] = {geo.block1.m, geo.block2.m};
  const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
  double h = 0.0;
  for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
    if (body >= 0 && body != b) continue;
    h += IG[b] * v.w[b] + m[b] * Cross(ch.G[b] - A, v.vG[b]);
  }
  return h;
}

std::array<std::array<Vec2, 4>, 2> BlockCorners(const Geometry& geo, Mode mode, const State& s) {
  const Tilts tl = TiltsOf(s);
  const Points pts = Place(geo, ContactsOf(mode), tl);
  std::array<std::array<Vec2, 4>, 2> out{};
  const BlockProps* p[2] = {&geo.block1, &geo.block2};
  const Vec2 G[2] = {pts.G1, pts.G2};
  const double sin_t[2] = {tl.sin1, tl.sin2}, cos_t[2] = {tl.cos1, tl.cos2};
  for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
    const double bx = p[b]->b, hy = p[b]->h;
    const Vec2 local[4] = {{-bx, -hy}, {bx, -hy}, {bx, hy}, {-bx, hy}};
    for (int k = 0; k < 4; ++k) out[b][k] = G[b] + RotateBack(sin_t[b], cos_t[b], local[k]);
  }
  return out;
}

}  // namespace rockbench::reference
