#include <algorithm>

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
  Sample out;
  if (segments_.empty()) return out;
  t_s = std::clamp(t_s, segments_.front().t0, segments_.back().t1);
  // The last segment starting at or before t (post-event state at an event time).
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                             [](double t, const Segment& s) { return t < s.t0; });
  if (it != segments_.begin()) --it;
  const Vec4 y = it->dense.At(std::min(t_s, it->t1));
  out.t_s = t_s;
  out.theta1_rad = y[0];
  out.theta2_rad = y[1];
  out.omega1_radps = y[2];
  out.omega2_radps = y[3];
  out.mode = it->mode;
  return out;
}

}  // namespace rockbench::reference
