// Synthetic ground motion (kind = "kanai_tajimi"): the sampled process has the target power
// spectral density within its statistical error over many seeds; the discretisation is the
// bilinear transform exactly; the envelope multiplies the stationary record; the record comes
// back to rest (zero end velocity and displacement) with a small correction; the same seed gives
// the same bytes on every machine; the scene reads it and names bad keys.
#include "motion/synthetic_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "scene/scene.h"

namespace rockbench {
namespace {

constexpr double kPi = std::numbers::pi;
// FNV-1a of seed 7 of TheSameSeedGivesTheSameBytesOnEveryMachine's definition with the
// high-pass and the residual correction.
constexpr std::uint64_t kCorrectedHash = 0x2a3db0cbe681e32dull;

// The stationary process alone: no envelope, no high-pass after it, no residual correction.
SyntheticMotionDef Stationary() {
  SyntheticMotionDef d;
  d.high_pass_hz = 0.0;
  d.zero_residuals = false;
  d.intensity_m2ps3 = 0.01;
  d.ground_frequency_hz = 2.5;
  d.ground_damping = 0.6;
  d.envelope = SyntheticEnvelope::kNone;
  d.dt_s = 0.01;
  d.duration_s = 45.0;
  return d;
}

TEST(PortableMath, ExpAndLogWithinTwoUlpsOfTheLibrary) {
  // The library's exp and log are within 1 ulp of the exact value (glibc), ours within 2 of
  // theirs: 3 ulp of the exact value at most.
  std::mt19937_64 rng(3);
  for (int i = 0; i < 20000; ++i) {
    const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double x = -700.0 + 1400.0 * u;
    const double e = std::exp(x);
    EXPECT_LE(std::abs(PortableExp(x) - e), 2.0 * (std::nextafter(e, INFINITY) - e)) << x;
    const double y = std::ldexp(0.5 + u, static_cast<int>(rng() % 200) - 100);
    const double l = std::log(y);
    const double ulp = std::nextafter(std::abs(l), INFINITY) - std::abs(l);
    EXPECT_LE(std::abs(PortableLog(y) - l), 2.0 * ulp) << y;
  }
  EXPECT_EQ(PortableExp(0.0), 1.0);
  EXPECT_EQ(PortableLog(1.0), 0.0);
  EXPECT_EQ(PortableExp(-800.0), 0.0);
  EXPECT_TRUE(std::isinf(PortableLog(0.0)));
}

TEST(SyntheticMotion, TheSampledSpectrumIsTheBilinearTransformOfKanaiTajimiAndCloughPenzien) {
  // The bilinear transform maps the continuous frequency w' = (2 / dt) tan(w dt / 2) to w, so
  // the sampled PSD at w is the continuous one at w', to rounding.
  for (const double filter_hz : {0.0, 0.3}) {
    SyntheticMotionDef d = Stationary();
    d.filter_frequency_hz = filter_hz;
    d.filter_damping = 0.7;
    for (const double high_pass_hz : {0.0, 0.2}) {
      d.high_pass_hz = high_pass_hz;
      for (double f = 0.05; f < 45.0; f *= 1.3) {
        const double w = 2.0 * kPi * f;
        const double warped = 2.0 / d.dt_s * std::tan(0.5 * w * d.dt_s);
        EXPECT_NEAR(SyntheticPsd(d, w), ContinuousKanaiTajimiPsd(d, warped),
                    1e-10 * ContinuousKanaiTajimiPsd(d, warped))
            << filter_hz << " Hz filter, " << high_pass_hz << " Hz high-pass, f " << f;
      }
    }
    d.high_pass_hz = 0.0;
    // The high-pass after the envelope, s^2 / (s + w_c)^2: |H|^2 = 1/4 at w_c, (w / w_c)^4
    // (1 + O(w)) far below it; 1 / (1 + (w_c / w)^2)^2 = 1 - 2 (w_c / w)^2 + ... far above it.
    {
      SyntheticMotionDef hp = d;
      hp.high_pass_hz = 0.2;
      const double wc = 2.0 * kPi * 0.2;
      auto ratio = [&](double w) {
        return ContinuousKanaiTajimiPsd(hp, w) / ContinuousKanaiTajimiPsd(d, w);
      };
      EXPECT_NEAR(ratio(wc), 0.25, 1e-14);
      EXPECT_NEAR(ratio(1e-3 * wc), 1e-12, 1e-14);
      EXPECT_NEAR(ratio(100.0 * wc), 1.0 - 2e-4, 1e-7);
    }
    // Kanai-Tajimi: S0 at w = 0, S0 (1 + 4 z^2) / (4 z^2) at the ground frequency.
    const double wg = 2.0 * kPi * d.ground_frequency_hz, z = d.ground_damping;
    if (filter_hz == 0.0) {
      EXPECT_NEAR(ContinuousKanaiTajimiPsd(d, 0.0), d.intensity_m2ps3, 1e-15);
      EXPECT_NEAR(ContinuousKanaiTajimiPsd(d, wg),
                  d.intensity_m2ps3 * (1 + 4 * z * z) / (4 * z * z), 1e-12);
    } else {
      // Clough-Penzien removes the low frequencies: S = S0 (w / w_f)^4 (1 + O(w^2)) near 0,
      // 1.23e-6 S0 at 0.01 Hz against 0.3 Hz.
      const double ratio = std::pow(0.01 / filter_hz, 4);
      EXPECT_NEAR(SyntheticPsd(d, 2.0 * kPi * 0.01), ratio * d.intensity_m2ps3,
                  0.01 * ratio * d.intensity_m2ps3);
    }
  }
}

// The periodogram estimate dt / (2 pi N) |sum a_n exp(-i w n dt)|^2 at bin k of N samples.
double Periodogram(const std::vector<double>& a, size_t first, size_t n, double dt, int k) {
  const double w = 2.0 * kPi * k / (n * dt);
  std::complex<double> sum = 0.0;
  const std::complex<double> step = std::polar(1.0, -w * dt);
  std::complex<double> phase = 1.0;
  for (size_t i = 0; i < n; ++i) {
    sum += a[first + i] * phase;
    phase *= step;
  }
  return dt / (2.0 * kPi * n) * std::norm(sum);
}

TEST(SyntheticMotion, SampleSpectrumMatchesTheTargetWithinItsStatisticalError) {
  // 200 seeds of 40 s after a 5 s start (the filters start from rest; the transient decays as
  // exp(-z_g w_g t): 1e-20 after 5 s). At each of 24 frequencies from 0.3 to 20 Hz the
  // periodogram is averaged over 5 neighbouring bins (0.025 Hz apart) and the 200 seeds: 1000
  // independent exponential estimates, relative standard deviation 1 / sqrt(1000) = 3.2%.
  // The three cases: Kanai-Tajimi alone, with Clough-Penzien, with the high-pass after it (with
  // no envelope the high-pass is one more stationary filter).
  const int seeds = 200, band = 5;
  for (const auto& [filter_hz, high_pass_hz] : {std::pair{0.0, 0.0}, {0.3, 0.0}, {0.0, 0.3}}) {
    SyntheticMotionDef d = Stationary();
    d.filter_frequency_hz = filter_hz;
    d.filter_damping = 0.7;
    d.high_pass_hz = high_pass_hz;
    const size_t first = 500, n = 4000;
    std::vector<double> freqs_hz;
    for (double f = 0.3; f < 20.0; f *= 1.2) freqs_hz.push_back(f);
    std::vector<double> mean(freqs_hz.size(), 0.0);
    for (int s = 0; s < seeds; ++s) {
      d.seed = 1000 + s;
      const std::vector<double> a = GenerateSyntheticMotion(d);
      ASSERT_EQ(a.size(), 4501u);
      for (size_t j = 0; j < freqs_hz.size(); ++j) {
        const int k0 = static_cast<int>(std::round(freqs_hz[j] * n * d.dt_s));
        for (int k = k0 - band / 2; k <= k0 + band / 2; ++k) {
          mean[j] += Periodogram(a, first, n, d.dt_s, k) / (seeds * band);
        }
      }
    }
    const double sd = 1.0 / std::sqrt(static_cast<double>(seeds * band));
    double chi2 = 0.0;
    for (size_t j = 0; j < freqs_hz.size(); ++j) {
      const int k0 = static_cast<int>(std::round(freqs_hz[j] * n * d.dt_s));
      double target = 0.0;
      for (int k = k0 - band / 2; k <= k0 + band / 2; ++k) {
        target += SyntheticPsd(d, 2.0 * kPi * k / (n * d.dt_s)) / band;
      }
      const double z = (mean[j] / target - 1.0) / sd;
      chi2 += z * z;
      // 4 standard deviations at each frequency.
      EXPECT_LT(std::abs(z), 4.0) << filter_hz << " Hz filter, " << high_pass_hz
                                  << " Hz high-pass, " << freqs_hz[j] << " Hz: " << mean[j]
                                  << " against " << target;
    }
    // Over all frequencies the squared deviations add up to a chi-square with 24 degrees of
    // freedom: between its 0.1% and 99.9% points (8.1 and 51.2).
    EXPECT_GT(chi2, 8.1) << filter_hz;
    EXPECT_LT(chi2, 51.2) << filter_hz;
  }
}

TEST(SyntheticMotion, TheEnvelopeMultipliesTheStationaryRecord) {
  SyntheticMotionDef d = Stationary();
  d.duration_s = 20.0;
  const std::vector<double> stationary = GenerateSyntheticMotion(d);
  d.envelope = SyntheticEnvelope::kJennings;
  d.rise_s = 2.0;
  d.strong_end_s = 8.0;
  d.decay_per_s = 0.5;
  const std::vector<double> shaped = GenerateSyntheticMotion(d);
  ASSERT_EQ(shaped.size(), stationary.size());
  for (size_t i = 0; i < shaped.size(); ++i) {
    const double t = i * d.dt_s;
    const double e = t < 2.0 ? (t / 2.0) * (t / 2.0) : t <= 8.0 ? 1.0 : std::exp(-0.5 * (t - 8.0));
    EXPECT_NEAR(SyntheticEnvelopeAt(d, t), e, 4e-16) << t;
    EXPECT_EQ(shaped[i], stationary[i] * SyntheticEnvelopeAt(d, t)) << t;
  }
  // A target peak scales the record so that its largest |a| is the target.
  d.target_peak_mps2 = 3.0;
  const std::vector<double> scaled = GenerateSyntheticMotion(d);
  double peak = 0.0;
  for (double v : scaled) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak, 3.0, 4e-16);
}

// FNV-1a over the samples' bytes.
std::uint64_t Fnv1a(const std::vector<double>& a) {
  std::uint64_t h = 1469598103934665603ull;
  for (double v : a) {
    unsigned char bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  }
  return h;
}

TEST(SyntheticMotion, TheSameSeedGivesTheSameBytesOnEveryMachine) {
  SyntheticMotionDef d = Stationary();
  d.envelope = SyntheticEnvelope::kJennings;
  d.filter_frequency_hz = 0.3;
  d.seed = 7;
  const std::vector<double> a = GenerateSyntheticMotion(d);
  EXPECT_EQ(Fnv1a(GenerateSyntheticMotion(d)), Fnv1a(a));
  d.seed = 8;
  EXPECT_NE(Fnv1a(GenerateSyntheticMotion(d)), Fnv1a(a));
  // The bits this definition gives (x86-64, GCC 12). Built only from IEEE-754
  // basic operations without contraction (synthetic_motion.h), they are the same on every
  // IEEE-754 machine: a different hash is a portability bug, not a tolerance to widen.
  EXPECT_EQ(Fnv1a(a), 0xefd35032a00677e0ull) << std::hex << Fnv1a(a);
  // The same with the high-pass and the residual correction (the defaults).
  d.seed = 7;
  d.high_pass_hz = 0.1;
  d.zero_residuals = true;
  const std::vector<double> b = GenerateSyntheticMotion(d);
  EXPECT_EQ(Fnv1a(b), kCorrectedHash) << std::hex << Fnv1a(b);
}

// The shipped study's process (scenes/studies/synthetic_stack.toml: soft soil, Clough-Penzien
// at 0.1 Hz, Jennings envelope to 8 s), scaled to 0.6 g.
SyntheticMotionDef SoftSoil(std::uint64_t seed) {
  SyntheticMotionDef d;
  d.target_peak_mps2 = 0.6 * 9.80665;
  d.ground_frequency_hz = 1.0;
  d.ground_damping = 0.4;
  d.filter_frequency_hz = 0.1;
  d.filter_damping = 0.6;
  d.rise_s = 2.0;
  d.strong_end_s = 8.0;
  d.decay_per_s = 0.35;
  d.dt_s = 0.01;
  d.duration_s = 20.0;
  d.seed = seed;
  return d;
}

TEST(SyntheticMotion, TheRecordComesBackToRest) {
  // ResidualsOf is exact for a piecewise-linear record: a = 1 for T = 2 s gives v = 2, d = 2;
  // a = t gives v = T^2 / 2, d = T^3 / 6.
  {
    const RecordResiduals r = ResidualsOf(std::vector<double>(201, 1.0), 0.01);
    EXPECT_NEAR(r.velocity_mps, 2.0, 1e-13);
    EXPECT_NEAR(r.displacement_m, 2.0, 1e-13);
    std::vector<double> ramp(201);
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = 0.01 * i;
    const RecordResiduals q = ResidualsOf(ramp, 0.01);
    EXPECT_NEAR(q.velocity_mps, 2.0, 1e-13);
    EXPECT_NEAR(q.displacement_m, 8.0 / 6.0, 1e-13);
  }
  double largest_correction = 0.0, drift_before = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SyntheticMotionDef d = SoftSoil(seed);
    const std::vector<double> a = GenerateSyntheticMotion(d);
    // Zero to rounding: about 2000 terms of up to 0.06 m/s (velocity) and 1.2 m (displacement)
    // each, so a few 1e-14 m/s and 1e-13 m; the bounds are 100 times that.
    const RecordResiduals r = ResidualsOf(a, d.dt_s);
    EXPECT_LT(std::abs(r.velocity_mps), 1e-12) << seed;
    EXPECT_LT(std::abs(r.displacement_m), 1e-11) << seed;
    // Nothing where the envelope is zero.
    EXPECT_EQ(a[0], 0.0);
    // The correction is small: the high-pass has left residuals of mm/s and cm, spread over
    // the strong phase. Measured (seeds 1 to 10): at most 0.57% of the peak; bound 1%.
    d.zero_residuals = false;
    const std::vector<double> b = GenerateSyntheticMotion(d);
    for (size_t i = 0; i < a.size(); ++i) {
      largest_correction = std::max(largest_correction, std::abs(a[i] - b[i]) / d.target_peak_mps2);
    }
    // Without the high-pass after the envelope the record drifts: up to 29 m by its end
    // (measured, seeds 1 to 10).
    d.high_pass_hz = 0.0;
    drift_before = std::max(
        drift_before, std::abs(ResidualsOf(GenerateSyntheticMotion(d), d.dt_s).displacement_m));
  }
  EXPECT_LT(largest_correction, 0.01);
  EXPECT_GT(drift_before, 1.0);
}

TEST(SyntheticMotion, SceneReadsTheKindAndNamesBadKeys) {
  const std::string blocks = "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n";
  const std::string motion =
      "[base.horizontal]\nkind = \"kanai_tajimi\"\namplitude_g = 0.3\nground_frequency_hz = "
      "2.5\nground_damping = 0.6\nfilter_frequency_hz = 0.3\nfilter_damping = 0.7\nrise_s = "
      "1\nstrong_end_s = 5\ndecay_per_s = 0.4\nduration_s = 10\ndt = 0.01\nseed = 4\n";
  const Scene s = ParseScene(blocks + motion, "scenes/x.toml", {});
  ASSERT_TRUE(s.horizontal.has_value());
  EXPECT_EQ(s.horizontal->kind, MotionKind::kKanaiTajimi);
  EXPECT_EQ(s.horizontal->synthetic.seed, 4u);
  const GroundMotion m = GroundMotion::FromScene(s);
  ASSERT_TRUE(m.horizontal().has_value());
  const MotionInfo& info = m.horizontal()->info();
  EXPECT_EQ(info.format, "synthetic");
  EXPECT_EQ(info.npts, 1001);
  EXPECT_NEAR(info.peak_g, 0.3, 1e-15);
  EXPECT_EQ(info.source, "kanai_tajimi (seed 4)");
  // The high-pass and the residual correction are on unless the scene says otherwise.
  EXPECT_EQ(s.horizontal->synthetic.high_pass_hz, 0.1);
  EXPECT_TRUE(s.horizontal->synthetic.zero_residuals);
  {
    const Scene off = ParseScene(blocks + motion + "high_pass_hz = 0\nzero_residuals = false\n",
                                 "scenes/x.toml", {});
    EXPECT_EQ(off.horizontal->synthetic.high_pass_hz, 0.0);
    EXPECT_FALSE(off.horizontal->synthetic.zero_residuals);
    const Scene set =
        ParseScene(blocks + motion, "scenes/x.toml", {"base.horizontal.high_pass_hz=0.2"});
    EXPECT_EQ(set.horizontal->synthetic.high_pass_hz, 0.2);
  }

  auto error = [&](const std::string& text) {
    try {
      ParseScene(blocks + text, "scenes/x.toml", {});
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto expect = [&](const std::string& text, const std::string& needle) {
    const std::string e = error(text);
    EXPECT_NE(e.find(needle), std::string::npos) << "got: " << e;
    EXPECT_NE(e.find("scenes/x.toml:"), std::string::npos) << e;
  };
  expect(motion + "intensity = 0.1\n", "not both");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nground_frequency_hz = 2\nground_damping = "
      "0.5\nenvelope = \"none\"\nduration_s = 5\n",
      "missing intensity");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nintensity = 0.1\nground_damping = "
      "0.5\nenvelope = \"none\"\nduration_s = 5\n",
      "ground_frequency_hz");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nintensity = 0.1\nground_frequency_hz = "
      "80\nground_damping = 0.5\nenvelope = \"none\"\nduration_s = 5\ndt = 0.01\n",
      "below the Nyquist frequency");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nintensity = 0.1\nground_frequency_hz = "
      "2\nground_damping = 0.5\nenvelope = \"none\"\nrise_s = 1\nduration_s = 5\n",
      "rise_s");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nintensity = 0.1\nground_frequency_hz = "
      "2\nground_damping = 0.5\nenvelope = \"boxcar\"\nduration_s = 5\n",
      "envelope");
  expect(
      "[base.horizontal]\nkind = \"kanai_tajimi\"\nintensity = 0.1\nground_frequency_hz = "
      "2\nground_damping = 0.5\nrise_s = 3\nstrong_end_s = 2\ndecay_per_s = 1\nduration_s = "
      "5\n",
      "strong_end_s must be >= rise_s");
  expect("[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 2\nseed = 3\n",
         "only for kind = \"kanai_tajimi\"");
  expect(
      "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 2\n"
      "zero_residuals = true\n",
      "only for kind = \"kanai_tajimi\"");
  expect(motion + "high_pass_hz = -0.1\n", "base.horizontal.high_pass_hz");
  expect(motion + "high_pass_hz = 60\n", "high_pass_hz must be >= 0");
  expect(motion + "zero_residuals = 1\n", "expected true or false");
}

}  // namespace
}  // namespace rockbench
