#pragma once
/// The comparison tolerance of a block as a function of time: an error is judged on the scale of
/// the motion at that time, not on the whole run's peak (docs/verdicts.md, "The error scale").
///
///   tol_i(t) = clamp(envelope_fraction * min(env_i(t), alpha_i), floor_i, cap_i)
///   env_i(t) = max |theta_ref_i(s)| over |s - t| <= window_half_s_i
///
/// - alpha_i = atan(B_i / H_i), the block's critical angle; beyond it the block falls under
///   gravity alone, so the envelope is capped there and an overturning run is judged on the
///   scale of the motion that decided it, not against pi/2.
/// - window_half_s_i = window_periods / p_i, p_i = sqrt(3 g / (4 R_i)) (Housner's frequency
///   parameter of the block): a full window of 2 window_periods / p_i = 4 / p_i is one free
///   rocking cycle of the block at about a third of its critical angle (T = (4 / p) acosh(1 /
///   (1 - theta0 / alpha))), the order of a cycle whatever the amplitude.
/// - floor_i = floor_critical_fraction * alpha_i: a block at rest in the reference is held to a
///   tolerance, not zero.
/// A scene's `[compare] tolerance` replaces the rule by a constant.
#include <optional>
#include <string>
#include <vector>

#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench {

/// The rule's constants (the defaults are the documented rule).
struct ToleranceConfig {
  /// The tolerance as a fraction of the local envelope.
  double envelope_fraction = 0.1;
  /// Half the window, in units of 1 / p_i.
  double window_periods = 2.0;
  /// Floor, as a fraction of the critical angle.
  double floor_critical_fraction = 0.01;
  /// Cap: the envelope never exceeds the critical angle (so the cap is envelope_fraction *
  /// alpha_i).
  double cap_critical_fraction = 1.0;
};

/// One block's tolerance on a regular grid t_k = k * grid_dt_s (held constant past the end).
struct ToleranceProfile {
  std::optional<double> fixed_rad;  ///< the scene's [compare] tolerance, when set
  double grid_dt_s = 0.0;
  double window_half_s = 0.0;
  double floor_rad = 0.0, cap_rad = 0.0;
  std::vector<double> tol_rad;  ///< on the grid
  /// The tolerance at t (the grid value of the cell containing t: the envelope is a maximum over
  /// a window of several cells, so the cell's value is representative).
  double At(double t_s) const;
  double Min() const;
  double Max() const;
};

/// The profile of block `block` (1 or 2) from the reference's history (samples at the output
/// interval and every event time), on the output grid to the end of the run. For a body of
/// another kind the envelope is of the length of its compared angles' vector: a cylinder's
/// tilt, sqrt(tilt_x^2 + tilt_y^2), with its critical angle atan(D / H) and the window of the
/// block rule with B = D (docs/three-d.md, "Comparison").
ToleranceProfile LocalTolerance(const Scene& scene, int block, const History& reference,
                                const ToleranceConfig& config = {});

/// The rule's value for an envelope of `envelope_rad` (block 1 or 2): clamp(envelope_fraction *
/// min(envelope, alpha cap), floor, cap), or the scene's [compare] tolerance. LocalTolerance
/// applies it at every time; at the reference's peak it is AngleTolerance_rad (compare.h).
double ToleranceAtEnvelope_rad(const Scene& scene, int block, double envelope_rad,
                               const ToleranceConfig& config = {});

/// The rule in words, for comparison.json and the report.
std::string ToleranceRuleText(const ToleranceConfig& config = {});

/// The tolerance of block `block` (1 or 2) at the scale of the reference's peak, rad: the scene's
/// [compare] tolerance, else 10% of the peak |theta| (capped at the block's critical angle
/// atan(B/H)), never below 1% of the critical angle: the local rule above where the
/// envelope is the peak. The convergence check, the perturbation members' statistics and the final
/// state use it; the agreement horizon uses the local tolerance.
double AngleTolerance_rad(const Scene& scene, int block, double reference_peak_rad);

}  // namespace rockbench
