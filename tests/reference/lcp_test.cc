// Lemke's method (reference/lcp.h) against a brute-force enumeration of the complementary
// bases written here: on random P-matrix problems (a unique solution, which both must find),
// on random 2-D friction problems of the unilateral model's form (Lemke's solution checked for
// complementarity), on degenerate problems, and on one with no solution.
#include "reference/unilateral/lcp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rockbench::reference {
namespace {

// Solves a x = b (n x n, row-major) by Gaussian elimination with partial pivoting; false when
// a pivot is below 1e-12 of the largest entry.
bool Solve(std::vector<double> a, std::vector<double>& b, int n) {
  double big = 0.0;
  for (const double x : a) big = std::max(big, std::abs(x));
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r) {
      if (std::abs(a[r * n + c]) > std::abs(a[p * n + c])) p = r;
    }
    if (std::abs(a[p * n + c]) <= 1e-12 * big) return false;
    for (int j = 0; j < n; ++j) std::swap(a[c * n + j], a[p * n + j]);
    std::swap(b[c], b[p]);
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] / a[c * n + c];
      for (int j = c; j < n; ++j) a[r * n + j] -= f * a[c * n + j];
      b[r] -= f * b[c];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    for (int j = r + 1; j < n; ++j) b[r] -= a[r * n + j] * b[j];
    b[r] /= a[r * n + r];
  }
  return true;
}

// Every solution of LCP(M, q) found by trying each set of basic z's: z_a = -M_aa^-1 q_a,
// z = 0 elsewhere, kept when z >= -tol and w = M z + q >= -tol.
std::vector<std::vector<double>> BruteForce(const std::vector<double>& M,
                                            const std::vector<double>& q, int n, double tol) {
  std::vector<std::vector<double>> out;
  for (int set = 0; set < (1 << n); ++set) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i) {
      if (set & (1 << i)) idx.push_back(i);
    }
    const int k = static_cast<int>(idx.size());
    std::vector<double> a(static_cast<size_t>(k * k)), b(static_cast<size_t>(k));
    for (int r = 0; r < k; ++r) {
      b[r] = -q[idx[r]];
      for (int c = 0; c < k; ++c) a[r * k + c] = M[idx[r] * n + idx[c]];
    }
    if (k > 0 && !Solve(a, b, k)) continue;
    std::vector<double> z(static_cast<size_t>(n), 0.0);
    for (int r = 0; r < k; ++r) z[idx[r]] = b[r];
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) {
      double w = q[i];
      for (int j = 0; j < n; ++j) w += M[i * n + j] * z[j];
      ok = z[i] >= -tol && w >= -tol;
    }
    if (ok) out.push_back(z);
  }
  return out;
}

// The largest violation of z >= 0, w >= 0 and z_i w_i = 0 (the product as min(z_i, w_i)).
double Violation(const std::vector<double>& M, const std::vector<double>& q,
                 const std::vector<double>& z, int n) {
  double v = 0.0;
  for (int i = 0; i < n; ++i) {
    double w = q[i];
    for (int j = 0; j < n; ++j) w += M[i * n + j] * z[j];
    v = std::max({v, -z[i], -w, std::min(std::abs(z[i]), std::abs(w))});
  }
  return v;
}

// P-matrices (M = B B^T + S + 0.1 I with S skew: x^T M x > 0, so every principal minor is
// positive): the LCP has exactly one solution for every q (Cottle, Pang & Stone, Theorem
// 3.3.7). Lemke's solution equals the enumerated one; both are computed by eliminations of
// order-one entries with condition numbers below ~1e4 here: 1e-8 of the solution's size.
TEST(Lemke, PMatrixProblemsHaveTheEnumeratedSolution) {
  std::mt19937_64 rng(37);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 7;
    std::vector<double> B(static_cast<size_t>(n * n)), M(static_cast<size_t>(n * n), 0.0);
    std::vector<double> q(static_cast<size_t>(n));
    for (double& x : B) x = g(rng);
    for (int i = 0; i < n; ++i) {
      q[i] = g(rng);
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) M[i * n + j] += B[i * n + k] * B[j * n + k];
        if (j > i) {
          const double s = g(rng);
          M[i * n + j] += s;
          M[j * n + i] -= s;
        }
      }
      M[i * n + i] += 0.1;
    }
    const auto all = BruteForce(M, q, n, 1e-10);
    ASSERT_EQ(all.size(), 1u) << trial;
    const LcpResult r = SolveLcpLemke(M, q, n);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << trial;
    double size = 1.0;
    for (const double z : all[0]) size = std::max(size, std::abs(z));
    for (int i = 0; i < n; ++i) EXPECT_NEAR(r.z[i], all[0][i], 1e-8 * size) << trial;
  }
}

// The unilateral model's friction LCP (unilateral.cc, LemkeMode) for one or two contacts at an
// impact: normal impulses N_j, per interface T+, T- and sigma, with A = J M^-1 J^T positive
// definite (rows n_j and t), q = J v-:
//   w_n = A_n. (N, T+ - T-) + q_n,  w_+ = A_t. (...) + q_t + sigma,  w_- = -(A_t. (...) + q_t)
//   + sigma,  w_sigma = mu sum N_j - T+ - T-.
// Its matrix is copositive-plus and the problem feasible (it is Stewart & Trinkle's impulse
// LCP), so Lemke finds a solution; checked for complementarity to 1e-9 of the problem's scale
// (rounding of a few dozen pivots on order-one entries), and against the enumeration: some
// complementary basis solves it too.
TEST(Lemke, FrictionProblemsAreSolvedToComplementarity) {
  std::mt19937_64 rng(24);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int solved = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int contacts = 1 + trial % 2;  // normal rows, then one tangential row
    const int rows = contacts + 1;
    // J: rows x 3 (a body in the plane), M^-1 = diag of random positive entries.
    std::vector<double> J(static_cast<size_t>(rows * 3)), inv(3);
    for (double& x : J) x = g(rng);
    for (double& x : inv) x = 0.2 + u(rng);
    std::vector<double> A(static_cast<size_t>(rows * rows), 0.0), b(static_cast<size_t>(rows));
    for (int r = 0; r < rows; ++r) {
      b[r] = g(rng);
      for (int c = 0; c < rows; ++c) {
        for (int i = 0; i < 3; ++i) A[r * rows + c] += J[r * 3 + i] * inv[i] * J[c * 3 + i];
      }
    }
    const double mu = 1.5 * u(rng);
    const int n = contacts + 3, tp = contacts, tm = contacts + 1, sg = contacts + 2;
    std::vector<double> M(static_cast<size_t>(n * n), 0.0), q(static_cast<size_t>(n), 0.0);
    const int t = contacts;  // the tangential row of A
    for (int r = 0; r < contacts; ++r) {
      for (int c = 0; c < contacts; ++c) M[r * n + c] = A[r * rows + c];
      M[r * n + tp] = A[r * rows + t];
      M[r * n + tm] = -A[r * rows + t];
      q[r] = b[r];
    }
    for (int c = 0; c < contacts; ++c) {
      M[tp * n + c] = A[t * rows + c];
      M[tm * n + c] = -A[t * rows + c];
      M[sg * n + c] = mu;
    }
    M[tp * n + tp] = A[t * rows + t];
    M[tp * n + tm] = -A[t * rows + t];
    M[tm * n + tp] = -A[t * rows + t];
    M[tm * n + tm] = A[t * rows + t];
    M[tp * n + sg] = 1.0;
    M[tm * n + sg] = 1.0;
    M[sg * n + tp] = -1.0;
    M[sg * n + tm] = -1.0;
    q[tp] = b[t];
    q[tm] = -b[t];
    const LcpResult r = SolveLcpLemke(M, q, n);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << trial;
    double scale = 1.0;
    for (const double x : q) scale = std::max(scale, std::abs(x));
    EXPECT_LE(Violation(M, q, r.z, n), 1e-9 * scale) << trial;
    EXPECT_FALSE(BruteForce(M, q, n, 1e-9 * scale).empty()) << trial;
    ++solved;
  }
  EXPECT_EQ(solved, 300);
}

// Degenerate problems, where a plain minimum ratio test ties: redundant rows (M of rank one)
// and zero entries of q. The lexicographic rule ends on a solution: z1 + z2 = 1 for the first
// (every split solves it), z = 0 where q >= 0.
TEST(Lemke, DegenerateProblemsTerminateOnASolution) {
  {
    const std::vector<double> M{1, 1, 1, 1}, q{-1, -1};
    const LcpResult r = SolveLcpLemke(M, q, 2);
    ASSERT_EQ(r.status, LcpStatus::kSolved);
    EXPECT_NEAR(r.z[0] + r.z[1], 1.0, 1e-12);
    EXPECT_LE(Violation(M, q, r.z, 2), 1e-12);
  }
  {
    // Equal entries of q and a zero: ratios tie at the first pivots.
    const std::vector<double> M3{2, 1, 1, 1, 2, 1, 1, 1, 2}, q{-1, -1, 0};
    const LcpResult r = SolveLcpLemke(M3, q, 3);
    ASSERT_EQ(r.status, LcpStatus::kSolved);
    EXPECT_LE(Violation(M3, q, r.z, 3), 1e-12);
  }
  {
    const std::vector<double> M{1, 0, 0, 1}, q{0, 2};
    const LcpResult r = SolveLcpLemke(M, q, 2);
    ASSERT_EQ(r.status, LcpStatus::kSolved);
    EXPECT_EQ(r.z[0], 0.0);
    EXPECT_EQ(r.z[1], 0.0);
  }
}

// No solution: w = -z - 1 >= 0 has none for z >= 0 (the enumeration agrees). Lemke ends on a
// ray, which it reports as such (not as a solution).
TEST(Lemke, NoSolutionEndsOnARay) {
  const std::vector<double> M{-1}, q{-1};
  EXPECT_TRUE(BruteForce(M, q, 1, 0.0).empty());
  EXPECT_EQ(SolveLcpLemke(M, q, 1).status, LcpStatus::kRay);
}

}  // namespace
}  // namespace rockbench::reference
