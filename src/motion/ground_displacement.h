#pragma once
/// The ground's displacement from its acceleration, defined once. Two rules, for two uses:
///
/// - The kinematic drive's path (IntegrateGroundPath): the acceleration sampled on a step grid
///   t_n = n dt (SampleGroundAcceleration), integrated twice with the leapfrog rule, then
///   optionally baseline-corrected by a zero-phase Butterworth high-pass. The engines move their
///   ground along it (engines/common/engine_input.h) and the animations draw the ground along
///   it (renders/drawn_motion.h), so that a picture shows the path a kinematic-drive engine saw.
/// - The exact integrals of the piecewise-linear acceleration of a component, from rest, with
///   no correction (ExactGroundPeaks): the peak ground velocity and displacement of the
///   intensity measures (motion/intensity.h).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "motion/ground_motion.h"

namespace rockbench {

/// Steps of a fixed-step run of duration_s at step dt_s: ceil(duration / dt - 1e-9), at least
/// 0 (the 1e-9 keeps a duration that is a whole number of steps from taking one more).
std::int64_t StepCount(double duration_s, double dt_s);

/// The motion's acceleration on the grid t_n = n dt_s, n = 0 .. steps - 1, m/s^2: ax from the
/// horizontal component, ay from the vertical one (0 where a component is absent). Each sample
/// is the acceleration during step n (the leapfrog force time of a symplectic Euler step).
void SampleGroundAcceleration(const GroundMotion& motion, double dt_s, std::size_t steps,
                              std::vector<double>* ax_mps2, std::vector<double>* ay_mps2);

/// One component of the kinematic drive's ground path.
struct GroundPath {
  std::vector<double> u_m;           ///< displacement at t_n, n = 0 .. a.size(), m
  double velocity_before_mps = 0.0;  ///< the ground's velocity before step 0, m/s
  double raw_peak_m = 0.0;           ///< peak |u| before the baseline correction, m
};

/// The kinematic drive's ground displacement from the acceleration samples a_n (m/s^2) on the
/// grid of step dt_s (s). Integrates twice with the leapfrog rule (u_{n+1} - 2 u_n + u_{n-1} =
/// dt^2 a_n, u_0 = 0, at rest before t = 0: u_{-1} = 0), so that the ground's second difference
/// is exactly the velocity change the inertial drive gives the blocks in step n. Then removes
/// the baseline B = zero-phase low-pass of u (2nd-order Butterworth by the bilinear transform
/// with pre-warping, run forward and backward, corner highpass_hz; the ends are padded with
/// 1.2 / highpass_hz s: zeros before t = 0, odd reflection after the last sample). Because
/// |H_LP|^2 + |H_HP|^2 = 1 for a Butterworth pair, u - B is the zero-phase 4th-order high-pass
/// of u: a component of frequency f keeps r^4 / (1 + r^4) of its amplitude, r = tan(pi f dt) /
/// tan(pi highpass_hz dt), with no phase shift. highpass_hz = 0 disables the correction (then
/// the velocity before step 0 is 0).
GroundPath IntegrateGroundPath(const std::vector<double>& accel_mps2, double dt_s,
                               double highpass_hz);

/// Peak |v| and |d| of the exact integrals v(t), d(t) of a piecewise-linear acceleration.
struct GroundPeaks {
  double velocity_mps = 0.0;    ///< peak |v|, m/s
  double displacement_m = 0.0;  ///< peak |d|, m
};

/// The peaks of the exact integrals of the acceleration linear between the samples a_i
/// (m/s^2, step dt_s), from rest (v = d = 0 at the first sample), no baseline correction;
/// after the last sample the acceleration is 0 for hold_s more seconds (v constant, d linear).
/// The peaks inside a segment are found where v (for d) or a (for v) vanishes.
GroundPeaks ExactGroundPeaks(const std::vector<double>& accel_mps2, double dt_s, double hold_s);

}  // namespace rockbench
