// The reference model's driver: integrates the mode's equations, locates events on the dense
// output, applies impacts and transitions, and monitors the model's assumptions.
#include "reference/simulate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

#include "reference/geometry.h"
#include "reference/impact.h"
#include "reference/kinematics.h"
#include "reference/modes.h"
#include "reference/transitions.h"

namespace rockbench::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Every time constant of the driver is a multiple of the geometry's time scale sqrt(R / g)
// (R: block 1's pivot to the stack's mass centre; 0.4385 s for the thesis's stack) or of the
// motion's (MotionTimeScale), so that a scene scaled by k in length, with its motion's time
// axis scaled by sqrt(k), takes the same steps and finds the same events at sqrt(k) times the
// times (tests/reference/similarity_test.cc).
// Events are located to this width, in units of sqrt(R / g) (4.4e-13 s for the thesis's stack;
// the issue asks for better than 1e-10 s).
constexpr double kEventTolRel = 1e-12;
// Largest dopri5 step, in units of sqrt(R / g) (0.022 s for the thesis's stack) and of the
// motion's time scale: each event function then changes monotonically, or has one extremum,
// over a few of the interior points at which the step is searched for a double crossing.
constexpr double kMaxStepRel = 0.05;
constexpr double kMaxStepMotion = 1.0 / 16.0;
// The first trial step and the smallest step, in units of sqrt(R / g).
constexpr double kFirstStepRel = 2e-3;
constexpr double kMinStepRel = 1e-14;
// While at rest under an analytic motion, the initiation criteria are checked at this fraction
// of the motion's time scale, and at the minimum of the parabola through the last three checks
// when it lies between them (7.8 ms for a 2 Hz pulse, 0.31 ms at 50 Hz). Between record samples
// the accelerations are linear in time, so each corner force is linear and the smallest of
// them concave: checking the samples is exact.
constexpr double kRestScanMotion = 1.0 / 64.0;
// Interior points at which the cheap event functions (angles, on the dense output) are
// checked in every step, between which their minima are found from the rates.
constexpr int kInteriorChecks = 4;
// Above this rate (rad/s) the energy at each step's end is checked to be finite: below it the
// kinetic energy, about I omega^2 / 2, stays finite for any moment of inertia under 1e100 kg m^2
// (the scene's limits allow about 1e23), and the check costs nothing on a valid run.
constexpr double kEnergyCheckRate_radps = 1e100;

// The time scale of the analytic components of a motion (s): the period 1/f of a harmonic,
// sine or cosine pulse or Ricker wavelet; +inf for records (their steps end at every sample)
// and rectangular pulses (constant between their breakpoints). From MotionInfo: a sine or
// cosine pulse lasts 1/f, a Ricker wavelet 2/f, a harmonic peaks first a quarter period after
// its start (at its end when it is shorter: then 4 times that is shorter than the period).
double MotionTimeScale(const GroundMotion& motion) {
  double scale = kInf;
  for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
    if (!*c || !(*c)->samples_mps2().empty()) continue;
    const MotionInfo& in = (*c)->info();
    double period = kInf;
    if (in.source == "harmonic") {
      period = 4.0 * (in.peak_t_s - (*c)->t0_s());
    } else if (in.source == "sine_pulse" || in.source == "cosine_pulse") {
      period = in.duration_s;
    } else if (in.source == "ricker") {
      period = 0.5 * in.duration_s;
    }
    if (period > 0.0) scale = std::min(scale, period);
  }
  return scale;
}

// The k-th of the n + 1 equally spaced points of [ta, tb] (the last is tb exactly).
double ProbeTime(double ta, double tb, int k, int n) {
  return k >= n ? tb : ta + (tb - ta) * k / n;
}

// The earliest point found in (t[0], t[n]] where fn < 0, and fn there; (t[n], fn(t[n])) when
// none (fn(t[n]) >= 0 then). For a cheap fn = fy(state) with a known rate ry(state): fn is
// checked at the n + 1 points t[k] (states y[k]) and, between two of them where its rate turns
// from negative to positive, at the minimum (the rate's root, on the states at(t)). Exact
// while the rate changes sign at most once between points.
template <class Fy, class Ry, class At>
std::pair<double, double> ProbeCheap(const Fy& fy, const Ry& ry, const At& at, const double* t,
                                     const Vec4* y, int n, double tol) {
  double tp = t[0], rp = ry(y[0]);
  for (int k = 1;; ++k) {
    const double tk = t[k];
    const double rk = ry(y[k]);
    if (rp < 0.0 && rk > 0.0) {
      const auto br = BrentBracket([&](double tt) { return ry(at(tt)); }, tp, tk, rp, rk, tol);
      for (const double tm : {br.first, br.second}) {
        const double fm = fy(at(tm));
        if (fm < 0.0) return {tm, fm};
      }
    }
    const double fk = fy(y[k]);
    if (fk < 0.0 || k >= n) return {tk, fk};
    tp = tk;
    rp = rk;
  }
}

// The same for an expensive fn known at both ends (f0 >= 0): fn is checked at the midpoint,
// then at the minimum of the parabola through the lowest value and its neighbours, as long as
// that minimum lies between them, is predicted below an eighth of their spread (near zero for
// how much fn varies there) and is not within tol of a point already checked (at most three
// more values). Exact for a quadratic fn; the steps are short enough (kMaxStepRel,
// kMaxStepMotion) that fn is close to one.
template <class F>
std::pair<double, double> ProbeExpensive(const F& fn, double t0, double f0, double t1, double f1,
                                         double tol) {
  const double tm = 0.5 * (t0 + t1);
  const double fm = fn(tm);
  if (fm < 0.0) return {tm, fm};
  if (f1 < 0.0) return {t1, f1};
  std::array<std::pair<double, double>, 6> p{};
  p[0] = {t0, f0};
  p[1] = {tm, fm};
  p[2] = {t1, f1};
  int n = 3;
  for (int it = 0; it < 3; ++it) {
    int i = 0;
    for (int j = 1; j < n; ++j) {
      if (p[j].second < p[i].second) i = j;
    }
    i = std::clamp(i, 1, n - 2);
    const auto [x0, y0] = p[i - 1];
    const auto [x1, y1] = p[i];
    const auto [x2, y2] = p[i + 1];
    const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
    const double a = (d12 - d01) / (x2 - x0);
    if (!(a > 0.0)) break;
    const double xv = 0.5 * (x0 + x1) - d01 / (2.0 * a);
    const double yv = y0 + d01 * (xv - x0) + a * (xv - x0) * (xv - x1);
    const double spread = std::max({y0, y1, y2}) - std::min({y0, y1, y2});
    if (!(xv > x0 + tol && xv < x2 - tol) || std::abs(xv - x1) <= tol || !(yv < 0.125 * spread)) {
      break;
    }
    const double fv = fn(xv);
    if (fv < 0.0) return {xv, fv};
    const int at = xv < x1 ? i : i + 1;
    for (int j = n; j > at; --j) p[j] = p[j - 1];
    p[at] = {xv, fv};
    ++n;
  }
  return {t1, f1};
}

// A value that is not finite, in words: "NaN", "+inf" or "-inf".
const char* NonFiniteText(double v) {
  return std::isnan(v) ? "NaN" : (v > 0.0 ? "+inf" : "-inf");
}

// A time for a message, s, to 9 significant digits.
std::string TimeText(double t_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", t_s);
  return buf;
}

State ToState(const Vec4& y) {
  return {y[0], y[1], y[2], y[3]};
}
Vec4 ToVec(const State& s) {
  return {s.theta1, s.theta2, s.omega1, s.omega2};
}

double Side(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

// One component of the base motion, evaluated through the record's straight piece that held the
// last time asked for (bit for bit MotionComponent::accel_mps2, without its search at every
// call; an analytic component is evaluated directly).
class MotionCursor {
 public:
  explicit MotionCursor(const std::optional<MotionComponent>& c) : c_(c ? &*c : nullptr) {}
  double At(double t_s) const {
    if (!c_) return 0.0;
    if (piece_.Holds(t_s)) return piece_.At(t_s);
    if (c_->kind() == MotionKind::kFile) {
      piece_ = c_->piece_at(t_s);
      if (piece_.Holds(t_s)) return piece_.At(t_s);
    }
    return c_->accel_mps2(t_s);
  }

 private:
  const MotionComponent* c_;
  mutable MotionComponent::LinearPiece piece_;
};

// An event at t from `before` (rates of `pre`) to `after` (rates of `post`) of a stack of
// `blocks` (1 or 2) blocks, in the history's vocabulary: one configuration and one rate per
// block. Out of line: events are rare, and the integration loop's inlining is not to change.
[[gnu::noinline]] Event MakeEvent(int blocks, double t, const char* kind, Mode before, Mode after,
                                  const State& pre, const State& post) {
  Event ev(blocks);
  ev.t_s = t;
  ev.kind = kind;
  ev.mode_before = ConfigurationOf(before, blocks);
  ev.mode_after = ConfigurationOf(after, blocks);
  ev.omega_before_radps[0] = pre.omega1;
  ev.omega_after_radps[0] = post.omega1;
  if (blocks == 2) {
    ev.omega_before_radps[1] = pre.omega2;
    ev.omega_after_radps[1] = post.omega2;
  }
  return ev;
}

// The per-block figures of the summary while a run of one or two blocks goes on, as plain
// numbers in the integration loop (Summary's per-block vectors are filled at the end).
struct Figures {
  double peak_theta1_rad = 0.0, peak_theta1_t_s = 0.0;
  double peak_theta2_rad = 0.0, peak_theta2_t_s = 0.0;
  int impacts_ground = 0, impacts_interface = 0;
  double friction_required_ground = 0.0, friction_required_interface = 0.0;
  double min_normal_ground_n = kInf, min_normal_interface_n = kInf;
};

class Simulator {
 public:
  Simulator(const Scene& scene, const GroundMotion& motion)
      : scene_(scene),
        cfg_(scene.model),
        motion_(motion),
        xg_(motion.horizontal()),
        yg_(motion.vertical()),
        geo_(MakeGeometry(scene)),
        blocks_(geo_.two_blocks ? 2 : 1) {
    result_.summary = Summary(blocks_);
    result_.history.blocks = blocks_;
    result_.trajectory.set_blocks(blocks_);
    for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
      if (*c && (*c)->samples_mps2().empty()) analytic_motion_ = true;
    }
    const double t_geo = std::sqrt(geo_.R / geo_.g);
    const double t_motion = MotionTimeScale(motion);
    event_tol_ = kEventTolRel * t_geo;
    max_step_ = std::min(kMaxStepRel * t_geo, kMaxStepMotion * t_motion);
    min_step_ = kMinStepRel * t_geo;
    rest_scan_ = kRestScanMotion * t_motion;
    h_ = std::min(kFirstStepRel * t_geo, max_step_);
  }

  Result Run();

 private:
  // Base accelerations (m/s^2) at t.
  double Xg(double t) const { return xg_.At(t); }
  double Yg(double t) const { return yg_.At(t); }
  Vec4 Rhs(double t, const Vec4& y) const {
    const auto acc = ModeAccelerations(geo_, mode_, ToState(y), Xg(t), Yg(t), cfg_.equations);
    ++rhs_count_;
    return {y[2], y[3], acc[0], acc[1]};
  }
  // Projects a state onto the mode's constraints (mode 3: theta2 = theta1; mode 4: theta1 = 0).
  Vec4 Project(const Vec4& y) const {
    Vec4 p = y;
    const Contacts c = ContactsOf(mode_);
    if (!geo_.two_blocks) {
      p[1] = p[0];
      p[3] = p[2];
    } else if (c.interface == Contact::kFace) {
      p[1] = p[0];
      p[3] = p[2];
    }
    if (c.ground == Contact::kFace) {
      p[0] = 0.0;
      p[2] = 0.0;
    }
    return p;
  }

  // Records the samples of the output times up to t_end (inclusive or not): most calls have
  // none to record, and return at once.
  void EmitSamplesUntil(double t_end, bool inclusive) {
    const double ts = next_sample_ * scene_.run.output_interval_s;
    if (ts > t_end_ + 1e-12 * t_end_ || (inclusive ? ts > t_end : ts >= t_end)) return;
    EmitSamples(t_end, inclusive);
  }
  [[gnu::noinline]] void EmitSamples(double t_end, bool inclusive);
  // Out of line, as every path that records events or samples: rare work, kept out of the
  // integration loop's inlining.
  [[gnu::noinline]] void AddEvent(Event ev) { result_.history.events.push_back(std::move(ev)); }
  Event NewEvent(double t, const char* kind, Mode before, Mode after, const State& pre,
                 const State& post) const {
    return MakeEvent(blocks_, t, kind, before, after, pre, post);
  }
  void Track(double t, const State& s);
  bool StartMode(double t, const State& s, const char* kind, Mode before, const std::string& note);
  // At a located switch the choice of mode can hang on rounding (a face force or an opening
  // acceleration of ~1e-16): the first time from t on (1e-12 s, doubling, up to t_max) at which
  // a mode other than `leaving` is consistent; t itself when none is found.
  template <class StateAt>
  double SwitchTime(double t, double t_max, Mode leaving, const StateAt& state_at) const {
    for (double dt = 0.0; t + dt <= t_max; dt = dt == 0.0 ? EventTol(t) : 2 * dt) {
      const double tt = t + dt;
      const ModeSelection sel = SelectMode(geo_, state_at(tt), Xg(tt), Yg(tt), cfg_.equations);
      if (sel.consistent && sel.mode != leaving) return tt;
    }
    return t;
  }
  void DoImpact(double t, const State& s, ImpactKind kind);
  void RunRest();
  // RunMoving's parts: one step of the mode's equations, the earliest event inside it, the
  // step's record (trajectory, samples, peaks, reactions) and the event's handling.
  enum class StepEvent { kNone, kGroundImpact, kInterfaceImpact, kOverturn, kMargin };
  struct LocatedEvent {
    StepEvent which = StepEvent::kNone;
    double t = kInf;     // s, the located bracket's lower end (the event time)
    double t_hi = kInf;  // s, its upper end (just past the root)
  };
  // The state at t inside the step that starts at (t0, y0), projected onto the mode, and an
  // enclosure [lo, hi] of it over the whole step (DenseStep::Bounds, projected: Project only
  // copies and zeroes components). The states at the probe points (ProbeTime), which the cheap
  // event functions check, are evaluated once, when first asked for (Probe), and kept.
  struct StepDense {
    StepDense(const Simulator& s, const StepResult& r, double t_start, const Vec4& y_start)
        : sim(s), st(r), t0(t_start), y0(y_start) {
      r.dense.Bounds(&lo, &hi);
      lo = s.Project(lo);
      hi = s.Project(hi);
    }
    const Simulator& sim;
    const StepResult& st;
    double t0;
    Vec4 y0;
    Vec4 lo{}, hi{};
    mutable bool probed = false;
    mutable std::array<double, kInteriorChecks + 1> probe_t{};
    mutable std::array<Vec4, kInteriorChecks + 1> probe_y{};
    Vec4 Evaluate(double t) const { return sim.Project(t == t0 ? y0 : st.dense.At(t)); }
    void Probe(double t1) const {
      if (probed) return;
      for (int k = 0; k <= kInteriorChecks; ++k) {
        probe_t[k] = ProbeTime(t0, t1, k, kInteriorChecks);
        probe_y[k] = Evaluate(probe_t[k]);
      }
      probed = true;
    }
    // The largest |y[i]| anywhere in the step.
    double MaxAbs(int i) const { return std::max(std::abs(lo[i]), std::abs(hi[i])); }
    Vec4 operator()(double t) const { return Evaluate(t); }
  };
  StepResult AdvanceOneStep(bool rk4, const Vec4& f0, double* h_taken);
  // The first zero of fn in [t_pos, t_neg], given fn(t_pos) = f_pos >= 0 > fn(t_neg) = f_neg,
  // kept in *ev when it is earlier than the event already there.
  template <class Fn>
  void Locate(StepEvent kind, const Fn& fn, double t_pos, double f_pos, double t_neg, double f_neg,
              LocatedEvent* ev) const;
  // fy, ry: the event function and its rate as functions of the state; lower: a lower bound of
  // fy over the step from the enclosure (at.lo, at.hi). When it is positive the function
  // cannot vanish in the step and the search is skipped: it would find nothing.
  template <class Fy, class Ry>
  void ConsiderCheap(StepEvent kind, const Fy& fy, const Ry& ry, double lower, const StepDense& at,
                     double t1, bool thesis_events, LocatedEvent* ev) const;
  LocatedEvent FindEvent(const StepDense& at, double t1, const ContactMargins& cm1,
                         bool thesis_events);
  void RecordStep(const StepDense& at, const DenseStep& dense, double t_seg_end, const Vec4& y_end,
                  const ContactMargins& cm_end);
  // True when more than 20 events fall at one instant (an endless cascade).
  bool EventCascade(double t_ev);
  void HandleEvent(const LocatedEvent& ev, const StepDense& at, double t1, State s);
  void RunMoving();
  // A quantity of the run that is not finite: its name and value (an empty name: none).
  struct NonFinite {
    std::string quantity;
    double value = 0.0;
    bool found() const { return !quantity.empty(); }
  };
  // The first of a state's angles and rates that is not finite (block 1's only for one block,
  // whose block-2 components mirror them).
  [[gnu::cold]] NonFinite NonFiniteState(const Vec4& y) const;
  // The same for a step: its end state y1, the enclosure of its dense output (every state the
  // step's samples and events are taken from), the contact margins at its end and, above
  // kEnergyCheckRate_radps, the energy there. Called only when StepFinite says a value is not
  // finite (never on a valid run).
  [[gnu::cold]] NonFinite NonFiniteStep(const StepDense& at, const Vec4& y1,
                                        const ContactMargins& cm1) const;
  // Whether NonFiniteStep finds nothing, cheaply: a sum is finite when every term is (a finite
  // sum that overflows is sorted out by NonFiniteStep).
  static bool StepFinite(const StepDense& at, const Vec4& y1, const ContactMargins& cm1) {
    double sum = cm1.face + cm1.point;
    for (int i = 0; i < 4; ++i) sum += y1[i] + at.lo[i] + at.hi[i];
    return std::isfinite(sum) &&
           std::max(std::abs(y1[2]), std::abs(y1[3])) <= kEnergyCheckRate_radps;
  }
  // Ends the run at its last finite state `last`, at t_: status non_finite with `nf`, found at
  // t_bad (s), named in status_detail and in a "non_finite" event (Finish; the caller ends the
  // trajectory with EndTrajectory).
  [[gnu::cold]] void StopNonFinite(const NonFinite& nf, double t_bad, const State& last);
  // After a stop at t_: the trajectory ends at t_ in y_, and the samples up to t_ are emitted.
  void EndTrajectory();
  double GapGround(const Vec4& y) const { return Side(ContactsOf(mode_).ground) * y[0]; }
  double GapInterface(const Vec4& y) const {
    const Contacts c = ContactsOf(mode_);
    const double rel = c.ground == Contact::kFace ? y[1] : y[1] - y[0];
    return Side(c.interface) * rel;
  }
  ContactMargins Margins(double t, const Vec4& y) const {
    return EvaluateContacts(geo_, mode_, ToState(y), Xg(t), Yg(t), cfg_.equations);
  }
  // Width to which an event near t is located: kEventTolRel sqrt(R / g), and never below a
  // few ulps of t.
  double EventTol(double t) const {
    return std::max(event_tol_, 8 * std::numeric_limits<double>::epsilon() * std::abs(t));
  }
  // Records an event that ends the run at t_ in state s (no change of state).
  [[gnu::noinline]] void StopWith(const char* kind, const State& s, const std::string& note,
                                  RunStatus status) {
    Event ev = NewEvent(t_, kind, mode_, mode_, s, s);
    ev.energy_before_j = ev.energy_after_j = Energy(geo_, mode_, s);
    ev.note = note;
    AddEvent(std::move(ev));
    y_ = ToVec(s);
    Finish(status);
  }
  // Smallest normal reactions seen (summary).
  void NoteNormalForces(const Reactions& r) {
    Figures& sum = fig_;
    sum.min_normal_ground_n = std::min(sum.min_normal_ground_n, r.N_ground);
    if (geo_.two_blocks)
      sum.min_normal_interface_n = std::min(sum.min_normal_interface_n, r.N_interface);
  }
  // The result's summary gets the per-block figures.
  Result TakeResult() {
    Summary& sum = result_.summary;
    sum.peak_theta_rad[0] = fig_.peak_theta1_rad;
    sum.peak_theta_t_s[0] = fig_.peak_theta1_t_s;
    sum.impacts_at[0] = fig_.impacts_ground;
    sum.friction_required[0] = fig_.friction_required_ground;
    sum.min_normal_n[0] = fig_.min_normal_ground_n;
    if (blocks_ == 2) {
      sum.peak_theta_rad[1] = fig_.peak_theta2_rad;
      sum.peak_theta_t_s[1] = fig_.peak_theta2_t_s;
      sum.impacts_at[1] = fig_.impacts_interface;
      sum.friction_required[1] = fig_.friction_required_interface;
      sum.min_normal_n[1] = fig_.min_normal_interface_n;
    }
    return std::move(result_);
  }
  void Finish(RunStatus status) {
    if (result_.summary.status == RunStatus::kCompleted) result_.summary.status = status;
    done_ = true;
  }

  const Scene& scene_;
  const ModelConfig& cfg_;
  const GroundMotion& motion_;
  MotionCursor xg_, yg_;
  const Geometry geo_;
  const int blocks_;  // 1 or 2: the history's and the summary's
  Result result_;
  Figures fig_;
  Mode mode_ = Mode::kRest;
  double t_ = 0.0;
  Vec4 y_{};
  double t_end_ = 0.0;
  long next_sample_ = 0;
  bool done_ = false;
  bool analytic_motion_ = false;  // some component is an analytic kind (not a record)
  double event_tol_ = 0.0;        // s, see kEventTolRel
  double max_step_ = kInf;        // s, see kMaxStepRel
  double min_step_ = 0.0;         // s, see kMinStepRel
  double rest_scan_ = kInf;       // s, see kRestScanMotion
  double h_ = 0.0;                // the next trial step, s
  ContactMargins cm0_;            // the margins at the step start (when cm0_valid_)
  bool cm0_valid_ = false;
  mutable long rhs_count_ = 0;
  int same_time_events_ = 0;
  double last_event_t_ = -1.0;
};

void Simulator::Track(double t, const State& s) {
  Figures& sum = fig_;
  if (std::abs(s.theta1) > sum.peak_theta1_rad) {
    sum.peak_theta1_rad = std::abs(s.theta1);
    sum.peak_theta1_t_s = t;
  }
  if (geo_.two_blocks && std::abs(s.theta2) > sum.peak_theta2_rad) {
    sum.peak_theta2_rad = std::abs(s.theta2);
    sum.peak_theta2_t_s = t;
  }
}

void Simulator::EmitSamples(double t_end, bool inclusive) {
  const double dt = scene_.run.output_interval_s;
  auto& samples = result_.history.samples;
  while (true) {
    const double ts = next_sample_ * dt;
    if (ts > t_end_ + 1e-12 * t_end_) break;
    if (inclusive ? ts > t_end : ts >= t_end) break;
    samples.push_back(result_.trajectory.At(ts));
    samples.back().t_s = ts;
    ++next_sample_;
  }
}

bool Simulator::StartMode(double t, const State& s, const char* kind, Mode before,
                          const std::string& note) {
  const ModeSelection sel = SelectMode(geo_, s, Xg(t), Yg(t), cfg_.equations);
  if (sel.consistent && sel.mode == before) {
    mode_ = sel.mode;  // no event to record
    return true;
  }
  Event ev = NewEvent(t, kind, before, before, s, s);
  ev.energy_before_j = ev.energy_after_j = Energy(geo_, before, s);
  if (!sel.consistent) {
    ev.kind = "assumption_violated";
    ev.note = "no mode satisfies the contact conditions (tensile normal force: uplift)";
    result_.summary.status_detail = ev.note;
    AddEvent(std::move(ev));
    result_.summary.status = RunStatus::kAssumptionViolated;
    done_ = true;
    return false;
  }
  ev.mode_after = ConfigurationOf(sel.mode, blocks_);
  ev.note = note;
  if (std::string(kind) == "initiation") ++result_.summary.initiations;
  if (std::string(kind) == "transition") ++result_.summary.transitions;
  AddEvent(std::move(ev));
  mode_ = sel.mode;
  return true;
}

void Simulator::DoImpact(double t, const State& pre, ImpactKind kind) {
  const Mode before = mode_;
  const ImpactResult ir = ResolveImpact(geo_, before, pre, kind, cfg_.rest_rate_rel);
  // A post-impact state or energy that is not finite ends the run before the impact.
  NonFinite nf = NonFiniteState(ToVec(ir.chosen.state));
  for (const double e : {ir.energy_before_j, ir.chosen.energy_after_j}) {
    if (!nf.found() && !std::isfinite(e)) nf = {"energy", e};
  }
  if (nf.found()) {
    nf.quantity +=
        kind == ImpactKind::kGround ? " after a ground impact" : " after an interface impact";
    StopNonFinite(nf, t, pre);
    return;
  }
  Summary& sum = result_.summary;
  Event ev = NewEvent(t, kind == ImpactKind::kGround ? "ground_impact" : "interface_impact", before,
                      ir.chosen.mode, pre, ir.chosen.state);
  ev.energy_before_j = ir.energy_before_j;
  ev.energy_after_j = ir.chosen.energy_after_j;
  ev.note = ir.note;
  const double kinetic =
      std::max(0.0, ir.energy_before_j - Energy(geo_, before, {pre.theta1, pre.theta2, 0, 0}));
  if (ev.energy_after_j - ev.energy_before_j > 1e-9 * kinetic + 1e-12) {
    ++sum.impacts_energy_gain;
    ev.note += std::string(ev.note.empty() ? "" : " ") + "ENERGY GAIN";
  }
  if (!ir.admissible) ++sum.impacts_inadmissible;
  (kind == ImpactKind::kGround ? fig_.impacts_ground : fig_.impacts_interface)++;
  AddEvent(std::move(ev));
  mode_ = ir.chosen.mode;
  // The post-impact mode must also satisfy the contact forces (a locked pair may open at once).
  StartMode(t, ir.chosen.state, "transition", mode_, "after impact");
  y_ = ToVec(ir.chosen.state);
}

void Simulator::RunRest() {
  // Criterion while at rest: the smallest corner force of the two faces (linear in xg'', yg'').
  // The last few values (a check starts where the last one ended).
  std::array<std::pair<double, double>, 4> memo;
  memo.fill({-kInf, 0.0});
  int next_memo = 0;
  // The first time a corner force at rest was not finite (an absurd base acceleration), and
  // its value; -1: none.
  double bad_t = -1.0, bad_value = 0.0;
  auto margin = [&](double t) {
    for (const auto& [tm, m] : memo) {
      if (tm == t) return m;
    }
    const ContactMargins cm =
        EvaluateContacts(geo_, Mode::kRest, State{}, Xg(t), Yg(t), cfg_.equations);
    if (!std::isfinite(cm.face)) {
      if (bad_t < 0.0) {
        bad_t = t;
        bad_value = cm.face;
      }
    } else {
      NoteNormalForces(cm.reactions);
    }
    memo[next_memo] = {t, cm.face};
    next_memo = (next_memo + 1) % static_cast<int>(memo.size());
    return cm.face;
  };
  const double motion_end = motion_.end_s();
  y_ = Vec4{};
  while (!done_) {
    const double t0 = t_;
    if (t0 >= motion_end && margin(t0) >= 0.0) {
      // Nothing will move again: the blocks stay at rest to the end of the run.
      Trajectory::Segment seg{t0, t_end_, Mode::kRest, DenseStep{}};
      result_.trajectory.Append(seg);
      EmitSamplesUntil(t_end_, true);
      t_ = t_end_;
      Finish(RunStatus::kAtRest);
      return;
    }
    double t1 = std::min(motion_.next_breakpoint_after(t0), t_end_);
    if (analytic_motion_) t1 = std::min(t1, t0 + rest_scan_);
    const double m1 = margin(t1);
    double t_start = -1.0;
    // Between record samples the margin is concave (see kRestScanMotion): the ends decide.
    double t_neg = t1, m_neg = m1;
    if (analytic_motion_ && m1 >= 0.0 && t1 > t0) {
      const double m0 = margin(t0);
      if (m0 >= 0.0) std::tie(t_neg, m_neg) = ProbeExpensive(margin, t0, m0, t1, m1, EventTol(t1));
    }
    if (m_neg < 0.0) {
      const double m0 = margin(t0);
      if (m0 < 0.0) {
        t_start = t0;
      } else {
        const auto br = BrentBracket(margin, t0, t_neg, m0, m_neg, EventTol(t_neg));
        t_start = br.second;
      }
      t_start = SwitchTime(t_start, t_neg, Mode::kRest, [](double) { return State{}; });
      t1 = t_start;
    }
    if (bad_t >= 0.0) {
      // The blocks are at rest at t0, the last finite state.
      StopNonFinite({"normal force at rest", bad_value}, bad_t, State{});
      EndTrajectory();
      return;
    }
    Trajectory::Segment seg{t0, t1, Mode::kRest, DenseStep{}};
    result_.trajectory.Append(seg);
    EmitSamplesUntil(t1, false);
    t_ = t1;
    if (t_start >= 0.0) {
      StartMode(t_, State{}, "initiation", Mode::kRest, "");
      if (mode_ != Mode::kRest || done_) return;
      // The located bracket end was still consistent with rest: step past it.
      t_ = std::nextafter(t_, kInf);
    }
    if (t_ >= t_end_) {
      EmitSamplesUntil(t_end_, true);
      done_ = true;
      return;
    }
  }
}

StepResult Simulator::AdvanceOneStep(bool rk4, const Vec4& f0, double* h_taken) {
  Summary& sum = result_.summary;
  const double t_break = motion_.next_breakpoint_after(t_);
  double h = rk4 ? cfg_.step_s : std::min(h_, max_step_);
  h = std::min({h, t_break - t_, t_end_ - t_});
  if (h <= 0.0) h = std::max(t_end_ - t_, 0.0);
  StepResult st;
  if (rk4) {
    st = Rk4Step([this](double t, const Vec4& y) { return Rhs(t, y); }, t_, y_, f0, h);
  } else {
    // Step-size control as in dopri5.f and dop853.f: the error scales as h^(q + 1) with q the
    // order of the estimate the controller trusts (4 and 7), within their bounds on the ratio.
    const auto rhs = [this](double t, const Vec4& y) { return Rhs(t, y); };
    const bool dop853 = cfg_.integrator == Integrator::kDop853;
    const double expo = dop853 ? -1.0 / 8.0 : -0.2;
    const double fac_min = dop853 ? 1.0 / 3.0 : 0.2, fac_max = dop853 ? 6.0 : 5.0;
    while (true) {
      st = dop853 ? Dop853Step(rhs, t_, y_, f0, h, cfg_.rtol, cfg_.atol)
                  : Dopri5Step(rhs, t_, y_, f0, h, cfg_.rtol, cfg_.atol);
      if (st.err <= 1.0 || h < min_step_) break;
      ++sum.steps_rejected;
      h *= std::max(fac_min, 0.9 * std::pow(st.err, expo));
    }
    const double fac = st.err > 0 ? std::min(fac_max, 0.9 * std::pow(st.err, expo)) : fac_max;
    h_ = h * fac;
  }
  ++sum.steps_accepted;
  *h_taken = h;
  return st;
}

template <class Fn>
void Simulator::Locate(StepEvent kind, const Fn& fn, double t_pos, double f_pos, double t_neg,
                       double f_neg, LocatedEvent* ev) const {
  double lo = t_pos, hi = t_pos;
  double ta = t_pos, fta = f_pos;
  if (f_pos == 0.0) {
    // The step starts on the event surface (a contact that just opened): the function may
    // rise before it falls. Start the search from the last positive interior sample.
    for (int k = 1; k < 16; ++k) {
      const double tk = t_pos + (t_neg - t_pos) * k / 16.0;
      const double fk = fn(tk);
      if (fk > 0.0) {
        ta = tk;
        fta = fk;
      }
    }
    // A short excursion near the start: look closer, geometrically.
    for (int k = 5; k < 48 && !(fta > 0.0); ++k) {
      const double tk = t_pos + std::ldexp(t_neg - t_pos, -k);
      const double fk = fn(tk);
      if (fk > 0.0) {
        ta = tk;
        fta = fk;
      }
    }
  }
  if (fta > 0.0) {
    const auto br = BrentBracket(fn, ta, t_neg, fta, f_neg, EventTol(t_neg));
    lo = br.first;
    hi = br.second;
  }
  if (lo < ev->t) {
    ev->t = lo;
    ev->t_hi = hi;
    ev->which = kind;
  }
}

template <class Fy, class Ry>
void Simulator::ConsiderCheap(StepEvent kind, const Fy& fy, const Ry& ry, double lower,
                              const StepDense& at, double t1, bool thesis_events,
                              LocatedEvent* ev) const {
  if (!thesis_events) {
    if (lower > 0.0) return;
    at.Probe(t1);
  }
  auto fn = [&](double t) { return fy(at(t)); };
  const double fa = fn(t_);
  const auto [t_neg, f_neg] = thesis_events
                                  ? std::pair{t1, fn(t1)}
                                  : ProbeCheap(fy, ry, at, at.probe_t.data(), at.probe_y.data(),
                                               kInteriorChecks, EventTol(t1));
  if (f_neg < 0.0) Locate(kind, fn, t_, fa, t_neg, f_neg, ev);
}

Simulator::LocatedEvent Simulator::FindEvent(const StepDense& at, double t1,
                                             const ContactMargins& cm1, bool thesis_events) {
  // Event functions, positive while nothing happens; the earliest zero is located. Besides
  // the step end, the step's interior is searched (ProbeCheap, ProbeExpensive) so that a
  // function that dips below zero and comes back within one step is not missed (the
  // thesis's scheme sees only the step end).
  const Contacts c = ContactsOf(mode_);
  const bool ground_moves = c.ground != Contact::kFace;
  const bool interface_moves = geo_.two_blocks && c.interface != Contact::kFace;
  LocatedEvent ev;
  // The angles' event functions cost one dense-output evaluation: checked at interior points
  // and at the minima between them (roots of their rates), unless the step's enclosure keeps
  // them positive. Each lower bound is a difference that is positive exactly when the
  // function's own floating-point value is positive wherever the enclosure holds.
  if (ground_moves) {
    const double side = Side(c.ground);
    const double lower = side > 0.0 ? at.lo[0] : -at.hi[0];
    ConsiderCheap(
        StepEvent::kGroundImpact, [&](const Vec4& y) { return GapGround(y); },
        [&](const Vec4& y) { return side * y[2]; }, lower, at, t1, thesis_events, &ev);
  }
  if (interface_moves) {
    // theta2 - theta1 (with theta1 = 0 on a grounded face, where [lo, hi] is [0, 0]).
    const double side = Side(c.interface);
    const double lower = side > 0.0 ? at.lo[1] - at.hi[0] : at.lo[0] - at.hi[1];
    ConsiderCheap(
        StepEvent::kInterfaceImpact, [&](const Vec4& y) { return GapInterface(y); },
        [&](const Vec4& y) { return side * (ground_moves ? y[3] - y[2] : y[3]); }, lower, at, t1,
        thesis_events, &ev);
  }
  // Overturning: each block's |theta| reaching overturn_angle.
  const double over = cfg_.overturn_rad;
  for (int k = 0; k < (geo_.two_blocks ? 2 : 1); ++k) {
    ConsiderCheap(
        StepEvent::kOverturn, [&](const Vec4& y) { return over - std::abs(y[k]); },
        [&](const Vec4& y) { return y[k] < 0.0 ? y[2 + k] : -y[2 + k]; }, over - at.MaxAbs(k), at,
        t1, thesis_events, &ev);
  }
  // The contact margins (face corners opening: a transition; a point contact pulling: a
  // violation) cost a contact-force evaluation: checked at the midpoint and at the minimum of
  // the parabola through the values when it lies inside the step and near zero.
  if (!cm0_valid_) cm0_ = Margins(t_, at(t_));
  auto margin_of = [&](const ContactMargins& cm) {
    return cfg_.check_transitions ? std::min(cm.face, cm.point) : cm.point;
  };
  {
    auto fn = [&](double t) { return margin_of(Margins(t, at(t))); };
    const double m0 = margin_of(cm0_), m1 = margin_of(cm1);
    const auto [t_neg, f_neg] =
        thesis_events ? std::pair{t1, m1} : ProbeExpensive(fn, t_, m0, t1, m1, EventTol(t1));
    if (f_neg < 0.0) Locate(StepEvent::kMargin, fn, t_, m0, t_neg, f_neg, &ev);
  }
  if (thesis_events && ev.which != StepEvent::kNone) {
    // The thesis's scheme: the event is seen at the step end, pre-impact rates are the
    // previous step's.
    ev.t = ev.t_hi = t1;
  }
  return ev;
}

void Simulator::RecordStep(const StepDense& at, const DenseStep& dense, double t_seg_end,
                           const Vec4& y_end, const ContactMargins& cm_end) {
  Figures& sum = fig_;
  Trajectory::Segment seg{t_, t_seg_end, mode_, dense};
  result_.trajectory.Append(seg);
  EmitSamplesUntil(t_seg_end, false);
  // Peaks: |theta| extremes sit where the rate vanishes inside the step, or at its ends. No
  // state of the step can raise a peak when the step's enclosure stays within both.
  const bool within_peaks = at.MaxAbs(0) <= sum.peak_theta1_rad &&
                            (!geo_.two_blocks || at.MaxAbs(1) <= sum.peak_theta2_rad);
  const int searched = within_peaks ? 0 : (geo_.two_blocks ? 2 : 1);
  for (int k = 0; k < searched; ++k) {
    auto rate = [&](double t) { return at(t)[2 + k]; };
    const double ra = rate(t_), rb = rate(t_seg_end);
    if (ra * rb < 0.0) {
      const auto br = BrentBracket(rate, t_, t_seg_end, ra, rb, EventTol(t_seg_end));
      Track(br.first, ToState(at(br.first)));
    }
  }
  Track(t_seg_end, ToState(y_end));
  // Friction needed and normal forces along the solution (at step ends).
  sum.friction_required_ground = std::max(sum.friction_required_ground, cm_end.mu_ground);
  sum.friction_required_interface = std::max(sum.friction_required_interface, cm_end.mu_interface);
  NoteNormalForces(cm_end.reactions);
}

bool Simulator::EventCascade(double t_ev) {
  if (std::abs(t_ev - last_event_t_) <= EventTol(t_ev)) {
    if (++same_time_events_ > 20) return true;
  } else {
    same_time_events_ = 0;
  }
  last_event_t_ = t_ev;
  return false;
}

void Simulator::HandleEvent(const LocatedEvent& ev, const StepDense& at, double t1, State s) {
  Summary& sum = result_.summary;
  const Contacts c = ContactsOf(mode_);
  const bool ground_moves = c.ground != Contact::kFace;
  const bool interface_moves = geo_.two_blocks && c.interface != Contact::kFace;
  t_ = ev.t;
  switch (ev.which) {
    case StepEvent::kGroundImpact:
      s.theta1 = 0.0;
      if (!interface_moves) s.theta2 = 0.0;
      DoImpact(t_, s, ImpactKind::kGround);
      break;
    case StepEvent::kInterfaceImpact:
      s.theta2 = ground_moves ? s.theta1 : 0.0;
      DoImpact(t_, s, ImpactKind::kInterface);
      break;
    case StepEvent::kOverturn: {
      const bool first = std::abs(s.theta1) >= std::abs(s.theta2) || !geo_.two_blocks;
      sum.overturn_block = first ? 1 : 2;
      sum.overturn_t_s = t_;
      StopWith("overturn", s, first ? "block 1" : "block 2", RunStatus::kOverturned);
      break;
    }
    case StepEvent::kMargin: {
      // Just past the located root: the smaller of the two margins is the one that crossed.
      const ContactMargins cmh = Margins(ev.t_hi, at(ev.t_hi));
      if (cfg_.check_transitions && cmh.face <= cmh.point) {
        // A face force has turned tensile: the face opens.
        t_ = SwitchTime(ev.t_hi, t1, mode_, [&](double t) { return ToState(at(t)); });
        const State sh = ToState(at(t_));
        y_ = ToVec(sh);
        StartMode(t_, sh, "transition", mode_, "face opens");
      } else {
        sum.status_detail = "tensile normal force at a pivot (uplift)";
        StopWith("assumption_violated", s, sum.status_detail, RunStatus::kAssumptionViolated);
      }
      break;
    }
    case StepEvent::kNone:
      break;
  }
  if (done_) EndTrajectory();
}

void Simulator::EndTrajectory() {
  // The run stops at t_: the trajectory ends there.
  Trajectory::Segment last{t_, t_, mode_, DenseStep{}};
  last.dense.c[0] = y_;
  result_.trajectory.Append(last);
  const double stop = t_;
  t_end_ = stop;
  EmitSamplesUntil(stop, true);
}

Simulator::NonFinite Simulator::NonFiniteState(const Vec4& y) const {
  static constexpr const char* kNames[4] = {"theta1", "theta2", "omega1", "omega2"};
  for (int i = 0; i < 4; ++i) {
    if (!geo_.two_blocks && (i == 1 || i == 3)) continue;
    if (!std::isfinite(y[i])) return {kNames[i], y[i]};
  }
  return {};
}

Simulator::NonFinite Simulator::NonFiniteStep(const StepDense& at, const Vec4& y1,
                                              const ContactMargins& cm1) const {
  for (const Vec4* y : {&y1, &at.lo, &at.hi}) {
    if (NonFinite nf = NonFiniteState(*y); nf.found()) return nf;
  }
  if (const double e = Energy(geo_, mode_, ToState(y1)); !std::isfinite(e)) return {"energy", e};
  for (const double m : {cm1.face, cm1.point}) {
    if (!std::isfinite(m)) return {"contact force", m};
  }
  return {};
}

void Simulator::StopNonFinite(const NonFinite& nf, double t_bad, const State& last) {
  Summary& sum = result_.summary;
  sum.non_finite_quantity = nf.quantity;
  sum.non_finite_value = NonFiniteText(nf.value);
  sum.non_finite_t_s = t_bad;
  sum.non_finite_last_t_s = t_;
  sum.status_detail = nf.quantity + " is " + sum.non_finite_value + " at t = " + TimeText(t_bad) +
                      " s; the run stops at its last finite state, t = " + TimeText(t_) + " s";
  StopWith("non_finite", last, sum.status_detail, RunStatus::kNonFinite);
}

void Simulator::RunMoving() {
  const bool thesis_events = cfg_.events == EventScheme::kThesis;
  const bool rk4 = cfg_.integrator == Integrator::kRk4 || thesis_events;
  Vec4 f0 = Rhs(t_, y_);
  cm0_valid_ = false;
  while (!done_) {
    double h = 0.0;
    const StepResult st = AdvanceOneStep(rk4, f0, &h);
    const double t1 = t_ + h;
    const Vec4 y1 = Project(st.y1);
    const StepDense at(*this, st, t_, y_);
    // The last stage f(t1, y1) holds the mode's accelerations at the step end: the contact
    // margins there reuse them (y1 is already on the mode's constraints, so Project keeps it).
    const ContactMargins cm1 = y1 == st.y1 ? EvaluateContacts(geo_, mode_, ToState(y1),
                                                              {st.f1[2], st.f1[3]}, Xg(t1), Yg(t1))
                                           : Margins(t1, y1);
    // A step that reaches a value that is not finite is not recorded: the run ends at its
    // start, the last finite state.
    if (!StepFinite(at, y1, cm1)) {
      if (const NonFinite nf = NonFiniteStep(at, y1, cm1); nf.found()) {
        StopNonFinite(nf, t1, ToState(y_));
        EndTrajectory();
        return;
      }
    }
    const LocatedEvent ev = FindEvent(at, t1, cm1, thesis_events);
    if (ev.which != StepEvent::kNone && !std::isfinite(ev.t)) {
      StopNonFinite({"event time", ev.t}, t1, ToState(y_));
      EndTrajectory();
      return;
    }
    const bool none = ev.which == StepEvent::kNone;
    const double t_seg_end = none ? t1 : ev.t;
    const Vec4 y_end = none ? y1 : at(ev.t);
    RecordStep(at, st.dense, t_seg_end, y_end, none ? cm1 : Margins(t_seg_end, y_end));
    if (none) {
      t_ = t1;
      y_ = y1;
      f0 = st.f1;
      cm0_ = cm1;
      cm0_valid_ = true;
      if (t_ >= t_end_) {
        EmitSamplesUntil(t_end_, true);
        done_ = true;
      }
      continue;
    }
    // Guard against an endless cascade of events at one instant.
    if (EventCascade(ev.t)) {
      result_.summary.status_detail = "event cascade at one instant";
      Finish(RunStatus::kAssumptionViolated);
      return;
    }
    State s = ToState(y_end);
    if (thesis_events) {
      s.omega1 = y_[2];
      s.omega2 = y_[3];
    }
    HandleEvent(ev, at, t1, s);
    // After an event the caller restarts integration (new mode, new first stage).
    return;
  }
}

Result Simulator::Run() {
  ValidateScene(scene_);
  t_end_ = scene_.run.duration_s;
  const InitialState& in = scene_.initial;
  // One block: the stack is the one block (theta2 = theta1), as the equations expect.
  const int top = geo_.two_blocks ? 1 : 0;
  State s{in.theta_rad[0], in.theta_rad[top], in.omega_radps[0], in.omega_radps[top]};
  Track(0.0, s);
  if (std::abs(s.theta1) >= cfg_.overturn_rad || std::abs(s.theta2) >= cfg_.overturn_rad) {
    throw SceneError(scene_.path.string() + ": initial angle beyond model.overturn_angle");
  }
  mode_ = Mode::kRest;
  // The initial mode: a contact with a gap or a rate is open on that side; closed contacts
  // stay closed unless the forces open them.
  const double xg0 = Xg(0.0), yg0 = Yg(0.0);
  const ModeSelection sel = SelectMode(geo_, s, xg0, yg0, cfg_.equations);
  y_ = ToVec(s);
  if (!sel.consistent) {
    // No mode is consistent: an uplift, unless some mode's contact forces are not finite (an
    // absurd base acceleration at t = 0, for which no comparison of forces holds).
    NonFinite bad;
    for (const Contact g : {Contact::kFace, Contact::kRight, Contact::kLeft}) {
      for (const Contact i : {Contact::kFace, Contact::kRight, Contact::kLeft}) {
        if (bad.found() || (!geo_.two_blocks && i != Contact::kFace)) continue;
        const ContactMargins cm =
            EvaluateContacts(geo_, ModeOf({g, i}, geo_.two_blocks), s, xg0, yg0, cfg_.equations);
        for (const double m : {cm.face, cm.point}) {
          if (!std::isfinite(m)) bad = {"contact force", m};
        }
      }
    }
    if (!bad.found()) {
      result_.summary.status = RunStatus::kAssumptionViolated;
      result_.summary.status_detail = "the initial state satisfies no mode's contact conditions";
      Trajectory::Segment seg{0.0, 0.0, Mode::kRest, DenseStep{}};
      seg.dense.c[0] = y_;
      result_.trajectory.Append(seg);
      t_end_ = 0.0;
      EmitSamplesUntil(0.0, true);
      return TakeResult();
    }
    StopNonFinite(bad, 0.0, s);
    EndTrajectory();
  } else {
    mode_ = sel.mode;
  }
  if (!done_ && mode_ != Mode::kRest && s.theta1 == 0.0 && s.theta2 == 0.0 && s.omega1 == 0.0 &&
      s.omega2 == 0.0) {
    // Motion starts at t = 0 from rest.
    Event ev = NewEvent(0.0, "initiation", Mode::kRest, mode_, State{}, State{});
    ev.energy_before_j = ev.energy_after_j = Energy(geo_, Mode::kRest, s);
    AddEvent(std::move(ev));
    ++result_.summary.initiations;
  }
  while (!done_ && t_ < t_end_) {
    if (mode_ == Mode::kRest) {
      RunRest();
    } else {
      RunMoving();
    }
  }
  if (!done_) EmitSamplesUntil(t_end_, true);
  // Every event time is a sample too (the post-event state).
  auto& samples = result_.history.samples;
  std::vector<Sample> merged;
  merged.reserve(samples.size() + result_.history.events.size());
  size_t k = 0;
  for (const Event& ev : result_.history.events) {
    while (k < samples.size() && samples[k].t_s < ev.t_s) merged.push_back(std::move(samples[k++]));
    if (k < samples.size() && samples[k].t_s == ev.t_s) continue;
    if (!merged.empty() && merged.back().t_s == ev.t_s) continue;
    merged.push_back(result_.trajectory.At(ev.t_s));
  }
  while (k < samples.size()) merged.push_back(std::move(samples[k++]));
  samples = std::move(merged);
  if (result_.summary.status == RunStatus::kCompleted && mode_ == Mode::kRest &&
      t_ >= motion_.end_s()) {
    result_.summary.status = RunStatus::kAtRest;
  }
  result_.summary.rhs_evaluations = rhs_count_;
  return TakeResult();
}

}  // namespace

Result Simulate(const Scene& scene, const GroundMotion& motion) {
  // The scene's rules first (the same for every engine): its messages name the key and limit.
  ValidateScene(scene);
  RequireAtMostTwoBlocks(scene, "reference model");
  Simulator sim(scene, motion);
  return sim.Run();
}

}  // namespace rockbench::reference
