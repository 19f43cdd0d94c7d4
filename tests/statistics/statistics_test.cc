// Ensemble statistics against closed forms, published values and brute-force enumeration (never
// against numbers copied from the code under test).
#include "statistics/statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rockbench::stats {
namespace {

using Sample = std::vector<double>;

/// C(n, k) as a double (exact for the small arguments used here).
double Choose(int n, int k) {
  long double c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return static_cast<double>(std::round(c));
}

Sample Uniforms(std::mt19937_64& rng, int n, double shift = 0.0) {
  Sample s(n);
  for (double& v : s) v = UniformUnit(rng) + shift;
  return s;
}

/// Calls f(mask) for every way of choosing k of n items (bit i set: item i chosen).
template <typename F>
void ForEachSubset(int n, int k, F&& f) {
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    if (std::popcount(mask) == k) f(mask);
  }
}

std::pair<Sample, Sample> Split(const Sample& pooled, unsigned mask) {
  Sample a, b;
  for (size_t i = 0; i < pooled.size(); ++i) ((mask >> i) & 1u ? a : b).push_back(pooled[i]);
  return {a, b};
}

/// D n m from the definition: |n_b #{a <= v} - n_a #{b <= v}| at every pooled value v.
long long ScaledKsByDefinition(const Sample& a, const Sample& b) {
  long long d = 0;
  const long long n = static_cast<long long>(a.size()), m = static_cast<long long>(b.size());
  for (const Sample* s : {&a, &b}) {
    for (double v : *s) {
      const long long ca = std::count_if(a.begin(), a.end(), [&](double x) { return x <= v; });
      const long long cb = std::count_if(b.begin(), b.end(), [&](double x) { return x <= v; });
      d = std::max(d, std::llabs(ca * m - cb * n));
    }
  }
  return d;
}

/// The permutation p-value of KS over all C(N, n_a) splits of the pooled sample.
double KsByEnumeration(const Sample& a, const Sample& b) {
  Sample pooled = a;
  pooled.insert(pooled.end(), b.begin(), b.end());
  const long long observed = ScaledKsByDefinition(a, b);
  double at_least = 0, total = 0;
  ForEachSubset(static_cast<int>(pooled.size()), static_cast<int>(a.size()), [&](unsigned mask) {
    auto [x, y] = Split(pooled, mask);
    total += 1;
    at_least += ScaledKsByDefinition(x, y) >= observed;
  });
  return at_least / total;
}

/// The permutation p-value of AD over all C(N, n_a) splits of the pooled sample.
double AdByEnumeration(const Sample& a, const Sample& b) {
  Sample pooled = a;
  pooled.insert(pooled.end(), b.begin(), b.end());
  const double observed = AndersonDarlingStatistic(a, b);
  double at_least = 0, total = 0;
  ForEachSubset(static_cast<int>(pooled.size()), static_cast<int>(a.size()), [&](unsigned mask) {
    auto [x, y] = Split(pooled, mask);
    total += 1;
    at_least += AndersonDarlingStatistic(x, y) >= observed - 1e-12 * std::max(1.0, observed);
  });
  return at_least / total;
}

/// The central `coverage` band [lo, hi] of Binomial(trials, p) counts.
std::pair<int, int> BinomialBand(int trials, double p, double coverage) {
  const double tail = (1 - coverage) / 2;
  long double cdf = 0;
  int lo = -1, hi = trials;
  for (int k = 0; k <= trials; ++k) {
    const long double log_pmf = std::lgamma(trials + 1.0L) - std::lgamma(k + 1.0L) -
                                std::lgamma(trials - k + 1.0L) + k * std::log((long double)p) +
                                (trials - k) * std::log1p(-(long double)p);
    cdf += std::exp(log_pmf);
    if (lo < 0 && cdf > tail) lo = k;
    if (cdf >= 1 - tail) {
      hi = k;
      break;
    }
  }
  return {lo, hi};
}

/// Monte-Carlo tolerance of a permutation p-value with B relabellings around the true p.
double PermutationTolerance(double p, int b) {
  return 4.5 * std::sqrt(p * (1 - p) / b) + 2.0 / b;
}

// --- Bootstrap ---------------------------------------------------------------------------------

// The bootstrap distribution of a sample mean has the closed-form variance s^2 / n, with s^2
// the plug-in variance (1/n) sum (x - mean)^2 (Efron & Tibshirani 1993, sec. 6.2). Over 4000
// resamples the draws' standard deviation estimates its root with a relative standard error of
// about 1 / sqrt(2 * 4000) = 1.1%: bound 5% (4.5 of those errors).
TEST(Bootstrap, DrawsOfAMeanHaveTheClosedFormSpread) {
  std::vector<double> x;
  for (int i = 0; i < 50; ++i) x.push_back(std::sin(1.0 + i) + 0.01 * i * i);
  const double n = static_cast<double>(x.size());
  double mean = 0.0, plugin = 0.0;
  for (double v : x) mean += v / n;
  for (double v : x) plugin += (v - mean) * (v - mean) / n;
  const BootstrapDraws d = Bootstrap(x.size(), 4000, 42, 1,
                                     [&](std::span<const std::size_t> m, std::vector<double>& out) {
                                       out[0] = 0.0;
                                       for (std::size_t i : m) out[0] += x[i] / n;
                                       return true;
                                     });
  ASSERT_EQ(d.values.size(), 1u);
  ASSERT_EQ(d.values[0].size(), 4000u);
  EXPECT_EQ(d.resamples, 4000);
  EXPECT_EQ(d.degenerate, 0);
  EXPECT_TRUE(std::is_sorted(d.values[0].begin(), d.values[0].end()));
  double dm = 0.0, dv = 0.0;
  for (double v : d.values[0]) dm += v / 4000.0;
  for (double v : d.values[0]) dv += (v - dm) * (v - dm) / 3999.0;
  EXPECT_NEAR(std::sqrt(dv) / std::sqrt(plugin / n), 1.0, 0.05);
  // The lower order statistic: index floor(p (m - 1)).
  EXPECT_EQ(LowerOrderPercentile(d.values[0], 0.0), d.values[0].front());
  EXPECT_EQ(LowerOrderPercentile(d.values[0], 1.0), d.values[0].back());
  EXPECT_EQ(LowerOrderPercentile(d.values[0], 0.025), d.values[0][99]);
}

TEST(Bootstrap, SameSeedSameDrawsAndResamplesWithoutValuesAreCounted) {
  std::vector<std::vector<std::size_t>> first, second;
  const auto record = [](std::vector<std::vector<std::size_t>>& into) {
    return [&into](std::span<const std::size_t> m, std::vector<double>& out) {
      into.emplace_back(m.begin(), m.end());
      out[0] = static_cast<double>(m[0]);
      return into.size() % 3 != 0;  // every third resample has no value
    };
  };
  const BootstrapDraws a = Bootstrap(7, 30, 5, 1, record(first));
  const BootstrapDraws b = Bootstrap(7, 30, 5, 1, record(second));
  EXPECT_EQ(first, second);
  EXPECT_EQ(a.degenerate, 10);
  EXPECT_EQ(a.values[0].size(), 20u);
  EXPECT_EQ(a.values, b.values);
  for (const auto& m : first) {
    EXPECT_EQ(m.size(), 7u);
    for (std::size_t i : m) EXPECT_LT(i, 7u);
  }
  EXPECT_THROW(Bootstrap(0, 1, 5, 1, record(first)), std::invalid_argument);
  EXPECT_THROW(LowerOrderPercentile({}, 0.5), std::invalid_argument);
}

// --- Kolmogorov-Smirnov ----------------------------------------------------------------------

TEST(KolmogorovSmirnov, StatisticOfHandMadeSamples) {
  // Sorted pooled: .1a .2b .3b .4a .5b .7a .9b; |F_a - F_b| = 1/3, 1/12, 1/6, 1/6, 1/12, 1/4, 0.
  EXPECT_DOUBLE_EQ(KolmogorovSmirnovStatistic(Sample{0.1, 0.4, 0.7}, Sample{0.2, 0.3, 0.5, 0.9}),
                   1.0 / 3.0);
  // Ties: evaluated at each distinct value, F_a - F_b = 1/3, 5/12, 1/2, 1/4, 0 at 1..5 (walking
  // the pooled order without grouping ties would see 2/3 after "1a 2a").
  const Sample a{1, 2, 3}, b{2, 3, 4, 5};
  EXPECT_DOUBLE_EQ(KolmogorovSmirnovStatistic(a, b), 0.5);
  EXPECT_DOUBLE_EQ(KolmogorovSmirnovStatistic(b, a), 0.5);
  EXPECT_DOUBLE_EQ(KolmogorovSmirnovTest(a, b).statistic, 0.5);
  EXPECT_EQ(KolmogorovSmirnovStatistic(Sample{1, 2, 2}, Sample{2, 1, 2}), 0.0);
  EXPECT_EQ(KolmogorovSmirnovStatistic(Sample{0, 1}, Sample{2, 3}), 1.0);
}

TEST(KolmogorovSmirnov, CompleteSeparationHasPTwoOverBinomial) {
  // Only the two extreme splits reach D = 1: p = 2 / C(n + m, n), however small.
  for (auto [n, m] : {std::pair{1, 1}, {2, 2}, {3, 5}, {5, 5}, {4, 9}, {10, 10}, {30, 30}}) {
    Sample a, b;
    for (int i = 0; i < n; ++i) a.push_back(i);
    for (int j = 0; j < m; ++j) b.push_back(100 + j);
    const TestResult r = KolmogorovSmirnovTest(a, b);
    const double expected = 2.0 / Choose(n + m, n);
    EXPECT_EQ(r.statistic, 1.0);
    EXPECT_NEAR(r.p_value, expected, 1e-12 * expected) << n << " vs " << m;
    EXPECT_EQ(r.method, "exact");
    EXPECT_DOUBLE_EQ(KolmogorovSmirnovTest(b, a).p_value, r.p_value);
  }
}

TEST(KolmogorovSmirnov, ExactMatchesGnedenkoKorolyukForEqualSizes) {
  // n = m: P(D >= k/n) = 2 sum_{i >= 1} (-1)^(i-1) C(2n, n - ik) / C(2n, n) (reflection
  // principle, Gnedenko & Korolyuk 1951). b lags a by k positions, so D = k/n.
  const int n = 50;
  for (int k = 1; k <= n; ++k) {
    Sample a, b;
    for (int i = 0; i < n; ++i) {
      a.push_back(i);
      b.push_back(i + k - 0.5);
    }
    long double sum = 0;
    for (int i = 1; i * k <= n; ++i) {
      long double ratio = 1;  // C(2n, n - ik) / C(2n, n)
      for (int t = 1; t <= i * k; ++t) ratio *= static_cast<long double>(n - t + 1) / (n + t);
      sum += (i % 2 == 1 ? 2 : -2) * ratio;
    }
    const double expected = static_cast<double>(sum);
    const TestResult r = KolmogorovSmirnovTest(a, b);
    EXPECT_DOUBLE_EQ(r.statistic, static_cast<double>(k) / n);
    EXPECT_NEAR(r.p_value, expected, 1e-12 + 1e-10 * expected) << "k = " << k;
  }
}

TEST(KolmogorovSmirnov, ExactMatchesEnumerationOfAllSplits) {
  std::mt19937_64 rng(11);
  std::vector<std::pair<Sample, Sample>> cases;
  cases.emplace_back(Uniforms(rng, 5), Uniforms(rng, 7, 0.2));                // no ties
  cases.emplace_back(Uniforms(rng, 6), Uniforms(rng, 6, 0.4));                // no ties
  cases.emplace_back(Sample{1, 2, 2, 3, 5, 5}, Sample{2, 3, 3, 4, 5, 6});     // ties across samples
  cases.emplace_back(Sample{0, 1, 1, 2}, Sample{0, 0, 0, 1, 2, 2, 2, 2, 2});  // three values
  cases.emplace_back(Sample{1, 1, 1}, Sample{1, 1, 2, 2, 2});
  cases.emplace_back(Sample{3}, Sample{0, 1, 2, 4, 5, 6});
  for (const auto& [a, b] : cases) {
    const TestResult r = KolmogorovSmirnovTest(a, b);
    const double expected = KsByEnumeration(a, b);
    EXPECT_EQ(r.method, "exact");
    EXPECT_DOUBLE_EQ(r.statistic, static_cast<double>(ScaledKsByDefinition(a, b)) /
                                      (static_cast<double>(a.size()) * b.size()));
    EXPECT_NEAR(r.p_value, expected, 1e-12 * expected) << a.size() << " vs " << b.size();
  }
}

TEST(KolmogorovSmirnov, PermutationAgreesWithExactUnderTies) {
  std::mt19937_64 rng(5);
  Sample a = Uniforms(rng, 40), b = Uniforms(rng, 50, 0.05);
  for (double& v : a) v = std::round(v * 8);  // heavy ties
  for (double& v : b) v = std::round(v * 8);
  const TestResult exact = KolmogorovSmirnovTest(a, b);
  ASSERT_EQ(exact.method, "exact");
  ASSERT_GT(exact.p_value, 0.01);  // an informative p-value, not a trivial one
  ASSERT_LT(exact.p_value, 0.9);
  const TestResult permutation = KolmogorovSmirnovTest(a, b, {PValueMethod::kPermutation});
  EXPECT_EQ(permutation.method, "permutation (B = 9999)");
  EXPECT_EQ(permutation.statistic, exact.statistic);
  EXPECT_NEAR(permutation.p_value, exact.p_value, PermutationTolerance(exact.p_value, 9999));
}

TEST(KolmogorovSmirnov, KolmogorovDistributionQuantiles) {
  // Published critical values of sqrt(n m / (n + m)) D: 1.2238 (10%), 1.3581 (5%), 1.6276 (1%).
  EXPECT_NEAR(KolmogorovSurvival(1.2238), 0.10, 1e-4);
  EXPECT_NEAR(KolmogorovSurvival(1.3581), 0.05, 1e-4);
  EXPECT_NEAR(KolmogorovSurvival(1.6276), 0.01, 1e-4);
  // The two series agree where the implementation switches between them.
  EXPECT_NEAR(KolmogorovSurvival(1.18 - 1e-12), KolmogorovSurvival(1.18), 1e-10);
  EXPECT_EQ(KolmogorovSurvival(0.0), 1.0);
  EXPECT_NEAR(KolmogorovSurvival(0.2), 1.0 - 5.05e-13, 1e-15);  // sqrt(2 pi)/0.2 e^(-pi^2/0.32)
  EXPECT_LT(KolmogorovSurvival(5.0), 1e-20);
}

TEST(KolmogorovSmirnov, AsymptoticCloseToExactForLargeSamples) {
  const int n = 1000, k = 60;  // D = 0.06, lambda = sqrt(500) 0.06 = 1.34
  Sample a, b;
  for (int i = 0; i < n; ++i) {
    a.push_back(i);
    b.push_back(i + k - 0.5);
  }
  const TestResult exact = KolmogorovSmirnovTest(a, b);
  const TestResult asymptotic = KolmogorovSmirnovTest(a, b, {PValueMethod::kAsymptotic});
  EXPECT_EQ(exact.method, "exact");
  EXPECT_EQ(asymptotic.method, "asymptotic");
  EXPECT_DOUBLE_EQ(asymptotic.p_value, KolmogorovSurvival(std::sqrt(500.0) * 0.06));
  EXPECT_NEAR(asymptotic.p_value, exact.p_value, 0.1 * exact.p_value);
}

TEST(KolmogorovSmirnov, AutomaticMethodBySizeAndTies) {
  std::mt19937_64 rng(3);
  EXPECT_EQ(KolmogorovSmirnovTest(Uniforms(rng, 30), Uniforms(rng, 30)).method, "exact");
  EXPECT_EQ(KolmogorovSmirnovTest(Sample{1, 1, 2}, Sample{1, 2, 2}).method, "exact");
  // Beyond kKolmogorovSmirnovExactMaxCells lattice cells without ties: asymptotic.
  int n = 3163;
  ASSERT_GT(static_cast<std::int64_t>(n) * n, kKolmogorovSmirnovExactMaxCells);
  Sample a = Uniforms(rng, n), b = Uniforms(rng, n);
  EXPECT_EQ(KolmogorovSmirnovTest(a, b).method, "asymptotic");
  for (double& v : a) v = std::round(v * 100);
  for (double& v : b) v = std::round(v * 100);
  EXPECT_EQ(KolmogorovSmirnovTest(a, b).method, "exact");  // ties
  // Beyond kKolmogorovSmirnovExactMaxCellsWithTies with ties: permutations.
  n = 10001;
  ASSERT_GT(static_cast<std::int64_t>(n) * n, kKolmogorovSmirnovExactMaxCellsWithTies);
  a = Uniforms(rng, n);
  b = Uniforms(rng, n);
  for (double& v : a) v = std::round(v * 100);
  for (double& v : b) v = std::round(v * 100);
  PValueOptions options;
  options.permutations = 99;
  EXPECT_EQ(KolmogorovSmirnovTest(a, b, options).method, "permutation (B = 99)");
}

TEST(KolmogorovSmirnov, DegenerateSamples) {
  const TestResult empty = KolmogorovSmirnovTest(Sample{}, Sample{1, 2});
  EXPECT_TRUE(std::isnan(empty.p_value));
  EXPECT_NE(empty.method.find("empty"), std::string::npos);
  EXPECT_EQ(empty.n_a, 0);
  EXPECT_EQ(empty.n_b, 2);
  const TestResult same = KolmogorovSmirnovTest(Sample{2, 2, 2}, Sample{2, 2});
  EXPECT_EQ(same.statistic, 0.0);
  EXPECT_EQ(same.p_value, 1.0);
  EXPECT_THROW(KolmogorovSmirnovTest(Sample{1, NAN}, Sample{1}), std::invalid_argument);
  const double inf = std::numeric_limits<double>::infinity();  // never overturned: a value
  EXPECT_DOUBLE_EQ(KolmogorovSmirnovStatistic(Sample{1, inf, inf}, Sample{1, 2, inf}), 1.0 / 3.0);
}

TEST(KolmogorovSmirnov, NullRejectionRateWithinBinomialBand) {
  // n = 32, m = 37: the exact test's attainable size at 0.05 is 0.0485 (big-integer path
  // counting in Python), close to the nominal level.
  const int trials = 2000;
  std::mt19937_64 rng(2024);
  int rejected = 0;
  for (int t = 0; t < trials; ++t) {
    rejected += KolmogorovSmirnovTest(Uniforms(rng, 32), Uniforms(rng, 37)).p_value <= 0.05;
  }
  const auto [lo, hi] = BinomialBand(trials, 0.05, 0.999);
  EXPECT_GE(rejected, lo);
  EXPECT_LE(rejected, hi);
}

// --- Anderson-Darling ------------------------------------------------------------------------

TEST(AndersonDarling, ScholzStephensPublishedExample) {
  // Scholz & Stephens (1987), Lenth's (1983) surface smoothness of four laboratories, with ties:
  // A2akN = 8.3926 and standardised T_akN = (A2akN - 3) / sigma_N = 4.480.
  const std::vector<Sample> labs = {
      {38.7, 41.5, 43.8, 44.5, 45.5, 46.0, 47.7, 58.0},
      {39.2, 39.3, 39.7, 41.4, 41.8, 42.9, 43.3, 45.8},
      {34.0, 35.0, 39.0, 40.0, 43.0, 43.0, 44.0, 45.0},
      {34.0, 34.8, 34.8, 35.4, 37.2, 37.8, 41.2, 42.8},
  };
  const double a2akn = AndersonDarlingStatistic(labs);
  EXPECT_NEAR(a2akn, 8.3926, 5e-5);
  const int sizes[] = {8, 8, 8, 8};
  const double sigma = std::sqrt(AndersonDarlingNullVariance(sizes));
  EXPECT_NEAR(sigma, 1.2038, 5e-5);
  EXPECT_NEAR((a2akn - 3.0) / sigma, 4.480, 5e-4);
}

TEST(AndersonDarling, NullVarianceTendsToAsymptoticValue) {
  // Var(A2) -> (k - 1) 2 (pi^2 - 9) / 3 as N grows (Scholz & Stephens 1987).
  const int sizes[] = {5000, 5000};
  const double pi = std::numbers::pi;
  EXPECT_NEAR(AndersonDarlingNullVariance(sizes), 2 * (pi * pi - 9) / 3, 1e-3);
}

TEST(AndersonDarling, TwoSampleFormEqualsKSampleForm) {
  const Sample a{1, 2, 2, 5, 7}, b{2, 3, 4, 4, 8, 9};
  const std::vector<Sample> both = {a, b};
  EXPECT_EQ(AndersonDarlingStatistic(a, b), AndersonDarlingStatistic(both));
  EXPECT_EQ(AndersonDarlingTest(a, b).statistic, AndersonDarlingStatistic(a, b));
}

TEST(AndersonDarling, ExactMatchesEnumerationOfAllSplits) {
  std::mt19937_64 rng(17);
  std::vector<std::pair<Sample, Sample>> cases;
  cases.emplace_back(Uniforms(rng, 5), Uniforms(rng, 6, 0.3));
  cases.emplace_back(Sample{1, 2, 2, 3, 5}, Sample{2, 3, 3, 4, 5, 6, 6});
  cases.emplace_back(Sample{0, 0, 1, 1}, Sample{0, 1, 1, 1, 1, 2, 2});
  for (const auto& [a, b] : cases) {
    const double expected = AdByEnumeration(a, b);
    const TestResult exact = AndersonDarlingTest(a, b);  // C(N, n_a) <= 10^4: enumerated
    EXPECT_EQ(exact.method, "exact");
    EXPECT_NEAR(exact.p_value, expected, 1e-12);
    const TestResult permutation = AndersonDarlingTest(a, b, {PValueMethod::kPermutation});
    EXPECT_EQ(permutation.method, "permutation (B = 9999)");
    EXPECT_NEAR(permutation.p_value, expected, PermutationTolerance(expected, 9999));
  }
}

TEST(AndersonDarling, CompleteSeparation) {
  // The two separated splits are the only ones as extreme (checked by enumeration in Python).
  const TestResult small = AndersonDarlingTest(Sample{1, 2, 3, 4}, Sample{5, 6, 7, 8});
  EXPECT_EQ(small.method, "exact");
  EXPECT_NEAR(small.p_value, 2.0 / 70.0, 1e-15);
  Sample a, b;
  for (int i = 0; i < 10; ++i) {
    a.push_back(i);
    b.push_back(20 + i);
  }
  const TestResult large = AndersonDarlingTest(a, b);  // C(20, 10) > B + 1: permutations
  EXPECT_EQ(large.method, "permutation (B = 9999)");
  EXPECT_LE(large.p_value, 3.0 / 10000.0);
  EXPECT_GE(large.p_value, 1.0 / 10000.0);
}

TEST(AndersonDarling, SymmetricAndInvariantUnderMonotoneTransforms) {
  std::mt19937_64 rng(23);
  const Sample a = Uniforms(rng, 12), b = Uniforms(rng, 15, 0.2);
  const TestResult r = AndersonDarlingTest(a, b);
  const TestResult swapped = AndersonDarlingTest(b, a);
  EXPECT_EQ(swapped.statistic, r.statistic);
  EXPECT_EQ(swapped.p_value, r.p_value);
  for (auto transform :
       {+[](double x) { return std::exp(x); }, +[](double x) { return 3 * x * x * x - 1; }}) {
    Sample ta = a, tb = b;
    for (double& v : ta) v = transform(v);
    for (double& v : tb) v = transform(v);
    const TestResult t = AndersonDarlingTest(ta, tb);
    EXPECT_EQ(t.statistic, r.statistic);
    EXPECT_EQ(t.p_value, r.p_value);
    EXPECT_EQ(KolmogorovSmirnovTest(ta, tb).p_value, KolmogorovSmirnovTest(a, b).p_value);
  }
}

TEST(AndersonDarling, DegenerateSamples) {
  const TestResult empty = AndersonDarlingTest(Sample{1}, Sample{});
  EXPECT_TRUE(std::isnan(empty.p_value));
  EXPECT_NE(empty.method.find("empty"), std::string::npos);
  const TestResult same = AndersonDarlingTest(Sample{4, 4}, Sample{4, 4, 4});
  EXPECT_EQ(same.statistic, 0.0);
  EXPECT_EQ(same.p_value, 1.0);
  EXPECT_THROW(AndersonDarlingTest(Sample{1}, Sample{2}, {PValueMethod::kAsymptotic}),
               std::invalid_argument);
  EXPECT_THROW(AndersonDarlingStatistic(Sample{NAN}, Sample{2}), std::invalid_argument);
}

TEST(AndersonDarling, NullRejectionRateWithinBinomialBand) {
  // With continuous data and B = 199, P(p <= 0.05) = 10 / 200 = 0.05 exactly.
  const int trials = 2000;
  std::mt19937_64 rng(7);
  PValueOptions options;
  options.permutations = 199;
  int rejected = 0;
  for (int t = 0; t < trials; ++t) {
    options.seed = t;
    rejected += AndersonDarlingTest(Uniforms(rng, 15), Uniforms(rng, 15), options).p_value <= 0.05;
  }
  const auto [lo, hi] = BinomialBand(trials, 0.05, 0.999);
  EXPECT_GE(rejected, lo);
  EXPECT_LE(rejected, hi);
}

TEST(Power, RejectionRateGrowsWithTheShift) {
  const int trials = 200, n = 25;
  PValueOptions options;
  options.permutations = 199;
  std::vector<double> ks_rate, ad_rate;
  for (double shift : {0.0, 0.15, 0.3, 0.5}) {
    std::mt19937_64 rng(99);  // the same base samples for every shift
    int ks = 0, ad = 0;
    for (int t = 0; t < trials; ++t) {
      const Sample a = Uniforms(rng, n), b = Uniforms(rng, n, shift);
      ks += KolmogorovSmirnovTest(a, b).p_value <= 0.05;
      ad += AndersonDarlingTest(a, b, options).p_value <= 0.05;
    }
    ks_rate.push_back(static_cast<double>(ks) / trials);
    ad_rate.push_back(static_cast<double>(ad) / trials);
  }
  for (size_t i = 1; i < ks_rate.size(); ++i) {
    EXPECT_GT(ks_rate[i], ks_rate[i - 1]) << "shift index " << i;
    EXPECT_GT(ad_rate[i], ad_rate[i - 1]) << "shift index " << i;
  }
  EXPECT_LT(ks_rate.front(), 0.1);
  EXPECT_LT(ad_rate.front(), 0.1);
  EXPECT_GT(ks_rate.back(), 0.95);
  EXPECT_GT(ad_rate.back(), 0.95);
}

TEST(Permutation, SameInputSameBytes) {
  std::mt19937_64 rng(1);
  Sample a = Uniforms(rng, 30), b = Uniforms(rng, 30, 0.1);
  for (double& v : a) v = std::round(v * 10);
  for (double& v : b) v = std::round(v * 10);
  for (int pass = 0; pass < 2; ++pass) {
    auto run = [&](std::uint64_t seed) {
      PValueOptions options{PValueMethod::kPermutation, 999, seed};
      return pass == 0 ? KolmogorovSmirnovTest(a, b, options).p_value
                       : AndersonDarlingTest(a, b, options).p_value;
    };
    const double first = run(kDefaultSeed), second = run(kDefaultSeed);
    EXPECT_EQ(std::memcmp(&first, &second, sizeof first), 0);
    bool seed_matters = false;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) seed_matters |= run(seed) != first;
    EXPECT_TRUE(seed_matters);
  }
}

TEST(Random, UniformDrawsFromTheRawOutput) {
  std::mt19937_64 rng(42), copy(42);
  EXPECT_EQ(UniformBelow(rng, 1), 0u);
  copy();
  EXPECT_EQ(UniformBelow(rng, 1000), UniformBelow(copy, 1000));
  int counts[3] = {0, 0, 0};
  const int draws = 30000;
  for (int i = 0; i < draws; ++i) ++counts[UniformBelow(rng, 3)];
  for (int c : counts) EXPECT_NEAR(c, draws / 3.0, 4.5 * std::sqrt(draws * (2.0 / 9.0)));
  std::mt19937_64 raw(9), unit(9);
  for (int i = 0; i < 100; ++i) {
    const double u = UniformUnit(unit);
    EXPECT_EQ(u, std::ldexp(static_cast<double>(raw() >> 11), -53));
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
  }
  EXPECT_THROW(UniformBelow(rng, 0), std::invalid_argument);
}

// --- Counts ----------------------------------------------------------------------------------

TEST(Fisher, LadyTastingTea) {
  // [[3, 1], [1, 3]]: hypergeometric counts 1, 16, 36, 16, 1 of C(8, 4) = 70 tables.
  const TestResult two_sided = FisherExactTest(3, 1, 1, 3);
  EXPECT_NEAR(two_sided.p_value, 34.0 / 70.0, 1e-12);  // 0.4857
  EXPECT_NEAR(two_sided.statistic, 16.0 / 70.0, 1e-12);
  EXPECT_EQ(two_sided.method, "exact");
  EXPECT_EQ(two_sided.n_a, 4);
  EXPECT_EQ(two_sided.n_b, 4);
  EXPECT_NEAR(FisherExactTest(3, 1, 1, 3, Alternative::kGreater).p_value, 17.0 / 70.0,
              1e-12);  // 0.2429
  EXPECT_NEAR(FisherExactTest(3, 1, 1, 3, Alternative::kLess).p_value, 69.0 / 70.0, 1e-12);
}

TEST(Fisher, TwoByTwoByTheHypergeometricFormula) {
  // [[2, 5], [7, 1]]: rows 7, 8; columns 9, 6; N = 15. P(X = x) = C(9, x) C(6, 7 - x) / C(15, 7)
  // for x = 1..7: 9, 216, 1260, 2520, 1890, 504, 36 out of 6435.
  const TestResult r = FisherExactTest(2, 5, 7, 1);
  EXPECT_NEAR(r.statistic, 216.0 / 6435.0, 1e-14);
  EXPECT_NEAR(r.p_value, (9.0 + 216.0 + 36.0) / 6435.0, 1e-14);
  EXPECT_NEAR(FisherExactTest(2, 5, 7, 1, Alternative::kLess).p_value, 225.0 / 6435.0, 1e-14);
  EXPECT_NEAR(FisherExactTest(2, 5, 7, 1, Alternative::kGreater).p_value, 6426.0 / 6435.0, 1e-14);
  // The transposed table has the same conditional distribution.
  EXPECT_NEAR(FisherExactTest(2, 7, 5, 1).p_value, r.p_value, 1e-14);
}

TEST(Fisher, TwoByKMatchesEnumerationOfAllSubsets) {
  // Freeman-Halton: over all C(N, n_a) ways to choose which runs form sample a, the fraction
  // whose table has no more ways (is no more likely) than the observed one.
  auto by_enumeration = [](const std::vector<int>& row_a, const std::vector<int>& row_b) {
    std::vector<int> category;  // the category of each of the N runs
    int n_a = 0;
    for (size_t j = 0; j < row_a.size(); ++j) {
      category.insert(category.end(), row_a[j] + row_b[j], static_cast<int>(j));
      n_a += row_a[j];
    }
    const int n = static_cast<int>(category.size());
    std::vector<std::vector<int>> tables;
    ForEachSubset(n, n_a, [&](unsigned mask) {
      std::vector<int> row(row_a.size(), 0);
      for (int i = 0; i < n; ++i) row[category[i]] += (mask >> i) & 1u;
      tables.push_back(row);
    });
    auto ways = [&](const std::vector<int>& row) {
      return static_cast<double>(std::count(tables.begin(), tables.end(), row));
    };
    const double observed = ways(row_a);
    double at_most = 0;
    for (const auto& t : tables) at_most += ways(t) <= observed;
    return at_most / static_cast<double>(tables.size());
  };
  const std::vector<std::pair<std::vector<int>, std::vector<int>>> cases = {
      {{3, 0, 2}, {1, 4, 1}}, {{2, 2, 2}, {0, 3, 5}}, {{5, 1, 0}, {1, 3, 2}}, {{4, 1}, {1, 6}}};
  for (const auto& [row_a, row_b] : cases) {
    const TestResult r = FisherExactTest(row_a, row_b);
    EXPECT_NEAR(r.p_value, by_enumeration(row_a, row_b), 1e-12);
    EXPECT_EQ(r.method, "exact");
  }
  // k = 2 is the 2x2 test; empty categories change nothing.
  const int a2[] = {2, 5}, b2[] = {7, 1};
  EXPECT_NEAR(FisherExactTest(a2, b2).p_value, FisherExactTest(2, 5, 7, 1).p_value, 1e-14);
  const int a3[] = {2, 0, 5}, b3[] = {7, 0, 1};
  EXPECT_NEAR(FisherExactTest(a3, b3).p_value, FisherExactTest(2, 5, 7, 1).p_value, 1e-14);
}

TEST(Fisher, DegenerateTables) {
  EXPECT_TRUE(std::isnan(FisherExactTest(0, 0, 3, 4).p_value));
  const int a[] = {0, 0, 0}, b[] = {1, 2, 3};
  EXPECT_TRUE(std::isnan(FisherExactTest(a, b).p_value));
  const int one_category_a[] = {5, 0}, one_category_b[] = {7, 0};
  EXPECT_EQ(FisherExactTest(one_category_a, one_category_b).p_value, 1.0);
  EXPECT_THROW(FisherExactTest(-1, 2, 3, 4), std::invalid_argument);
  const int short_row[] = {1};
  EXPECT_THROW(FisherExactTest(short_row, b), std::invalid_argument);
}

TEST(Binomial, ClosedFormsAndPublishedExample) {
  EXPECT_NEAR(BinomialTest(0, 10, 0.5).p_value, 2.0 / 1024.0, 1e-15);
  EXPECT_NEAR(BinomialTest(5, 10, 0.5).p_value, 1.0, 1e-12);
  EXPECT_NEAR(BinomialTest(8, 10, 0.5, Alternative::kGreater).p_value, 56.0 / 1024.0, 1e-15);
  EXPECT_NEAR(BinomialTest(2, 10, 0.5, Alternative::kLess).p_value, 56.0 / 1024.0, 1e-15);
  // n = 5, p = 0.3: P(4) = 5 0.3^4 0.7 = 0.02835 and P(5) = 0.00243 are the only outcomes no
  // more likely than 4 (P(0..3) = 0.16807, 0.36015, 0.3087, 0.1323).
  EXPECT_NEAR(BinomialTest(4, 5, 0.3).p_value, 0.02835 + 0.00243, 1e-12);
  // Conover (1971), R's binom.test example: 682 giant of 925 plants, p = 3/4: p-value 0.3825.
  const TestResult mendel = BinomialTest(682, 925, 0.75);
  EXPECT_NEAR(mendel.p_value, 0.3825, 5e-5);
  EXPECT_EQ(mendel.statistic, 682.0);
  EXPECT_EQ(mendel.n_a, 925);
  EXPECT_TRUE(std::isnan(BinomialTest(0, 0, 0.5).p_value));
  EXPECT_EQ(BinomialTest(0, 4, 0.0).p_value, 1.0);
  EXPECT_EQ(BinomialTest(1, 4, 0.0).p_value, 0.0);
  EXPECT_THROW(BinomialTest(3, 2, 0.5), std::invalid_argument);
  EXPECT_THROW(BinomialTest(1, 2, 1.5), std::invalid_argument);
}

// --- Multiple comparisons and summaries --------------------------------------------------------

TEST(Holm, HandExample) {
  // Sorted: 0.005 x 4 = 0.02, 0.01 x 3 = 0.03, 0.03 x 2 = 0.06, 0.04 x 1 = 0.04 -> 0.06.
  const double p[] = {0.01, 0.04, 0.03, 0.005};
  const std::vector<double> adjusted = HolmAdjust(p);
  ASSERT_EQ(adjusted.size(), 4u);
  EXPECT_NEAR(adjusted[0], 0.03, 1e-15);
  EXPECT_NEAR(adjusted[1], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[2], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[3], 0.02, 1e-15);
  const double with_nan[] = {0.01, NAN, 0.02};  // m = 2
  const std::vector<double> b = HolmAdjust(with_nan);
  EXPECT_NEAR(b[0], 0.02, 1e-15);
  EXPECT_TRUE(std::isnan(b[1]));
  EXPECT_NEAR(b[2], 0.02, 1e-15);
  const double large[] = {0.5, 0.6};
  EXPECT_EQ(HolmAdjust(large), (std::vector<double>{1.0, 1.0}));
  EXPECT_TRUE(HolmAdjust(std::span<const double>{}).empty());
  const double bad[] = {1.5};
  EXPECT_THROW(HolmAdjust(bad), std::invalid_argument);
}

TEST(Summary, MeanMedianQuantile) {
  const Sample four{4, 1, 3, 2};
  EXPECT_EQ(Mean(four), 2.5);
  EXPECT_EQ(Median(four), 2.5);
  EXPECT_EQ(Median(Sample{5, 1, 3}), 3.0);
  EXPECT_DOUBLE_EQ(Quantile(four, 0.25), 1.75);  // R: quantile(1:4, 0.25)
  EXPECT_EQ(Quantile(four, 0.0), 1.0);
  EXPECT_EQ(Quantile(four, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(Quantile(Sample{1, 2, 3, 4, 10}, 0.9), 7.6);  // h = 3.6: 4 + 0.6 (10 - 4)
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Median(Sample{1, inf, inf}), inf);
  EXPECT_TRUE(std::isnan(Mean(Sample{})));
  EXPECT_TRUE(std::isnan(Median(Sample{})));
  EXPECT_THROW(Quantile(four, 1.5), std::invalid_argument);
  EXPECT_THROW(Median(Sample{1, NAN}), std::invalid_argument);
}

// The verdict's family grows with the stack (issue 23): per block a peak, its time, an RMS and a
// residual, then the overturning: 4 N + 1 hypotheses (25 at N = 6, 257 at N = 64). Holm over
// them multiplies the smallest p-value by the family's size, and the others by their rank's
// complement, never above 1 (exactly: products of small integers and decimal p-values, to
// rounding 1e-15).
TEST(Holm, FamilyOfAStackOfSixBlocks) {
  for (const int blocks : {3, 6, 64}) {
    const int m = 4 * blocks + 1;
    std::vector<double> p(m, 0.5);
    p[m / 2] = 0.001;  // one quantity of one block differs
    p[0] = 0.01;
    const std::vector<double> adjusted = HolmAdjust(p);
    ASSERT_EQ(static_cast<int>(adjusted.size()), m);
    EXPECT_NEAR(adjusted[m / 2], std::min(1.0, m * 0.001), 1e-15) << blocks;
    EXPECT_NEAR(adjusted[0], std::min(1.0, (m - 1) * 0.01), 1e-15) << blocks;
    for (int k = 1; k < m; ++k) {
      if (k != m / 2) {
        EXPECT_EQ(adjusted[k], 1.0) << blocks << " " << k;
      }
    }
    // At alpha = 0.05 one differing quantity in 3 blocks' family (13) is found, in 6 blocks'
    // (25) too, in 64 blocks' (257) not: the price of testing every block.
    EXPECT_EQ(adjusted[m / 2] <= 0.05, blocks <= 6) << blocks;
  }
}

}  // namespace
}  // namespace rockbench::stats
