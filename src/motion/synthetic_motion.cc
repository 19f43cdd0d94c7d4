// Built with -ffp-contract=off (src/scene/CMakeLists.txt): every result below is a fixed
// sequence of IEEE-754 basic operations, the same bits on every machine.
#include "motion/synthetic_motion.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace rockbench {
namespace {

constexpr double kPi = std::numbers::pi;
// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (Cody and Waite).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;

// A second-order section y = H(z) x in transposed direct form II.
struct Biquad {
  double b0 = 0, b1 = 0, b2 = 0, a1 = 0, a2 = 0;  // a0 = 1
  double s1 = 0, s2 = 0;
  double Step(double x) {
    const double y = b0 * x + s1;
    s1 = b1 * x - a1 * y + s2;
    s2 = b2 * x - a2 * y;
    return y;
  }
  std::complex<double> At(std::complex<double> z) const {
    const std::complex<double> zi = 1.0 / z;
    return (b0 + zi * (b1 + zi * b2)) / (1.0 + zi * (a1 + zi * a2));
  }
};

// The bilinear transform of (n0 + n1 s + n2 s^2) / (d0 + d1 s + d2 s^2) at step dt:
// s = K (1 - 1/z) / (1 + 1/z), K = 2 / dt.
Biquad Bilinear(double n0, double n1, double n2, double d0, double d1, double d2, double dt) {
  const double k = 2.0 / dt, k2 = k * k;
  const double a0 = d0 + d1 * k + d2 * k2;
  Biquad q;
  q.b0 = (n0 + n1 * k + n2 * k2) / a0;
  q.b1 = (2.0 * n0 - 2.0 * n2 * k2) / a0;
  q.b2 = (n0 - n1 * k + n2 * k2) / a0;
  q.a1 = (2.0 * d0 - 2.0 * d2 * k2) / a0;
  q.a2 = (d0 - d1 * k + d2 * k2) / a0;
  return q;
}

Biquad KanaiTajimi(const SyntheticMotionDef& d) {
  const double w = 2.0 * kPi * d.ground_frequency_hz, z = d.ground_damping;
  return Bilinear(w * w, 2.0 * z * w, 0.0, w * w, 2.0 * z * w, 1.0, d.dt_s);
}

Biquad CloughPenzien(const SyntheticMotionDef& d) {
  const double w = 2.0 * kPi * d.filter_frequency_hz, z = d.filter_damping;
  return Bilinear(0.0, 0.0, 1.0, w * w, 2.0 * z * w, 1.0, d.dt_s);
}

// The high-pass after the envelope: s^2 / (s + w_c)^2, a critically damped oscillator's
// relative acceleration.
Biquad HighPass(const SyntheticMotionDef& d) {
  const double w = 2.0 * kPi * d.high_pass_hz;
  return Bilinear(0.0, 0.0, 1.0, w * w, 2.0 * w, 1.0, d.dt_s);
}

// The weights of the two linear functionals of a piecewise-linear record a_0 .. a_N that give
// its end velocity, sum cv_n a_n (the trapezoidal rule), and end displacement,
// sum cd_n a_n = integral of (T - t) a(t) dt: dt (T - t_n) inside, dt T / 2 - dt^2 / 6 and
// dt^2 / 6 at the ends (the half hats).
void ResidualWeights(std::size_t n_samples, double dt, std::vector<double>* cv,
                     std::vector<double>* cd) {
  const std::size_t last = n_samples - 1;
  const double total = static_cast<double>(last) * dt;
  cv->assign(n_samples, dt);
  cd->resize(n_samples);
  for (std::size_t i = 0; i < n_samples; ++i) {
    (*cd)[i] = dt * (total - static_cast<double>(i) * dt);
  }
  (*cv)[0] = 0.5 * dt;
  (*cv)[last] = 0.5 * dt;
  (*cd)[0] = 0.5 * dt * total - dt * dt / 6.0;
  (*cd)[last] = dt * dt / 6.0;
}

// Adds to a the correction w_n (l0 cv_n + l1 cd_n) (w_n = e_n^2, e_n the envelope at sample n)
// that zeroes both functionals: the least sum of da_n^2 / w_n that does (Lagrange), a 2 x 2
// system.
void ZeroResiduals(const std::vector<double>& envelope, double dt, std::vector<double>* a) {
  const std::size_t n = a->size();
  if (n < 2) return;
  std::vector<double> cv, cd;
  ResidualWeights(n, dt, &cv, &cd);
  double m00 = 0.0, m01 = 0.0, m11 = 0.0, r0 = 0.0, r1 = 0.0;
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) {
    w[i] = envelope[i] * envelope[i];
    m00 += w[i] * cv[i] * cv[i];
    m01 += w[i] * cv[i] * cd[i];
    m11 += w[i] * cd[i] * cd[i];
    r0 -= cv[i] * (*a)[i];
    r1 -= cd[i] * (*a)[i];
  }
  const double det = m00 * m11 - m01 * m01;
  if (!(det > 0.0)) return;  // an envelope nonzero at fewer than two samples
  const double l0 = (r0 * m11 - m01 * r1) / det, l1 = (m00 * r1 - m01 * r0) / det;
  for (std::size_t i = 0; i < n; ++i) (*a)[i] += w[i] * (l0 * cv[i] + l1 * cd[i]);
}

// Uniform on [0, 1) from the top 53 bits of one draw.
double Uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Pairs of independent standard normal numbers: Marsaglia's polar method.
class Normal {
 public:
  explicit Normal(std::uint64_t seed) : rng_(seed) {}
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0, v = 0, s = 0;
    do {
      u = 2.0 * Uniform01(rng_) - 1.0;
      v = 2.0 * Uniform01(rng_) - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * PortableLog(s) / s);  // sqrt is correctly rounded
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace

double PortableExp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.78) return std::numeric_limits<double>::infinity();
  if (x < -745.2) return 0.0;
  // x = k ln2 + r, |r| <= ln2 / 2; exp(r) by its Taylor series to r^18 / 18! (< 1e-24), in
  // Horner's form 1 + r (1 + r/2 (1 + r/3 (...))).
  const double k = std::nearbyint(x / (kLn2Hi + kLn2Lo));
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double p = 1.0;
  for (int i = 18; i >= 1; --i) p = 1.0 + p * r / i;
  return std::ldexp(p, static_cast<int>(k));
}

double PortableLog(double x) {
  if (!(x > 0.0)) return x == 0.0 ? -std::numeric_limits<double>::infinity() : NAN;
  if (std::isinf(x)) return x;
  // x = m 2^e with m in [sqrt(1/2), sqrt(2)); log m = 2 atanh(t), t = (m - 1) / (m + 1),
  // |t| <= 0.1716 (t^31 / 31 < 1e-25).
  int e = 0;
  double m = std::frexp(x, &e);
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    --e;
  }
  const double t = (m - 1.0) / (m + 1.0), t2 = t * t;
  // 1 + t^2/3 + t^4/5 + ... + t^30/31 in Horner's form.
  double q = 1.0 / 31.0;
  for (int n = 29; n >= 1; n -= 2) q = 1.0 / n + t2 * q;
  return e * kLn2Hi + (e * kLn2Lo + 2.0 * t * q);
}

double SyntheticEnvelopeAt(const SyntheticMotionDef& d, double t) {
  if (d.envelope == SyntheticEnvelope::kNone) return 1.0;
  if (t < d.rise_s) {
    const double r = t / d.rise_s;
    return r * r;
  }
  if (t <= d.strong_end_s) return 1.0;
  return PortableExp(-d.decay_per_s * (t - d.strong_end_s));
}

std::vector<double> GenerateSyntheticMotion(const SyntheticMotionDef& d) {
  const std::string problem = SyntheticMotionProblem(d);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const auto n = static_cast<std::size_t>(std::nearbyint(d.duration_s / d.dt_s));
  Biquad kt = KanaiTajimi(d), cp = CloughPenzien(d);
  const bool high_pass = d.filter_frequency_hz > 0.0;
  // The white noise's sample standard deviation: variance 2 pi S0 / dt.
  const double intensity = d.target_peak_mps2 > 0.0 ? 1.0 : d.intensity_m2ps3;
  const double sigma = std::sqrt(2.0 * kPi * intensity / d.dt_s);
  Normal normal(d.seed);
  std::vector<double> a(n + 1), envelope(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    double y = kt.Step(sigma * normal.Next());
    if (high_pass) y = cp.Step(y);
    envelope[i] = SyntheticEnvelopeAt(d, static_cast<double>(i) * d.dt_s);
    a[i] = y * envelope[i];
  }
  if (d.high_pass_hz > 0.0) {
    Biquad hp = HighPass(d);
    for (double& v : a) v = hp.Step(v);
  }
  if (d.zero_residuals) ZeroResiduals(envelope, d.dt_s, &a);
  double peak = 0.0;
  for (const double v : a) peak = std::max(peak, std::abs(v));
  if (d.target_peak_mps2 > 0.0 && peak > 0.0) {
    const double factor = d.target_peak_mps2 / peak;
    for (double& v : a) v *= factor;
  }
  return a;
}

double SyntheticPsd(const SyntheticMotionDef& d, double omega) {
  const std::complex<double> z = std::polar(1.0, omega * d.dt_s);
  std::complex<double> h = KanaiTajimi(d).At(z);
  if (d.filter_frequency_hz > 0.0) h *= CloughPenzien(d).At(z);
  if (d.high_pass_hz > 0.0) h *= HighPass(d).At(z);
  return d.intensity_m2ps3 * std::norm(h);
}

double ContinuousKanaiTajimiPsd(const SyntheticMotionDef& d, double omega) {
  const double wg = 2.0 * kPi * d.ground_frequency_hz, zg = d.ground_damping;
  const double w2 = omega * omega;
  double h2 = (wg * wg * wg * wg + 4.0 * zg * zg * wg * wg * w2) /
              ((wg * wg - w2) * (wg * wg - w2) + 4.0 * zg * zg * wg * wg * w2);
  if (d.filter_frequency_hz > 0.0) {
    const double wf = 2.0 * kPi * d.filter_frequency_hz, zf = d.filter_damping;
    h2 *= w2 * w2 / ((wf * wf - w2) * (wf * wf - w2) + 4.0 * zf * zf * wf * wf * w2);
  }
  if (d.high_pass_hz > 0.0) {
    // |s^2 / (s + w_c)^2|^2 at s = i omega.
    const double wc2 = 4.0 * kPi * kPi * d.high_pass_hz * d.high_pass_hz;
    h2 *= w2 * w2 / ((wc2 + w2) * (wc2 + w2));
  }
  return d.intensity_m2ps3 * h2;
}

RecordResiduals ResidualsOf(const std::vector<double>& a, double dt) {
  RecordResiduals r;
  for (std::size_t i = 1; i < a.size(); ++i) {
    // Exact over a linear piece: d += dt v + dt^2 (a0 / 3 + a1 / 6), v += dt (a0 + a1) / 2.
    r.displacement_m += dt * (r.velocity_mps + dt * (a[i - 1] / 3.0 + a[i] / 6.0));
    r.velocity_mps += 0.5 * dt * (a[i - 1] + a[i]);
  }
  return r;
}

}  // namespace rockbench
