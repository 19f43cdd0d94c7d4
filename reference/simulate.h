#pragma once
/// The reference model: the thesis's two-block rocking model (Roussis 1999), event-accurate.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "reference/integrator.h"
#include "scene/ground_motion.h"
#include "scene/history.h"
#include "scene/outcome.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// Continuous solution: piecewise dense-output segments between events. Evaluating at an event
/// time returns the post-event state.
class Trajectory {
 public:
  /// State at t (clamped to [0, end]); interpolated with the integrator's dense output.
  Sample At(double t_s) const;
  double end_s() const;
  bool empty() const;

  /// One integration step's interpolant on [t0, t1] (see integrator.h, DenseStep).
  struct Segment {
    double t0 = 0.0, t1 = 0.0;
    Mode mode = Mode::kRest;
    DenseStep dense;
  };
  /// One block or two (the samples At() gives have this many).
  void set_blocks(int blocks) { blocks_ = blocks; }
  int blocks() const { return blocks_; }
  void Append(Segment segment);
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  std::vector<Segment> segments_;
  int blocks_ = 2;
};

/// Summary figures of a reference run.
struct Summary {
  /// completed | overturned | at_rest | assumption_violated | non_finite
  RunStatus status = RunStatus::kCompleted;
  std::string status_detail;  ///< why, for assumption_violated and non_finite
  /// For status non_finite: the first quantity found not finite ("theta2", "omega1", "energy",
  /// "event time", "normal force at rest"), its value ("NaN", "+inf", "-inf") and the time it
  /// was computed for, s. The run (history, trajectory, peaks, counts) ends at its last finite
  /// state, non_finite_last_t_s (s): nothing after it was computed.
  std::string non_finite_quantity, non_finite_value;
  double non_finite_t_s = 0.0, non_finite_last_t_s = 0.0;
  std::optional<int> overturn_block;  ///< 1..N
  double overturn_t_s = 0.0;
  /// Peak |theta_k| and its time, one entry per block (block k at k - 1).
  std::vector<double> peak_theta_rad, peak_theta_t_s;
  /// Per interface, one entry per block: [0] block 1 (or the stack) on the ground, [k] block
  /// k + 1 on block k. Impacts there; the largest |T|/N the contact needed; its smallest normal
  /// reaction over the step ends, N (+infinity when the run took no step).
  std::vector<int> impacts_at;
  std::vector<double> friction_required;
  std::vector<double> min_normal_n;
  int impacts_inadmissible = 0;  ///< no thesis outcome was admissible (see README)
  int impacts_energy_gain = 0;   ///< impacts that would add energy (must stay 0)
  int transitions = 0;           ///< mode changes without impact
  int initiations = 0;           ///< starts from rest
  long steps_accepted = 0, steps_rejected = 0, rhs_evaluations = 0;

  /// No blocks (fill it, or build it for a number of blocks).
  Summary() = default;
  /// The summary of a run of `blocks` blocks before it starts.
  explicit Summary(int blocks)
      : peak_theta_rad(static_cast<size_t>(blocks), 0.0),
        peak_theta_t_s(static_cast<size_t>(blocks), 0.0),
        impacts_at(static_cast<size_t>(blocks), 0),
        friction_required(static_cast<size_t>(blocks), 0.0),
        min_normal_n(static_cast<size_t>(blocks), std::numeric_limits<double>::infinity()) {}
  int blocks() const { return static_cast<int>(peak_theta_rad.size()); }
  /// Impacts of block 1 (or the stack) on the ground.
  int impacts_ground() const { return impacts_at.empty() ? 0 : impacts_at[0]; }
  /// Impacts at every interface between blocks.
  int impacts_interface() const { return impacts() - impacts_ground(); }
  int impacts() const {
    int n = 0;
    for (const int i : impacts_at) n += i;
    return n;
  }
};

struct Result {
  History history;        ///< samples at the output interval plus every event time
  Trajectory trajectory;  ///< dense solution for comparison at any time
  Summary summary;
};

/// Runs the reference model on a scene of one or two blocks. Never throws for physics outcomes
/// (overturning, assumption violations are statuses); throws SceneError for impossible settings
/// and for a scene of three or more blocks (not simulated yet: issue 23). A state,
/// energy, event time or contact force that is not finite (an absurd base motion built in code)
/// ends the run with status "non_finite" at its last finite state: no NaN or infinity reaches
/// the history, the events or the summary.
Result Simulate(const Scene& scene, const GroundMotion& motion);

}  // namespace rockbench::reference
