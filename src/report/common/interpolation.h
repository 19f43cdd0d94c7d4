#pragma once
/// The reference's angles at any time from its history: what the run report's error figure
/// compares each engine's samples with.
#include <array>
#include <vector>

#include "scene/history.h"

namespace rockbench::report {

/// Angles of a reference history at any time: cubic Hermite between samples, using the rates
/// before each event (events.csv omega*_before) at the end of the interval it closes, so that
/// impacts do not smear. Clamped to the history's time span.
class HistoryInterpolator {
 public:
  HistoryInterpolator(const History& history, const std::vector<Event>& events);
  /// (theta1, theta2) at t, rad.
  std::array<double, 2> Angles(double t_s) const;
  double end_s() const;

 private:
  struct Node {
    double t = 0.0;
    double theta[2] = {0, 0};
    double rate_right[2] = {0, 0};  ///< rates just after t
    double rate_left[2] = {0, 0};   ///< rates just before t (differ at an impact)
  };
  std::vector<Node> nodes_;
};

}  // namespace rockbench::report
