#pragma once
/// The reference model: the thesis's rocking-block model (Roussis 1999) for a stack of N blocks,
/// with its unilateral model past the rigid chain's assumptions, event-accurate.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "reference/integration/integrator.h"
#include "scene/history.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// An allocator whose vectors leave new doubles uninitialised (resize without a fill: every
/// one is written before it is read).
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) {}
  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// How a trajectory segment's state of another layout than the chain's (angles, then rates)
/// becomes a sample: the unilateral model's maximal coordinates (unilateral_run.h).
class StateView {
 public:
  virtual ~StateView() = default;
  /// Components of the state.
  virtual int components() const = 0;
  /// Fills the sample's angles, rates, slip and lift from a state (the mode is the segment's).
  virtual void Fill(const double* state, Sample* out) const = 0;
};

/// Continuous solution: piecewise dense-output segments between events. Evaluating at an event
/// time returns the post-event state. Each segment keeps only the stack's own components (its
/// blocks' angles and rates, or the unilateral model's state), whatever the size of the state
/// the driver integrates.
class Trajectory {
 public:
  /// A trajectory of `blocks` blocks (1..kMaxBlocks); with slip and lift, its samples carry
  /// them (zero on the chain's segments: no slip, every pivot on its support).
  explicit Trajectory(int blocks = 2, bool slip_and_lift = false)
      : blocks_(blocks), slip_and_lift_(slip_and_lift) {}
  int blocks() const { return blocks_; }

  /// Segments appended from here with AppendState hold states that `view` reads.
  void SetStateView(std::shared_ptr<const StateView> view) { view_ = std::move(view); }
  /// Appends the step `dense` on [t0, t1] of a state whose components are those of the view
  /// (set first): its first view->components() / 2 at index 0 on, the rest at index `second`
  /// on.
  template <size_t D>
  void AppendState(double t0, double t1, const Configuration& mode, const DenseStepN<D>& dense,
                   size_t second) {
    segments_.push_back({t0, t1, mode});
    const size_t half = static_cast<size_t>(view_->components()) / 2;
    const size_t need = 2 * half * static_cast<size_t>(DenseKinds::Coefficients(dense.kind));
    double* out = Reserve(need);
    steps_.push_back({dense.kind, dense.t0, dense.h, static_cast<uint32_t>(chunks_.size() - 1),
                      static_cast<uint32_t>(used_), true});
    used_ += need;
    const size_t coefficients = need / (2 * half);
    for (size_t j = 0; j < coefficients; ++j, out += 2 * half) {
      std::copy_n(dense.c[j].data(), half, out);
      std::copy_n(dense.c[j].data() + second, half, out + half);
    }
  }

  /// State at t (clamped to [0, end]); interpolated with the integrator's dense output.
  Sample At(double t_s) const;
  /// The state view's components at t (the unilateral model's q then v, 3 per block each), from
  /// the segment that ends at t when `before_event` (the state just before an event at t), else
  /// from the one that starts there (just after it); empty where the trajectory holds the
  /// chain's angles and rates instead.
  std::vector<double> StateAt(double t_s, bool before_event) const;
  double end_s() const;
  bool empty() const;

  /// One integration step's interval [t0, t1] and the configuration the stack moved in.
  struct Segment {
    double t0 = 0.0, t1 = 0.0;
    Configuration mode;
  };
  const std::vector<Segment>& segments() const { return segments_; }

  /// Appends the step `dense` on [t0, t1] of a state whose block i has its angle at index i
  /// and its rate at index cap + i.
  template <size_t D>
  void Append(double t0, double t1, const Configuration& mode, const DenseStepN<D>& dense,
              size_t cap = D / 2) {
    segments_.push_back({t0, t1, mode});
    const size_t n = static_cast<size_t>(blocks_);
    const size_t need = 2 * n * static_cast<size_t>(DenseKinds::Coefficients(dense.kind));
    double* out = Reserve(need);
    steps_.push_back({dense.kind, dense.t0, dense.h, static_cast<uint32_t>(chunks_.size() - 1),
                      static_cast<uint32_t>(used_)});
    used_ += need;
    const size_t coefficients = need / (2 * n);
    if (n == cap && 2 * cap == D) {
      // The stack fills the state: each coefficient's angles and rates are already in place.
      // (A copy of a constant size, which the compiler writes inline.)
      for (size_t j = 0; j < coefficients; ++j, out += D) {
        std::memcpy(out, dense.c[j].data(), sizeof(double) * D);
      }
    } else {
      for (size_t j = 0; j < coefficients; ++j, out += 2 * n) {
        std::copy_n(dense.c[j].data(), n, out);
        std::copy_n(dense.c[j].data() + cap, n, out + n);
      }
    }
  }

 private:
  // Room for `need` doubles at the end of the last chunk (a step's coefficients never straddle
  // two chunks; a full chunk is never moved).
  double* Reserve(size_t need) {
    if (chunks_.empty() || chunks_.back().size() - used_ < need) {
      const size_t size =
          chunks_.empty() ? kFirstChunkDoubles : std::min(2 * chunks_.back().size(), kChunkDoubles);
      chunks_.emplace_back(std::max(size, need));
      used_ = 0;
    }
    return chunks_.back().data() + used_;
  }
  // Coefficients are kept in chunks, the first of kFirstChunkDoubles doubles, each next one
  // twice the last up to kChunkDoubles (128 KiB), so that a long run's trajectory grows without
  // copying what it holds, and a short one holds little.
  static constexpr size_t kFirstChunkDoubles = 1024, kChunkDoubles = 16384;
  // A segment's interpolant: its kind, start, length, and where its coefficients start
  // (chunks_[chunk][pos + j * 2 blocks + i]: coefficient j of component i, angles then rates).
  struct Step {
    DenseKinds::Kind kind = DenseKinds::kConstant;
    double t0 = 0.0, h = 0.0;
    uint32_t chunk = 0, pos = 0;
    bool state = false;  // the view's layout (AppendState), else angles then rates
  };
  int blocks_ = 2;
  bool slip_and_lift_ = false;
  std::shared_ptr<const StateView> view_;
  // The last segment starting at or before t (the state just after an event at t); segments_
  // not empty, t within them.
  std::vector<Segment>::const_iterator SegmentFrom(double t_s) const;
  // Segment `it`'s view components (its step holds the view's layout) at t, into out.
  void StateComponents(std::vector<Segment>::const_iterator it, double t_s, double* out) const;
  std::vector<Segment> segments_;
  std::vector<Step> steps_;
  std::vector<std::vector<double, UninitialisedAllocator<double>>> chunks_;
  size_t used_ = 0;  // doubles used in the last chunk
};

/// Appends to `samples` the trajectory's states at the output times next * dt_s, from *next
/// on, up to t_end_s (inclusive or not) and never past the run's end run_end_s (to 1e-12 of
/// it), advancing *next: the one sampling of a run's history, for the chain's driver and the
/// unilateral model's.
void EmitTrajectorySamples(const Trajectory& trajectory, double dt_s, double run_end_s,
                           double t_end_s, bool inclusive, long* next,
                           std::vector<Sample>* samples);

/// An event of a stack of n blocks at t_s, of `kind`, from mode `before` to `after`: block i's
/// rate before is omega_before[i * stride] and after omega_after[i * stride] (rad/s). The one
/// construction of an event for the chain's driver and the unilateral model's.
Event ModeChangeEvent(int n, double t_s, std::string kind, const Configuration& before,
                      const Configuration& after, const double* omega_before,
                      const double* omega_after, int stride);

/// Summary figures of a reference run: its peaks and impacts (PeaksAndImpacts, as every run's
/// outcome) and what the model alone counts.
struct Summary : PeaksAndImpacts {
  /// completed | overturned | at_rest | assumption_violated | non_finite | left_support
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
  /// The first block that slid off its support (its base left the top face of the block below;
  /// status left_support), 2..N, and when, s. Not an overturn.
  std::optional<int> left_support_block;
  double left_support_t_s = 0.0;
  /// Per interface, one entry per block as impacts_at (PeaksAndImpacts): the largest |T|/N the
  /// contact needed; its smallest normal reaction over the step ends, N (+infinity when the run
  /// took no step).
  std::vector<double> friction_required;
  std::vector<double> min_normal_n;
  int impacts_inadmissible = 0;  ///< no thesis outcome was admissible (see README)
  /// Impacts where several different motions were admissible: none, by impact.h's uniqueness
  /// argument, unless something is wrong. Counted where the rule evaluates every candidate (one
  /// or two blocks); the N-block search stops at the first admissible outcome.
  int impacts_ambiguous = 0;
  /// The first impact with no admissible outcome or several, s: from there the model does not
  /// decide the motion, and the history follows the outcome the rule chose (none: every impact
  /// had exactly one). Its detail says which impact and why.
  std::optional<double> undetermined_from_s;
  std::string undetermined_detail;
  int impacts_energy_gain = 0;  ///< impacts that would add energy (must stay 0)
  /// When the stack left the thesis's assumptions (a block slipped or lifted off) and the
  /// unilateral model took over (docs/sliding.md), s, and why; none: it never did.
  std::optional<double> unilateral_from_s;
  std::string unilateral_reason;
  int slip_starts = 0;  ///< an interface starting to slip (without impact)
  int lift_offs = 0;    ///< an interface opening entirely (the block above it flies)
  /// Energy the friction dissipated while interfaces slipped, J (>= 0).
  double friction_work_j = 0.0;
  int transitions = 0;  ///< mode changes without impact
  int initiations = 0;  ///< starts from rest
  long steps_accepted = 0, steps_rejected = 0, rhs_evaluations = 0;

  /// No blocks (fill it, or build it for a number of blocks).
  Summary() = default;
  /// The summary of a run of `blocks` blocks before it starts.
  explicit Summary(int blocks)
      : PeaksAndImpacts(blocks),
        friction_required(static_cast<size_t>(blocks), 0.0),
        min_normal_n(static_cast<size_t>(blocks), std::numeric_limits<double>::infinity()) {}
};

struct Result {
  History history;        ///< samples at the output interval plus every event time
  Trajectory trajectory;  ///< dense solution for comparison at any time
  Summary summary;
};

/// Runs the reference model on a scene of any number of blocks: the thesis's equations for one
/// or two (unless model.formulation = "chain"), the N-block chain otherwise (mechanics.h). Never
/// throws for physics outcomes (overturning, assumption violations are statuses); throws
/// SceneError for impossible settings. A state,
/// energy, event time or contact force that is not finite (an absurd base motion built in code)
/// ends the run with status "non_finite" at its last finite state: no NaN or infinity reaches
/// the history, the events or the summary.
Result Simulate(const Scene& scene, const GroundMotion& motion);

/// Whether a scene runs on the thesis's equations (one or two blocks, model.formulation not
/// "chain") rather than the N-block chain.
bool UsesThesisEquations(const Scene& scene);

}  // namespace rockbench::reference
