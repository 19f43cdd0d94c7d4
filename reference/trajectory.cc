#include <algorithm>
#include <iterator>

#include "reference/simulate.h"

namespace rockbench::reference {

void Trajectory::Append(Segment segment) {
  segments_.push_back(std::move(segment));
}

bool Trajectory::empty() const {
  return segments_.empty();
}

double Trajectory::end_s() const {
  return segments_.empty() ? 0.0 : segments_.back().t1;
}

Sample Trajectory::At(double t_s) const {
  Sample out(blocks_);
  if (segments_.empty()) return out;
  t_s = std::clamp(t_s, segments_.front().t0, segments_.back().t1);
  // The last segment starting at or before t (post-event state at an event time): the last
  // one for the samples a run records as it goes, else found by bisection.
  auto it = std::prev(segments_.end());
  if (t_s < it->t0) {
    it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                          [](double t, const Segment& s) { return t < s.t0; });
    if (it != segments_.begin()) --it;
  }
  const Vec4 y = it->dense.At(std::min(t_s, it->t1));
  out.t_s = t_s;
  out.theta_rad[0] = y[0];
  out.omega_radps[0] = y[2];
  if (blocks_ == 2) {
    out.theta_rad[1] = y[1];
    out.omega_radps[1] = y[3];
  }
  out.mode = ConfigurationOf(it->mode, blocks_);
  return out;
}

}  // namespace rockbench::reference
