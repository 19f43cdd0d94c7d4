#pragma once
/// Synthetic ground motion: a stationary filtered white noise (Kanai-Tajimi, optionally with the
/// Clough-Penzien high-pass) times a deterministic envelope (Jennings et al. 1968), reproducible
/// bit for bit from a seed on every machine.
///
/// The process: a white noise w(t) of two-sided power spectral density S0 (E[w(t) w(t + tau)] =
/// 2 pi S0 delta(tau), m^2/s^3) drives the ground filter (Kanai 1957, Tajimi 1960) whose
/// absolute acceleration has the transfer function
///   H_KT(s) = (w_g^2 + 2 z_g w_g s) / (s^2 + 2 z_g w_g s + w_g^2),
/// and, when filter_frequency_hz > 0, the Clough-Penzien high-pass that keeps the ground
/// velocity and displacement finite,
///   H_CP(s) = s^2 / (s^2 + 2 z_f w_f s + w_f^2).
/// The modulated record x(t) = e(t) y(t) (y the filtered process, e the envelope) is then made a
/// ground motion whose velocity and displacement come back to rest, in two steps (both on by
/// default; a modulated process has low-frequency content that no stationary filter before the
/// envelope removes: without them the thesis's soft-soil study had PGD up to 72 m):
/// - high_pass_hz > 0: the critically damped high-pass of Rezaeian and Der Kiureghian's
///   modulated filtered white-noise model (Probabilistic Engineering Mechanics 23, 2008;
///   Earthquake Engineering and Structural Dynamics 39, 2010), applied after the envelope:
///   u'' + 2 w_c u' + w_c^2 u = x(t) from rest, and the record is u''; its transfer function
///   s^2 / (s + w_c)^2 (bilinear, like the others). The velocity and displacement of u'' are u'
///   and u, which decay once the motion has: residuals of mm/s and cm at the record's end.
/// - zero_residuals: the smallest correction da (in the norm sum da_n^2 / e_n^2: nothing where
///   the envelope is zero, most where the motion is strong) that makes the record's velocity
///   and displacement at its last sample exactly zero (to rounding), as the simulations
///   integrate it: piecewise linear between samples, from rest at t = 0.
/// Sampled at dt, w is a sequence of independent standard normal numbers times
/// sqrt(2 pi S0 / dt); each filter is discretised with the bilinear (Tustin) transform, so the
/// sampled stationary process (no envelope, no residual correction) has exactly the PSD
/// S0 |H_KT(z) H_CP(z) H_HP(z)|^2, z = exp(i w dt)
/// (SyntheticPsd), which matches the continuous one to the bilinear transform's frequency warping
/// (tan(w dt / 2) / (dt / 2) for w: 0.8% at a fifth of the Nyquist frequency).
///
/// Reproducibility: the normal numbers come from std::mt19937_64 (specified bit for bit by the
/// C++ standard) through Marsaglia's polar method with our own logarithm, and the envelope's
/// exponential is our own too, both made of IEEE-754 basic operations only (the library's log and
/// exp may differ in the last bit between C libraries); the file is compiled without
/// floating-point contraction (-ffp-contract=off). The same definition gives the same bytes on
/// every IEEE-754 machine.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/synthetic_motion_def.h"

namespace rockbench {

/// The record: acceleration samples at t = n dt, n = 0 .. round(duration / dt), m/s^2. Throws
/// std::invalid_argument with SyntheticMotionProblem's text for an invalid definition.
std::vector<double> GenerateSyntheticMotion(const SyntheticMotionDef& def);

/// The exact two-sided PSD of the sampled stationary process (no envelope, no residual
/// correction, no target peak) at angular frequency omega (rad/s, |omega| <= pi / dt):
/// S0 |H_KT(z) H_CP(z) H_HP(z)|^2, m^2/s^3 (a filter that is off is 1).
double SyntheticPsd(const SyntheticMotionDef& def, double omega_radps);
/// The continuous process's PSD at omega: S0 |H_KT H_CP H_HP|^2 at s = i omega, m^2/s^3.
double ContinuousKanaiTajimiPsd(const SyntheticMotionDef& def, double omega_radps);

/// The velocity (m/s) and displacement (m) at the last sample of a record a (m/s^2) sampled at
/// dt and linear between samples, from rest at its first sample: the exact integrals.
struct RecordResiduals {
  double velocity_mps = 0.0;
  double displacement_m = 0.0;
};
RecordResiduals ResidualsOf(const std::vector<double>& a, double dt_s);

/// The envelope at t (s from the record's start).
double SyntheticEnvelopeAt(const SyntheticMotionDef& def, double t_s);

/// exp(x) and log(x) (x > 0) from IEEE-754 basic operations, ldexp and frexp only: the same
/// bits on every IEEE-754 machine; within 2 ulp of the correctly rounded values.
double PortableExp(double x);
double PortableLog(double x);

}  // namespace rockbench
