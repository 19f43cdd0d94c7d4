#include "report/common/interpolation.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace rockbench::report {

HistoryInterpolator::HistoryInterpolator(const History& history, const std::vector<Event>& events) {
  // Pre-event rates by event time: the first event at a time holds the rates before them all.
  std::map<double, const Event*> first_event;
  for (const Event& e : events) first_event.emplace(e.t_s, &e);
  // One block or two: a single block's "block 2" is the block itself. N >= 3: every block.
  width_ = std::max(history.blocks, 2);
  const auto block = [&](int k) {
    return history.blocks == 1 ? size_t{0} : static_cast<size_t>(k);
  };
  const auto fill = [&](std::vector<double>& out, const BlockValues& v) {
    out.resize(static_cast<size_t>(width_));
    for (int k = 0; k < width_; ++k) out[k] = v[std::min(block(k), v.size() - 1)];
  };
  for (const Sample& s : history.samples) {
    if (!nodes_.empty() && s.t_s <= nodes_.back().t) {
      // Several samples at one instant (a cascade of events): keep the last state after it.
      Node& n = nodes_.back();
      fill(n.theta, s.theta_rad);
      fill(n.rate_right, s.omega_radps);
      continue;
    }
    Node n;
    n.t = s.t_s;
    fill(n.theta, s.theta_rad);
    fill(n.rate_right, s.omega_radps);
    n.rate_left = n.rate_right;
    if (const auto it = first_event.find(s.t_s); it != first_event.end()) {
      fill(n.rate_left, it->second->omega_before_radps);
    }
    nodes_.push_back(std::move(n));
  }
  if (nodes_.empty()) throw std::invalid_argument("HistoryInterpolator: empty history");
}

std::vector<double> HistoryInterpolator::Angles(double t) const {
  if (t <= nodes_.front().t) return nodes_.front().theta;
  if (t >= nodes_.back().t) return nodes_.back().theta;
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
  std::vector<double> out(static_cast<size_t>(width_));
  for (int k = 0; k < width_; ++k) {
    out[k] =
        h00 * a.theta[k] + h10 * h * a.rate_right[k] + h01 * b.theta[k] + h11 * h * b.rate_left[k];
  }
  return out;
}

double HistoryInterpolator::end_s() const {
  return nodes_.back().t;
}

}  // namespace rockbench::report
