#include "statistics/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace rockbench::stats {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Relative tolerance on "no more likely than the observed" (R's fisher.test and binom.test).
constexpr double kRelativeTolerance = 1e-7;
/// Most relabellings AndersonDarlingTest enumerates when asked for an exact p-value.
constexpr std::uint64_t kAndersonDarlingExactMaxSplits = 10'000'000;
/// Most tables the Fisher-Freeman-Halton test enumerates.
constexpr double kFreemanHaltonMaxTables = 1e9;

void RequireNoNaN(std::span<const double> values, const char* where) {
  for (double v : values) {
    if (std::isnan(v)) throw std::invalid_argument(std::string(where) + ": NaN in a sample");
  }
}

/// log k! for k = 0..n, by compensated (Neumaier) summation of log k: deterministic, thread-safe
/// (no lgamma and its global signgam) and accurate to a few ulps of log n!.
std::vector<double> LogFactorials(int n) {
  std::vector<double> lf(static_cast<size_t>(n) + 1, 0.0);
  double sum = 0.0, compensation = 0.0;
  for (int k = 2; k <= n; ++k) {
    const double term = std::log(static_cast<double>(k));
    const double t = sum + term;
    compensation += std::abs(sum) >= std::abs(term) ? (sum - t) + term : (term - t) + sum;
    sum = t;
    lf[static_cast<size_t>(k)] = sum + compensation;
  }
  return lf;
}

std::int64_t Abs(std::int64_t x) {
  return x < 0 ? -x : x;
}

double LogChoose(const std::vector<double>& lf, int n, int k) {
  return lf[n] - lf[k] - lf[n - k];
}

// p-value of an exact test on a discrete statistic with support [lo, hi] and log-pmf log_pmf,
// observed at `observed_x`: the probability of the outcomes at least as extreme (greater: x >=
// observed_x; less: x <= observed_x; two-sided: no more probable than the observed one, to a
// relative tolerance), capped at 1.
template <typename LogPmf>
double ExactPValue(int lo, int hi, int observed_x, const LogPmf& log_pmf, Alternative alternative) {
  const double observed = log_pmf(observed_x);
  double p = 0.0;
  for (int x = lo; x <= hi; ++x) {
    const double lp = log_pmf(x);
    const bool counted = alternative == Alternative::kGreater ? x >= observed_x
                         : alternative == Alternative::kLess
                             ? x <= observed_x
                             : lp <= observed + std::log1p(kRelativeTolerance);
    if (counted) p += std::exp(lp);
  }
  return std::min(p, 1.0);
}

/// C(n, k), or cap + 1 if it exceeds cap (cap <= 2^40 keeps every product exact in 64 bits).
std::uint64_t ChooseCapped(int n, int k, std::uint64_t cap) {
  k = std::min(k, n - k);
  std::uint64_t c = 1;
  for (int i = 1; i <= k; ++i) {
    c = c * static_cast<std::uint64_t>(n - k + i) / static_cast<std::uint64_t>(i);
    if (c > cap) return cap + 1;
  }
  return c;
}

std::string PermutationMethod(int permutations) {
  return "permutation (B = " + std::to_string(permutations) + ")";
}

void Shuffle(std::vector<int>& labels, std::mt19937_64& rng) {
  for (size_t i = labels.size(); i-- > 1;) {
    std::swap(labels[i], labels[UniformBelow(rng, i + 1)]);
  }
}

/// Permutation p-value (1 + #{relabellings at least as extreme}) / (1 + B) over B random
/// relabellings of `labels` (seeded by options.seed); `at_least_observed(labels)` says whether
/// a relabelling's statistic reaches the observed one.
template <class AtLeastObserved>
double PermutationPValue(std::vector<int> labels, const PValueOptions& options,
                         AtLeastObserved at_least_observed) {
  std::mt19937_64 rng(options.seed);
  long long at_least = 0;
  for (int k = 0; k < options.permutations; ++k) {
    Shuffle(labels, rng);
    if (at_least_observed(labels)) ++at_least;
  }
  return (1.0 + at_least) / (1.0 + options.permutations);
}

/// A two-sample test's result with its name and sizes, after checking both samples for NaN
/// (std::invalid_argument naming `where`). False when either sample is empty: the result then
/// says the test is undefined.
bool StartTwoSampleTest(std::span<const double> a, std::span<const double> b, const char* where,
                        const char* test, TestResult* r) {
  RequireNoNaN(a, where);
  RequireNoNaN(b, where);
  r->test = test;
  r->n_a = static_cast<int>(a.size());
  r->n_b = static_cast<int>(b.size());
  if (a.empty() || b.empty()) {
    r->method = "undefined: empty sample";
    return false;
  }
  return true;
}

/// The pooled sample sorted by value then by sample, as sample labels, with its groups of equal
/// values (in increasing order of value).
struct Pooled {
  std::vector<int> labels;
  std::vector<int> group_sizes;
  /// group_end[s] for s = 0..N: the first s pooled values end a group (the ECDFs are evaluated).
  std::vector<char> group_end;
  int size = 0;
  bool ties = false;
};

Pooled Pool(std::span<const std::span<const double>> samples) {
  std::vector<std::pair<double, int>> pooled;
  for (size_t i = 0; i < samples.size(); ++i) {
    for (double v : samples[i]) pooled.emplace_back(v, static_cast<int>(i));
  }
  std::sort(pooled.begin(), pooled.end());
  Pooled p;
  p.size = static_cast<int>(pooled.size());
  p.group_end.assign(pooled.size() + 1, 0);
  p.labels.reserve(pooled.size());
  int run = 0;
  for (size_t s = 0; s < pooled.size(); ++s) {
    p.labels.push_back(pooled[s].second);
    ++run;
    if (s + 1 == pooled.size() || pooled[s + 1].first != pooled[s].first) {
      p.group_end[s + 1] = 1;
      p.group_sizes.push_back(run);
      p.ties = p.ties || run > 1;
      run = 0;
    }
  }
  return p;
}

// --- Kolmogorov-Smirnov ----------------------------------------------------------------------

/// D n_a n_b = max over the group ends of |i n_b - j n_a|, i and j the counts of sample 0 and 1.
std::int64_t KsScaledStatistic(const std::vector<int>& labels, const std::vector<char>& group_end,
                               std::int64_t n_a, std::int64_t n_b) {
  std::int64_t i = 0, j = 0, d = 0;
  for (size_t s = 0; s < labels.size(); ++s) {
    (labels[s] == 0 ? i : j) += 1;
    if (group_end[s + 1]) d = std::max(d, Abs(i * n_b - j * n_a));
  }
  return d;
}

/// P(D* n_a n_b >= d) over the C(N, n_a) equally likely monotone paths from (0, 0) to (n_a, n_b),
/// D* checked only where a group of equal values ends. a(i, j) is the number of paths reaching
/// (i, j) without having touched the boundary, divided by C(i + j, i), so that
/// a(i, j) = (i a(i-1, j) + j a(i, j-1)) / (i + j) stays in [0, 1]. A path's first contact at
/// (i, j) has probability a(i, j) C(i + j, i) C(N - i - j, n_a - i) / C(N, n_a).
double KsExactPValue(const std::vector<char>& group_end, int n_a, int n_b, std::int64_t d) {
  const int n = n_a + n_b;
  const std::vector<double> lf = LogFactorials(n);
  const double log_total = LogChoose(lf, n, n_a);
  std::vector<double> a(static_cast<size_t>(n_b) + 1, 0.0);
  double p = 0.0;
  for (int i = 0; i <= n_a; ++i) {
    for (int j = 0; j <= n_b; ++j) {
      double v = 1.0;
      if (i + j > 0) {
        const double up = i > 0 ? a[j] * i : 0.0;
        const double left = j > 0 ? a[j - 1] * j : 0.0;
        v = (up + left) / (i + j);
      }
      if (v > 0.0 && group_end[i + j] &&
          Abs(static_cast<std::int64_t>(i) * n_b - static_cast<std::int64_t>(j) * n_a) >= d) {
        p += v * std::exp(LogChoose(lf, i + j, i) + LogChoose(lf, n - i - j, n_a - i) - log_total);
        v = 0.0;
      }
      a[j] = v;
    }
  }
  return std::min(p, 1.0);
}

/// D_slack n_a n_b for labels over the sorted pooled values; `upper[s]` = the number of pooled
/// values <= (value s) + slack, `group_end` as in Pool.
std::int64_t KsSlackScaledStatistic(const std::vector<int>& labels,
                                    const std::vector<char>& group_end,
                                    const std::vector<int>& upper, std::int64_t n_a,
                                    std::int64_t n_b, std::vector<std::int64_t>& count_a) {
  const size_t n = labels.size();
  count_a.assign(n + 1, 0);
  for (size_t s = 0; s < n; ++s) count_a[s + 1] = count_a[s] + (labels[s] == 0 ? 1 : 0);
  std::int64_t d = 0;
  for (size_t s = 0; s < n; ++s) {
    if (!group_end[s + 1]) continue;
    const std::int64_t a_at = count_a[s + 1], b_at = static_cast<std::int64_t>(s + 1) - a_at;
    const int u = upper[s];
    const std::int64_t a_up = count_a[u], b_up = u - a_up;
    d = std::max({d, b_at * n_a - a_up * n_b, a_at * n_b - b_up * n_a});
  }
  return d;
}

// --- Anderson-Darling ------------------------------------------------------------------------

/// A2akN of labellings of one pooled sample (Scholz & Stephens eq. 7): what does not depend on
/// the labels (B_j and the weight (l_j / N) / (B_j (N - B_j) - N l_j / 4) of each group) is
/// computed once.
class AndersonDarlingOfLabels {
 public:
  AndersonDarlingOfLabels(const Pooled& pooled, std::span<const int> sizes)
      : group_sizes_(pooled.group_sizes),
        sizes_(sizes.begin(), sizes.end()),
        cumulative_(sizes.size()),
        in_group_(sizes.size()),
        n_(pooled.size) {
    int less = 0;
    for (int l : group_sizes_) {
      const double b = less + 0.5 * l;
      b_.push_back(b);
      weight_.push_back(l / n_ / (b * (n_ - b) - n_ * l / 4.0));
      less += l;
    }
  }

  double operator()(const std::vector<int>& labels) {
    if (group_sizes_.size() < 2) return 0.0;  // all values equal (the weights are 0 / 0)
    std::fill(cumulative_.begin(), cumulative_.end(), 0);
    double total = 0.0;
    int position = 0;
    for (size_t j = 0; j < group_sizes_.size(); ++j) {
      std::fill(in_group_.begin(), in_group_.end(), 0);
      for (int t = 0; t < group_sizes_[j]; ++t) ++in_group_[labels[position + t]];
      double inner = 0.0;
      for (size_t i = 0; i < sizes_.size(); ++i) {
        const double m = cumulative_[i] + 0.5 * in_group_[i];
        const double diff = n_ * m - sizes_[i] * b_[j];
        inner += diff * diff / sizes_[i];
        cumulative_[i] += in_group_[i];
      }
      total += weight_[j] * inner;
      position += group_sizes_[j];
    }
    return total * (n_ - 1.0) / n_;
  }

 private:
  std::vector<int> group_sizes_;
  std::vector<int> sizes_;
  std::vector<int> cumulative_, in_group_;  // scratch
  std::vector<double> b_, weight_;
  double n_;
};

bool AnyEmpty(std::span<const std::span<const double>> samples) {
  return std::any_of(samples.begin(), samples.end(), [](auto s) { return s.empty(); });
}

double AndersonDarlingOfSpans(std::span<const std::span<const double>> samples) {
  for (auto s : samples) RequireNoNaN(s, "AndersonDarlingStatistic");
  if (samples.size() < 2 || AnyEmpty(samples)) return kNaN;
  const Pooled pooled = Pool(samples);
  std::vector<int> sizes;
  for (auto s : samples) sizes.push_back(static_cast<int>(s.size()));
  return AndersonDarlingOfLabels(pooled, sizes)(pooled.labels);
}

}  // namespace

std::uint64_t UniformBelow(std::mt19937_64& rng, std::uint64_t bound) {
  if (bound == 0) throw std::invalid_argument("UniformBelow: bound must be >= 1");
  const std::uint64_t threshold = (0 - bound) % bound;  // 2^64 mod bound
  for (;;) {
    const std::uint64_t x = rng();
    if (x >= threshold) return x % bound;
  }
}

double UniformUnit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

BootstrapDraws Bootstrap(
    std::size_t n, int resamples, std::uint64_t seed, std::size_t count,
    const std::function<bool(std::span<const std::size_t>, std::vector<double>&)>& statistics) {
  if (n == 0) throw std::invalid_argument("Bootstrap: no members to draw");
  BootstrapDraws out;
  out.values.resize(count);
  out.resamples = resamples;
  std::mt19937_64 rng(seed);
  std::vector<std::size_t> members(n);
  std::vector<double> values(count);
  for (int k = 0; k < resamples; ++k) {
    for (std::size_t& m : members) m = UniformBelow(rng, n);
    if (!statistics(members, values)) {
      ++out.degenerate;
      continue;
    }
    for (std::size_t q = 0; q < count; ++q) out.values[q].push_back(values[q]);
  }
  for (auto& v : out.values) std::sort(v.begin(), v.end());
  return out;
}

double LowerOrderPercentile(std::span<const double> sorted, double probability) {
  if (sorted.empty()) throw std::invalid_argument("LowerOrderPercentile: no draws");
  return sorted[static_cast<std::size_t>(std::floor(probability * (sorted.size() - 1)))];
}

// --- Kolmogorov-Smirnov ----------------------------------------------------------------------

double KolmogorovSmirnovStatistic(std::span<const double> a, std::span<const double> b) {
  RequireNoNaN(a, "KolmogorovSmirnovStatistic");
  RequireNoNaN(b, "KolmogorovSmirnovStatistic");
  if (a.empty() || b.empty()) return kNaN;
  const std::span<const double> samples[] = {a, b};
  const Pooled pooled = Pool(samples);
  const std::int64_t n_a = static_cast<std::int64_t>(a.size());
  const std::int64_t n_b = static_cast<std::int64_t>(b.size());
  const std::int64_t d = KsScaledStatistic(pooled.labels, pooled.group_end, n_a, n_b);
  return static_cast<double>(d) / (static_cast<double>(n_a) * static_cast<double>(n_b));
}

double KolmogorovSurvival(double lambda) {
  if (std::isnan(lambda)) return kNaN;
  if (lambda <= 0.0) return 1.0;
  constexpr double pi = std::numbers::pi;
  double sum = 0.0;
  if (lambda < 1.18) {
    const double f = -pi * pi / (8.0 * lambda * lambda);
    for (int k = 1; k <= 100; ++k) {
      const double t = std::exp((2.0 * k - 1.0) * (2.0 * k - 1.0) * f);
      sum += t;
      if (t <= 1e-17 * sum) break;
    }
    return std::clamp(1.0 - std::sqrt(2.0 * pi) / lambda * sum, 0.0, 1.0);
  }
  for (int k = 1; k <= 100; ++k) {
    const double t = std::exp(-2.0 * k * k * lambda * lambda);
    sum += k % 2 == 1 ? t : -t;
    if (t <= 1e-17) break;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

TestResult KolmogorovSmirnovTest(std::span<const double> a, std::span<const double> b,
                                 const PValueOptions& options) {
  TestResult r;
  if (!StartTwoSampleTest(a, b, "KolmogorovSmirnovTest", "two-sample Kolmogorov-Smirnov", &r)) {
    return r;
  }
  const std::span<const double> samples[] = {a, b};
  const Pooled pooled = Pool(samples);
  const std::int64_t n_a = r.n_a, n_b = r.n_b;
  const std::int64_t d = KsScaledStatistic(pooled.labels, pooled.group_end, n_a, n_b);
  r.statistic = static_cast<double>(d) / (static_cast<double>(n_a) * static_cast<double>(n_b));

  PValueMethod method = options.method;
  if (method == PValueMethod::kAuto) {
    const std::int64_t cells = n_a * n_b;
    if (cells <= kKolmogorovSmirnovExactMaxCells ||
        (pooled.ties && cells <= kKolmogorovSmirnovExactMaxCellsWithTies)) {
      method = PValueMethod::kExact;
    } else {
      method = pooled.ties ? PValueMethod::kPermutation : PValueMethod::kAsymptotic;
    }
  }
  if (method == PValueMethod::kPermutation && options.permutations < 1) {
    throw std::invalid_argument("KolmogorovSmirnovTest: permutations must be >= 1");
  }
  if (d == 0) {  // every relabelling has D* >= 0
    r.p_value = 1.0;
    r.method = method == PValueMethod::kPermutation  ? PermutationMethod(options.permutations)
               : method == PValueMethod::kAsymptotic ? "asymptotic"
                                                     : "exact";
    return r;
  }
  switch (method) {
    case PValueMethod::kAuto:
    case PValueMethod::kExact:
      r.p_value = KsExactPValue(pooled.group_end, r.n_a, r.n_b, d);
      r.method = "exact";
      break;
    case PValueMethod::kPermutation:
      r.p_value = PermutationPValue(pooled.labels, options, [&](const std::vector<int>& labels) {
        return KsScaledStatistic(labels, pooled.group_end, n_a, n_b) >= d;
      });
      r.method = PermutationMethod(options.permutations);
      break;
    case PValueMethod::kAsymptotic: {
      const double effective = static_cast<double>(n_a) * n_b / static_cast<double>(n_a + n_b);
      r.p_value = KolmogorovSurvival(std::sqrt(effective) * r.statistic);
      r.method = "asymptotic";
      break;
    }
  }
  return r;
}

TestResult KolmogorovSmirnovSlackTest(std::span<const double> a, std::span<const double> b,
                                      double slack, const PValueOptions& options) {
  if (!(slack >= 0.0)) {
    throw std::invalid_argument("KolmogorovSmirnovSlackTest: slack must be >= 0");
  }
  if (slack == 0.0) return KolmogorovSmirnovTest(a, b, options);
  if (options.permutations < 1) {
    throw std::invalid_argument("KolmogorovSmirnovSlackTest: permutations must be >= 1");
  }
  TestResult r;
  if (!StartTwoSampleTest(a, b, "KolmogorovSmirnovSlackTest",
                          "two-sample Kolmogorov-Smirnov with slack", &r)) {
    return r;
  }
  const std::span<const double> samples[] = {a, b};
  const Pooled pooled = Pool(samples);
  std::vector<double> values(a.begin(), a.end());
  values.insert(values.end(), b.begin(), b.end());
  std::sort(values.begin(), values.end());
  std::vector<int> upper(values.size());
  for (size_t s = 0; s < values.size(); ++s) {
    upper[s] = static_cast<int>(std::upper_bound(values.begin(), values.end(), values[s] + slack) -
                                values.begin());
  }
  const std::int64_t n_a = r.n_a, n_b = r.n_b;
  std::vector<std::int64_t> scratch;
  const std::int64_t d =
      KsSlackScaledStatistic(pooled.labels, pooled.group_end, upper, n_a, n_b, scratch);
  r.statistic = static_cast<double>(d) / (static_cast<double>(n_a) * static_cast<double>(n_b));
  r.method = PermutationMethod(options.permutations);
  if (d == 0) {
    r.p_value = 1.0;
    return r;
  }
  r.p_value = PermutationPValue(pooled.labels, options, [&](const std::vector<int>& labels) {
    return KsSlackScaledStatistic(labels, pooled.group_end, upper, n_a, n_b, scratch) >= d;
  });
  return r;
}

// --- Anderson-Darling ------------------------------------------------------------------------

double AndersonDarlingStatistic(std::span<const std::vector<double>> samples) {
  std::vector<std::span<const double>> spans(samples.begin(), samples.end());
  return AndersonDarlingOfSpans(spans);
}

double AndersonDarlingStatistic(std::span<const double> a, std::span<const double> b) {
  const std::span<const double> samples[] = {a, b};
  return AndersonDarlingOfSpans(samples);
}

double AndersonDarlingNullVariance(std::span<const int> sample_sizes) {
  const int k = static_cast<int>(sample_sizes.size());
  int total = 0;
  double big_h = 0.0;  // H = sum 1 / n_i
  for (int n : sample_sizes) {
    if (n < 1) throw std::invalid_argument("AndersonDarlingNullVariance: empty sample");
    total += n;
    big_h += 1.0 / n;
  }
  if (k < 2 || total < 4) {
    throw std::invalid_argument("AndersonDarlingNullVariance: needs k >= 2 and N >= 4");
  }
  const double n = total;
  // h = sum_{i=1}^{N-1} 1/i; g = sum_{i=1}^{N-2} sum_{j=i+1}^{N-1} 1 / ((N - i) j)
  //   = sum_{i=1}^{N-2} (h - H_i) / (N - i), H_i the i-th harmonic number.
  double h = 0.0;
  for (int i = 1; i <= total - 1; ++i) h += 1.0 / i;
  double g = 0.0, harmonic_i = 0.0;
  for (int i = 1; i <= total - 2; ++i) {
    harmonic_i += 1.0 / i;
    g += (h - harmonic_i) / (total - i);
  }
  const double kk = k;
  const double a = (4 * g - 6) * (kk - 1) + (10 - 6 * g) * big_h;
  const double b =
      (2 * g - 4) * kk * kk + 8 * h * kk + (2 * g - 14 * h - 4) * big_h - 8 * h + 4 * g - 6;
  const double c =
      (6 * h + 2 * g - 2) * kk * kk + (4 * h - 4 * g + 6) * kk + (2 * h - 6) * big_h + 4 * h;
  const double d = (2 * h + 6) * kk * kk - 4 * h * kk;
  return (a * n * n * n + b * n * n + c * n + d) / ((n - 1) * (n - 2) * (n - 3));
}

TestResult AndersonDarlingTest(std::span<const double> a, std::span<const double> b,
                               const PValueOptions& options) {
  TestResult r;
  if (!StartTwoSampleTest(a, b, "AndersonDarlingTest", "two-sample Anderson-Darling (A2akN)", &r)) {
    return r;
  }
  if (options.method == PValueMethod::kAsymptotic) {
    throw std::invalid_argument("AndersonDarlingTest: no asymptotic p-value (use kAuto)");
  }
  if (options.permutations < 1) {
    throw std::invalid_argument("AndersonDarlingTest: permutations must be >= 1");
  }
  const std::span<const double> samples[] = {a, b};
  const Pooled pooled = Pool(samples);
  const int sizes[] = {r.n_a, r.n_b};
  AndersonDarlingOfLabels statistic(pooled, sizes);
  r.statistic = statistic(pooled.labels);
  const double floor = r.statistic - 1e-12 * std::max(1.0, r.statistic);

  const int n = pooled.size;
  const std::uint64_t budget = options.method == PValueMethod::kExact
                                   ? kAndersonDarlingExactMaxSplits
                                   : static_cast<std::uint64_t>(options.permutations) + 1;
  const std::uint64_t splits = ChooseCapped(n, r.n_a, budget);
  const bool exact = options.method == PValueMethod::kExact ||
                     (options.method == PValueMethod::kAuto && splits <= budget);
  if (exact && splits > budget) {
    throw std::invalid_argument("AndersonDarlingTest: more than 10^7 relabellings to enumerate");
  }
  if (pooled.group_sizes.size() < 2) {  // all values equal: every relabelling gives A* = 0
    r.p_value = 1.0;
    r.method = exact ? "exact" : PermutationMethod(options.permutations);
    return r;
  }
  if (exact) {
    // Every choice of the n_a positions of sample a among the N pooled ones, in lexicographic
    // order of the positions.
    std::vector<int> chosen(static_cast<size_t>(r.n_a));
    for (int i = 0; i < r.n_a; ++i) chosen[i] = i;
    std::vector<int> labels(static_cast<size_t>(n));
    std::uint64_t at_least = 0, count = 0;
    for (;;) {
      std::fill(labels.begin(), labels.end(), 1);
      for (int c : chosen) labels[c] = 0;
      if (statistic(labels) >= floor) {
        ++at_least;
      }
      ++count;
      int i = r.n_a - 1;
      while (i >= 0 && chosen[i] == n - r.n_a + i) --i;
      if (i < 0) break;
      ++chosen[i];
      for (int t = i + 1; t < r.n_a; ++t) chosen[t] = chosen[t - 1] + 1;
    }
    r.p_value = static_cast<double>(at_least) / static_cast<double>(count);
    r.method = "exact";
    return r;
  }
  r.p_value = PermutationPValue(pooled.labels, options, [&](const std::vector<int>& labels) {
    return statistic(labels) >= floor;
  });
  r.method = PermutationMethod(options.permutations);
  return r;
}

// --- Counts ----------------------------------------------------------------------------------

TestResult FisherExactTest(int a11, int a12, int a21, int a22, Alternative alternative) {
  if (a11 < 0 || a12 < 0 || a21 < 0 || a22 < 0) {
    throw std::invalid_argument("FisherExactTest: negative count");
  }
  TestResult r;
  r.test = "Fisher exact";
  r.n_a = a11 + a12;
  r.n_b = a21 + a22;
  if (r.n_a == 0 || r.n_b == 0) {
    r.method = "undefined: empty sample";
    return r;
  }
  const int n = r.n_a + r.n_b, c1 = a11 + a21, c2 = a12 + a22;
  const std::vector<double> lf = LogFactorials(n);
  const double log_total = LogChoose(lf, n, r.n_a);
  auto log_p = [&](int x) {
    return LogChoose(lf, c1, x) + LogChoose(lf, c2, r.n_a - x) - log_total;
  };
  const int lo = std::max(0, r.n_a - c2), hi = std::min(r.n_a, c1);
  r.statistic = std::exp(log_p(a11));
  r.p_value = ExactPValue(lo, hi, a11, log_p, alternative);
  r.method = "exact";
  return r;
}

namespace {

struct FreemanHalton {
  std::vector<std::vector<double>> log_choose;  // [column][x] = log C(c_column, x)
  std::vector<int> totals;                      // column totals
  std::vector<int> capacity_after;              // sum of the totals of the later columns
  double threshold = 0.0;                       // log probability counted if <= this
  double log_total = 0.0;
  double p = 0.0;

  void Enumerate(size_t column, int remaining, double log_p) {
    if (column + 1 == totals.size()) {
      const double lp = log_p + log_choose[column][remaining] - log_total;
      if (lp <= threshold) p += std::exp(lp);
      return;
    }
    const int lo = std::max(0, remaining - capacity_after[column]);
    const int hi = std::min(totals[column], remaining);
    for (int x = lo; x <= hi; ++x) {
      Enumerate(column + 1, remaining - x, log_p + log_choose[column][x]);
    }
  }
};

}  // namespace

TestResult FisherExactTest(std::span<const int> row_a, std::span<const int> row_b) {
  if (row_a.size() != row_b.size()) {
    throw std::invalid_argument("FisherExactTest: rows of different lengths");
  }
  TestResult r;
  r.test = "Fisher-Freeman-Halton exact";
  std::vector<int> columns_a, totals;
  for (size_t j = 0; j < row_a.size(); ++j) {
    if (row_a[j] < 0 || row_b[j] < 0) throw std::invalid_argument("FisherExactTest: negative");
    r.n_a += row_a[j];
    r.n_b += row_b[j];
    if (row_a[j] + row_b[j] > 0) {  // empty categories do not change the test
      columns_a.push_back(row_a[j]);
      totals.push_back(row_a[j] + row_b[j]);
    }
  }
  if (r.n_a == 0 || r.n_b == 0) {
    r.method = "undefined: empty sample";
    return r;
  }
  const int n = r.n_a + r.n_b;
  const std::vector<double> lf = LogFactorials(n);
  FreemanHalton fh;
  fh.totals = totals;
  fh.log_total = LogChoose(lf, n, r.n_a);
  double tables = 1.0;
  double observed = -fh.log_total;
  for (size_t j = 0; j < totals.size(); ++j) {
    std::vector<double> lc(static_cast<size_t>(totals[j]) + 1);
    for (int x = 0; x <= totals[j]; ++x) lc[x] = LogChoose(lf, totals[j], x);
    observed += lc[columns_a[j]];
    fh.log_choose.push_back(std::move(lc));
    if (j + 1 < totals.size()) tables *= std::min(totals[j], r.n_a) + 1.0;
  }
  if (tables > kFreemanHaltonMaxTables) {
    throw std::length_error("FisherExactTest: more than 10^9 tables to enumerate");
  }
  fh.capacity_after.assign(totals.size(), 0);
  for (size_t j = totals.size(); j-- > 1;) {
    fh.capacity_after[j - 1] = fh.capacity_after[j] + totals[j];
  }
  fh.threshold = observed + std::log1p(kRelativeTolerance);
  fh.Enumerate(0, r.n_a, 0.0);
  r.statistic = std::exp(observed);
  r.p_value = std::min(fh.p, 1.0);
  r.method = "exact";
  return r;
}

TestResult BinomialTest(int successes, int trials, double probability, Alternative alternative) {
  if (trials < 0 || successes < 0 || successes > trials) {
    throw std::invalid_argument("BinomialTest: need 0 <= successes <= trials");
  }
  if (!(probability >= 0.0 && probability <= 1.0)) {
    throw std::invalid_argument("BinomialTest: probability outside [0, 1]");
  }
  TestResult r;
  r.test = "exact binomial";
  r.statistic = successes;
  r.n_a = trials;
  r.n_b = 0;
  if (trials == 0) {
    r.method = "undefined: no trials";
    return r;
  }
  const std::vector<double> lf = LogFactorials(trials);
  auto log_pmf = [&](int i) {
    if (probability == 0.0) return i == 0 ? 0.0 : -std::numeric_limits<double>::infinity();
    if (probability == 1.0) return i == trials ? 0.0 : -std::numeric_limits<double>::infinity();
    return LogChoose(lf, trials, i) + i * std::log(probability) +
           (trials - i) * std::log1p(-probability);
  };
  r.p_value = ExactPValue(0, trials, successes, log_pmf, alternative);
  r.method = "exact";
  return r;
}

// --- Multiple comparisons --------------------------------------------------------------------

std::vector<double> HolmAdjust(std::span<const double> p_values) {
  std::vector<size_t> order;
  for (size_t i = 0; i < p_values.size(); ++i) {
    const double p = p_values[i];
    if (std::isnan(p)) continue;
    if (p < 0.0 || p > 1.0) throw std::invalid_argument("HolmAdjust: p-value outside [0, 1]");
    order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return p_values[x] < p_values[y]; });
  std::vector<double> adjusted(p_values.begin(), p_values.end());
  const double m = static_cast<double>(order.size());
  double running = 0.0;
  for (size_t rank = 0; rank < order.size(); ++rank) {
    running = std::max(running, std::min(1.0, (m - rank) * p_values[order[rank]]));
    adjusted[order[rank]] = running;
  }
  return adjusted;
}

// --- Summaries -------------------------------------------------------------------------------

double Mean(std::span<const double> values) {
  RequireNoNaN(values, "Mean");
  if (values.empty()) return kNaN;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double Median(std::span<const double> values) {
  return Quantile(values, 0.5);
}

double Quantile(std::span<const double> values, double probability) {
  RequireNoNaN(values, "Quantile");
  if (!(probability >= 0.0 && probability <= 1.0)) {
    throw std::invalid_argument("Quantile: probability outside [0, 1]");
  }
  if (values.empty()) return kNaN;
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const double h = (static_cast<double>(sorted.size()) - 1.0) * probability;
  const size_t lo = static_cast<size_t>(std::floor(h));
  const double fraction = h - static_cast<double>(lo);
  if (fraction == 0.0 || sorted[lo] == sorted[lo + 1]) return sorted[lo];
  return sorted[lo] + fraction * (sorted[lo + 1] - sorted[lo]);
}

}  // namespace rockbench::stats
