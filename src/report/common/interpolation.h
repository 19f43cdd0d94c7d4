#pragma once
/// The reference's angles at any time from its history: what the run report's error figure
/// compares each engine's samples with.
#include <vector>

#include "scene/history.h"

namespace rockbench::report {

/// Angles of a reference history at any time: cubic Hermite between samples, using the rates
/// before each event (events.csv omega*_before) at the end of the interval it closes, so that
/// impacts do not smear. Clamped to the history's time span.
class HistoryInterpolator {
 public:
  HistoryInterpolator(const History& history, const std::vector<Event>& events);
  /// Every block's angle at t, rad: (theta1, theta2) for one or two blocks (a single block's
  /// "block 2" is the block itself), (theta1, ..., thetaN) for N >= 3.
  std::vector<double> Angles(double t_s) const;
  double end_s() const;

 private:
  struct Node {
    double t = 0.0;
    std::vector<double> theta;
    std::vector<double> rate_right;  ///< rates just after t
    std::vector<double> rate_left;   ///< rates just before t (differ at an impact)
  };
  int width_ = 2;  ///< angles per node
  std::vector<Node> nodes_;
};

}  // namespace rockbench::report
