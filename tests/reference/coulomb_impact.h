#pragma once
// An independent plastic impact with Coulomb friction for a planar stack of rectangular blocks,
// written for the tests only (it shares no code with reference/unilateral.cc): the contact
// Jacobians are central differences of the corners' gap and tangential-position functions, the
// impact's equations are one full KKT system solved by Eigen's full-pivot LU, and the contact
// states are enumerated to the end, so that every admissible outcome is found and counted.
//
// Law (Moreau's velocity-level law with zero restitution; Pfeiffer & Glocker 1996, ch. 7): each
// corner at a zero gap either ends the impact with a zero normal velocity and a compressive
// impulse, or separates with none; each interface either sticks (its tangential impulse within
// mu times its normal impulse) or slips after the impact with its tangential impulse -/+ mu times
// its normal one, opposing that slip.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace rockbench::test {

/// A block: half width b, half height h (m), mass m (kg), central inertia I (kg m^2), and the
/// friction coefficient of its base on its support (infinity: no slip).
struct ImpactBlock {
  double b = 0.0, h = 0.0, m = 0.0, I = 0.0, mu = std::numeric_limits<double>::infinity();
};

/// The outcome(s) of an impact.
struct CoulombImpactResult {
  /// Distinct admissible post-impact velocities (3 per block: vx, vy, omega clockwise).
  std::vector<Eigen::VectorXd> outcomes;
  /// Per outcome, per interface: 0 open, 1 stick, +-2 slip right / left after the impact.
  std::vector<std::vector<int>> states;
};

namespace detail {

// A point given in block i's frame (x right, y up) turned by theta clockwise (> 0: to the right)
// and placed at its mass centre.
inline Eigen::Vector2d Place(const Eigen::VectorXd& q, int i, double px, double py) {
  const double c = std::cos(q[3 * i + 2]), s = std::sin(q[3 * i + 2]);
  return {q[3 * i] + c * px + s * py, q[3 * i + 1] - s * px + c * py};
}

// The gradient of f at q by central differences (step 1e-6 of the length scale: truncation
// error ~1e-12 L relative, rounding ~1e-16 / 1e-6 = 1e-10; the Jacobians are good to 1e-9).
inline Eigen::VectorXd Gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& q, double step) {
  Eigen::VectorXd g(q.size());
  for (int i = 0; i < q.size(); ++i) {
    Eigen::VectorXd a = q, b = q;
    a[i] += step;
    b[i] -= step;
    g[i] = (f(a) - f(b)) / (2.0 * step);
  }
  return g;
}

}  // namespace detail

/// The impact of a stack (blocks bottom first, mass centres and angles q, velocities v_minus)
/// over every base corner whose gap is below gap_tol_m. Corners must lie over their support's
/// face (the tests place them so).
inline CoulombImpactResult CoulombImpact(const std::vector<ImpactBlock>& blocks,
                                         const Eigen::VectorXd& q, const Eigen::VectorXd& v_minus,
                                         double gap_tol_m = 1e-9) {
  const int n = static_cast<int>(blocks.size());
  const int dof = 3 * n;
  double length = 0.0;
  for (const ImpactBlock& b : blocks) length = std::max(length, std::hypot(b.b, b.h));
  // Contacts at a zero gap: (interface k, side j), with their normal and tangential rows.
  struct Contact {
    int k, j;
    Eigen::VectorXd n, t;
  };
  std::vector<Contact> contacts;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < 2; ++j) {
      const double side = j == 0 ? 1.0 : -1.0;
      const ImpactBlock& U = blocks[k];
      // The upper block's corner; the support's top face (its middle, normal and tangent).
      auto corner = [&](const Eigen::VectorXd& x) { return detail::Place(x, k, side * U.b, -U.h); };
      auto face = [&](const Eigen::VectorXd& x, Eigen::Vector2d* mid, Eigen::Vector2d* nrm,
                      Eigen::Vector2d* tan) {
        if (k == 0) {
          *mid = {0.0, 0.0};
          *nrm = {0.0, 1.0};
          *tan = {1.0, 0.0};
          return;
        }
        const double th = x[3 * (k - 1) + 2];
        *mid = detail::Place(x, k - 1, 0.0, blocks[k - 1].h);
        *nrm = {std::sin(th), std::cos(th)};
        *tan = {std::cos(th), -std::sin(th)};
      };
      auto gap = [&](const Eigen::VectorXd& x) {
        Eigen::Vector2d mid, nrm, tan;
        face(x, &mid, &nrm, &tan);
        return (corner(x) - mid).dot(nrm);
      };
      if (std::abs(gap(q)) > gap_tol_m) continue;
      // The support's material point under the corner at q, in the support's frame.
      Eigen::Vector2d p0 = corner(q);
      Eigen::Vector2d local{0.0, 0.0};
      if (k > 0) {
        const double th = q[3 * (k - 1) + 2], c = std::cos(th), s = std::sin(th);
        const Eigen::Vector2d d = p0 - Eigen::Vector2d(q[3 * (k - 1)], q[3 * (k - 1) + 1]);
        local = {c * d.x() - s * d.y(), s * d.x() + c * d.y()};
      } else {
        local = p0;
      }
      auto slide = [&](const Eigen::VectorXd& x) {
        Eigen::Vector2d mid, nrm, tan;
        face(x, &mid, &nrm, &tan);
        const Eigen::Vector2d material =
            k > 0 ? detail::Place(x, k - 1, local.x(), local.y()) : local;
        return (corner(x) - material).dot(tan);
      };
      const double step = 1e-6 * length;
      contacts.push_back({k, j, detail::Gradient(gap, q, step), detail::Gradient(slide, q, step)});
    }
  }
  Eigen::VectorXd mass(dof);
  for (int i = 0; i < n; ++i) mass.segment(3 * i, 3) << blocks[i].m, blocks[i].m, blocks[i].I;
  const int c = static_cast<int>(contacts.size());
  // Options: each contact closed or open; each interface with a closed contact sticks or slips.
  CoulombImpactResult out;
  double v_scale = 0.0;
  for (int i = 0; i < dof; ++i)
    v_scale = std::max(v_scale, std::abs(v_minus[i]) * (i % 3 == 2 ? length : 1.0));
  double m_total = 0.0;
  for (const ImpactBlock& b : blocks) m_total += b.m;
  const double tol_v = 1e-8 * v_scale, tol_p = 1e-8 * m_total * v_scale;
  for (long closed_bits = 0; closed_bits < (1L << c); ++closed_bits) {
    // Interfaces with a closed contact, and their tangential options.
    std::vector<int> active;
    for (int k = 0; k < n; ++k) {
      for (int a = 0; a < c; ++a) {
        if (contacts[a].k == k && ((closed_bits >> a) & 1)) {
          active.push_back(k);
          break;
        }
      }
    }
    const int na = static_cast<int>(active.size());
    std::vector<int> choice(static_cast<size_t>(na), 0);  // 0 stick, 1 slip right, 2 slip left
    while (true) {
      // Unknowns: v+ (dof), one normal impulse per closed contact, one tangential impulse per
      // sticking interface.
      std::vector<int> closed;
      for (int a = 0; a < c; ++a) {
        if ((closed_bits >> a) & 1) closed.push_back(a);
      }
      std::vector<int> sticking;
      bool skip = false;
      for (int i = 0; i < na; ++i) {
        const double mu = blocks[active[i]].mu;
        if (choice[i] == 0) sticking.push_back(i);
        if (choice[i] != 0 && std::isinf(mu)) skip = true;  // infinite friction never slips
      }
      if (!skip) {
        const int nc = static_cast<int>(closed.size()), ns = static_cast<int>(sticking.size());
        const int size = dof + nc + ns;
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(size, size);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
        A.topLeftCorner(dof, dof) = mass.asDiagonal();
        rhs.head(dof) = mass.cwiseProduct(v_minus);
        for (int r = 0; r < nc; ++r) {
          const Contact& ct = contacts[closed[r]];
          // M v+ - J_n^T lambda (- J_t^T mu lambda (-s)) = M v-; row: J_n v+ = 0.
          Eigen::VectorXd dir = ct.n;
          for (int i = 0; i < na; ++i) {
            if (active[i] == ct.k && choice[i] != 0) {
              const double s = choice[i] == 1 ? 1.0 : -1.0;
              dir -= s * blocks[ct.k].mu * ct.t;
            }
          }
          A.block(0, dof + r, dof, 1) = -dir;
          A.block(dof + r, 0, 1, dof) = ct.n.transpose();
        }
        for (int r = 0; r < ns; ++r) {
          // The interface's first closed contact's tangential row.
          const int k = active[sticking[r]];
          int a0 = -1;
          for (const int a : closed) {
            if (contacts[a].k == k) {
              a0 = a;
              break;
            }
          }
          A.block(0, dof + nc + r, dof, 1) = -contacts[a0].t;
          A.block(dof + nc + r, 0, 1, dof) = contacts[a0].t.transpose();
        }
        Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
        lu.setThreshold(1e-10);
        if (lu.isInvertible()) {
          const Eigen::VectorXd x = lu.solve(rhs);
          const Eigen::VectorXd vp = x.head(dof);
          bool ok = true;
          // Closed contacts push; open ones at a zero gap do not approach.
          std::vector<double> normal(static_cast<size_t>(n), 0.0),
              tangential(static_cast<size_t>(n), 0.0);
          for (int r = 0; r < nc; ++r) {
            ok = ok && x[dof + r] >= -tol_p;
            normal[contacts[closed[r]].k] += x[dof + r];
          }
          for (int a = 0; a < c; ++a) {
            if (!((closed_bits >> a) & 1)) ok = ok && contacts[a].n.dot(vp) >= -tol_v;
          }
          for (int r = 0; r < ns; ++r) tangential[active[sticking[r]]] = x[dof + nc + r];
          std::vector<int> state(static_cast<size_t>(n), 0);
          for (int i = 0; i < na && ok; ++i) {
            const int k = active[i];
            int a0 = -1;
            for (const int a : closed) {
              if (contacts[a].k == k) {
                a0 = a;
                break;
              }
            }
            if (choice[i] == 0) {
              state[k] = 1;
              ok = std::isinf(blocks[k].mu) ||
                   std::abs(tangential[k]) <= blocks[k].mu * normal[k] + tol_p;
            } else {
              const double s = choice[i] == 1 ? 1.0 : -1.0;
              state[k] = choice[i] == 1 ? 2 : -2;
              ok = s * contacts[a0].t.dot(vp) >= -tol_v;
            }
          }
          if (ok) {
            bool known = false;
            for (const Eigen::VectorXd& o : out.outcomes) {
              if ((o - vp).cwiseAbs().maxCoeff() <= 1e-6 * (v_scale + 1e-300)) known = true;
            }
            if (!known) {
              out.outcomes.push_back(vp);
              out.states.push_back(state);
            }
          }
        }
      }
      int i = 0;
      for (; i < na; ++i) {
        if (++choice[i] < 3) break;
        choice[i] = 0;
      }
      if (i == na) break;
    }
  }
  return out;
}

}  // namespace rockbench::test
