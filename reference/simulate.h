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
  void Append(Segment segment);
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  std::vector<Segment> segments_;
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
  std::optional<int> overturn_block;  ///< 1 or 2
  double overturn_t_s = 0.0;
  double peak_theta1_rad = 0.0, peak_theta1_t_s = 0.0;  ///< peak |theta1| and its time
  double peak_theta2_rad = 0.0, peak_theta2_t_s = 0.0;
  int impacts_ground = 0;                    ///< block 1 (or the stack) hits the ground
  int impacts_interface = 0;                 ///< block 2 hits block 1
  int impacts_inadmissible = 0;              ///< no thesis outcome was admissible (see README)
  int impacts_energy_gain = 0;               ///< impacts that would add energy (must stay 0)
  int transitions = 0;                       ///< mode changes without impact
  int initiations = 0;                       ///< starts from rest
  double friction_required_ground = 0.0;     ///< max |T|/N at the ground contact
  double friction_required_interface = 0.0;  ///< max |T|/N at the block-1/block-2 contact
  /// Smallest normal reaction at the ground and at the interface (two blocks) over the step
  /// ends, N; +infinity when the run took no step.
  double min_normal_ground_n = std::numeric_limits<double>::infinity();
  double min_normal_interface_n = std::numeric_limits<double>::infinity();
  long steps_accepted = 0, steps_rejected = 0, rhs_evaluations = 0;
};

struct Result {
  History history;        ///< samples at the output interval plus every event time
  Trajectory trajectory;  ///< dense solution for comparison at any time
  Summary summary;
};

/// Runs the reference model on a scene. Never throws for physics outcomes (overturning,
/// assumption violations are statuses); throws SceneError for impossible settings. A state,
/// energy, event time or contact force that is not finite (an absurd base motion built in code)
/// ends the run with status "non_finite" at its last finite state: no NaN or infinity reaches
/// the history, the events or the summary.
Result Simulate(const Scene& scene, const GroundMotion& motion);

}  // namespace rockbench::reference
