#include "run/tolerance.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {

double ToleranceProfile::At(double t_s) const {
  if (fixed_rad) return *fixed_rad;
  if (tol_rad.empty()) return floor_rad;
  const double k = std::floor(t_s / grid_dt_s + 0.5);
  if (!(k > 0.0)) return tol_rad.front();
  const auto i = static_cast<size_t>(k);
  return i < tol_rad.size() ? tol_rad[i] : tol_rad.back();
}

double ToleranceProfile::Min() const {
  if (fixed_rad) return *fixed_rad;
  return tol_rad.empty() ? floor_rad : *std::min_element(tol_rad.begin(), tol_rad.end());
}

double ToleranceProfile::Max() const {
  if (fixed_rad) return *fixed_rad;
  return tol_rad.empty() ? floor_rad : *std::max_element(tol_rad.begin(), tol_rad.end());
}

namespace {

// The block's side of the rule: its critical angle and Housner's frequency parameter.
struct BlockScale {
  double alpha_rad = 0.0, p_radps = 0.0;
};

BlockScale ScaleOf(const Scene& scene, int block) {
  const BlockDef& b =
      block >= 2 && block <= scene.block_count() ? scene.blocks[block - 1] : scene.blocks.at(0);
  const double r_m = 0.5 * std::hypot(b.width_m, b.height_m);
  return {std::atan(b.width_m / b.height_m), std::sqrt(3.0 * scene.run.gravity_mps2 / (4.0 * r_m))};
}

double Clamped(double envelope_rad, double alpha_rad, const ToleranceConfig& c) {
  return std::clamp(
      c.envelope_fraction * std::min(envelope_rad, c.cap_critical_fraction * alpha_rad),
      c.floor_critical_fraction * alpha_rad,
      c.envelope_fraction * c.cap_critical_fraction * alpha_rad);
}

}  // namespace

double ToleranceAtEnvelope_rad(const Scene& scene, int block, double envelope_rad,
                               const ToleranceConfig& config) {
  if (scene.compare.tolerance_rad) return *scene.compare.tolerance_rad;
  return Clamped(envelope_rad, ScaleOf(scene, block).alpha_rad, config);
}

ToleranceProfile LocalTolerance(const Scene& scene, int block, const History& reference,
                                const ToleranceConfig& config) {
  ToleranceProfile p;
  if (scene.compare.tolerance_rad) {
    p.fixed_rad = *scene.compare.tolerance_rad;
    p.floor_rad = p.cap_rad = *scene.compare.tolerance_rad;
    return p;
  }
  const BlockScale scale = ScaleOf(scene, block);
  const double alpha_rad = scale.alpha_rad;
  p.grid_dt_s = scene.run.output_interval_s;
  p.window_half_s = config.window_periods / scale.p_radps;
  p.floor_rad = config.floor_critical_fraction * alpha_rad;
  p.cap_rad = config.envelope_fraction * config.cap_critical_fraction * alpha_rad;

  // |theta| per grid cell (the largest sample in the cell), cells of width grid_dt_s centred
  // on the grid times; a cell without a sample holds the last value (the reference at rest or
  // stopped keeps its state).
  const auto n = static_cast<size_t>(std::floor(scene.run.duration_s / p.grid_dt_s + 1e-9)) + 1;
  std::vector<double> cell(n, -1.0);
  double last = 0.0;
  // A body of another kind: the length of its compared angles' vector (a cylinder's tilt, from
  // tilt_x and tilt_y), so that each component is judged on the scale of the whole motion.
  std::vector<StateQuantityReader> compared;
  if (const BodyKind* kind = FindBodyKind(reference.shape);
      kind != nullptr && reference.shape != PlanarBlockKind().shape) {
    for (const StateQuantity& q : kind->state) {
      if (q.compared_angle) compared.emplace_back(reference, q.stem);
    }
  }
  const int body = block >= 1 && block <= reference.blocks ? block : 1;
  for (const Sample& s : reference.samples) {
    double norm2 = 0.0;
    for (const StateQuantityReader& q : compared) norm2 += q(s, body) * q(s, body);
    const double v =
        !compared.empty()
            ? std::sqrt(norm2)
            : std::abs(block >= 2 && block <= s.blocks() ? s.theta_rad[block - 1] : s.theta_rad[0]);
    if (!std::isfinite(v)) continue;
    const double k = std::floor(s.t_s / p.grid_dt_s + 0.5);
    const size_t i = k <= 0.0 ? 0 : std::min(n - 1, static_cast<size_t>(k));
    cell[i] = std::max(cell[i], v);
  }
  for (double& c : cell) {
    if (c < 0.0) {
      c = last;
    } else {
      last = c;
    }
  }
  // Sliding maximum over +-w cells (monotonic deque of indices).
  const auto w = static_cast<size_t>(std::ceil(p.window_half_s / p.grid_dt_s - 1e-9));
  p.tol_rad.assign(n, 0.0);
  std::deque<size_t> q;
  size_t next = 0;  // next cell to enter the window
  for (size_t k = 0; k < n; ++k) {
    const size_t hi = std::min(n - 1, k + w);
    for (; next <= hi; ++next) {
      while (!q.empty() && cell[q.back()] <= cell[next]) q.pop_back();
      q.push_back(next);
    }
    while (q.front() + w < k) q.pop_front();
    p.tol_rad[k] = Clamped(cell[q.front()], alpha_rad, config);
  }
  return p;
}

std::string ToleranceRuleText(const ToleranceConfig& c) {
  return Format("%g", 100.0 * c.envelope_fraction) +
         "% of the reference's local envelope (largest |theta| within +-" +
         Format("%g", c.window_periods) +
         " / p of the time, p = sqrt(3 g / 4 R) of the block; the envelope capped at " +
         (c.cap_critical_fraction == 1.0 ? std::string("the")
                                         : Format("%g", c.cap_critical_fraction) + " x the") +
         " block's critical angle atan(B/H)), at least " +
         Format("%g", 100.0 * c.floor_critical_fraction) + "% of the critical angle";
}

double AngleTolerance_rad(const Scene& scene, int block, double reference_peak_rad) {
  // LocalTolerance's value where the envelope is the peak.
  return ToleranceAtEnvelope_rad(scene, block, reference_peak_rad);
}

}  // namespace rockbench
