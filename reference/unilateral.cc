#include "reference/unilateral.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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

// Dense solve of a x = b (n x n, row-major) by Gaussian elimination with partial pivoting;
// false when a pivot is below tol times the largest entry (the equations are singular).
bool SolveDense(std::vector<double>& a, std::vector<double>& b, int n) {
  double scale = 0.0;
  for (const double x : a) scale = std::max(scale, std::abs(x));
  if (n == 0) return true;
  if (!(scale > 0.0) || !std::isfinite(scale)) return false;
  const double tol = 1e-12 * scale;
  for (int col = 0; col < n; ++col) {
    int piv = col;
    for (int r = col + 1; r < n; ++r) {
      if (std::abs(a[r * n + col]) > std::abs(a[piv * n + col])) piv = r;
    }
    if (std::abs(a[piv * n + col]) <= tol) return false;
    if (piv != col) {
      for (int j = 0; j < n; ++j) std::swap(a[col * n + j], a[piv * n + j]);
      std::swap(b[col], b[piv]);
    }
    for (int r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      if (f == 0.0) continue;
      for (int j = col; j < n; ++j) a[r * n + j] -= f * a[col * n + j];
      b[r] -= f * b[col];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int j = r + 1; j < n; ++j) s -= a[r * n + j] * b[j];
    b[r] = s / a[r * n + r];
  }
  return true;
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

bool UnilateralStack::SolveCandidate(const ContactMode& mode,
                                     const std::vector<std::array<SlotKinematics, 2>>& slots,
                                     const double* rhs_base, bool impact, ModeSolution* out) const {
  // The unknowns (columns) and the constraints (rows): a closed slot's normal force (with its
  // friction when the interface slips) and zero normal relative acceleration (impact: velocity);
  // a sticking interface's tangential force and zero slip acceleration (velocity) at its first
  // closed slot.
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
    int ref = -1;
    for (int j = 0; j < 2; ++j) {
      if (!mode.closed[k][j]) continue;
      const SlotKinematics& s = slots[k][j];
      if (ref < 0) ref = j;
      Column c{k, s.wn, s.wn, s.kappa_n};
      if (slip != Slip::kStick && mu > 0.0) {
        const double f = -static_cast<double>(static_cast<int>(slip)) * mu;
        for (int i = 0; i < 6; ++i) c.w[i] += f * s.wt[i];
      }
      cols.push_back(c);
    }
    if (slip == Slip::kStick) {
      const SlotKinematics& s = slots[k][ref];
      cols.push_back({k, s.wt, s.wt, s.kappa_t});
    }
  }
  const int m = static_cast<int>(cols.size());
  // M^-1 applied to a column's two blocks' entries.
  auto inv_mass = [&](int block, int i) {
    const UnilateralBlock& b = blocks_[block];
    return i == 2 ? 1.0 / b.inertia_kgm2 : 1.0 / b.mass_kg;
  };
  auto dot_row = [&](const Column& r, const double* x) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i) s += r.row[i] * x[3 * r.k + i];
    if (r.k > 0) {
      for (int i = 0; i < 3; ++i) s += r.row[3 + i] * x[3 * (r.k - 1) + i];
    }
    return s;
  };
  std::vector<double> A(static_cast<size_t>(m * m), 0.0), b(static_cast<size_t>(m), 0.0);
  std::vector<double> tmp(static_cast<size_t>(3 * n_), 0.0);
  for (int c = 0; c < m; ++c) {
    std::fill(tmp.begin(), tmp.end(), 0.0);
    const Column& col = cols[c];
    for (int i = 0; i < 3; ++i) tmp[3 * col.k + i] += inv_mass(col.k, i) * col.w[i];
    if (col.k > 0) {
      for (int i = 0; i < 3; ++i) tmp[3 * (col.k - 1) + i] += inv_mass(col.k - 1, i) * col.w[3 + i];
    }
    for (int r = 0; r < m; ++r) A[r * m + c] = dot_row(cols[r], tmp.data());
  }
  // rhs_base: M^-1 f (accelerations) or v- (impact); the rows' values there.
  for (int r = 0; r < m; ++r) b[r] = -(dot_row(cols[r], rhs_base) + (impact ? 0.0 : cols[r].kappa));
  if (!SolveDense(A, b, m)) return false;
  out->result.assign(rhs_base, rhs_base + 3 * n_);
  out->normal.assign(static_cast<size_t>(n_), 0.0);
  out->tangential.assign(static_cast<size_t>(n_), 0.0);
  out->slot_normal.assign(static_cast<size_t>(n_), {0.0, 0.0});
  int c = 0;
  for (int k = 0; k < n_; ++k) {
    if (!mode.any_closed(k)) continue;
    const double mu = blocks_[k].friction;
    for (int j = 0; j < 2; ++j) {
      if (!mode.closed[k][j]) continue;
      out->slot_normal[k][j] = b[c];
      out->normal[k] += b[c];
      ++c;
    }
    if (mode.slip[k] == Slip::kStick) {
      out->tangential[k] = b[c++];
    } else {
      out->tangential[k] = mu > 0.0 ? -static_cast<int>(mode.slip[k]) * mu * out->normal[k] : 0.0;
    }
  }
  for (int cc = 0; cc < m; ++cc) {
    const Column& col = cols[cc];
    for (int i = 0; i < 3; ++i) out->result[3 * col.k + i] += inv_mass(col.k, i) * col.w[i] * b[cc];
    if (col.k > 0) {
      for (int i = 0; i < 3; ++i) {
        out->result[3 * (col.k - 1) + i] += inv_mass(col.k - 1, i) * col.w[3 + i] * b[cc];
      }
    }
  }
  out->mode = mode;
  return true;
}

bool UnilateralStack::Accelerations(const ContactMode& mode, const double* q, const double* v,
                                    double xg_mps2, double yg_mps2, double* accel,
                                    ModeSolution* forces) const {
  std::vector<std::array<SlotKinematics, 2>> slots(static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) {
    if (mode.any_closed(k)) slots[k] = Slots(k, q, v, &mode);
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
// tangential states its friction and slip rate allow.
std::vector<ContactOption> ContactOptionsOf(const std::array<SlotKinematics, 2>& s,
                                            const std::array<bool, 2>& zero, double mu,
                                            bool slipping, double slip_rate) {
  std::vector<ContactOption> out;
  std::vector<Slip> tangential;
  if (std::isinf(mu)) {
    tangential = {Slip::kStick};
  } else if (mu == 0.0) {
    tangential = {Slip::kRight};  // frictionless: the tangential state plays no part
  } else if (slipping) {
    tangential = {slip_rate > 0.0 ? Slip::kRight : Slip::kLeft};
  } else {
    tangential = {Slip::kStick, Slip::kRight, Slip::kLeft};
  }
  (void)s;
  const std::array<std::array<bool, 2>, 3> subsets = {{{true, true}, {true, false}, {false, true}}};
  for (const auto& sub : subsets) {
    if ((sub[0] && !zero[0]) || (sub[1] && !zero[1])) continue;
    for (const Slip t : tangential) out.push_back({sub, t});
  }
  out.push_back({{false, false}, Slip::kStick});  // open
  return out;
}

}  // namespace

namespace {

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

// Whether two solutions are the same motion: every translational component within 1e-6 of
// `linear` and every angular one within 1e-6 of `linear` / `length` (accelerations: g; impacts:
// the largest velocity). Solutions that differ only by the contact conditions' tolerances (a
// slip that starts at an acceleration of 1e-9 g, a contact that stays closed with a force of
// 1e-9 of the weight) are one motion.
bool SameMotion(const std::vector<double>& a, const std::vector<double>& b, double linear,
                double length) {
  for (size_t i = 0; i < a.size(); ++i) {
    const double scale = i % 3 == 2 ? linear / length : linear;
    if (!(std::abs(a[i] - b[i]) <= 1e-6 * scale)) return false;
  }
  return true;
}

constexpr long kCandidateCap = 200000;

}  // namespace

namespace {

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

ModeSolution UnilateralStack::Search(const std::vector<std::array<SlotKinematics, 2>>& slots,
                                     const std::vector<std::array<bool, 2>>& zero,
                                     const std::vector<std::vector<ContactOption>>& options,
                                     const double* base, bool impact, double tol_force,
                                     double tol_motion, double rate_tol_mps, double same_scale,
                                     bool exhaustive) const {
  ModeSolution best;
  best.exhaustive = exhaustive;
  ContactMode mode(n_);
  // A row's value in a solution: the rate (impact) or the acceleration with its velocity terms.
  auto row = [&](const std::array<double, 6>& w, double kappa, int k, const double* x) {
    return RowTimes(w, k, x) + (impact ? 0.0 : kappa);
  };
  const long tried = Enumerate(options, kCandidateCap, [&](const std::vector<int>& pick) {
    for (int k = 0; k < n_; ++k) {
      const ContactOption& o = options[k][pick[k]];
      mode.closed[k] = o.closed;
      mode.slip[k] = o.slip;
      mode.support_corner[k] = {!slots[k][0].upper_corner, !slots[k][1].upper_corner};
    }
    ModeSolution sol;
    if (!SolveCandidate(mode, slots, base, impact, &sol)) return false;
    const double* x = sol.result.data();
    for (int k = 0; k < n_; ++k) {
      const double mu = blocks_[k].friction;
      int ref = -1;
      for (int j = 0; j < 2; ++j) {
        if (mode.closed[k][j]) {
          if (ref < 0) ref = j;
          if (sol.slot_normal[k][j] < -tol_force) return false;
        } else if (zero[k][j] && row(slots[k][j].wn, slots[k][j].kappa_n, k, x) < -tol_motion) {
          return false;  // left open, it would move (accelerate) into its support
        }
      }
      if (ref < 0) continue;
      if (mode.slip[k] == Slip::kStick) {
        if (!std::isinf(mu) && std::abs(sol.tangential[k]) > mu * sol.normal[k] + tol_force) {
          return false;
        }
      } else if (mu > 0.0 && (impact || std::abs(slots[k][ref].slip_rate_mps) <= rate_tol_mps)) {
        // Friction opposes the slip after an impact; from a zero slip rate the interface must
        // accelerate the way it slips.
        const double t = row(slots[k][ref].wt, slots[k][ref].kappa_t, k, x);
        if (static_cast<int>(mode.slip[k]) * t < -tol_motion) return false;
      }
    }
    if (!best.found) {
      sol.solutions = 1;
      sol.found = true;
      sol.exhaustive = best.exhaustive;
      best = std::move(sol);
      return !best.exhaustive;
    }
    if (!SameMotion(best.result, sol.result, same_scale, length_)) ++best.solutions;
    return false;
  });
  best.candidates = tried;
  if (!best.found) best.mode = ContactMode(n_);
  return best;
}

ModeSolution UnilateralStack::Solve(const double* q, const double* v, double xg_mps2,
                                    double yg_mps2, const ContactMode& hint, double gap_tol_m,
                                    double rate_tol_mps, long exhaustive_limit) const {
  std::vector<std::array<SlotKinematics, 2>> slots(static_cast<size_t>(n_));
  std::vector<std::vector<ContactOption>> options(static_cast<size_t>(n_));
  std::vector<std::array<bool, 2>> zero(static_cast<size_t>(n_));
  long total = 1;
  for (int k = 0; k < n_; ++k) {
    slots[k] = Slots(k, q, v);
    for (int j = 0; j < 2; ++j) {
      const SlotKinematics& s = slots[k][j];
      // In contact: at a zero gap, or past it (a projection onto other constraints may push an
      // open corner a little into its face).
      zero[k][j] = s.exists && s.gap_m <= gap_tol_m && std::abs(s.gap_rate_mps) <= rate_tol_mps;
    }
    // The slip rate of the interface: at its first zero slot.
    double rate = 0.0;
    for (int j = 1; j >= 0; --j) {
      if (zero[k][j]) rate = slots[k][j].slip_rate_mps;
    }
    const bool slipping = std::abs(rate) > rate_tol_mps;
    options[k] = ContactOptionsOf(slots[k], zero[k], blocks_[k].friction, slipping, rate);
    // The hint's option first when it is one of them.
    if (k < static_cast<int>(hint.closed.size())) {
      const ContactOption want{hint.closed[k], hint.any_closed(k) ? hint.slip[k] : Slip::kStick};
      const auto it = std::find(options[k].begin(), options[k].end(), want);
      if (it != options[k].end()) std::rotate(options[k].begin(), it, it + 1);
    }
    total = std::min(total * static_cast<long>(options[k].size()), kCandidateCap + 1);
  }
  std::vector<double> free(static_cast<size_t>(3 * n_), 0.0);
  for (int i = 0; i < n_; ++i) {
    free[3 * i] = -xg_mps2;
    free[3 * i + 1] = -(g_ + yg_mps2);
  }
  ModeSolution best = Search(slots, zero, options, free.data(), false, 1e-9 * weight_, 1e-9 * g_,
                             rate_tol_mps, g_, total <= exhaustive_limit);
  if (!best.found) {
    best.note =
        best.candidates >= kCandidateCap
            ? "the contact search stopped after " + std::to_string(kCandidateCap) + " states"
            : "no contact state satisfies Coulomb's and the contact conditions "
              "(Painleve: no solution)";
  } else if (best.solutions > 1) {
    best.note = std::to_string(best.solutions) +
                " contact states give different motions (Painleve: several solutions)";
  }
  return best;
}

ModeSolution UnilateralStack::SolveImpact(const double* q, const double* v_minus,
                                          const ContactMode& hint, double gap_tol_m,
                                          double rest_rate_mps, long exhaustive_limit) const {
  std::vector<std::array<SlotKinematics, 2>> slots(static_cast<size_t>(n_));
  std::vector<std::vector<ContactOption>> options(static_cast<size_t>(n_));
  std::vector<std::array<bool, 2>> zero(static_cast<size_t>(n_));
  long total = 1;
  double v_scale = 0.0, p_scale = 0.0;
  for (int i = 0; i < 3 * n_; ++i) {
    const double r = i % 3 == 2 ? length_ : 1.0;
    v_scale = std::max(v_scale, std::abs(v_minus[i]) * r);
  }
  for (const UnilateralBlock& b : blocks_) p_scale += b.mass_kg;
  p_scale *= v_scale;
  for (int k = 0; k < n_; ++k) {
    slots[k] = Slots(k, q, v_minus);
    for (int j = 0; j < 2; ++j) {
      zero[k][j] = slots[k][j].exists && slots[k][j].gap_m <= gap_tol_m;
    }
    // After an impact any tangential state may follow (the impulses decide).
    options[k] = ContactOptionsOf(slots[k], zero[k], blocks_[k].friction, false, 0.0);
    if (k < static_cast<int>(hint.closed.size())) {
      // Preferred: every zero slot closed, the hint's tangential state.
      const ContactOption want{zero[k], hint.any_closed(k) ? hint.slip[k] : Slip::kStick};
      const auto it = std::find(options[k].begin(), options[k].end(), want);
      if (it != options[k].end()) std::rotate(options[k].begin(), it, it + 1);
    }
    total = std::min(total * static_cast<long>(options[k].size()), kCandidateCap + 1);
  }
  ModeSolution best =
      Search(slots, zero, options, v_minus, true, 1e-9 * p_scale + 1e-300, 1e-9 * v_scale + 1e-300,
             0.0, std::max(v_scale, 1e-300), total <= exhaustive_limit);
  if (!best.found) {
    best.result.assign(v_minus, v_minus + 3 * n_);
    best.note = "no impact outcome satisfies Coulomb's and the contact conditions";
    return best;
  }
  if (best.solutions > 1) {
    best.note = std::to_string(best.solutions) + " impact outcomes give different motions";
  }
  // The rest rule: a zero slot that would separate slower than rest_rate_mps stays closed.
  bool rest = false;
  ContactMode held = best.mode;
  for (int k = 0; k < n_; ++k) {
    for (int j = 0; j < 2; ++j) {
      if (zero[k][j] && !best.mode.closed[k][j] &&
          RowTimes(slots[k][j].wn, k, best.result.data()) < rest_rate_mps) {
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
    auto inv_mass = [&](int block, int i) {
      return i == 2 ? 1.0 / blocks_[block].inertia_kgm2 : 1.0 / blocks_[block].mass_kg;
    };
    // A_rc = w_r . M^-1 w_c over the blocks the two rows share.
    std::vector<double> A(static_cast<size_t>(m * m), 0.0), b(static_cast<size_t>(m));
    for (int r = 0; r < m; ++r) {
      b[r] = -rows[r].r;
      for (int c = 0; c < m; ++c) {
        double sum = 0.0;
        for (int side_r = 0; side_r < 2; ++side_r) {
          const int br = rows[r].k - side_r;
          if (br < 0) continue;
          for (int side_c = 0; side_c < 2; ++side_c) {
            if (rows[c].k - side_c != br) continue;
            for (int i = 0; i < 3; ++i) {
              sum += rows[r].w[3 * side_r + i] * inv_mass(br, i) * rows[c].w[3 * side_c + i];
            }
          }
        }
        A[r * m + c] = sum;
      }
    }
    if (!SolveDense(A, b, m)) return;
    for (int c = 0; c < m; ++c) {
      for (int side = 0; side < 2; ++side) {
        const int blk = rows[c].k - side;
        if (blk < 0) continue;
        for (int i = 0; i < 3; ++i)
          x[3 * blk + i] += inv_mass(blk, i) * rows[c].w[3 * side + i] * b[c];
      }
    }
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
