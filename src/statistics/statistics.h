#pragma once
/// Comparing an engine's ensemble of outcomes with a reference ensemble.
///
/// Rocking blocks are chaotic: beyond a predictability horizon two correct simulations of the
/// same scene disagree run by run, and only the distributions of their outcomes (peak rotation,
/// time to overturning, which block fell) can be compared. This module holds the few
/// distribution-free tests that comparison needs, with no dependency beyond the standard library:
///
///  - two-sample Kolmogorov-Smirnov (sensitive to a shift of the bulk of the distribution);
///  - Anderson-Darling k-sample, Scholz & Stephens (1987) A2akN (more weight in the tails);
///  - Fisher's exact test on a 2x2 table and its 2xk generalisation (Freeman-Halton) for
///    categorical outcomes, and the exact binomial test;
///  - Holm-Bonferroni adjustment for a family of tests;
///  - mean, median and quantile of an ensemble.
///
/// Results are deterministic: the same input gives the same bytes. The only randomness is in
/// permutation p-values, drawn from a seeded std::mt19937_64 in a fixed, documented way (see
/// UniformBelow and PValueOptions); no std::*_distribution, whose output is
/// implementation-defined, is used. Tied values are handled exactly by every test (ties are
/// common in outcomes such as "time to overturning" of blocks that never overturned).
///
/// Sample values must not be NaN (std::invalid_argument); infinities are ordinary values.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace rockbench::stats {

/// The outcome of one test.
struct TestResult {
  /// Which test, e.g. "two-sample Kolmogorov-Smirnov".
  std::string test;
  /// The test statistic (see each test for which one); NaN when undefined.
  double statistic = std::numeric_limits<double>::quiet_NaN();
  /// The p-value; NaN when the test is undefined (then `method` says why).
  double p_value = std::numeric_limits<double>::quiet_NaN();
  /// The sizes of the two samples compared (for a binomial test: trials and 0).
  int n_a = 0, n_b = 0;
  /// How the p-value was obtained: "exact", "permutation (B = 9999)", "asymptotic", or
  /// "undefined: ..." with the reason.
  std::string method;
};

/// The alternative hypothesis of a test that has one-sided versions.
enum class Alternative {
  kTwoSided,
  /// The statistic is smaller than under the null (lower tail).
  kLess,
  /// The statistic is larger than under the null (upper tail).
  kGreater,
};

/// How a two-sample test obtains its p-value.
enum class PValueMethod {
  /// The test's documented choice by sample size and ties.
  kAuto,
  /// The exact null distribution (conditional on the pooled values when there are ties).
  kExact,
  /// B random relabellings of the pooled sample: p = (1 + #{T* >= T}) / (1 + B).
  kPermutation,
  /// The large-sample limit (Kolmogorov-Smirnov only; conservative with ties).
  kAsymptotic,
};

/// The default number of random relabellings B of a permutation p-value (p resolves 1e-4).
inline constexpr int kDefaultPermutations = 9999;
/// The default seed of the permutation generator.
inline constexpr std::uint64_t kDefaultSeed = 0x726f636b62656e63;  // "rockbenc"

/// Options of a two-sample test's p-value.
///
/// A permutation p-value relabels the pooled sample (sorted by value, then by sample) with B
/// successive Fisher-Yates shuffles of one label array, each of them
/// `for i = N-1 down to 1: swap(label[i], label[UniformBelow(rng, i + 1)])`, the generator a
/// std::mt19937_64 seeded once with `seed`; relabelling b + 1 shuffles the labels left by b.
struct PValueOptions {
  PValueMethod method = PValueMethod::kAuto;
  /// B, the number of random relabellings when the p-value is a permutation one (>= 1).
  int permutations = kDefaultPermutations;
  /// Seed of the std::mt19937_64 that draws the relabellings.
  std::uint64_t seed = kDefaultSeed;
};

// ---------------------------------------------------------------------------------------------
// Random draws (fixed, documented use of the generator's raw 64-bit output).

/// A uniform integer in [0, bound) (bound >= 1), by rejection: draws x = rng() until
/// x >= 2^64 mod bound and returns x mod bound. Unbiased, and the same on every platform.
std::uint64_t UniformBelow(std::mt19937_64& rng, std::uint64_t bound);

/// A uniform double in [0, 1): the top 53 bits of one rng() output times 2^-53.
double UniformUnit(std::mt19937_64& rng);

// ---------------------------------------------------------------------------------------------
// Percentile bootstrap over members (paired when the caller applies one draw to two samples).

/// The draws of a bootstrap: per statistic, its values over the resamples that had them.
struct BootstrapDraws {
  std::vector<std::vector<double>> values;  ///< values[q]: statistic q, sorted ascending
  int resamples = 0;                        ///< resamples drawn
  int degenerate = 0;                       ///< resamples without values (left out)
};

/// `resamples` resamples of the members 0..n-1 with replacement: member i of a resample is
/// UniformBelow(rng, n), drawn in order i = 0..n-1 from a std::mt19937_64 seeded with `seed`.
/// `statistics(members, values)` writes the resample's `count` values into `values` (sized
/// `count`) and returns true, or returns false when the resample has none (a fit that failed).
/// Applying the same `members` to two runs' samples makes the bootstrap paired. Throws
/// std::invalid_argument for n = 0.
BootstrapDraws Bootstrap(
    std::size_t n, int resamples, std::uint64_t seed, std::size_t count,
    const std::function<bool(std::span<const std::size_t>, std::vector<double>&)>& statistics);

/// The percentile interval's end from sorted draws, by the lower order statistic:
/// x_floor(probability (m - 1)), no interpolation. `sorted` must not be empty.
double LowerOrderPercentile(std::span<const double> sorted, double probability);

// ---------------------------------------------------------------------------------------------
// Two-sample Kolmogorov-Smirnov.

/// The two-sample Kolmogorov-Smirnov statistic D = sup_x |F_a(x) - F_b(x)|, with F the empirical
/// distribution functions (right-continuous: with ties, evaluated once at every distinct value).
/// NaN if a sample is empty.
double KolmogorovSmirnovStatistic(std::span<const double> a, std::span<const double> b);

/// The exact Kolmogorov-Smirnov p-value costs a few nanoseconds per lattice cell (n_a * n_b);
/// without ties it is used up to this many cells, beyond which the asymptotic one is accurate.
inline constexpr std::int64_t kKolmogorovSmirnovExactMaxCells = 10'000'000;
/// With ties (where the asymptotic p-value is only conservative) the exact p-value is used up
/// to this many cells: it stays cheaper than B relabellings (n_a * n_b against B * N).
inline constexpr std::int64_t kKolmogorovSmirnovExactMaxCellsWithTies = 100'000'000;

/// The two-sided two-sample Kolmogorov-Smirnov test of "a and b come from the same distribution".
/// statistic = D. The p-value P(D* >= D) under random relabelling of the pooled sample is, with
/// kAuto:
///  - "exact" when n_a * n_b <= kKolmogorovSmirnovExactMaxCells, or when there are ties and
///    n_a * n_b <= kKolmogorovSmirnovExactMaxCellsWithTies: counting the monotone lattice paths
///    from (0, 0) to (n_a, n_b) that reach |i/n_a - j/n_b| >= D at a point where the pooled
///    sample changes value (Hodges 1957 / Kim & Jennrich 1973 recursion, normalised so that
///    every number is a probability; the paths' first contacts with the boundary are summed, so
///    small p-values keep full relative precision). With ties this is the exact permutation
///    p-value conditional on the pooled values.
///  - otherwise, without ties, "asymptotic": P(K > sqrt(n_a n_b / (n_a + n_b)) D) of the
///    Kolmogorov distribution (KolmogorovSurvival).
///  - otherwise (ties) "permutation (B = ...)": B relabellings as documented above, D* compared
///    with D in exact integer arithmetic (D n_a n_b is an integer), so no rounding tolerance.
/// An empty sample gives p NaN ("undefined: empty sample"); when all values of both samples are
/// equal, D = 0 and p = 1. P-values below about 1e-300 underflow to 0.
TestResult KolmogorovSmirnovTest(std::span<const double> a, std::span<const double> b,
                                 const PValueOptions& options = {});

/// The two-sample Kolmogorov-Smirnov test with a slack: differences of value smaller than `slack`
/// (the resolution of the quantity compared) are not differences. Statistic
///   D_slack = sup_x max(F_b(x) - F_a(x + slack), F_a(x) - F_b(x + slack)),
/// the distance of Levy's metric at a fixed horizontal slack (D_0 = D; D_slack = 0 when every
/// value of one sample lies within `slack` of the other's distribution function). The p-value
/// P(D* >= D) is a permutation one (B random relabellings as documented above, compared in
/// exact integer arithmetic), which is valid for any statistic; slack = 0 gives
/// KolmogorovSmirnovTest. D_slack = 0 gives p = 1. slack < 0 or NaN throws
/// std::invalid_argument.
TestResult KolmogorovSmirnovSlackTest(std::span<const double> a, std::span<const double> b,
                                      double slack, const PValueOptions& options = {});

/// P(K > lambda) for the Kolmogorov distribution, the limit of sqrt(n_a n_b / (n_a + n_b)) D:
/// 2 sum_k (-1)^(k-1) exp(-2 k^2 lambda^2), or 1 - sqrt(2 pi)/lambda sum_k
/// exp(-(2k-1)^2 pi^2 / (8 lambda^2)) for lambda < 1.18 where that converges faster.
double KolmogorovSurvival(double lambda);

// ---------------------------------------------------------------------------------------------
// Anderson-Darling k-sample (Scholz & Stephens 1987).

/// The Anderson-Darling k-sample statistic A2akN of Scholz & Stephens (1987, eq. 7), the version
/// for ties (midranks): with z*_1 < ... < z*_L the distinct pooled values, l_j their
/// multiplicities, B_j = #{pooled < z*_j} + l_j / 2 and M_ij = #{sample i < z*_j} + #{sample i
/// = z*_j} / 2,
///   A2akN = (N - 1) / N  sum_i 1/n_i  sum_j (l_j / N) (N M_ij - n_i B_j)^2
///                                           / (B_j (N - B_j) - N l_j / 4).
/// Its null mean is k - 1. 0 when every pooled value is equal; NaN if a sample is empty or there
/// are fewer than two samples.
double AndersonDarlingStatistic(std::span<const std::vector<double>> samples);

/// A2akN of two samples (the same number as the k-sample form with k = 2).
double AndersonDarlingStatistic(std::span<const double> a, std::span<const double> b);

/// The variance of A2akN under the null for continuous data (Scholz & Stephens 1987, eq. 4),
/// for the standardised T = (A2akN - (k - 1)) / sqrt(variance). Needs N = sum of sizes >= 4.
double AndersonDarlingNullVariance(std::span<const int> sample_sizes);

/// The two-sample Anderson-Darling test of "a and b come from the same distribution".
/// statistic = A2akN. The p-value P(A* >= A) under random relabelling of the pooled sample
/// (A* >= A - 1e-12 * max(1, A), so that rounding does not drop the observed labelling), with
/// kAuto:
///  - "exact" when the C(N, n_a) relabellings number at most B + 1: all of them are enumerated;
///  - "permutation (B = ...)" otherwise.
/// kExact enumerates up to 10^7 relabellings (std::invalid_argument beyond); kAsymptotic is not
/// offered (std::invalid_argument). An empty sample gives p NaN; all values equal give A = 0,
/// p = 1.
TestResult AndersonDarlingTest(std::span<const double> a, std::span<const double> b,
                               const PValueOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Counts: Fisher's exact test and the exact binomial test.

/// Fisher's exact test on the 2x2 table [[a11, a12], [a21, a22]], rows the two samples, columns
/// two outcomes, conditional on all margins (X = a11 is hypergeometric). statistic = the
/// probability of the observed table under the null.
///  - kTwoSided: the sum of the probabilities of all tables with these margins whose probability
///    is <= the observed one's times (1 + 1e-7) (the relative tolerance of R's fisher.test).
///  - kGreater: P(X >= a11) (odds ratio > 1); kLess: P(X <= a11).
/// method "exact"; a row of zeros (an empty sample) gives p NaN. Negative counts throw
/// std::invalid_argument.
TestResult FisherExactTest(int a11, int a12, int a21, int a22,
                           Alternative alternative = Alternative::kTwoSided);

/// The Fisher-Freeman-Halton exact test on the 2xk table whose rows are the counts of the k
/// outcome categories in each sample (e.g. none / block 1 / block 2 overturned), two-sided in
/// the same sense as the 2x2 test (which it equals for k = 2). statistic = the probability of
/// the observed table. Every table with the observed margins is enumerated: fine for the few
/// categories of an ensemble (k = 3 and a few thousand runs take milliseconds); throws
/// std::length_error beyond 10^9 tables, std::invalid_argument on rows of different lengths or
/// negative counts. An empty row gives p NaN.
TestResult FisherExactTest(std::span<const int> row_a, std::span<const int> row_b);

/// The exact binomial test of "successes out of trials has success probability `probability`".
/// statistic = successes. kTwoSided: the sum of the probabilities of all outcomes no more likely
/// than the observed one (relative tolerance 1 + 1e-7, as R's binom.test); kGreater:
/// P(X >= successes); kLess: P(X <= successes). trials = 0 gives p NaN; counts or probability out
/// of range throw std::invalid_argument. n_a = trials, n_b = 0.
TestResult BinomialTest(int successes, int trials, double probability,
                        Alternative alternative = Alternative::kTwoSided);

// ---------------------------------------------------------------------------------------------
// Multiple comparisons.

/// Holm-Bonferroni adjusted p-values, in input order: with p_(1) <= ... <= p_(m) sorted,
/// adjusted p_(i) = min(1, max_{j <= i} (m - j + 1) p_(j)). Reject the hypotheses whose adjusted
/// p is <= alpha to control the family-wise error rate at alpha. NaN entries stay NaN and do not
/// count in m (as R's p.adjust); values outside [0, 1] throw std::invalid_argument.
std::vector<double> HolmAdjust(std::span<const double> p_values);

// ---------------------------------------------------------------------------------------------
// Summaries of an ensemble (NaN when empty; NaN values throw std::invalid_argument).

/// The arithmetic mean.
double Mean(std::span<const double> values);

/// The median (the quantile of probability 1/2: the mean of the middle two for an even count).
double Median(std::span<const double> values);

/// The sample quantile of `probability` in [0, 1], Hyndman & Fan type 7 (R's default): with the
/// values sorted x_0 <= ... <= x_(n-1) and h = (n - 1) probability, x_floor(h) + (h - floor(h))
/// (x_(floor(h)+1) - x_floor(h)). Throws std::invalid_argument for a probability outside [0, 1].
double Quantile(std::span<const double> values, double probability);

}  // namespace rockbench::stats
