#include <algorithm>
#include <array>
#include <iterator>

#include "reference/simulate.h"

namespace rockbench::reference {

bool Trajectory::empty() const {
  return segments_.empty();
}

double Trajectory::end_s() const {
  return segments_.empty() ? 0.0 : segments_.back().t1;
}

std::vector<Trajectory::Segment>::const_iterator Trajectory::SegmentFrom(double t_s) const {
  // The last one for the samples a run records as it goes, else found by bisection.
  auto it = std::prev(segments_.end());
  if (t_s < it->t0) {
    it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                          [](double t, const Segment& s) { return t < s.t0; });
    if (it != segments_.begin()) --it;
  }
  return it;
}

void Trajectory::StateComponents(std::vector<Segment>::const_iterator it, double t_s,
                                 double* out) const {
  const Step& step = steps_[static_cast<size_t>(it - segments_.begin())];
  const double t = std::clamp(t_s, it->t0, it->t1);
  // The view's state: its components one after the other.
  const size_t m = static_cast<size_t>(view_->components());
  const double* c = chunks_[step.chunk].data() + step.pos;
  // As DenseStepN::At: a constant step (or one of zero length) is its first coefficient.
  const bool constant = step.kind == DenseKinds::kConstant || step.h == 0.0;
  const double s = constant ? 0.0 : (t - step.t0) / step.h;
  for (size_t i = 0; i < m; ++i) {
    out[i] = constant ? c[i] : DenseKinds::Component(step.kind, s, c + i, m);
  }
}

Sample Trajectory::At(double t_s) const {
  Sample out(blocks_, slip_and_lift_);
  if (segments_.empty()) return out;
  t_s = std::clamp(t_s, segments_.front().t0, segments_.back().t1);
  // The last segment starting at or before t (post-event state at an event time).
  const auto it = SegmentFrom(t_s);
  const Step& step = steps_[static_cast<size_t>(it - segments_.begin())];
  if (step.state) {
    // The unilateral model's state: 6 components a block.
    std::array<double, 6 * kUnilateralMaxBlocks> buffer{};
    StateComponents(it, t_s, buffer.data());
    view_->Fill(buffer.data(), &out);
  } else {
    const double t = std::min(t_s, it->t1);
    const size_t stride = 2 * static_cast<size_t>(blocks_);
    const double* c = chunks_[step.chunk].data() + step.pos;
    // As DenseStepN::At: a constant step (or one of zero length) is its first coefficient.
    const bool constant = step.kind == DenseKinds::kConstant || step.h == 0.0;
    const double s = constant ? 0.0 : (t - step.t0) / step.h;
    auto value = [&](size_t i) {
      return constant ? c[i] : DenseKinds::Component(step.kind, s, c + i, stride);
    };
    for (int i = 0; i < blocks_; ++i) {
      out.theta_rad[i] = value(static_cast<size_t>(i));
      out.omega_radps[i] = value(static_cast<size_t>(blocks_ + i));
    }
  }
  out.t_s = t_s;
  out.mode = it->mode;
  return out;
}

std::vector<double> Trajectory::StateAt(double t_s, bool before_event) const {
  if (segments_.empty() || !view_) return {};
  t_s = std::clamp(t_s, segments_.front().t0, segments_.back().t1);
  // Before an event at t: the first segment that ends at or after t; after it: the last that
  // starts at or before it.
  auto it = before_event ? std::lower_bound(segments_.begin(), segments_.end(), t_s,
                                            [](const Segment& s, double t) { return s.t1 < t; })
                         : SegmentFrom(t_s);
  if (it == segments_.end()) it = std::prev(segments_.end());
  if (!steps_[static_cast<size_t>(it - segments_.begin())].state) return {};
  std::vector<double> out(static_cast<size_t>(view_->components()));
  StateComponents(it, t_s, out.data());
  return out;
}

Event ModeChangeEvent(int n, double t_s, std::string kind, const Configuration& before,
                      const Configuration& after, const double* omega_before,
                      const double* omega_after, int stride) {
  Event ev(n);
  ev.t_s = t_s;
  ev.kind = std::move(kind);
  ev.mode_before = before;
  ev.mode_after = after;
  for (int i = 0; i < n; ++i) {
    ev.omega_before_radps[i] = omega_before[i * stride];
    ev.omega_after_radps[i] = omega_after[i * stride];
  }
  return ev;
}

void EmitTrajectorySamples(const Trajectory& trajectory, double dt_s, double run_end_s,
                           double t_end_s, bool inclusive, long* next,
                           std::vector<Sample>* samples) {
  while (true) {
    const double ts = static_cast<double>(*next) * dt_s;
    if (ts > run_end_s + 1e-12 * run_end_s) break;
    if (inclusive ? ts > t_end_s : ts >= t_end_s) break;
    samples->push_back(trajectory.At(ts));
    samples->back().t_s = ts;
    ++*next;
  }
}

}  // namespace rockbench::reference
