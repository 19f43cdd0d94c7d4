// The lognormal fragility fit: the two-level design where the maximum-likelihood fit passes
// through both observed fractions exactly; a large sample from a known curve recovered within
// four standard errors of the Fisher information; degenerate data said so; a bootstrap interval
// that covers the truth; the same bytes from the same input.
#include "study/fragility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/normal_cdf.h"

namespace rockbench::stats {
namespace {

using testing_util::Phi;
using testing_util::PhiInverse;

std::vector<FragilityPoint> Level(double im, int n, int failed) {
  std::vector<FragilityPoint> out;
  for (int i = 0; i < n; ++i) out.push_back({im, i < failed});
  return out;
}

TEST(Fragility, TwoLevelsAreFittedExactly) {
  // With members at two IM levels only, the two-parameter curve can pass through both observed
  // fractions, and the binomial likelihood is largest when it does: Phi((ln x_k - ln m) / b) =
  // p_k, so b = (ln x2 - ln x1) / (z2 - z1), ln m = ln x1 - b z1 with z_k = Phi^-1(p_k).
  std::vector<FragilityPoint> pts = Level(0.2, 10, 3);
  for (const auto& p : Level(0.6, 10, 8)) pts.push_back(p);
  const LognormalFragility fit = FitLognormalFragility(pts, 0);
  ASSERT_TRUE(fit.available) << fit.reason;
  const double z1 = PhiInverse(0.3), z2 = PhiInverse(0.8);
  const double beta = (std::log(0.6) - std::log(0.2)) / (z2 - z1);
  const double median = std::exp(std::log(0.2) - beta * z1);
  // The optimiser stops at a gradient of 1e-9 per member: parameters to ~1e-8.
  EXPECT_NEAR(fit.beta, beta, 1e-6);
  EXPECT_NEAR(fit.median, median, 1e-6);
  EXPECT_NEAR(FragilityAt(fit, 0.2), 0.3, 1e-6);
  EXPECT_NEAR(FragilityAt(fit, 0.6), 0.8, 1e-6);
  EXPECT_EQ(fit.n, 20);
  EXPECT_EQ(fit.failures, 11);
  // The log-likelihood at the fit: sum of n_k [p_k ln p_k + (1 - p_k) ln(1 - p_k)].
  const double ll = 10 * (0.3 * std::log(0.3) + 0.7 * std::log(0.7)) +
                    10 * (0.8 * std::log(0.8) + 0.2 * std::log(0.2));
  EXPECT_NEAR(fit.log_likelihood, ll, 1e-9);
}

TEST(Fragility, RecoversAKnownCurveWithinItsStandardErrors) {
  // 1000 members, IM log-uniform over [0.05, 3], each failing with Phi(ln(x / 0.4) / 0.5).
  const double median = 0.4, beta = 0.5;
  std::mt19937_64 rng(11);
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<FragilityPoint> pts;
  for (int i = 0; i < 1000; ++i) {
    const double x = 0.05 * std::pow(3.0 / 0.05, uniform());
    pts.push_back({x, uniform() < Phi(std::log(x / median) / beta)});
  }
  const LognormalFragility fit = FitLognormalFragility(pts, 200, 5);
  ASSERT_TRUE(fit.available) << fit.reason;
  // The Fisher information of (ln m, b) for this design: sum of phi^2 / (Phi Q) grad z grad z',
  // z = (ln x - ln m) / b, dz/d ln m = -1 / b, dz/db = -z / b.
  double i11 = 0, i12 = 0, i22 = 0;
  for (const auto& p : pts) {
    const double z = std::log(p.im / median) / beta;
    const double phi = std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI);
    const double w = phi * phi / (Phi(z) * Phi(-z));
    i11 += w / (beta * beta);
    i12 += w * z / (beta * beta);
    i22 += w * z * z / (beta * beta);
  }
  const double det = i11 * i22 - i12 * i12;
  const double se_ln_median = std::sqrt(i22 / det), se_beta = std::sqrt(i11 / det);
  EXPECT_LT(std::abs(std::log(fit.median / median)), 4 * se_ln_median)
      << fit.median << " (SE of ln median " << se_ln_median << ")";
  EXPECT_LT(std::abs(fit.beta - beta), 4 * se_beta) << fit.beta << " (SE " << se_beta << ")";
  // The 95% bootstrap intervals hold the fit, and their widths are those of the asymptotic
  // normal intervals (2 x 1.96 SE) to within a factor 1.5 (200 resamples).
  EXPECT_EQ(fit.bootstrap, 200);
  EXPECT_EQ(fit.bootstrap_degenerate, 0);
  EXPECT_LT(fit.median_lo, fit.median);
  EXPECT_GT(fit.median_hi, fit.median);
  EXPECT_LT(fit.beta_lo, fit.beta);
  EXPECT_GT(fit.beta_hi, fit.beta);
  const double width_ln = std::log(fit.median_hi / fit.median_lo);
  EXPECT_GT(width_ln, 3.92 * se_ln_median / 1.5);
  EXPECT_LT(width_ln, 3.92 * se_ln_median * 1.5);
  const double width_beta = fit.beta_hi - fit.beta_lo;
  EXPECT_GT(width_beta, 3.92 * se_beta / 1.5);
  EXPECT_LT(width_beta, 3.92 * se_beta * 1.5);
  // Deterministic.
  const LognormalFragility again = FitLognormalFragility(pts, 200, 5);
  EXPECT_EQ(again.median, fit.median);
  EXPECT_EQ(again.median_lo, fit.median_lo);
  EXPECT_EQ(again.beta_hi, fit.beta_hi);
}

TEST(Fragility, DegenerateDataAreSaidSo) {
  EXPECT_EQ(FitLognormalFragility(Level(0.3, 5, 0), 0).reason, "no member failed");
  EXPECT_EQ(FitLognormalFragility(Level(0.3, 5, 5), 0).reason, "every member failed");
  std::vector<FragilityPoint> separated = Level(0.2, 5, 0);
  for (const auto& p : Level(0.5, 5, 5)) separated.push_back(p);
  const LognormalFragility s = FitLognormalFragility(separated, 0);
  EXPECT_FALSE(s.available);
  EXPECT_NE(s.reason.find("separated"), std::string::npos) << s.reason;
  EXPECT_NE(s.reason.find("between 0.2 and 0.5"), std::string::npos) << s.reason;
  EXPECT_TRUE(std::isnan(FragilityAt(s, 0.3)));
  EXPECT_THROW(FitLognormalFragility(std::vector<FragilityPoint>{{0.0, true}}, 0),
               std::invalid_argument);
  EXPECT_THROW(FitLognormalFragility(Level(0.3, 5, 2), 10, 1, 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace rockbench::stats
