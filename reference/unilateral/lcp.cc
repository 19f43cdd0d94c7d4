#include "reference/unilateral/lcp.h"

#include <algorithm>
#include <cmath>

namespace rockbench::reference {

LcpResult SolveLcpLemke(const std::vector<double>& M, const std::vector<double>& q, int n,
                        int max_pivots, const std::vector<double>& covering) {
  LcpResult out;
  out.z.assign(static_cast<size_t>(n), 0.0);
  out.w = q;
  if (n == 0 || *std::min_element(q.begin(), q.end()) >= 0.0) {
    out.status = LcpStatus::kSolved;  // z = 0
    return out;
  }
  if (max_pivots <= 0) max_pivots = 50 * n + 100;
  // Variables: w_i = i, z_i = n + i, z0 = 2n; the tableau's columns are theirs, then the
  // right-hand side. Rows: w - M z - d z0 = q.
  const int cols = 2 * n + 2, z0 = 2 * n, rhs = 2 * n + 1;
  std::vector<double> T(static_cast<size_t>(n * cols), 0.0);
  auto at = [&](int i, int j) -> double& { return T[static_cast<size_t>(i * cols + j)]; };
  for (int i = 0; i < n; ++i) {
    at(i, i) = 1.0;
    for (int j = 0; j < n; ++j) at(i, n + j) = -M[static_cast<size_t>(i * n + j)];
    at(i, z0) = covering.empty() ? -1.0 : -covering[static_cast<size_t>(i)];
    at(i, rhs) = q[static_cast<size_t>(i)];
  }
  std::vector<int> basis(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) basis[i] = i;
  auto pivot = [&](int r, int e) {
    const double p = at(r, e);
    for (int j = 0; j < cols; ++j) at(r, j) /= p;
    for (int i = 0; i < n; ++i) {
      if (i == r) continue;
      const double f = at(i, e);
      if (f == 0.0) continue;
      for (int j = 0; j < cols; ++j) at(i, j) -= f * at(r, j);
      at(i, e) = 0.0;
    }
    basis[r] = e;
    ++out.pivots;
  };
  // z0 enters at the most negative q_i / d_i; ties: the last such row (its (q, B^-1) rows
  // then stay lexicographically positive: e_i - e_r is, for i < r).
  auto d = [&](int i) { return covering.empty() ? 1.0 : covering[static_cast<size_t>(i)]; };
  int r = 0;
  for (int i = 1; i < n; ++i) {
    if (q[i] / d(i) <= q[r] / d(r)) r = i;
  }
  int leaving = basis[r];
  pivot(r, z0);
  // Two ratios equal to rounding: relative 1e-12 of their size (and of 1: the problem is
  // scaled to order one).
  auto same = [](double a, double b) {
    return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
  };
  while (out.pivots < max_pivots) {
    // The complement of the variable that left enters.
    const int e = leaving < n ? leaving + n : leaving - n;
    double col_max = 1.0;
    for (int i = 0; i < n; ++i) col_max = std::max(col_max, std::abs(at(i, e)));
    const double tol = 1e-13 * col_max;
    // The lexicographic minimum ratio test over rows with a positive entry.
    int best = -1, z0_row = -1;
    for (int i = 0; i < n; ++i) {
      if (!(at(i, e) > tol)) continue;
      if (basis[i] == z0) z0_row = i;
      if (best < 0) {
        best = i;
        continue;
      }
      // (rhs, B^-1 row) / a_ie, compared entry by entry.
      const double ai = at(i, e), ab = at(best, e);
      int cmp = 0;
      {
        const double x = at(i, rhs) / ai, y = at(best, rhs) / ab;
        if (!same(x, y)) cmp = x < y ? -1 : 1;
      }
      for (int j = 0; j < n && cmp == 0; ++j) {
        const double x = at(i, j) / ai, y = at(best, j) / ab;
        if (!same(x, y)) cmp = x < y ? -1 : 1;
      }
      if (cmp < 0) best = i;
    }
    if (best < 0) {
      out.status = LcpStatus::kRay;
      break;
    }
    // z0 leaves whenever its ratio ties the smallest: the solution at once.
    if (z0_row >= 0 && same(at(z0_row, rhs) / at(z0_row, e), at(best, rhs) / at(best, e))) {
      best = z0_row;
    }
    leaving = basis[best];
    pivot(best, e);
    if (leaving == z0) {
      out.status = LcpStatus::kSolved;
      break;
    }
  }
  if (out.pivots >= max_pivots && out.status != LcpStatus::kSolved) {
    out.status = LcpStatus::kPivotLimit;
  }
  // The basis's values (rounding may leave a basic value a hair below zero: clamped).
  std::fill(out.w.begin(), out.w.end(), 0.0);
  for (int i = 0; i < n; ++i) {
    const double x = std::max(0.0, at(i, rhs));
    if (basis[i] < n) {
      out.w[basis[i]] = x;
    } else if (basis[i] < 2 * n) {
      out.z[basis[i] - n] = x;
    }
  }
  if (out.status == LcpStatus::kSolved) {
    // w from z (the tableau's w are exact to the pivots' rounding; M z + q is what the caller
    // checks).
    for (int i = 0; i < n; ++i) {
      double s = q[i];
      for (int j = 0; j < n; ++j) s += M[static_cast<size_t>(i * n + j)] * out.z[j];
      out.w[i] = s;
    }
  }
  return out;
}

}  // namespace rockbench::reference
