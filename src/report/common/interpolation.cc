#include "report/common/interpolation.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace rockbench::report {

HistoryInterpolator::HistoryInterpolator(const History& history, const std::vector<Event>& events) {
  // Pre-event rates by event time: the first event at a time holds the rates before them all.
  std::map<double, const Event*> first_event;
  for (const Event& e : events) first_event.emplace(e.t_s, &e);
  // One block or two: a single block's "block 2" is the block itself.
  const size_t top = history.blocks == 2 ? 1 : 0;
  for (const Sample& s : history.samples) {
    const double th2 = s.theta_rad[top];
    const double w2 = s.omega_radps[top];
    if (!nodes_.empty() && s.t_s <= nodes_.back().t) {
      // Several samples at one instant (a cascade of events): keep the last state after it.
      Node& n = nodes_.back();
      n.theta[0] = s.theta_rad[0];
      n.theta[1] = th2;
      n.rate_right[0] = s.omega_radps[0];
      n.rate_right[1] = w2;
      continue;
    }
    Node n;
    n.t = s.t_s;
    n.theta[0] = s.theta_rad[0];
    n.theta[1] = th2;
    n.rate_right[0] = n.rate_left[0] = s.omega_radps[0];
    n.rate_right[1] = n.rate_left[1] = w2;
    if (const auto it = first_event.find(s.t_s); it != first_event.end()) {
      const BlockValues& w = it->second->omega_before_radps;
      n.rate_left[0] = w[0];
      n.rate_left[1] = w.size() > top ? w[top] : w[0];
    }
    nodes_.push_back(n);
  }
  if (nodes_.empty()) throw std::invalid_argument("HistoryInterpolator: empty history");
}

std::array<double, 2> HistoryInterpolator::Angles(double t) const {
  if (t <= nodes_.front().t) return {nodes_.front().theta[0], nodes_.front().theta[1]};
  if (t >= nodes_.back().t) return {nodes_.back().theta[0], nodes_.back().theta[1]};
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t,
                                   [](double v, const Node& n) { return v < n.t; });
  const Node& b = *it;
  const Node& a = *(it - 1);
  const double h = b.t - a.t;
  const double s = (t - a.t) / h;
  const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
  const double h10 = s * (1.0 - s) * (1.0 - s);
  const double h01 = s * s * (3.0 - 2.0 * s);
  const double h11 = s * s * (s - 1.0);
  std::array<double, 2> out{};
  for (int k = 0; k < 2; ++k) {
    out[k] =
        h00 * a.theta[k] + h10 * h * a.rate_right[k] + h01 * b.theta[k] + h11 * h * b.rate_left[k];
  }
  return out;
}

double HistoryInterpolator::end_s() const {
  return nodes_.back().t;
}

}  // namespace rockbench::report
