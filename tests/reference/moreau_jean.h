#pragma once
// An independent time-stepping scheme for a planar stack of rectangular blocks on a moving base,
// written for the tests only (it shares no code with reference/): Moreau-Jean's scheme (Moreau
// 1988, "Unilateral contact and dry friction in finite freedom dynamics"; Jean 1999, "The
// non-smooth contact dynamics method"; Acary & Brogliato 2008, "Numerical Methods for Nonsmooth
// Dynamical Systems", ch. 10) with theta = 1/2:
//
//   q_m     = q_k + h/2 v_k                            (the step's predicted position)
//   v_{k+1} = v_k + h M^-1 f(t_k + h/2) + M^-1 sum_c (w_n,c P_n,c + w_t,c P_t,c)
//   q_{k+1} = q_k + h/2 (v_k + v_{k+1})
//
// The contacts of the step are the index set at q_m: every block's two base corners whose gap
// to its support's top face (the ground for block 1) is <= 0 there (to rounding: kActivation).
// Their rows w_n, w_t (the corner's normal and tangential velocity relative to the support's
// material point under it) are taken at q_m. The impulses P follow Moreau's velocity-level law with
// zero restitution and Coulomb's friction on each face: every contact either ends the step with a
// zero normal velocity and a compressive impulse, or with a non-negative one and none; every face
// with a closed contact either sticks (zero tangential velocity, |P_T| <= mu sum P_N over its
// closed contacts) or slips after the step with P_T = -/+ mu P_N at each closed contact, against
// its slip. A face's tangential row is the mean of its closed contacts' rows (at a zero gap both
// corners slide alike). In 2-D this is a linear complementarity problem; it is solved here by
// enumerating the contact states (per face: which corners close, and stick / slip right / slip
// left), a preferred state first (every contact of the index set closed, each face in its last
// step's tangential state), then the others by the number of faces that differ from it, each
// state's equations solved exactly (Eigen's full-pivot LU) and its conditions checked to a relative
// 1e-10 (well above the solve's rounding, ~1e-15). The first admissible state is taken.
//
// Coordinates (as in coulomb_impact.h): block i's mass centre (x, y) and angle theta (clockwise
// > 0: tilted to the right) at q[3i..3i+2], in the base frame (x right, y up, origin at block
// 1's base centre at rest); the base acceleration enters as the inertial force -m xg'' and the
// effective gravity -m (g + yg''). The contacts are corners on faces only: a caller checks that
// no corner passes its support's edge (CornerOffFace).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace rockbench::test {

/// A block: half width b and half height h (m), mass (kg), central inertia (kg m^2), and the
/// friction coefficient of its base on its support (infinity: never slips).
struct MjBlock {
  double b_m = 0.0, h_m = 0.0, mass_kg = 0.0, inertia_kgm2 = 0.0;
  double friction = std::numeric_limits<double>::infinity();
};

/// One contact slot: block k's base corner on side j (0 right, 1 left) on its support's top
/// face, at a configuration.
struct MjSlot {
  double gap_m = 0.0;  ///< the corner's height above the support's top-face line (< 0: inside)
  double xi_m = 0.0;   ///< where the corner is along that face, from its middle (> 0: right)
  /// Generalized rows (3 per block) of the corner's normal and tangential velocity relative to
  /// the support's material point under it.
  Eigen::VectorXd wn, wt;
};

/// A face's contact state: which of its corners are closed, and its tangential state.
struct MjFaceState {
  std::array<bool, 2> closed{false, false};
  int slip = 0;  ///< 0 stick, +1 the upper block slips right on its support, -1 left
  bool operator==(const MjFaceState&) const = default;
};

/// What one step did.
struct MjStepInfo {
  int active = 0;       ///< contacts in the index set
  long candidates = 0;  ///< contact states tried
  bool solved = true;   ///< an admissible state was found (else the step was taken free)
};

class MoreauJeanStack {
 public:
  /// blocks bottom first; gravity g (m/s^2); the base's horizontal and vertical acceleration
  /// as functions of time (m/s^2; empty: none).
  MoreauJeanStack(std::vector<MjBlock> blocks, double g_mps2,
                  std::function<double(double)> xg_mps2 = {},
                  std::function<double(double)> yg_mps2 = {})
      : blocks_(std::move(blocks)),
        n_(static_cast<int>(blocks_.size())),
        g_(g_mps2),
        xg_(std::move(xg_mps2)),
        yg_(std::move(yg_mps2)),
        state_(blocks_.size()) {
    minv_.resize(3 * n_);
    for (int i = 0; i < n_; ++i) {
      minv_.segment(3 * i, 3) << 1.0 / blocks_[i].mass_kg, 1.0 / blocks_[i].mass_kg,
          1.0 / blocks_[i].inertia_kgm2;
      mass_total_ += blocks_[i].mass_kg;
      length_ = std::max(length_, std::hypot(blocks_[i].b_m, blocks_[i].h_m));
    }
  }

  /// The index set's threshold, relative to the length scale (the largest half-diagonal): a
  /// contact is in the step's index set when its predicted gap is <= 0 to rounding, 1e-12 L.
  /// Exactly 0 would drop a pivot at a zero gap (the reference's state at rest) whenever its
  /// normal velocity, zero to rounding (1e-20 m/s), predicts a gap of +1e-25 m: the block then
  /// falls freely for a step, a kick of xg'' h (measured: 5e-6 m/s at h = 3.1 us, which raised
  /// the error of the 6.79 s cascade in chattering_independent_test.cc from 1.7e-7 to 1.3e-6
  /// rad at that step). 1e-12 L is 1e4 roundings of a position of size L, and 1e-6 of the
  /// smallest lift the tests meet (7e-6 m).
  static constexpr double kActivation = 1e-12;

  int size() const { return n_; }
  const MjBlock& block(int i) const { return blocks_[i]; }
  /// The contact state the last step ended in, per face.
  const std::vector<MjFaceState>& faces() const { return state_; }

  /// Slot j of interface k (block k on its support) at q.
  MjSlot Slot(const Eigen::VectorXd& q, int k, int j) const {
    const MjBlock& U = blocks_[k];
    const double side = j == 0 ? 1.0 : -1.0;
    const double c = std::cos(q[3 * k + 2]), s = std::sin(q[3 * k + 2]);
    // The corner's offset from block k's mass centre (the local point (side b, -h) turned by
    // theta clockwise) and where it is.
    const Eigen::Vector2d r{c * side * U.b_m - s * U.h_m, -s * side * U.b_m - c * U.h_m};
    const Eigen::Vector2d corner = Eigen::Vector2d(q[3 * k], q[3 * k + 1]) + r;
    Eigen::Vector2d mid{0.0, 0.0}, nrm{0.0, 1.0}, tan{1.0, 0.0}, d{0.0, 0.0};
    if (k > 0) {
      const double th = q[3 * (k - 1) + 2];
      nrm = {std::sin(th), std::cos(th)};
      tan = {std::cos(th), -std::sin(th)};
      const Eigen::Vector2d g_s(q[3 * (k - 1)], q[3 * (k - 1) + 1]);
      mid = g_s + blocks_[k - 1].h_m * nrm;
      d = corner - g_s;  // the support's material point under the corner, from its centre
    }
    MjSlot out;
    out.gap_m = (corner - mid).dot(nrm);
    out.xi_m = (corner - mid).dot(tan);
    out.wn = Eigen::VectorXd::Zero(3 * n_);
    out.wt = Eigen::VectorXd::Zero(3 * n_);
    // A point p of a body turning clockwise at rate w moves at w (p_y, -p_x) about its centre.
    const Eigen::Vector2d rp{r.y(), -r.x()}, dp{d.y(), -d.x()};
    out.wn.segment(3 * k, 3) << nrm.x(), nrm.y(), rp.dot(nrm);
    out.wt.segment(3 * k, 3) << tan.x(), tan.y(), rp.dot(tan);
    if (k > 0) {
      out.wn.segment(3 * (k - 1), 3) << -nrm.x(), -nrm.y(), -dp.dot(nrm);
      out.wt.segment(3 * (k - 1), 3) << -tan.x(), -tan.y(), -dp.dot(tan);
    }
    return out;
  }

  /// Whether some block's base corner lies past its support's top face (the scheme's contacts
  /// are corners on faces only; the ground has no edge).
  bool CornerOffFace(const Eigen::VectorXd& q) const {
    for (int k = 1; k < n_; ++k) {
      for (int j = 0; j < 2; ++j) {
        if (std::abs(Slot(q, k, j).xi_m) > blocks_[k - 1].b_m) return true;
      }
    }
    return false;
  }

  /// One step of length h_s from time t_s: (q, v) at t_s in, at t_s + h_s out.
  MjStepInfo Step(double t_s, double h_s, Eigen::VectorXd* q, Eigen::VectorXd* v) {
    MjStepInfo info;
    const Eigen::VectorXd qm = *q + 0.5 * h_s * *v;
    const double tm = t_s + 0.5 * h_s;
    const double xg = xg_ ? xg_(tm) : 0.0, yg = yg_ ? yg_(tm) : 0.0;
    Eigen::VectorXd v_free = *v;
    for (int i = 0; i < n_; ++i) {
      v_free[3 * i] -= h_s * xg;
      v_free[3 * i + 1] -= h_s * (g_ + yg);
    }
    // The index set at the predicted position.
    std::vector<std::array<bool, 2>> active(static_cast<size_t>(n_), {false, false});
    std::vector<std::array<MjSlot, 2>> slots(static_cast<size_t>(n_));
    for (int k = 0; k < n_; ++k) {
      for (int j = 0; j < 2; ++j) {
        slots[k][j] = Slot(qm, k, j);
        active[k][j] = slots[k][j].gap_m <= kActivation * length_;
        info.active += active[k][j];
      }
    }
    // Tolerances of the conditions: 1e-10 of the step's velocity scale (the free velocities,
    // rotations times the length scale, and the velocity gravity gives in one step) and of
    // the impulses that scale gives the whole stack.
    double v_scale = g_ * h_s;
    for (int i = 0; i < 3 * n_; ++i) {
      v_scale = std::max(v_scale, std::abs(v_free[i]) * (i % 3 == 2 ? length_ : 1.0));
    }
    const double tol_v = 1e-10 * v_scale, tol_p = tol_v * mass_total_;
    // Per face, its options (which active corners close; then stick, slip right, slip left),
    // and the preferred one: every active corner closed, in the last step's tangential state.
    std::vector<std::vector<MjFaceState>> options(static_cast<size_t>(n_));
    std::vector<MjFaceState> preferred(static_cast<size_t>(n_));
    for (int k = 0; k < n_; ++k) {
      MjFaceState p;
      const bool was_closed = state_[k].closed[0] || state_[k].closed[1];
      p.closed = active[k];
      p.slip = (p.closed[0] || p.closed[1]) && was_closed ? state_[k].slip : 0;
      preferred[k] = p;
      for (int mask = 0; mask < 4; ++mask) {
        const std::array<bool, 2> closed{(mask & 1) != 0, (mask & 2) != 0};
        if ((closed[0] && !active[k][0]) || (closed[1] && !active[k][1])) continue;
        if (!closed[0] && !closed[1]) {
          options[k].push_back({closed, 0});
          continue;
        }
        for (const int slip : {0, 1, -1}) {
          if (slip != 0 && std::isinf(blocks_[k].friction)) continue;
          options[k].push_back({closed, slip});
        }
      }
    }
    // Try the preferred state, then every state by how many faces differ from it.
    std::vector<MjFaceState> trial = preferred;
    Eigen::VectorXd v_plus;
    ++info.candidates;
    bool ok = Admissible(slots, active, trial, v_free, tol_v, tol_p, &v_plus);
    if (!ok) {
      std::vector<std::pair<int, std::vector<MjFaceState>>> all;
      std::vector<size_t> index(static_cast<size_t>(n_), 0);
      while (true) {
        std::vector<MjFaceState> s(static_cast<size_t>(n_));
        int differ = 0;
        for (int k = 0; k < n_; ++k) {
          s[k] = options[k][index[k]];
          differ += !(s[k] == preferred[k]);
        }
        if (differ > 0) all.push_back({differ, s});
        int k = 0;
        for (; k < n_; ++k) {
          if (++index[k] < options[k].size()) break;
          index[k] = 0;
        }
        if (k == n_) break;
      }
      std::stable_sort(all.begin(), all.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [differ, s] : all) {
        ++info.candidates;
        if (Admissible(slots, active, s, v_free, tol_v, tol_p, &v_plus)) {
          trial = s;
          ok = true;
          break;
        }
      }
    }
    if (!ok) {
      // No admissible state (not met in the tests: they assert solved on every step).
      info.solved = false;
      v_plus = v_free;
      trial.assign(static_cast<size_t>(n_), MjFaceState{});
    }
    state_ = trial;
    *q += 0.5 * h_s * (*v + v_plus);
    *v = v_plus;
    return info;
  }

 private:
  // Whether `faces` solves the step's contact problem: its equations solved, then its
  // conditions checked; the velocities after the step in *v_plus.
  bool Admissible(const std::vector<std::array<MjSlot, 2>>& slots,
                  const std::vector<std::array<bool, 2>>& active,
                  const std::vector<MjFaceState>& faces, const Eigen::VectorXd& v_free,
                  double tol_v, double tol_p, Eigen::VectorXd* v_plus) const {
    // Unknowns: a normal impulse per closed corner, a tangential one per sticking face. Each
    // acts along its direction (a slipping face's friction rides on its normal impulses); each
    // row's velocity after the step is zero.
    std::vector<Eigen::VectorXd> dirs, rows;
    std::vector<int> normal_face, stick_face;
    std::vector<Eigen::VectorXd> face_t(static_cast<size_t>(n_));
    for (int k = 0; k < n_; ++k) {
      const int closed = faces[k].closed[0] + faces[k].closed[1];
      if (closed == 0) continue;
      face_t[k] = Eigen::VectorXd::Zero(3 * n_);
      for (int j = 0; j < 2; ++j) {
        if (faces[k].closed[j]) face_t[k] += slots[k][j].wt / closed;
      }
      for (int j = 0; j < 2; ++j) {
        if (!faces[k].closed[j]) continue;
        rows.push_back(slots[k][j].wn);
        dirs.push_back(faces[k].slip == 0
                           ? slots[k][j].wn
                           : slots[k][j].wn - faces[k].slip * blocks_[k].friction * face_t[k]);
        normal_face.push_back(k);
      }
    }
    const int nn = static_cast<int>(rows.size());
    for (int k = 0; k < n_; ++k) {
      if ((faces[k].closed[0] || faces[k].closed[1]) && faces[k].slip == 0) {
        rows.push_back(face_t[k]);
        dirs.push_back(face_t[k]);
        stick_face.push_back(k);
      }
    }
    const int m = static_cast<int>(rows.size());
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
    if (m > 0) {
      Eigen::MatrixXd a(m, m);
      Eigen::VectorXd rhs(m);
      for (int r = 0; r < m; ++r) {
        rhs[r] = -rows[r].dot(v_free);
        for (int c = 0; c < m; ++c) a(r, c) = rows[r].dot(minv_.cwiseProduct(dirs[c]));
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
      lu.setThreshold(1e-10);
      if (!lu.isInvertible()) return false;
      lambda = lu.solve(rhs);
    }
    *v_plus = v_free;
    for (int c = 0; c < m; ++c) *v_plus += minv_.cwiseProduct(dirs[c]) * lambda[c];
    // Closed corners push; active open ones do not approach.
    std::vector<double> normal(static_cast<size_t>(n_), 0.0);
    for (int r = 0; r < nn; ++r) {
      if (lambda[r] < -tol_p) return false;
      normal[normal_face[r]] += lambda[r];
    }
    for (int k = 0; k < n_; ++k) {
      for (int j = 0; j < 2; ++j) {
        if (active[k][j] && !faces[k].closed[j] && slots[k][j].wn.dot(*v_plus) < -tol_v) {
          return false;
        }
      }
    }
    // Sticking faces within their cone; slipping ones slip the way their friction opposes.
    for (size_t r = 0; r < stick_face.size(); ++r) {
      const int k = stick_face[r];
      if (!std::isinf(blocks_[k].friction) &&
          std::abs(lambda[nn + static_cast<int>(r)]) > blocks_[k].friction * normal[k] + tol_p) {
        return false;
      }
    }
    for (int k = 0; k < n_; ++k) {
      if ((faces[k].closed[0] || faces[k].closed[1]) && faces[k].slip != 0 &&
          faces[k].slip * face_t[k].dot(*v_plus) < -tol_v) {
        return false;
      }
    }
    return true;
  }

  std::vector<MjBlock> blocks_;
  int n_ = 0;
  double g_ = 9.81;
  std::function<double(double)> xg_, yg_;
  Eigen::VectorXd minv_;
  double mass_total_ = 0.0, length_ = 0.0;
  std::vector<MjFaceState> state_;
};

}  // namespace rockbench::test
