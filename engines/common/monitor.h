#pragma once
/// Watches an engine's run step by step, whatever the engine and the number of blocks N: reads
/// the thesis's angles back from the bodies' poses, infers the configuration (one contact per
/// interface), detects impacts and mode changes per interface, and measures what the model
/// forbids (slip at any interface, uplift, penetration, energy growth without input, blow-up,
/// out-of-plane motion). Interface k is block k on its support: the ground for k = 1, block
/// k - 1 above it; every per-interface quantity is block k's relative to its support, in the
/// support's frame. For one and two blocks every output is the one the two-block monitor gave.
#include <array>
#include <cstdint>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/outcome.h"
#include "engines/common/engine_input.h"
#include "scene/history.h"
#include "scene/mode.h"
#include "scene/rigid_block.h"

namespace rockbench {

/// The flags of RunOutcome::violations, in order.
inline constexpr const char* kViolationFlags[] = {"sliding", "uplift", "penetration",
                                                  "energy_growth", "blow_up"};

/// Thresholds of the monitor. Angles in rad, rates in rad/s, lengths in m.
struct MonitorConfig {
  /// The mode of a state is the reference's rule (scene/mode.h TiltContact and ModeOf, which
  /// the reference's ModeOfState applies) with the thresholds below, above the engines' noise: the
  /// reference's exact states need none, but two bodies of an engine tilted together differ by
  /// ~1e-13 rad, which the exact rule would read as block 2 rocking on block 1. A block (or block 2
  /// on block 1) counts as tilted to a side once |angle| exceeds angle_enter_rad, and as landed
  /// once its angle falls below angle_leave_rad (hysteresis, so numerical noise at rest does not
  /// chatter).
  double angle_enter_rad = 1e-5;
  double angle_leave_rad = 5e-6;
  /// A flat block (|angle| below angle_enter_rad) turning faster than this is passing through
  /// zero and is taken to rock towards the side of its rate; slower, it counts as still (mode
  /// rest or 4). 1e-2 rad/s leaves a flat band of at most 1e-5 / 1e-2 = 1 ms, so micro-rocking
  /// below the angle threshold does not make the mode chatter.
  double rate_tol_radps = 1e-2;
  /// A block whose lowest corner is higher than this above its support has no contact: uplift.
  double uplift_tol_m = 1e-5;
  /// Flags in the summary: slip above this fraction of the block's width is "sliding",
  /// penetration deeper than penetration_flag_m is "penetration", energy gained without base
  /// input above energy_growth_flag_rel of the tipping energy is "energy_growth".
  double slip_flag_rel = 1e-3;
  double penetration_flag_m = 1e-4;
  double energy_growth_flag_rel = 0.01;
  /// The verdict's scale of the contact flags (compare/verdict.h): uplift or penetration of
  /// a block counts against it once it exceeds this fraction of the block's critical angle
  /// alpha times its width B: a corner moved by d tilts the block by d / B, so this is 10% of
  /// the comparison's smallest tolerance (1% of alpha, run/tolerance.h), the same 10% of
  /// the scale the comparison applies to angles. Below it, the flag is reported only. Sliding
  /// counts as flagged (slip_flag_rel).
  double significant_critical_fraction = 1e-3;
  /// Blow-up: |rate| above blow_up_rate_radps, or energy gained without input above
  /// blow_up_energy_rel times the tipping energy. The run stops there. (A pose, velocity or
  /// energy that is not finite stops it too, with status "non_finite"; the blow_up flag is
  /// raised with it.)
  double blow_up_rate_radps = 1e3;
  double blow_up_energy_rel = 1.0;
  /// With EngineInput::stop_at_rest_after_s: the run stops once every block has been at rest
  /// (mode rest: no block tilted beyond angle_enter_rad) for this long after that time.
  double settled_for_s = 0.1;
  // No overturn setting here: a block overturns when |theta| reaches EngineInput::overturn_rad
  // (the scene's model.overturn_angle, the reference's definition), at the time interpolated
  // inside the step that crossed it.
};

/// One body's planar pose and velocity as read from the engine (world frame): mass centre (m), the
/// first column of its rotation (cos phi, sin phi) with phi the CCW angle about +z, centre
/// velocity (m/s) and CCW angular velocity (rad/s).
struct BodyReadout {
  double x_m = 0.0, y_m = 0.0, cos_phi = 1.0, sin_phi = 0.0;
  double vx_mps = 0.0, vy_mps = 0.0, w_radps = 0.0;
};

/// The state after a step.
struct StepReadout {
  double t_s = 0.0;
  /// Block k's body at index k - 1, bottom first: one per block of the stack (the monitor
  /// refuses a readout of another size).
  std::vector<BodyReadout> blocks;
  /// Base frame origin in the world (the ground top's reference point) and its velocity; zero
  /// for the inertial drive.
  double ground_x_m = 0.0, ground_y_m = 0.0, ground_vx_mps = 0.0, ground_vy_mps = 0.0;
  /// Largest out-of-plane displacement (|z - z0|, m) and rotation (rad) of the blocks.
  double out_of_plane_m = 0.0, out_of_plane_rad = 0.0;
  /// Whether the base accelerated during the step that ended here.
  bool base_accelerating = false;
  /// The engine's own report that an internal check failed in the step on a value that is not
  /// finite (ODE's assertion on a quaternion it cannot normalise), in its words; empty: none.
  /// The monitor ends the run there with status non_finite, as for a pose that is not finite.
  std::string engine_fault;

  StepReadout() = default;
  /// A readout of `blocks` bodies, each at the origin, upright and still.
  explicit StepReadout(int blocks) : blocks(static_cast<size_t>(blocks)) {}
};

/// Fills the base's part of the state after step n from the run input: the ground's position and
/// velocity (kinematic drive), and whether the base accelerated during the step that ended at
/// t_n (faster than 1e-4 m/s^2: below that, the kinematic drive's baseline tail and the rounding
/// of u's second difference, it counts as no base input for the energy check).
void ReadBaseMotion(const EngineInput& input, std::int64_t n, StepReadout* s);

class Monitor {
 public:
  explicit Monitor(const EngineInput& input, MonitorConfig config = {});

  /// The state at t = 0 (first sample).
  void Start(const StepReadout& s);
  /// The state after step n (1-based). Returns false when the run must stop (overturn, a block
  /// that left its support, blow-up, a state that is not finite). A block k >= 2 leaves its
  /// support (status left_support, not an overturn) once its base's middle point is further
  /// from the support's top middle, along the support's top face, than b_k + b_(k-1): the two
  /// faces no longer overlap (the reference's "slid off its support"); block 1 never leaves
  /// the ground, which is infinite. The time is the interpolated crossing inside the step. The
  /// overturn time is the interpolated crossing of model.overturn_angle inside the step; the last
  /// sample is the state at the step's end. A pose, velocity (of a block or of the ground) or
  /// energy that is not finite ends the run with status "non_finite" at the last finite state: the
  /// step is not recorded, a "non_finite" event is, and status_detail names the quantity, its value
  /// and the time.
  bool Step(std::int64_t n, const StepReadout& s);
  /// Ends the run: records the last state as a sample if it was not one.
  void Finish();

  const History& history() const { return history_; }
  History TakeHistory() { return std::move(history_); }
  /// The monitor's part of the summary: status, peaks, impact counts, violations.
  nlohmann::json Summary() const;
  /// The typed outcome (the same numbers as Summary()).
  RunOutcome Outcome() const;
  RunStatus status() const { return status_; }
  /// Last state read, in the thesis's convention.
  const Sample& last() const { return last_; }

 private:
  // Hysteresis side of one interface's relative tilt (interface k: block 1's tilt on the
  // ground, block k's tilt relative to block k - 1).
  struct Side {
    int side = 0;       // armed side: +1 right, -1 left, 0 flat
    double prev = 0.0;  // previous angle
  };
  struct Derived {
    explicit Derived(int blocks, bool slip_and_lift = false)
        : sample(blocks, slip_and_lift),
          gap_m(static_cast<size_t>(blocks), 0.0),
          pivot_x_m(static_cast<size_t>(blocks), 0.0),
          base_offset_m(static_cast<size_t>(blocks), 0.0) {}
    Sample sample;
    // Per interface k (index k - 1): block k's lowest corner above its support (block 1: any
    // corner above the ground; block k >= 2: a base corner above block k - 1's top face, in
    // block k - 1's frame), m; and block k's pivot along its support (block 1: x in the base
    // frame; block k: x in block k - 1's frame), m.
    std::vector<double> gap_m, pivot_x_m;
    // Per block k >= 2 (index k - 1): the middle of its base from the middle of its support's
    // top face, along that face (block k - 1's frame), m; 0 for block 1.
    std::vector<double> base_offset_m;
    double energy_j = 0.0;  // kinetic (base frame) + m g y_G of every block, J, as the reference
  };
  Derived Derive(const StepReadout& s);
  // Block k's slip u_k and lift z_k (index k) on its support, into d's sample (Sample::u_m,
  // z_m; docs/sliding.md): the support's top face has its middle point (xs, ys) + R(0, hs) and
  // the CCW angle whose cosine and sine are cs, ss; the block's centre is (x, y), its CCW
  // angle's cosine and sine c, sn; base frame, m.
  void SlipAndLift(int k, double x, double y, double c, double sn, double xs, double ys, double cs,
                   double ss, double hs, Derived* d) const;
  // The landing of one interface in a step (its tilted block's relative angle crossing zero or
  // falling below angle_leave_rad), from the hysteresis before the step.
  struct Landing {
    bool landed = false, crossed = false;
    double t_s = 0.0;         // the interpolated zero crossing (or the step's end)
    int side_before = 0;      // the side before the step
    double angle = 0.0;       // the interface's relative angle after the step
    double angle_prev = 0.0;  // and before it
  };
  // Updates the hysteresis with the step's state and sets landings_ (t_prev: the step's start).
  void DetectLandings(const Sample& cur, double t_prev);
  // Completes the pending impacts the step resolves (their post-impact state is `d`).
  void CompletePendingImpacts(const Derived& d);
  // Opens a pending impact per landing, with the state before the step as the pre-impact one.
  void OpenImpacts();
  // A mode change without impact: an initiation, a transition or a rest event.
  void RecordModeChange(const Derived& d);
  // The side interface k pivots on (+1 right, -1 left, 0 flat): the hysteresis's side, or for
  // a flat tilt the side of its relative rate above MonitorConfig::rate_tol_radps.
  int TiltSide(const Sample& s, int k) const;
  // The configuration of those sides, one contact per interface.
  Configuration InferMode(const Sample& s) const;
  // Pivot points of the state (for slip), into d, and the side of each interface, into
  // sides[0..blocks_).
  void Pivots(const StepReadout& s, Derived* d, int* sides) const;
  void Record(const Sample& s);
  // Slip, drift, uplift, penetration and out-of-plane motion of the step (sets d's pivots).
  void MeasureContacts(const StepReadout& s, Derived* d);
  // Peaks, the largest rate, and energy gained while the base is still.
  void MeasurePeaksAndEnergy(const Derived& d, bool base_accelerating);
  // Records the step's state if it is the one nearest to the next output time.
  void RecordOutput(const Sample& cur, double t);
  // Whether the run must stop after the step that produced `d` (overturn, settled at rest,
  // blow-up); sets the status. |theta| of every block before the step: abs_prev_.
  bool Stopped(const Derived& d, double t_prev);
  void PushEvent(Event e);
  // Which flags of kViolationFlags the run has raised so far.
  std::array<bool, std::size(kViolationFlags)> Raised() const;
  // The same at the verdict's scale (MonitorConfig::significant_critical_fraction).
  std::array<bool, std::size(kViolationFlags)> RaisedSignificantly() const;
  // Dates the flags raised for the first time at t_s.
  void NoteOnsets(double t_s);
  // Ends the run at the last finite state (last_): `quantity` is `value` ("NaN", "+inf",
  // "-inf", "not finite") at t_s, in step n; `why`, when not empty, is added to the detail.
  void StopNonFinite(const std::string& quantity, const std::string& value, double t_s,
                     std::int64_t n, const std::string& why = "");
  // Throws std::invalid_argument when a readout does not hold one body per block.
  void CheckBodies(const StepReadout& s) const;

  EngineInput in_meta_;  // geometry and settings (drive samples not kept)
  MonitorConfig cfg_;
  int blocks_ = 1;              // N
  bool slip_and_lift_ = false;  // samples carry u_m and z_m (EngineInput::slip_and_lift)
  // Per block (block k at k - 1): half width and height (m), mass (kg), properties for the
  // energy (scene/rigid_block.h).
  std::vector<double> b_, h_, m_;
  std::vector<BlockProps> props_;
  double g_ = 9.81, dt_ = 0.0, out_dt_ = 0.0, tipping_energy_j_ = 0.0;

  History history_;
  Sample last_{1};
  Derived prev_{1};
  std::vector<Side> hysteresis_;     // per interface
  std::vector<double> phi_;          // unwrapped CCW angles, per block
  std::vector<Landing> landings_;    // per interface, the last step's
  double landings_t_prev_ = 0.0;     // the start of that step, s
  std::vector<double> abs_prev_;     // |theta| of every block before the step being read
  std::vector<double> offset_prev_;  // |base_offset_m| of every block before that step
  std::vector<int> side_now_;        // scratch: the sides of the step being read
  std::int64_t next_out_ = 1;        // index of the next output time
  bool last_recorded_ = false;

  // Pending impacts: completed with the state one step later (a fixed-step engine such as
  // Bullet may resolve a contact in the step after the one that brought the corner down).
  struct PendingImpact {
    explicit PendingImpact(int blocks) : event(blocks) {}
    Event event;
    int interface = 0;     // the interface that landed (0: block 1 on the ground)
    int side = 0;          // side its block was tilted to before it landed
    bool crossed = false;  // its angle has crossed zero
    int waited = 0;        // steps waited without crossing
  };
  std::vector<PendingImpact> pending_;
  std::vector<int> pivot_side_;  // pivot side of each interface in the last state (for the slip)
  int suppress_mode_events_ = 0;
  double rest_since_s_ = -1.0;  // start of the current stretch at rest (mode rest); -1: moving

  // Peaks, per block.
  std::vector<double> peak_, peak_t_;
  // Counts: impacts per interface.
  std::vector<int> impacts_at_;
  int transitions_ = 0, initiations_ = 0, rests_ = 0;
  // Violations, per interface.
  struct ContactWatch {
    double slip_m = 0.0, drift_max_m = 0.0;
    double uplift_s = 0.0, uplift_max_m = 0.0;
    int uplift_episodes = 0;
    bool airborne = false;
    double penetration_max_m = 0.0;
  };
  std::vector<ContactWatch> contacts_;
  double energy_min_free_j_ = 0.0, energy_gain_max_j_ = 0.0, energy_gain_t_s_ = 0.0;
  bool free_ = false;
  double out_of_plane_m_ = 0.0, out_of_plane_rad_ = 0.0;
  double max_rate_radps_ = 0.0;
  // When each flag of kViolationFlags was first raised at the verdict's scale (NaN: not yet).
  std::array<double, std::size(kViolationFlags)> significant_t_s_ = {kNoOnset, kNoOnset, kNoOnset,
                                                                     kNoOnset, kNoOnset};
  // Per block, MonitorConfig::significant_critical_fraction times alpha B, m.
  std::vector<double> significant_m_;
  // When each flag of kViolationFlags was first raised (NaN: not yet).
  std::array<double, std::size(kViolationFlags)> onset_t_s_ = {kNoOnset, kNoOnset, kNoOnset,
                                                               kNoOnset, kNoOnset};
  static constexpr double kNoOnset = std::numeric_limits<double>::quiet_NaN();

  RunStatus status_ = RunStatus::kCompleted;
  std::string status_detail_;
  // Status non_finite: the quantity, its value in words and the time it was read, s.
  std::string non_finite_quantity_, non_finite_value_;
  double non_finite_t_s_ = 0.0;
  int overturn_block_ = 0;
  double overturn_t_s_ = 0.0, end_t_s_ = 0.0;
  int left_support_block_ = 0;  // 0: none; 2..N: the block that left its support
  double left_support_t_s_ = 0.0;
  std::int64_t steps_done_ = 0;
};

}  // namespace rockbench
