#include "reference/unilateral/unilateral.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "reference/thesis/impact.h"
#include "reference/unilateral/lcp.h"

namespace rockbench::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// J(d) = (d_y, -d_x): the velocity of offset d on a body turning clockwise at unit rate.
Vec2 J(Vec2 d) {
  return {d.y, -d.x};
}
// A body-frame offset p turned by the clockwise angle theta (its sine s and cosine c).
Vec2 Turn(double c, double s, Vec2 p) {
  return {p.x * c + p.y * s, -p.x * s + p.y * c};
}

// Dense solve of a x = b (n x n, row-major) by Gaussian elimination with partial pivoting on
// the system scaled symmetrically, D a D y = D b, x = D y: D_i = scale[i], or 1/sqrt(|a_ii|)
// (Jacobi scaling; 1 where a_ii = 0). The scaling makes the rows of blocks of very different
// masses (1e12) comparable: without it a heavy block's rows fall below the pivot tolerance.
// False when a pivot is below 1e-12 of the scaled system's largest entry (the equations are
// singular: never for a mode's rows, whose matrix is block triangular over the interfaces with
// full-rank diagonal blocks, docs/sliding.md).
//
// `group` (optional, nondecreasing): the interface of each row and column, when a row of
// interface k touches only the columns of interfaces k - 1 to k + 1 (a mode's rows: each
// acts on a block and its support). The elimination then stays inside the band: a column's
// pivot is sought among the rows of its interface and the next, and a pivot row (of the next
// interface at most) reaches the columns of the interface after that.
bool SolveDense(std::vector<double>& a, std::vector<double>& b, int n,
                const double* scale = nullptr, const int* group = nullptr) {
  if (n == 0) return true;
  std::vector<double> d(static_cast<size_t>(n), 1.0);
  for (int i = 0; i < n; ++i) {
    const double aii = std::abs(a[i * n + i]);
    d[i] = scale != nullptr ? scale[i] : (aii > 0.0 ? 1.0 / std::sqrt(aii) : 1.0);
    if (!(d[i] > 0.0) || !std::isfinite(d[i])) return false;
  }
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) a[r * n + c] *= d[r] * d[c];
    b[r] *= d[r];
  }
  double scale_max = 0.0;
  for (const double x : a) scale_max = std::max(scale_max, std::abs(x));
  if (!(scale_max > 0.0) || !std::isfinite(scale_max)) return false;
  const double tol = 1e-12 * scale_max;
  // The end of the rows (and columns) of interfaces up to group[i] + 1 and + 2.
  std::vector<int> end1(static_cast<size_t>(n), n), end2(static_cast<size_t>(n), n);
  if (group != nullptr) {
    for (int i = n - 1, e1 = n, e2 = n; i >= 0; --i) {
      int j = i;
      while (j < n && group[j] <= group[i] + 1) ++j;
      e1 = j;
      while (j < n && group[j] <= group[i] + 2) ++j;
      e2 = j;
      end1[i] = e1;
      end2[i] = e2;
    }
  }
  for (int col = 0; col < n; ++col) {
    const int rows = end1[col], cols = end2[col];
    int piv = col;
    for (int r = col + 1; r < rows; ++r) {
      if (std::abs(a[r * n + col]) > std::abs(a[piv * n + col])) piv = r;
    }
    if (std::abs(a[piv * n + col]) <= tol) return false;
    if (piv != col) {
      for (int j = col; j < cols; ++j) std::swap(a[col * n + j], a[piv * n + j]);
      std::swap(b[col], b[piv]);
    }
    for (int r = col + 1; r < rows; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      if (f == 0.0) continue;
      for (int j = col; j < cols; ++j) a[r * n + j] -= f * a[col * n + j];
      b[r] -= f * b[col];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int j = r + 1; j < end2[r]; ++j) s -= a[r * n + j] * b[j];
    b[r] = s / a[r * n + r];
  }
  for (int r = 0; r < n; ++r) b[r] *= d[r];
  return true;
}

// A constraint row w (its upper block's three entries, then its support's) times x (3 per
// block): the relative normal or tangential rate (or acceleration, without its velocity terms)
// of interface k's contact.
double RowTimes(const std::array<double, 6>& w, int k, const double* x) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i) s += w[i] * x[3 * k + i];
  if (k > 0) {
    for (int i = 0; i < 3; ++i) s += w[3 + i] * x[3 * (k - 1) + i];
  }
  return s;
}

}  // namespace

UnilateralStack::UnilateralStack(std::vector<UnilateralBlock> blocks, double g_mps2)
    : blocks_(std::move(blocks)), n_(static_cast<int>(blocks_.size())), g_(g_mps2) {
  if (n_ < 1 || n_ > kUnilateralMaxBlocks) {
    throw std::invalid_argument("the unilateral model takes 1 to " +
                                std::to_string(kUnilateralMaxBlocks) + " blocks");
  }
  double mass = 0.0;
  length_ = 0.0;
  for (const UnilateralBlock& b : blocks_) {
    mass += b.mass_kg;
    length_ = std::max(length_, std::hypot(b.b_m, b.h_m));
  }
  weight_ = mass * g_;
  // The rest rule's speed per interface (the chain's rule, stack_contacts.h RestRate, as a
  // separation speed): R_k from block k's base corner to the mass centre of blocks k..N at
  // rest, and the two contact points 2 min(b_k, b_(k-1)) apart (the upper block's base corners,
  // or its support's top corners where the support is the narrower).
  const std::vector<double> radius_m = RestRadii_m(n_, [&](int k) {
    const UnilateralBlock& b = blocks_[k];
    return std::array<double, 3>{b.b_m, b.h_m, b.mass_kg};
  });
  rest_speed_rel_.assign(static_cast<size_t>(n_), 0.0);
  for (int k = 0; k < n_; ++k) {
    const double b = blocks_[k].b_m, span = 2.0 * (k > 0 ? std::min(b, blocks_[k - 1].b_m) : b);
    rest_speed_rel_[k] = std::sqrt(g_ / radius_m[k]) * span;
  }
  resolved_speed_ = std::sqrt(2.0 * g_ * 4.0 * std::numeric_limits<double>::epsilon() * length_);
}

UnilateralStack UnilateralStack::OfScene(const Scene& scene) {
  std::vector<UnilateralBlock> blocks;
  for (const BlockDef& d : scene.blocks) {
    UnilateralBlock b;
    b.b_m = d.width_m / 2;
    b.h_m = d.height_m / 2;
    b.mass_kg = d.mass_kg;
    b.inertia_kgm2 = d.mass_kg * (b.b_m * b.b_m + b.h_m * b.h_m) / 3.0;
    b.friction = d.friction;
    blocks.push_back(b);
  }
  return UnilateralStack(std::move(blocks), scene.run.gravity_mps2);
}

std::array<SlotKinematics, 2> UnilateralStack::Slots(int k, const double* q, const double* v,
                                                     const ContactMode* mode) const {
  std::array<SlotKinematics, 2> out;
  const UnilateralBlock& U = blocks_[k];
  const Vec2 GU{q[3 * k], q[3 * k + 1]};
  const Vec2 vU{v[3 * k], v[3 * k + 1]};
  const double thU = q[3 * k + 2], wU = v[3 * k + 2];
  const double cU = std::cos(thU), sU = std::sin(thU);
  const bool ground = k == 0;
  Vec2 GL{0.0, 0.0}, vL{0.0, 0.0};
  double wL = 0.0, cL = 1.0, sL = 0.0, bL = kInf, hL = 0.0;
  if (!ground) {
    GL = {q[3 * (k - 1)], q[3 * (k - 1) + 1]};
    vL = {v[3 * (k - 1)], v[3 * (k - 1) + 1]};
    wL = v[3 * (k - 1) + 2];
    cL = std::cos(q[3 * (k - 1) + 2]);
    sL = std::sin(q[3 * (k - 1) + 2]);
    bL = blocks_[k - 1].b_m;
    hL = blocks_[k - 1].h_m;
  }
  // The support's top face (its middle, normal, tangent) and the upper block's base.
  const Vec2 top = GL + Turn(cL, sL, {0.0, hL});
  const Vec2 nL{sL, cL}, tL{cL, -sL};
  const Vec2 base = GU + Turn(cU, sU, {0.0, -U.h_m});
  const Vec2 nU{sU, cU}, tU{cU, -sU};
  for (int j = 0; j < 2; ++j) {
    const double side = j == 0 ? 1.0 : -1.0;
    SlotKinematics& s = out[j];
    Vec2 point, n, t;
    double w_owner = 0.0;
    const Vec2 corner_u = GU + Turn(cU, sU, {side * U.b_m, -U.h_m});
    const double xi_a = Dot(corner_u - top, tL);
    s.xi_upper_corner_m = xi_a;
    if (!ground) {
      s.xi_support_corner_m = Dot(GL + Turn(cL, sL, {side * bL, hL}) - base, tU);
    }
    // The mode's point for a closed slot; else the corner over a face.
    const bool fixed = mode != nullptr && mode->closed[k][j];
    const bool use_upper =
        ground || (fixed ? !mode->support_corner[k][j] : std::abs(xi_a) <= bL * (1.0 + 1e-9));
    if (use_upper) {
      // The upper block's corner over the support's face.
      s.upper_corner = true;
      point = corner_u;
      n = nL;
      t = tL;
      w_owner = wL;
      s.gap_m = Dot(corner_u - top, nL);
      s.xi_m = xi_a;
      s.extent_m = bL;
      s.exists = ground || std::abs(xi_a) <= bL * (1.0 + 1e-9);
    } else {
      const Vec2 corner_l = GL + Turn(cL, sL, {side * bL, hL});
      const double xi_b = s.xi_support_corner_m;
      s.exists = std::abs(xi_b) < U.b_m;
      if (!s.exists && !fixed) continue;  // past both: the slot is empty
      s.upper_corner = false;
      point = corner_l;
      n = nU;
      t = tU;
      w_owner = wU;
      s.gap_m = Dot(base - corner_l, nU);
      s.xi_m = xi_b;
      s.extent_m = U.b_m;
    }
    const Vec2 dU = point - GU, dL = point - GL;
    const Vec2 v_rel = (vU + wU * J(dU)) - (vL + wL * J(dL));
    s.gap_rate_mps = Dot(v_rel, n);
    s.slip_rate_mps = Dot(v_rel, t);
    // Generalized directions: the force n (or t) on the upper block at the point and minus it
    // on the support; a clockwise moment is J(d) . F.
    s.wn = {n.x, n.y, Dot(J(dU), n), -n.x, -n.y, -Dot(J(dL), n)};
    s.wt = {t.x, t.y, Dot(J(dU), t), -t.x, -t.y, -Dot(J(dL), t)};
    // The relative acceleration's velocity-product terms: the centripetal accelerations of the
    // two material points, and the turning of the face's normal (docs/sliding.md).
    const Vec2 centripetal = (-wU * wU) * dU - (-wL * wL) * dL;
    s.kappa_n = Dot(centripetal, n) + 2.0 * w_owner * Dot(v_rel, t);
    s.kappa_t = Dot(centripetal, t) - w_owner * Dot(v_rel, n);
  }
  return out;
}

double UnilateralStack::Coupling(int kw, const std::array<double, 6>& w, int kv,
                                 const std::array<double, 6>& v) const {
  double sum = 0.0;
  for (int side_w = 0; side_w < 2; ++side_w) {
    const int blk = kw - side_w;
    if (blk < 0) continue;
    for (int side_v = 0; side_v < 2; ++side_v) {
      if (kv - side_v != blk) continue;
      const UnilateralBlock& b = blocks_[blk];
      sum += (w[3 * side_w] * v[3 * side_v] + w[3 * side_w + 1] * v[3 * side_v + 1]) / b.mass_kg +
             w[3 * side_w + 2] * v[3 * side_v + 2] / b.inertia_kgm2;
    }
  }
  return sum;
}

bool UnilateralStack::SolveConstrained(const std::vector<Constraint>& cons, const double* base,
                                       double* x, double* lam) const {
  // Unknowns in chain order: interface k's multipliers (group 2k), then block k's three
  // coordinates (group 2k + 1); the equations in the same order (a row of interface k touches
  // blocks k - 1 and k, block k's equations the multipliers of interfaces k and k + 1).
  const int m = static_cast<int>(cons.size());
  const int size = m + 3 * n_;
  std::vector<int> at_block(static_cast<size_t>(n_)), at_con(static_cast<size_t>(m));
  std::vector<int> group(static_cast<size_t>(size));
  {
    int i = 0, c = 0;
    for (int k = 0; k < n_; ++k) {
      for (; c < m && cons[c].k == k; ++c) {
        at_con[c] = i;
        group[i++] = 2 * k;
      }
      at_block[k] = i;
      for (int j = 0; j < 3; ++j) group[i++] = 2 * k + 1;
    }
    if (c != m) return false;  // not ordered by interface
  }
  // Scaled unknowns: x = D y (D = M^-1/2 per block), lam_c = s_c l_c (s_c = 1 / |row_c|_M^-1).
  auto d = [&](int blk, int i) {
    const UnilateralBlock& b = blocks_[blk];
    return 1.0 / std::sqrt(i == 2 ? b.inertia_kgm2 : b.mass_kg);
  };
  std::vector<double> s(static_cast<size_t>(m));
  for (int c = 0; c < m; ++c) {
    s[c] = 1.0 / std::sqrt(Coupling(cons[c].k, cons[c].row, cons[c].k, cons[c].row));
  }
  std::vector<double> K(static_cast<size_t>(size * size), 0.0), r(static_cast<size_t>(size), 0.0);
  auto Kat = [&](int i, int j) -> double& { return K[static_cast<size_t>(i * size + j)]; };
  for (int c = 0; c < m; ++c) {
    const Constraint& con = cons[c];
    const int row = at_con[c];
    // s_c (row_c . D y) = -s_c rhs_c.
    for (int side = 0; side < 2; ++side) {
      const int blk = con.k - side;
      if (blk < 0) continue;
      for (int i = 0; i < 3; ++i) {
        Kat(row, at_block[blk] + i) = s[c] * con.row[3 * side + i] * d(blk, i);
        // Block equations, scaled by D: y - D dir_c s_c l_c = D M base.
        Kat(at_block[blk] + i, row) = -d(blk, i) * con.dir[3 * side + i] * s[c];
      }
    }
    r[row] = -s[c] * con.rhs;
  }
  for (int blk = 0; blk < n_; ++blk) {
    for (int i = 0; i < 3; ++i) {
      Kat(at_block[blk] + i, at_block[blk] + i) = 1.0;
      r[at_block[blk] + i] = base[3 * blk + i] / d(blk, i);
    }
  }
  const std::vector<double> ones(static_cast<size_t>(size), 1.0);
  if (!SolveDense(K, r, size, ones.data(), group.data())) return false;
  for (int blk = 0; blk < n_; ++blk) {
    for (int i = 0; i < 3; ++i) x[3 * blk + i] = d(blk, i) * r[at_block[blk] + i];
  }
  for (int c = 0; c < m; ++c) lam[c] = s[c] * r[at_con[c]];
  return true;
}

bool UnilateralStack::SolveCandidate(const ContactMode& mode,
                                     const std::vector<std::array<SlotKinematics, 2>>& slots,
                                     const double* rhs_base, bool impact, ModeSolution* out) const {
  // The unknowns (columns) and the constraints (rows): a closed slot's normal force (with its
  // friction when the interface slips) and zero normal relative acceleration (impact: velocity);
  // a sticking interface's tangential force and zero slip acceleration (velocity) at its first
  // closed slot. A limit slip at infinite friction (the header): the slot's friction tau
  // along -slip, and zero normal acceleration.
  struct Column {
    int k;
    std::array<double, 6> w;
    std::array<double, 6> row;
    double kappa;
  };
  std::vector<Column> cols;
  cols.reserve(static_cast<size_t>(3 * n_));
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    const double mu = blocks_[k].friction;
    const Slip slip = mode.slip[k];
    const double sign = static_cast<double>(static_cast<int>(slip));
    int ref = -1;
    for (int j = 0; j < 2; ++j) {
      if (!mode.closed[k][j]) continue;
      const SlotKinematics& s = slots[k][j];
      if (ref < 0) ref = j;
      Column c{k, s.wn, s.wn, s.kappa_n};
      if (slip != Slip::kStick && std::isinf(mu)) {
        for (int i = 0; i < 6; ++i) c.w[i] = -sign * s.wt[i];
      } else if (slip != Slip::kStick && mu > 0.0) {
        for (int i = 0; i < 6; ++i) c.w[i] += -sign * mu * s.wt[i];
      }
      cols.push_back(c);
    }
    if (slip == Slip::kStick) {
      const SlotKinematics& s = slots[k][ref];
      cols.push_back({k, s.wt, s.wt, s.kappa_t});
    }
  }
  const int m = static_cast<int>(cols.size());
  std::vector<double> x(static_cast<size_t>(3 * n_)), b(static_cast<size_t>(m));
  // rhs_base: M^-1 f (accelerations) or v- (impact). The Schur complement W^T M^-1 W of the
  // rows (banded, Jacobi-scaled: the cheaper system); where it is singular to working
  // precision (a light block between heavy ones), the augmented system.
  bool solved = false;
  {
    std::vector<double> A(static_cast<size_t>(m * m), 0.0), scale(static_cast<size_t>(m));
    std::vector<int> group(static_cast<size_t>(m));
    for (int r = 0; r < m; ++r) {
      for (int c = 0; c < m; ++c) {
        if (std::abs(cols[r].k - cols[c].k) > 1) continue;
        A[r * m + c] = Coupling(cols[r].k, cols[r].row, cols[c].k, cols[c].w);
      }
      // The row's own norm in the mass metric scales it (a friction column's diagonal entry
      // may be small or negative; the row's norm is not).
      scale[r] = 1.0 / std::sqrt(Coupling(cols[r].k, cols[r].row, cols[r].k, cols[r].row));
      b[r] = -(RowTimes(cols[r].row, cols[r].k, rhs_base) + (impact ? 0.0 : cols[r].kappa));
      group[r] = cols[r].k;
    }
    if (SolveDense(A, b, m, scale.data(), group.data())) {
      solved = true;
      std::copy(rhs_base, rhs_base + 3 * n_, x.begin());
      for (int c = 0; c < m; ++c) {
        const Column& col = cols[c];
        for (int side = 0; side < 2; ++side) {
          const int blk = col.k - side;
          if (blk < 0) continue;
          const UnilateralBlock& B = blocks_[blk];
          x[3 * blk] += col.w[3 * side] * b[c] / B.mass_kg;
          x[3 * blk + 1] += col.w[3 * side + 1] * b[c] / B.mass_kg;
          x[3 * blk + 2] += col.w[3 * side + 2] * b[c] / B.inertia_kgm2;
        }
      }
    }
  }
  if (!solved) {
    std::vector<Constraint> cons(static_cast<size_t>(m));
    for (int c = 0; c < m; ++c) {
      cons[c] = {cols[c].k, cols[c].w, cols[c].row, impact ? 0.0 : cols[c].kappa};
    }
    if (!SolveConstrained(cons, rhs_base, x.data(), b.data())) return false;
  }
  out->normal.assign(static_cast<size_t>(n_), 0.0);
  out->tangential.assign(static_cast<size_t>(n_), 0.0);
  out->slot_normal.assign(static_cast<size_t>(n_), {0.0, 0.0});
  int c = 0;
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    const double mu = blocks_[k].friction;
    const double sign = static_cast<double>(static_cast<int>(mode.slip[k]));
    const bool limit = mode.slip[k] != Slip::kStick && std::isinf(mu);
    for (int j = 0; j < 2; ++j) {
      if (!mode.closed[k][j]) continue;
      out->slot_normal[k][j] = b[c];
      if (limit) {
        out->tangential[k] += -sign * b[c];  // tau along -slip; the normal force is zero
      } else {
        out->normal[k] += b[c];
      }
      ++c;
    }
    if (mode.slip[k] == Slip::kStick) {
      out->tangential[k] = b[c++];
    } else if (!limit) {
      out->tangential[k] = mu > 0.0 ? -sign * mu * out->normal[k] : 0.0;
    }
  }
  out->result = x;
  out->mode = mode;
  return true;
}

bool UnilateralStack::Accelerations(const ContactMode& mode, const double* q, const double* v,
                                    double xg_mps2, double yg_mps2, double* accel,
                                    ModeSolution* forces) const {
  std::vector<std::array<SlotKinematics, 2>> slots(static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    slots[k] = Slots(k, q, v, &mode);
    // A limit slip (infinite friction) holds only while it slips its way: the driver has no
    // slip-stop event for infinite friction, so a reversed slip makes the equations fail (the
    // step is refused and shrinks, and the run stops there, stated).
    if (mode.slip[k] != Slip::kStick && std::isinf(blocks_[k].friction)) {
      const SlotKinematics& ref = mode.closed[k][0] ? slots[k][0] : slots[k][1];
      if (static_cast<int>(mode.slip[k]) * ref.slip_rate_mps < -1e-9 * std::sqrt(g_ * length_)) {
        return false;
      }
    }
  }
  // M^-1 f: the effective gravity.
  std::vector<double> free(static_cast<size_t>(3 * n_), 0.0);
  for (int i = 0; i < n_; ++i) {
    free[3 * i] = -xg_mps2;
    free[3 * i + 1] = -(g_ + yg_mps2);
  }
  ModeSolution local;
  ModeSolution* out = forces != nullptr ? forces : &local;
  if (!SolveCandidate(mode, slots, free.data(), false, out)) return false;
  std::copy(out->result.begin(), out->result.end(), accel);
  return true;
}

namespace {

// The options of one interface: its slots at a zero gap closed in every subset, each with the
// tangential states its friction and slip rate allow (`slipping`: the sign of a slip under way,
// else 0). Infinite friction sticks; with `limit_slip`, or while it slips, one closed corner
// may also slip (the limit of mu -> infinity, the header).
std::vector<ContactOption> ContactOptionsOf(const std::array<bool, 2>& zero, double mu,
                                            int slipping, bool limit_slip) {
  std::vector<ContactOption> out;
  const std::array<std::array<bool, 2>, 3> subsets = {{{true, true}, {true, false}, {false, true}}};
  const Slip dir = slipping > 0 ? Slip::kRight : Slip::kLeft;
  for (const auto& sub : subsets) {
    if ((sub[0] && !zero[0]) || (sub[1] && !zero[1])) continue;
    const bool one = sub[0] != sub[1];
    std::vector<Slip> tangential;
    if (std::isinf(mu)) {
      if (slipping != 0) {
        if (one) tangential = {dir};
      } else {
        tangential = {Slip::kStick};
        if (limit_slip && one) tangential = {Slip::kStick, Slip::kRight, Slip::kLeft};
      }
    } else if (mu == 0.0) {
      tangential = {Slip::kRight};  // frictionless: the tangential state plays no part
    } else if (slipping != 0) {
      tangential = {dir};
    } else {
      tangential = {Slip::kStick, Slip::kRight, Slip::kLeft};
    }
    for (const Slip t : tangential) out.push_back({sub, t});
  }
  out.push_back({{false, false}, Slip::kStick});  // open
  return out;
}

// Enumerates combinations of per-interface options, by the number of interfaces that differ
// from the preferred option (index 0 of each list), calling try_one until it returns true (stop)
// or `limit` combinations were tried. Returns the number tried.
template <class F>
long Enumerate(const std::vector<std::vector<ContactOption>>& options, long limit,
               const F& try_one) {
  const int n = static_cast<int>(options.size());
  std::vector<int> pick(static_cast<size_t>(n), 0);
  long tried = 0;
  // The interfaces with a choice.
  std::vector<int> free;
  for (int k = 0; k < n; ++k) {
    if (options[k].size() > 1) free.push_back(k);
  }
  const int f = static_cast<int>(free.size());
  for (int d = 0; d <= f; ++d) {
    // Every subset of d free interfaces (lexicographic), each with every non-preferred option.
    std::vector<int> idx(static_cast<size_t>(d));
    for (int i = 0; i < d; ++i) idx[i] = i;
    while (true) {
      // Odometer over the chosen interfaces' non-preferred options.
      std::vector<int> alt(static_cast<size_t>(d), 1);
      while (true) {
        std::fill(pick.begin(), pick.end(), 0);
        for (int i = 0; i < d; ++i) pick[free[idx[i]]] = alt[i];
        if (tried >= limit) return tried;
        ++tried;
        if (try_one(pick)) return tried;
        int i = 0;
        for (; i < d; ++i) {
          if (++alt[i] < static_cast<int>(options[free[idx[i]]].size())) break;
          alt[i] = 1;
        }
        if (i == d) break;
      }
      // Next subset.
      int i = d - 1;
      while (i >= 0 && idx[i] == f - d + i) --i;
      if (i < 0) break;
      ++idx[i];
      for (int j = i + 1; j < d; ++j) idx[j] = idx[j - 1] + 1;
    }
  }
  return tried;
}

// Whether two solutions are the same motion: every translational component within
// kSameImpactMotion (1e-4, the chain's, impact.h) of `linear` and every angular one within it of
// `linear` / `length` (accelerations: g; impacts: the largest velocity). Two solutions that pass
// the contact conditions only within their tolerances (forces and impulses to 1e-9 of their
// scale, rates to 1e-9) differ, by the complementarity of each pair, by at most (x1 - x2)^T M
// (x1 - x2) <= sum(eps |lambda| + eps' |g|), about 1e-9 of the motion's energy scale: a
// difference of sqrt(1e-9) ~ 3e-5 of the scale (impact.h, "Uniqueness"). They are one motion.
// Measured on 200 three-block scenes: the first two different solutions of each undetermined
// run differ by 3.7e-5 to 0.30 of the scale (median 1.7e-2); the 10 of 59 below 1e-4 were such
// tolerance variants, counted as two motions by the former bound of 1e-6.
bool SameMotion(const std::vector<double>& a, const std::vector<double>& b, double linear,
                double length) {
  for (size_t i = 0; i < a.size(); ++i) {
    const double scale = i % 3 == 2 ? linear / length : linear;
    if (!(std::abs(a[i] - b[i]) <= kSameImpactMotion * scale)) return false;
  }
  return true;
}

// The most states an enumeration tries (exhaustive or from a hint).
constexpr long kCandidateCap = 200000;
// The most an enumeration after Lemke tries: every state within two interfaces of Lemke's
// mode (or the hint) for 20 blocks (20 x 9 + 190 x 81 = 15,570).
constexpr long kFallbackCap = 20000;
// The friction coefficient that stands for an infinite one in the LCP: a sticking solution's
// |T| / N above it is mapped to stick all the same and checked; one of the LCP's slips there is
// a limit slip (the header) when those are allowed.
constexpr double kLcpInfiniteFriction = 1e4;

}  // namespace

ContactMode UnilateralStack::ModeOf(const Problem& p,
                                    const std::vector<ContactOption>& pick) const {
  ContactMode mode(n_);
  for (int k = 0; k < n_; ++k) {
    mode.closed[k] = pick[k].closed;
    mode.slip[k] = pick[k].slip;
    mode.support_corner[k] = {!p.slots[k][0].upper_corner, !p.slots[k][1].upper_corner};
  }
  return mode;
}

bool UnilateralStack::Check(const Problem& p, const ContactMode& mode, ModeSolution* sol) const {
  if (!SolveCandidate(mode, p.slots, p.base.data(), p.impact, sol)) return false;
  const double* x = sol->result.data();
  // A row's value in a solution: the rate (impact) or the acceleration with its velocity terms.
  auto row = [&](const std::array<double, 6>& w, double kappa, int k) {
    return RowTimes(w, k, x) + (p.impact ? 0.0 : kappa);
  };
  for (int k = 0; k < n_; ++k) {
    const double mu = blocks_[k].friction;
    int ref = -1;
    for (int j = 0; j < 2; ++j) {
      const SlotKinematics& s = p.slots[k][j];
      if (mode.closed[k][j]) {
        if (ref < 0) ref = j;
        if (sol->slot_normal[k][j] < -p.tol_force) return false;
      } else if (p.zero[k][j] && row(s.wn, s.kappa_n, k) < -p.tol_motion) {
        return false;  // left open, it would move (accelerate) into its support
      }
    }
    if (ref < 0) continue;
    if (mode.slip[k] == Slip::kStick) {
      if (!std::isinf(mu) && std::abs(sol->tangential[k]) > mu * sol->normal[k] + p.tol_force) {
        return false;
      }
    } else if (mu > 0.0 && (p.impact || std::abs(p.slots[k][ref].slip_rate_mps) <= p.rate_tol)) {
      // Friction opposes the slip after an impact; from a zero slip rate the interface must
      // accelerate the way it slips.
      const SlotKinematics& s = p.slots[k][ref];
      if (static_cast<int>(mode.slip[k]) * row(s.wt, s.kappa_t, k) < -p.tol_motion) return false;
    }
  }
  return true;
}

ModeSolution UnilateralStack::Search(const Problem& p,
                                     const std::vector<std::vector<ContactOption>>& options,
                                     bool exhaustive, long cap) const {
  ModeSolution best;
  best.exhaustive = exhaustive;
  const long tried = Enumerate(options, cap, [&](const std::vector<int>& pick) {
    std::vector<ContactOption> chosen(static_cast<size_t>(n_));
    for (int k = 0; k < n_; ++k) chosen[k] = options[k][pick[k]];
    ModeSolution sol;
    if (!Check(p, ModeOf(p, chosen), &sol)) return false;
    if (!best.found) {
      sol.solutions = 1;
      sol.found = true;
      sol.exhaustive = best.exhaustive;
      best = std::move(sol);
      return !best.exhaustive;
    }
    if (!SameMotion(best.result, sol.result, p.same_scale, length_)) ++best.solutions;
    return false;
  });
  best.candidates = tried;
  // An enumeration that ends before its cap has tried every state.
  if (tried < cap) best.exhaustive = true;
  if (!exhaustive && best.found) best.exhaustive = false;
  if (!best.found) best.mode = ContactMode(n_);
  return best;
}

std::vector<std::vector<ContactOption>> UnilateralStack::Options(
    const Problem& p, const std::vector<ContactOption>& preferred, bool limit_slip) const {
  std::vector<std::vector<ContactOption>> options(static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) {
    options[k] = ContactOptionsOf(p.zero[k], blocks_[k].friction, p.slipping[k], limit_slip);
    if (k < static_cast<int>(preferred.size())) {
      const auto it = std::find(options[k].begin(), options[k].end(), preferred[k]);
      if (it != options[k].end()) std::rotate(options[k].begin(), it, it + 1);
    }
  }
  return options;
}

std::vector<UnilateralStack::ForceColumn> UnilateralStack::ForceColumns(const Problem& p,
                                                                        int* nv) const {
  std::vector<ForceColumn> f;
  *nv = 0;
  for (int k = 0; k < n_; ++k) {
    const double mu = blocks_[k].friction;
    const int slipping = p.slipping[k];
    int ref = -1;
    for (int j = 0; j < 2; ++j) {
      if (!p.zero[k][j]) continue;
      if (ref < 0) ref = j;
      const SlotKinematics& s = p.slots[k][j];
      ForceColumn c{k, j, false, s.wn, s.wn, s.kappa_n, 1.0, (*nv)++};
      if (slipping != 0 && std::isinf(mu)) {
        for (int i = 0; i < 6; ++i) c.dir[i] = -slipping * s.wt[i];
      } else if (slipping != 0 && mu > 0.0) {
        for (int i = 0; i < 6; ++i) c.dir[i] += -slipping * mu * s.wt[i];
      }
      f.push_back(c);
    }
    if (ref >= 0 && slipping == 0 && mu > 0.0) {
      const SlotKinematics& s = p.slots[k][ref];
      f.push_back({k, ref, true, s.wt, s.wt, s.kappa_t, 1.0, *nv});
      *nv += 3;
    }
  }
  return f;
}

double UnilateralStack::ScaledCouplings(const Problem& p, std::vector<ForceColumn>* f,
                                        std::vector<double>* A, std::vector<double>* b) const {
  std::vector<ForceColumn>& fc = *f;
  const int m = static_cast<int>(fc.size());
  A->assign(static_cast<size_t>(m * m), 0.0);
  b->assign(static_cast<size_t>(m), 0.0);
  for (int r = 0; r < m; ++r) {
    fc[r].scale = 1.0 / std::sqrt(Coupling(fc[r].k, fc[r].row, fc[r].k, fc[r].row));
  }
  double b_max = 0.0;
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < m; ++c) {
      if (std::abs(fc[r].k - fc[c].k) > 1) continue;
      (*A)[r * m + c] =
          fc[r].scale * Coupling(fc[r].k, fc[r].row, fc[c].k, fc[c].dir) * fc[c].scale;
    }
    (*b)[r] = fc[r].scale *
              (RowTimes(fc[r].row, fc[r].k, p.base.data()) + (p.impact ? 0.0 : fc[r].kappa));
    b_max = std::max(b_max, std::abs((*b)[r]));
  }
  return b_max;
}

void UnilateralStack::ForceLcp(const std::vector<ForceColumn>& f, const std::vector<double>& A,
                               const std::vector<double>& b, int nv, std::vector<double>* M_out,
                               std::vector<double>* q_out) const {
  const int m = static_cast<int>(f.size());
  std::vector<double>& M = *M_out;
  std::vector<double>& q = *q_out;
  M.assign(static_cast<size_t>(nv * nv), 0.0);
  q.assign(static_cast<size_t>(nv), 0.0);
  auto Mat = [&](int i, int j) -> double& { return M[static_cast<size_t>(i * nv + j)]; };
  auto add_row = [&](int var, int r, double sign) {
    for (int c = 0; c < m; ++c) {
      const double a = sign * A[r * m + c];
      if (a == 0.0) continue;
      Mat(var, f[c].var) += a;
      if (f[c].tangential) Mat(var, f[c].var + 1) -= a;
    }
    q[var] = sign * b[r];
  };
  for (int r = 0; r < m; ++r) {
    if (!f[r].tangential) {
      add_row(f[r].var, r, 1.0);
      continue;
    }
    const int tp = f[r].var, tm = tp + 1, sg = tp + 2;
    add_row(tp, r, 1.0);
    add_row(tm, r, -1.0);
    Mat(tp, sg) = 1.0;
    Mat(tm, sg) = 1.0;
    const double mu =
        std::isinf(blocks_[f[r].k].friction) ? kLcpInfiniteFriction : blocks_[f[r].k].friction;
    for (int c = 0; c < m; ++c) {
      if (f[c].tangential || f[c].k != f[r].k) continue;
      Mat(sg, f[c].var) = mu * f[c].scale / f[r].scale;
    }
    Mat(sg, tp) = -1.0;
    Mat(sg, tm) = -1.0;
  }
}

namespace {

// Lemke's method on LCP(M, q) of nv variables; where it ends on a ray, two more covering vectors
// (Lemke's path depends on it): the rows' own sizes (relative to b_max), and a fixed spread.
// Adds the pivots of every attempt to *pivots.
LcpResult SolveLemkeCovered(const std::vector<double>& M, const std::vector<double>& q, int nv,
                            double b_max, int* pivots) {
  LcpResult lcp = SolveLcpLemke(M, q, nv);
  *pivots = lcp.pivots;
  for (int attempt = 0; attempt < 2 && lcp.status != LcpStatus::kSolved; ++attempt) {
    std::vector<double> cover(static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) {
      cover[i] = attempt == 0 ? 1.0 + std::abs(q[i]) / std::max(b_max, 1e-300)
                              : 1.0 + 0.5 * std::sin(1.0 + 7.0 * i);
    }
    lcp = SolveLcpLemke(M, q, nv, 0, cover);
    *pivots += lcp.pivots;
  }
  return lcp;
}

}  // namespace

void UnilateralStack::ModeOfLcp(const Problem& p, const ContactMode& hint, bool limit_slip,
                                const std::vector<ForceColumn>& f, const std::vector<double>& z,
                                const std::vector<double>& w, double b_max,
                                ContactMode* mode) const {
  double z_max = 0.0;
  for (const double zi : z) z_max = std::max(z_max, zi);
  const double tol = 1e-9 * std::max(b_max, z_max);
  *mode = ContactMode(n_);
  for (int k = 0; k < n_; ++k) {
    mode->support_corner[k] = {!p.slots[k][0].upper_corner, !p.slots[k][1].upper_corner};
  }
  for (const ForceColumn& c : f) {
    if (c.tangential) continue;
    const double zc = z[c.var], wc = w[c.var];
    const bool hinted = c.k < static_cast<int>(hint.closed.size()) && hint.closed[c.k][c.j];
    mode->closed[c.k][c.j] = zc > tol || (wc <= tol && hinted);
  }
  for (int k = 0; k < n_; ++k) {
    if (!mode->any_closed(k)) continue;
    const double mu = blocks_[k].friction;
    if (p.slipping[k] != 0) {
      mode->slip[k] = p.slipping[k] > 0 ? Slip::kRight : Slip::kLeft;
    } else if (mu == 0.0) {
      mode->slip[k] = Slip::kRight;
    }
  }
  for (const ForceColumn& c : f) {
    if (!c.tangential || !mode->any_closed(c.k)) continue;
    const double tp = z[c.var], tm = z[c.var + 1], sigma = z[c.var + 2];
    const bool slips = sigma > tol;
    const Slip dir = tp > tm ? Slip::kLeft : Slip::kRight;  // friction + t: a slip to the left
    if (!std::isinf(blocks_[c.k].friction)) {
      mode->slip[c.k] = slips ? dir : Slip::kStick;
    } else if (slips && limit_slip && mode->closed[c.k][0] != mode->closed[c.k][1]) {
      mode->slip[c.k] = dir;
    }
  }
}

bool UnilateralStack::LemkeMode(const Problem& p, const ContactMode& hint, bool limit_slip,
                                ContactMode* mode, int* pivots) const {
  int nv = 0;
  std::vector<ForceColumn> f = ForceColumns(p, &nv);
  if (f.empty()) {
    *mode = ContactMode(n_);
    return true;
  }
  std::vector<double> A, b, M, q;
  const double b_max = ScaledCouplings(p, &f, &A, &b);
  ForceLcp(f, A, b, nv, &M, &q);
  const LcpResult lcp = SolveLemkeCovered(M, q, nv, b_max, pivots);
  if (lcp.status != LcpStatus::kSolved) return false;
  ModeOfLcp(p, hint, limit_slip, f, lcp.z, lcp.w, b_max, mode);
  return true;
}

ModeSolution UnilateralStack::Resolve(const Problem& p, const std::vector<ContactOption>& preferred,
                                      bool limit_slip, long exhaustive_limit) const {
  const std::vector<std::vector<ContactOption>> options = Options(p, preferred, limit_slip);
  long total = 1;
  for (const auto& o : options) {
    total = std::min(total * static_cast<long>(o.size()), kCandidateCap + 1);
  }
  if (total <= exhaustive_limit) {
    ModeSolution best = Search(p, options, true, kCandidateCap);
    best.method = "enumeration";
    return best;
  }
  // The preferred state (each interface's first option) first: a mode that goes on.
  std::vector<ContactOption> first(static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) first[k] = options[k][0];
  const ContactMode hint = ModeOf(p, first);
  ModeSolution sol;
  if (Check(p, hint, &sol)) {
    sol.found = true;
    sol.solutions = 1;
    sol.candidates = 1;
    sol.method = "preferred";
    return sol;
  }
  // Lemke's method, its mode checked.
  ContactMode lemke(n_);
  int pivots = 0;
  const bool solved = LemkeMode(p, hint, limit_slip, &lemke, &pivots);
  if (solved && Check(p, lemke, &sol)) {
    sol.found = true;
    sol.solutions = 1;
    sol.candidates = 2;
    sol.method = "lemke";
    sol.lcp_pivots = pivots;
    return sol;
  }
  // Else an enumeration from Lemke's mode (or, after a ray, from the hint).
  std::vector<ContactOption> from = first;
  if (solved) {
    for (int k = 0; k < n_; ++k) {
      from[k] = {lemke.closed[k], lemke.any_closed(k) ? lemke.slip[k] : Slip::kStick};
    }
  }
  ModeSolution best = Search(p, Options(p, from, limit_slip), false, kFallbackCap);
  best.candidates += 2;
  best.method = solved ? "lemke+search" : "search";
  best.lcp_pivots = pivots;
  if (!best.found && !best.exhaustive) {
    best.note = solved ? "Lemke's mode failed its check"
                       : "no solution found by Lemke (ray termination: not a proof)";
  }
  return best;
}

ModeSolution UnilateralStack::Solve(const double* q, const double* v, double xg_mps2,
                                    double yg_mps2, const ContactMode& hint, double gap_tol_m,
                                    double rate_tol_mps, long exhaustive_limit) const {
  Problem p;
  p.slots.resize(static_cast<size_t>(n_));
  p.zero.resize(static_cast<size_t>(n_));
  p.slipping.assign(static_cast<size_t>(n_), 0);
  std::vector<ContactOption> preferred(static_cast<size_t>(n_));
  bool infinite = false;
  for (int k = 0; k < n_; ++k) {
    p.slots[k] = Slots(k, q, v);
    for (int j = 0; j < 2; ++j) {
      const SlotKinematics& s = p.slots[k][j];
      // In contact: at a zero gap, or past it (a projection onto other constraints may push an
      // open corner a little into its face).
      p.zero[k][j] = s.exists && s.gap_m <= gap_tol_m && std::abs(s.gap_rate_mps) <= rate_tol_mps;
    }
    // The slip rate of the interface: at its first zero slot.
    double rate = 0.0;
    for (int j = 1; j >= 0; --j) {
      if (p.zero[k][j]) rate = p.slots[k][j].slip_rate_mps;
    }
    if (std::abs(rate) > rate_tol_mps && blocks_[k].friction > 0.0)
      p.slipping[k] = rate > 0 ? 1 : -1;
    infinite = infinite || (std::isinf(blocks_[k].friction) && (p.zero[k][0] || p.zero[k][1]));
    // The hint's option first when it is one of them.
    if (k < static_cast<int>(hint.closed.size())) {
      preferred[k] = {hint.closed[k], hint.any_closed(k) ? hint.slip[k] : Slip::kStick};
    }
  }
  p.base.assign(static_cast<size_t>(3 * n_), 0.0);
  for (int i = 0; i < n_; ++i) {
    p.base[3 * i] = -xg_mps2;
    p.base[3 * i + 1] = -(g_ + yg_mps2);
  }
  p.impact = false;
  p.tol_force = 1e-9 * weight_;
  p.tol_motion = 1e-9 * g_;
  p.rate_tol = rate_tol_mps;
  p.same_scale = g_;
  ModeSolution best = Resolve(p, preferred, false, exhaustive_limit);
  if (!best.found && infinite) {
    // No state of stick or open at infinite friction: the limit slips (the header).
    const long before = best.candidates;
    best = Resolve(p, preferred, true, exhaustive_limit);
    best.candidates += before;
    if (best.found) {
      best.note = "infinite friction: no sticking state; the limit of slip as mu -> infinity";
      if (best.solutions > 1) {
        best.note += "; " + std::to_string(best.solutions) +
                     " contact states give different motions (Painleve: several solutions)";
      }
      return best;
    }
  }
  if (!best.found) {
    const std::string why = best.note;
    best.note = best.exhaustive ? "no contact state satisfies Coulomb's and the contact conditions "
                                  "(Painleve: no solution)"
                                : "the contact search stopped after " +
                                      std::to_string(best.candidates) + " states";
    if (!why.empty()) best.note += " (" + why + ")";
  } else if (best.solutions > 1) {
    best.note = std::to_string(best.solutions) +
                " contact states give different motions (Painleve: several solutions)";
  }
  return best;
}

ModeSolution UnilateralStack::SolveImpact(const double* q, const double* v_minus,
                                          const ContactMode& hint, double gap_tol_m,
                                          double rest_rate_rel, long exhaustive_limit) const {
  Problem p;
  p.slots.resize(static_cast<size_t>(n_));
  p.zero.resize(static_cast<size_t>(n_));
  p.slipping.assign(static_cast<size_t>(n_), 0);  // after an impact any tangential state
  std::vector<ContactOption> preferred(static_cast<size_t>(n_));
  double v_scale = 0.0, p_scale = 0.0;
  for (int i = 0; i < 3 * n_; ++i) {
    const double r = i % 3 == 2 ? length_ : 1.0;
    v_scale = std::max(v_scale, std::abs(v_minus[i]) * r);
  }
  for (const UnilateralBlock& b : blocks_) p_scale += b.mass_kg;
  p_scale *= v_scale;
  for (int k = 0; k < n_; ++k) {
    p.slots[k] = Slots(k, q, v_minus);
    for (int j = 0; j < 2; ++j) {
      p.zero[k][j] = p.slots[k][j].exists && p.slots[k][j].gap_m <= gap_tol_m;
    }
    if (k < static_cast<int>(hint.closed.size())) {
      // Preferred: every zero slot closed, the hint's tangential state.
      preferred[k] = {p.zero[k], hint.any_closed(k) ? hint.slip[k] : Slip::kStick};
    }
  }
  p.base.assign(v_minus, v_minus + 3 * n_);
  p.impact = true;
  p.tol_force = 1e-9 * p_scale + 1e-300;
  p.tol_motion = 1e-9 * v_scale + 1e-300;
  p.rate_tol = 0.0;
  p.same_scale = std::max(v_scale, 1e-300);
  ModeSolution best = Resolve(p, preferred, false, exhaustive_limit);
  const auto& slots = p.slots;
  const auto& zero = p.zero;
  if (!best.found) {
    best.result.assign(v_minus, v_minus + 3 * n_);
    best.note = "no impact outcome satisfies Coulomb's and the contact conditions" +
                (best.note.empty() ? std::string() : " (" + best.note + ")");
    return best;
  }
  if (best.solutions > 1) {
    best.note = std::to_string(best.solutions) + " impact outcomes give different motions";
  }
  // The rest rule: a zero slot that would separate slower than its interface's rest speed
  // stays closed.
  bool rest = false;
  ContactMode held = best.mode;
  for (int k = 0; k < n_; ++k) {
    for (int j = 0; j < 2; ++j) {
      if (zero[k][j] && !best.mode.closed[k][j] &&
          RowTimes(slots[k][j].wn, k, best.result.data()) < RestSpeed(k, rest_rate_rel)) {
        if (!held.any_closed(k)) held.slip[k] = Slip::kStick;
        held.closed[k][j] = true;
        rest = true;
      }
    }
  }
  if (rest) {
    ModeSolution sol;
    if (SolveCandidate(held, slots, v_minus, true, &sol)) {
      sol.found = true;
      sol.solutions = best.solutions;
      sol.exhaustive = best.exhaustive;
      sol.candidates = best.candidates;
      sol.method = best.method;
      sol.lcp_pivots = best.lcp_pivots;
      sol.note = best.note.empty() ? "rest rule" : best.note + "; rest rule";
      return sol;
    }
  }
  return best;
}

void UnilateralStack::Project(const ContactMode& mode, double* q, double* v) const {
  // Rows: (interface, direction w, value); a correction x += M^-1 W lambda with W^T x = -r.
  struct Row {
    int k;
    std::array<double, 6> w;
    double r;
  };
  auto correct = [&](const std::vector<Row>& rows, double* x) {
    const int m = static_cast<int>(rows.size());
    if (m == 0) return;
    // The smallest correction in the mass metric: M dx = W lambda, W^T dx = -r.
    std::vector<Constraint> cons(static_cast<size_t>(m));
    for (int c = 0; c < m; ++c) cons[c] = {rows[c].k, rows[c].w, rows[c].w, rows[c].r};
    std::vector<double> dx(static_cast<size_t>(3 * n_), 0.0), lam(static_cast<size_t>(m));
    // The Schur complement (banded, Jacobi-scaled), else the augmented system (as a mode's
    // equations).
    std::vector<double> A(static_cast<size_t>(m * m), 0.0);
    std::vector<int> group(static_cast<size_t>(m));
    for (int r = 0; r < m; ++r) {
      for (int c = 0; c < m; ++c) {
        if (std::abs(rows[r].k - rows[c].k) <= 1) {
          A[r * m + c] = Coupling(rows[r].k, rows[r].w, rows[c].k, rows[c].w);
        }
      }
      lam[r] = -rows[r].r;
      group[r] = rows[r].k;
    }
    if (SolveDense(A, lam, m, nullptr, group.data())) {
      for (int c = 0; c < m; ++c) {
        for (int side = 0; side < 2; ++side) {
          const int blk = rows[c].k - side;
          if (blk < 0) continue;
          const UnilateralBlock& B = blocks_[blk];
          dx[3 * blk] += rows[c].w[3 * side] * lam[c] / B.mass_kg;
          dx[3 * blk + 1] += rows[c].w[3 * side + 1] * lam[c] / B.mass_kg;
          dx[3 * blk + 2] += rows[c].w[3 * side + 2] * lam[c] / B.inertia_kgm2;
        }
      }
    } else {
      const std::vector<double> still(static_cast<size_t>(3 * n_), 0.0);
      if (!SolveConstrained(cons, still.data(), dx.data(), lam.data())) return;
    }
    for (int i = 0; i < 3 * n_; ++i) x[i] += dx[i];
  };
  std::vector<Row> rows;
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    const auto s = Slots(k, q, v, &mode);
    for (int j = 0; j < 2; ++j) {
      if (mode.closed[k][j]) rows.push_back({k, s[j].wn, s[j].gap_m});
    }
  }
  correct(rows, q);
  rows.clear();
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    const auto s = Slots(k, q, v, &mode);
    int ref = -1;
    for (int j = 0; j < 2; ++j) {
      if (!mode.closed[k][j]) continue;
      if (ref < 0) ref = j;
      rows.push_back({k, s[j].wn, s[j].gap_rate_mps});
    }
    if (ref >= 0 && mode.slip[k] == Slip::kStick)
      rows.push_back({k, s[ref].wt, s[ref].slip_rate_mps});
  }
  correct(rows, v);
}

double UnilateralStack::Energy(const double* q, const double* v) const {
  double e = 0.0;
  for (int i = 0; i < n_; ++i) {
    const UnilateralBlock& b = blocks_[i];
    e += 0.5 * b.mass_kg * (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1]) +
         0.5 * b.inertia_kgm2 * v[3 * i + 2] * v[3 * i + 2] + b.mass_kg * g_ * q[3 * i + 1];
  }
  return e;
}

void UnilateralStack::FromChain(const Configuration& c, const double* theta_rad,
                                const double* omega_radps, double* q, double* v) const {
  // The pivot chain (docs/n-blocks.md): P_1 = (s_1 b_1, 0), P_(k+1) = P_k + R(theta_k)((s_(k+1)
  // b_(k+1), 2 h_k) - (s_k b_k, 0)), G_k = P_k + R(theta_k)((0, h_k) - (s_k b_k, 0)).
  auto side = [&](int k) { return c[k] == Contact::kLeft ? -1.0 : 1.0; };
  Vec2 P{side(0) * blocks_[0].b_m, 0.0}, vP{0.0, 0.0};
  for (int k = 0; k < n_; ++k) {
    const UnilateralBlock& b = blocks_[k];
    const double ct = std::cos(theta_rad[k]), st = std::sin(theta_rad[k]);
    const double s = side(k);
    const Vec2 dG = Turn(ct, st, {-s * b.b_m, b.h_m});
    const Vec2 G = P + dG;
    const Vec2 vG = vP + omega_radps[k] * J(dG);
    q[3 * k] = G.x;
    q[3 * k + 1] = G.y;
    q[3 * k + 2] = theta_rad[k];
    v[3 * k] = vG.x;
    v[3 * k + 1] = vG.y;
    v[3 * k + 2] = omega_radps[k];
    if (k + 1 < n_) {
      const Vec2 dP = Turn(ct, st, {side(k + 1) * blocks_[k + 1].b_m - s * b.b_m, 2.0 * b.h_m});
      vP = vP + omega_radps[k] * J(dP);
      P = P + dP;
    }
  }
}

void UnilateralStack::SlipAndLift(int k, const double* q, double* u_m, double* z_m) const {
  const UnilateralBlock& U = blocks_[k];
  const Vec2 GU{q[3 * k], q[3 * k + 1]};
  const double thU = q[3 * k + 2];
  const double cU = std::cos(thU), sU = std::sin(thU);
  Vec2 top{0.0, 0.0};
  double thL = 0.0;
  if (k > 0) {
    thL = q[3 * (k - 1) + 2];
    top = Vec2{q[3 * (k - 1)], q[3 * (k - 1) + 1]} +
          Turn(std::cos(thL), std::sin(thL), {0.0, blocks_[k - 1].h_m});
  }
  const Vec2 nL{std::sin(thL), std::cos(thL)}, tL{std::cos(thL), -std::sin(thL)};
  const Vec2 right = GU + Turn(cU, sU, {U.b_m, -U.h_m});
  const Vec2 left = GU + Turn(cU, sU, {-U.b_m, -U.h_m});
  const double zr = Dot(right - top, nL), zl = Dot(left - top, nL);
  // The corner on the side of the relative tilt (> 0: tilted right, the right corner lowest).
  const bool right_side = thU - thL >= 0.0;
  *u_m = right_side ? Dot(right - top, tL) - U.b_m : Dot(left - top, tL) + U.b_m;
  *z_m = std::min(zr, zl);
}

Configuration UnilateralStack::ConfigurationOf(const ContactMode& mode, const double* q) const {
  Configuration c(n_);
  for (int k = 0; k < n_; ++k) {
    const bool r = mode.closed[k][0], l = mode.closed[k][1];
    if (r && l) {
      c.set(k, Contact::kFace);
    } else if (r) {
      c.set(k, Contact::kRight);
    } else if (l) {
      c.set(k, Contact::kLeft);
    } else {
      const double rel = q[3 * k + 2] - (k > 0 ? q[3 * (k - 1) + 2] : 0.0);
      c.set(k, rel > 0.0 ? Contact::kRight : rel < 0.0 ? Contact::kLeft : Contact::kFace);
    }
  }
  return c;
}

}  // namespace rockbench::reference
