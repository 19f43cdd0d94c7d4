#include "compare/angle_error.h"

#include <algorithm>
#include <cmath>

namespace rockbench {

void AngleErrorSums::Add(double t_s, double e, double tol, AngleAgreement* g) {
  const bool predictable = t_s <= predictability_horizon_s_;
  ++n_;
  g->max_abs_error_rad = std::max(g->max_abs_error_rad, e);
  all_ += e * e;
  if (predictable) {
    g->max_abs_error_predictable_rad = std::max(g->max_abs_error_predictable_rad, e);
    predictable_ += e * e;
    ++n_predictable_;
  } else {
    g->max_abs_error_beyond_rad = std::max(g->max_abs_error_beyond_rad, e);
    beyond_ += e * e;
    ++g->samples_beyond;
  }
  // The error on the scale of the motion at that time.
  const double ratio = e / tol;
  if (ratio > g->max_error_ratio) {
    g->max_error_ratio = ratio;
    g->max_error_ratio_t_s = t_s;
  }
  if (predictable) g->max_error_ratio_predictable = std::max(g->max_error_ratio_predictable, ratio);
  if (g->within_tolerance && e > tol) {
    g->within_tolerance = false;
    g->horizon_s = t_s;
    g->tolerance_at_horizon_rad = tol;
  }
  if (g->within_tolerance) {
    g->max_abs_error_horizon_rad = std::max(g->max_abs_error_horizon_rad, e);
    horizon_ += e * e;
    ++n_horizon_;
  }
}

void AngleErrorSums::Finish(AngleAgreement* g) const {
  auto rms = [](double sum, int n) { return n > 0 ? std::sqrt(sum / n) : 0.0; };
  g->rms_error_rad = rms(all_, n_);
  g->rms_error_horizon_rad = rms(horizon_, n_horizon_);
  g->rms_error_predictable_rad = rms(predictable_, n_predictable_);
  g->rms_error_beyond_rad = rms(beyond_, g->samples_beyond);
}

}  // namespace rockbench
