#pragma once
/// A linear complementarity problem (LCP) solver: Lemke's complementary pivoting algorithm with
/// the lexicographic degeneracy rule (Cottle, Pang & Stone 1992, "The Linear Complementarity
/// Problem", sections 4.4 and 4.9; Murty 1988, ch. 2).
///
/// LCP(M, q): find z >= 0 with w = M z + q >= 0 and z . w = 0 (n x n, M row-major).
///
/// Method. The tableau w - M z - d z0 = q with the covering vector d = (1, ..., 1) and the
/// artificial variable z0 starts from the basis of the w's. z0 enters at the row of the most
/// negative q_i; then each step brings in the complement of the variable that left, the row
/// that leaves chosen by the minimum ratio test, ties broken lexicographically on the rows of
/// the basis inverse (each ratio row (q_i, B^-1_i) / a_ie, the lexicographically smallest
/// leaves; z0 leaves whenever its row is among the smallest). The lexicographic rule keeps every
/// basis lexicographically feasible, so that no basis repeats: in exact arithmetic the method
/// terminates after finitely many pivots (Cottle, Pang & Stone, Theorem 4.9.4), either with z0
/// out of the basis (a solution), or on a secondary ray (the entering column has no positive
/// entry). In floating point a pivot limit guards against cycling by rounding.
///
/// What termination means. A solution is a solution (checked by the caller to its tolerance).
/// Ray termination proves no solution only for some classes of M (copositive-plus M: then the
/// LCP has no feasible point; P-matrices never end on a ray); for the others it is stated as
/// "no solution found by Lemke", never as a proof.
#include <vector>

namespace rockbench::reference {

/// How Lemke's method ended.
enum class LcpStatus {
  kSolved,      ///< z0 left the basis: z, w solve the LCP (to rounding)
  kRay,         ///< secondary ray: no solution found by Lemke (not a proof in general)
  kPivotLimit,  ///< the pivot limit was reached (cycling by rounding)
};

/// What Lemke's method gave.
struct LcpResult {
  LcpStatus status = LcpStatus::kRay;
  std::vector<double> z, w;  ///< the solution (kSolved), else the last basis's values
  int pivots = 0;            ///< pivots made (the first, z0's entry, included)
};

/// Lemke's method on LCP(M, q), M n x n row-major. `max_pivots` <= 0: 50 n + 100. A pivot is
/// refused below 1e-13 of its column's largest entry (and of 1): scale M's rows and columns
/// to order one first (a diagonal scaling keeps the problem's solutions). `covering`: the
/// covering vector d (all entries > 0; empty: all ones). Lemke's path depends on d: where it
/// ends on a ray, another d may still find a solution.
LcpResult SolveLcpLemke(const std::vector<double>& M, const std::vector<double>& q, int n,
                        int max_pivots = 0, const std::vector<double>& covering = {});

}  // namespace rockbench::reference
