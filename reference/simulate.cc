// The reference model's driver: integrates the configuration's equations, locates events on
// the dense output, applies impacts and transitions, and monitors the model's assumptions. One
// driver for every stack: its mechanics (mechanics.h) are the thesis's explicit equations for one
// or two blocks, or the N-block chain.
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

#include "engine/non_finite.h"
#include "reference/mechanics.h"
#include "reference/unilateral_run.h"

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
template <class Fy, class Ry, class At, class Y>
std::pair<double, double> ProbeCheap(const Fy& fy, const Ry& ry, const At& at, const double* t,
                                     const Y* y, int n, double tol) {
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

double Side(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

// One component of the base motion, evaluated through the record's straight piece that held the
// last time asked for (bit for bit MotionComponent::accel_mps2, without its search at every
// call; an analytic component is evaluated directly).
class MotionCursor {
 public:
  explicit MotionCursor(const std::optional<MotionComponent>& c) : c_(c ? &*c : nullptr) {}
  // The common cases inline (no component, the same piece as last time), the rest out of line.
  [[gnu::always_inline]] double At(double t_s) const {
    if (!c_) return 0.0;
    if (piece_.Holds(t_s)) return piece_.At(t_s);
    return Seek(t_s);
  }

 private:
  [[gnu::noinline]] double Seek(double t_s) const {
    if (c_->kind() == MotionKind::kFile) {
      piece_ = c_->piece_at(t_s);
      if (piece_.Holds(t_s)) return piece_.At(t_s);
    }
    return c_->accel_mps2(t_s);
  }

  const MotionComponent* c_;
  mutable MotionComponent::LinearPiece piece_;
};

// The driver, on the mechanics Mech (mechanics.h): its state Y holds block i's angle at i and
// its rate at Mech::kCap + i.
template <class Mech>
class Simulator {
 public:
  using Y = typename Mech::Y;
  using Margins = typename Mech::Margins;
  using Dense = DenseStepN<std::tuple_size<Y>::value>;
  using Step = StepResultN<std::tuple_size<Y>::value>;
  static constexpr size_t kCap = Mech::kCap;

  Simulator(const Scene& scene, const GroundMotion& motion)
      : scene_(scene),
        cfg_(scene.model),
        motion_(motion),
        xg_(motion.horizontal()),
        yg_(motion.vertical()),
        mech_(scene),
        n_(mech_.blocks()),
        rest_(n_),
        config_(n_) {
    result_.summary = Summary(n_);
    result_.history.blocks = n_;
    result_.history.slip_and_lift = scene.tracks_slip_and_lift();
    result_.trajectory = Trajectory(n_, scene.tracks_slip_and_lift());
    unilateral_ = UnilateralApplies(scene, &unilateral_why_);
    double mass = 0.0;
    for (int k = 0; k < n_; ++k) {
      friction_[k] = scene.blocks[k].friction;
      finite_friction_ = finite_friction_ || std::isfinite(friction_[k]);
      mass += scene.blocks[k].mass_kg;
    }
    weight_n_ = mass * scene.run.gravity_mps2;
    for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
      if (*c && (*c)->samples_mps2().empty()) analytic_motion_ = true;
    }
    const double t_geo = mech_.time_scale_s();
    const double t_motion = MotionTimeScale(motion);
    event_tol_ = kEventTolRel * t_geo;
    max_step_ = std::min(kMaxStepRel * t_geo, kMaxStepMotion * t_motion);
    min_step_ = kMinStepRel * t_geo;
    rest_scan_ = kRestScanMotion * t_motion;
    h_ = std::min(kFirstStepRel * t_geo, max_step_);
    fig_.min_normal_n.fill(kInf);
    for (int k = 0; k < n_; ++k) impact_kinds_.push_back(InterfaceName(k, n_) + "_impact");
  }

  Result Run();

 private:
  // Base accelerations (m/s^2) at t.
  double Xg(double t) const { return xg_.At(t); }
  double Yg(double t) const { return yg_.At(t); }
  [[gnu::always_inline]] Y Rhs(double t, const Y& y) const {
    const Y f = mech_.Rhs(config_, y, Xg(t), Yg(t));
    ++rhs_count_;
    return f;
  }
  // Projects a state onto the configuration's constraints (a closed interface's block turns
  // with its support).
  Y Project(const Y& y) const { return mech_.Project(config_, y); }
  // Interface k's relative angle and rate (block k on its support; the ground's are zero).
  static double Rel(const Y& y, int k) { return k == 0 ? y[0] : y[k] - y[k - 1]; }
  static double RelRate(const Y& y, int k) {
    return k == 0 ? y[kCap] : y[kCap + k] - y[kCap + k - 1];
  }
  // Whether every angle and rate of a state is zero.
  bool AtRestState(const Y& y) const {
    for (int i = 0; i < n_; ++i) {
      if (y[i] != 0.0 || y[kCap + i] != 0.0) return false;
    }
    return true;
  }

  // The smallest friction margin (mu N - |T|) / (M g) over the interfaces of finite friction
  // that carry a compressive normal force; 1 when there is none. `tightest` (optional): that
  // interface (0 when there is none).
  double SlipMargin(const Margins& cm, int* tightest = nullptr) const {
    double m = 1.0;
    if (tightest != nullptr) *tightest = 0;
    if (!finite_friction_) return m;
    for (int k = 0; k < n_; ++k) {
      if (std::isfinite(friction_[k]) && cm.normal_n[k] > 0.0) {
        const double mk = cm.normal_n[k] * (friction_[k] - cm.mu[k]) / weight_n_;
        if (mk < m && tightest != nullptr) *tightest = k;
        m = std::min(m, mk);
      }
    }
    return m;
  }
  // The first interface whose friction margin is negative (-1: none).
  int SlippingInterface(const Margins& cm) const {
    for (int k = 0; k < n_ && finite_friction_; ++k) {
      if (std::isfinite(friction_[k]) && cm.normal_n[k] > 0.0 && cm.mu[k] > friction_[k]) return k;
    }
    return -1;
  }
  // Hands the run over to the unilateral model at (t, y) (unilateral_run.h): it runs to the
  // end.
  // `impact_interface` >= 0: at an impact of that interface, y the state just before it (the
  // unilateral model resolves the impact).
  void HandOver(double t, const Y& y, const std::string& reason, int impact_interface = -1);
  // Whether Coulomb's law forbids the chain's impact outcome `ir` from (before, pre): an
  // interface's impulse pulls or leaves its friction cone, or the outcome is inadmissible; `why`
  // says which.
  bool ChainImpactForbidden(const Configuration& before, const Y& pre,
                            const typename Mech::Impact& ir, int interface, std::string* why) const;

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
  [[gnu::noinline]] void AddEvent(Event&& ev) { result_.history.events.push_back(std::move(ev)); }
  // An event at t from `before` (rates of `pre`) to `after` (rates of `post`).
  [[gnu::noinline]] Event NewEvent(double t, const char* kind, const Configuration& before,
                                   const Configuration& after, const Y& pre, const Y& post) const {
    return ModeChangeEvent(n_, t, kind, before, after, pre.data() + kCap, post.data() + kCap, 1);
  }
  void Track(double t, const Y& y) {
    for (int i = 0; i < n_; ++i) {
      if (std::abs(y[i]) > fig_.peak_theta_rad[i]) {
        fig_.peak_theta_rad[i] = std::abs(y[i]);
        fig_.peak_theta_t_s[i] = t;
      }
    }
  }
  bool StartMode(double t, const Y& y, const char* kind, const Configuration& before,
                 const std::string& note);
  // At a located switch the choice of configuration can hang on rounding (a face force or an
  // opening acceleration of ~1e-16): the first time from t on (1e-12 s, doubling, up to t_max)
  // at which a configuration other than `leaving` is consistent; t itself when none is found.
  template <class StateAt>
  double SwitchTime(double t, double t_max, const Configuration& leaving,
                    const StateAt& state_at) const {
    for (double dt = 0.0; t + dt <= t_max; dt = dt == 0.0 ? EventTol(t) : 2 * dt) {
      const double tt = t + dt;
      const Selection sel = mech_.Select(state_at(tt), Xg(tt), Yg(tt));
      if (sel.consistent && sel.config != leaving) return tt;
    }
    return t;
  }
  void DoImpact(double t, const Y& pre, int interface);
  void RunRest();
  // RunMoving's parts: one step of the configuration's equations, the earliest event inside it,
  // the step's record (trajectory, samples, peaks, reactions) and the event's handling.
  enum class StepEvent { kNone, kImpact, kOverturn, kMargin };
  struct LocatedEvent {
    StepEvent which = StepEvent::kNone;
    int interface = 0;   // kImpact: the interface that lands
    double t = kInf;     // s, the located bracket's lower end (the event time)
    double t_hi = kInf;  // s, its upper end (just past the root)
  };
  // The state at t inside the step that starts at (t0, y0), projected onto the configuration,
  // and an enclosure [lo, hi] of it over the whole step (DenseStepN::Bounds, projected: Project
  // only copies and zeroes components). The states at the probe points (ProbeTime), which the
  // cheap event functions check, are evaluated once, when first asked for (Probe), and kept.
  struct StepDense {
    StepDense(const Simulator& s, const Step& r, double t_start, const Y& y_start)
        : sim(s), st(r), t0(t_start), y0(y_start) {
      r.dense.Bounds(&lo, &hi);
      lo = s.Project(lo);
      hi = s.Project(hi);
    }
    const Simulator& sim;
    const Step& st;
    double t0;
    Y y0;
    Y lo{}, hi{};
    mutable bool probed = false;
    mutable std::array<double, kInteriorChecks + 1> probe_t{};
    mutable std::array<Y, kInteriorChecks + 1> probe_y{};
    Y Evaluate(double t) const { return sim.Project(t == t0 ? y0 : st.dense.At(t)); }
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
    Y operator()(double t) const { return Evaluate(t); }
  };
  Step AdvanceOneStep(bool rk4, const Y& f0, double* h_taken);
  // The first zero of fn in [t_pos, t_neg], given fn(t_pos) = f_pos >= 0 > fn(t_neg) = f_neg,
  // kept in *ev when it is earlier than the event already there.
  template <class Fn>
  void Locate(StepEvent kind, int interface, const Fn& fn, double t_pos, double f_pos, double t_neg,
              double f_neg, LocatedEvent* ev) const;
  // fy, ry: the event function and its rate as functions of the state; lower: a lower bound of
  // fy over the step from the enclosure (at.lo, at.hi). When it is positive the function
  // cannot vanish in the step and the search is skipped: it would find nothing.
  template <class Fy, class Ry>
  void ConsiderCheap(StepEvent kind, int interface, const Fy& fy, const Ry& ry, double lower,
                     const StepDense& at, double t1, bool thesis_events, LocatedEvent* ev) const;
  LocatedEvent FindEvent(const StepDense& at, double t1, const Margins& cm1, bool thesis_events);
  void RecordStep(const StepDense& at, const Dense& dense, double t_seg_end, const Y& y_end,
                  const Margins& cm_end);
  // True when more than 20 events fall at one instant (an endless cascade).
  bool EventCascade(double t_ev);
  void HandleEvent(const LocatedEvent& ev, const StepDense& at, double t1, Y y);
  void RunMoving();
  // A quantity of the run that is not finite: its name and value (an empty name: none).
  struct NonFinite {
    std::string quantity;
    double value = 0.0;
    bool found() const { return !quantity.empty(); }
  };
  // The first of a state's angles and rates that is not finite: the angles block by block,
  // then the rates.
  [[gnu::cold]] NonFinite NonFiniteState(const Y& y) const;
  // The same for a step: its end state y1, the enclosure of its dense output (every state the
  // step's samples and events are taken from), the contact margins at its end and, above
  // kEnergyCheckRate_radps, the energy there. Called only when StepFinite says a value is not
  // finite (never on a valid run).
  [[gnu::cold]] NonFinite NonFiniteStep(const StepDense& at, const Y& y1, const Margins& cm1) const;
  // Whether NonFiniteStep finds nothing, cheaply: a sum is finite when every term is (a finite
  // sum that overflows is sorted out by NonFiniteStep).
  static bool StepFinite(const StepDense& at, const Y& y1, const Margins& cm1) {
    double sum = cm1.face + cm1.point;
    for (size_t i = 0; i < y1.size(); ++i) sum += y1[i] + at.lo[i] + at.hi[i];
    double rate = 0.0;
    for (size_t i = 0; i < kCap; ++i) rate = std::max(rate, std::abs(y1[kCap + i]));
    return std::isfinite(sum) && rate <= kEnergyCheckRate_radps;
  }
  // Ends the run at its last finite state `last`, at t_: status non_finite with `nf`, found at
  // t_bad (s), named in status_detail and in a "non_finite" event (Finish; the caller ends the
  // trajectory with EndTrajectory).
  [[gnu::cold]] void StopNonFinite(const NonFinite& nf, double t_bad, const Y& last);
  // After a stop at t_: the trajectory ends at t_ in y_, and the samples up to t_ are emitted.
  void EndTrajectory();
  Margins EvaluateAt(double t, const Y& y) const {
    return mech_.Evaluate(config_, y, Xg(t), Yg(t));
  }
  // Width to which an event near t is located: kEventTolRel sqrt(R / g), and never below a
  // few ulps of t.
  double EventTol(double t) const {
    return std::max(event_tol_, 8 * std::numeric_limits<double>::epsilon() * std::abs(t));
  }
  // Records an event that ends the run at t_ in state y (no change of state).
  [[gnu::noinline]] void StopWith(const char* kind, const Y& y, const std::string& note,
                                  RunStatus status) {
    Event ev = NewEvent(t_, kind, config_, config_, y, y);
    ev.energy_before_j = ev.energy_after_j = mech_.Energy(config_, y);
    ev.note = note;
    AddEvent(std::move(ev));
    y_ = y;
    Finish(status);
  }
  // Smallest normal reactions seen (summary).
  void NoteNormalForces(const Margins& cm) {
    for (int k = 0; k < n_; ++k) {
      fig_.min_normal_n[k] = std::min(fig_.min_normal_n[k], cm.normal_n[k]);
    }
  }
  // The result's summary gets the per-block figures.
  // The per-block figures into the summary (once: after a hand-over the unilateral model
  // carries the summary's on).
  void FlushFigures() {
    if (handed_over_) return;
    Summary& sum = result_.summary;
    for (int i = 0; i < n_; ++i) {
      sum.peak_theta_rad[i] = fig_.peak_theta_rad[i];
      sum.peak_theta_t_s[i] = fig_.peak_theta_t_s[i];
      sum.impacts_at[i] = fig_.impacts_at[i];
      sum.friction_required[i] = fig_.friction_required[i];
      sum.min_normal_n[i] = fig_.min_normal_n[i];
    }
  }
  Result TakeResult() {
    FlushFigures();
    return std::move(result_);
  }
  bool HandOverOrStop(double t, const Y& y, const std::string& reason) {
    if (!unilateral_) return false;
    HandOver(t, y, reason);
    return true;
  }
  void Finish(RunStatus status) {
    if (result_.summary.status == RunStatus::kCompleted) result_.summary.status = status;
    done_ = true;
  }

  const Scene& scene_;
  const ModelConfig& cfg_;
  const GroundMotion& motion_;
  MotionCursor xg_, yg_;
  const Mech mech_;
  const int n_;               // blocks
  const Configuration rest_;  // every interface closed
  Result result_;
  // The per-block figures of the summary while the run goes on (plain arrays in the loop).
  struct Figures {
    std::array<double, kCap> peak_theta_rad{}, peak_theta_t_s{};
    std::array<int, kCap> impacts_at{};
    std::array<double, kCap> friction_required{}, min_normal_n{};
  } fig_;
  std::vector<std::string> impact_kinds_;  // an impact's event kind, per interface
  Configuration config_;
  double t_ = 0.0;
  Y y_{};
  double t_end_ = 0.0;
  long next_sample_ = 0;
  bool done_ = false;
  bool analytic_motion_ = false;  // some component is an analytic kind (not a record)
  double event_tol_ = 0.0;        // s, see kEventTolRel
  double max_step_ = kInf;        // s, see kMaxStepRel
  double min_step_ = 0.0;         // s, see kMinStepRel
  double rest_scan_ = kInf;       // s, see kRestScanMotion
  double h_ = 0.0;                // the next trial step, s
  double break_from_ = kInf;      // s: motion_.next_breakpoint_after(t) is break_at_ for t in
  double break_at_ = kInf;        //    [break_from_, break_at_) (AdvanceOneStep)
  Margins cm0_;                   // the margins at the step start (when cm0_valid_)
  bool cm0_valid_ = false;
  mutable long rhs_count_ = 0;
  // The unilateral model (sliding and lift-off): whether it can take over, why not, each
  // block's friction, the total weight (N), and whether it took over and how it ended.
  bool unilateral_ = false;
  std::string unilateral_why_;
  std::array<double, kCap> friction_{};
  bool finite_friction_ = false;
  double weight_n_ = 1.0;
  bool handed_over_ = false;
  bool unilateral_at_rest_ = false;
  int same_time_events_ = 0;
  double last_event_t_ = -1.0;
};

template <class Mech>
void Simulator<Mech>::EmitSamples(double t_end, bool inclusive) {
  EmitTrajectorySamples(result_.trajectory, scene_.run.output_interval_s, t_end_, t_end, inclusive,
                        &next_sample_, &result_.history.samples);
}

template <class Mech>
bool Simulator<Mech>::StartMode(double t, const Y& y, const char* kind, const Configuration& before,
                                const std::string& note) {
  const Selection sel = mech_.Select(y, Xg(t), Yg(t));
  if (sel.consistent && finite_friction_) {
    // The configuration the thesis's contact conditions choose must also hold by friction.
    const int k = SlippingInterface(mech_.Evaluate(sel.config, y, Xg(t), Yg(t)));
    if (k >= 0 && HandOverOrStop(t, y, "block " + std::to_string(k + 1) + " slips")) {
      return false;
    }
  }
  if (!sel.consistent && HandOverOrStop(t, y, "a contact would pull (lift-off)")) return false;
  if (sel.consistent && sel.config == before) {
    config_ = sel.config;  // no event to record
    return true;
  }
  Event ev = NewEvent(t, kind, before, before, y, y);
  ev.energy_before_j = ev.energy_after_j = mech_.Energy(before, y);
  if (!sel.consistent) {
    ev.kind = "assumption_violated";
    ev.note = std::string("no ") + (n_ <= 2 ? "mode" : "configuration") +
              " satisfies the contact conditions (tensile normal force: uplift)";
    if (!unilateral_why_.empty()) ev.note += "; " + unilateral_why_;
    if (!sel.note.empty()) ev.note += "; " + sel.note;
    result_.summary.status_detail = ev.note;
    AddEvent(std::move(ev));
    result_.summary.status = RunStatus::kAssumptionViolated;
    done_ = true;
    return false;
  }
  ev.mode_after = sel.config;
  ev.note = note;
  if (std::string(kind) == "initiation") ++result_.summary.initiations;
  if (std::string(kind) == "transition") ++result_.summary.transitions;
  AddEvent(std::move(ev));
  config_ = sel.config;
  return true;
}

template <class Mech>
void Simulator<Mech>::DoImpact(double t, const Y& pre, int interface) {
  const Configuration before = config_;
  const typename Mech::Impact ir = mech_.ResolveImpact(before, pre, interface, cfg_.rest_rate_rel);
  // A post-impact state or energy that is not finite ends the run before the impact.
  NonFinite nf = NonFiniteState(ir.y);
  for (const double e : {ir.energy_before_j, ir.energy_after_j}) {
    if (!nf.found() && !std::isfinite(e)) nf = {"energy", e};
  }
  if (nf.found()) {
    nf.quantity += " after a" + std::string(interface == 0 ? " " : "n ") +
                   InterfaceName(interface, n_) + " impact";
    StopNonFinite(nf, t, pre);
    return;
  }
  // An impact whose no-slip impulse Coulomb's law forbids (it pulls, or leaves a friction cone)
  // is the unilateral model's: the run is handed over just before it, and that model resolves
  // it at the impulse level.
  if (unilateral_ && (finite_friction_ || !ir.admissible)) {
    std::string why;
    if (ChainImpactForbidden(before, pre, ir, interface, &why)) {
      HandOver(t, pre, why, interface);
      return;
    }
  }
  Summary& sum = result_.summary;
  Event ev = NewEvent(t, impact_kinds_[interface].c_str(), before, ir.config, pre, ir.y);
  ev.energy_before_j = ir.energy_before_j;
  ev.energy_after_j = ir.energy_after_j;
  ev.note = ir.note;
  Y still = pre;
  for (size_t i = 0; i < kCap; ++i) still[kCap + i] = 0.0;
  const double kinetic = std::max(0.0, ir.energy_before_j - mech_.Energy(before, still));
  if (ev.energy_after_j - ev.energy_before_j > 1e-9 * kinetic + 1e-12) {
    ++sum.impacts_energy_gain;
    ev.note += std::string(ev.note.empty() ? "" : " ") + "ENERGY GAIN";
  }
  if (!ir.admissible) ++sum.impacts_inadmissible;
  if (ir.admissible_outcomes > 1) ++sum.impacts_ambiguous;
  // From the first impact whose outcome the model does not decide, its history is one choice.
  if ((!ir.admissible || ir.admissible_outcomes > 1) && !sum.undetermined_from_s) {
    sum.undetermined_from_s = t;
    sum.undetermined_detail =
        "the " + InterfaceName(interface, n_) + " impact at t = " + MessageTimeText(t) + " s has " +
        (ir.admissible ? std::to_string(ir.admissible_outcomes) + " admissible outcomes"
                       : std::string("no admissible outcome"));
  }
  ++fig_.impacts_at[interface];
  AddEvent(std::move(ev));
  config_ = ir.config;
  // The post-impact configuration must also satisfy the contact forces (a locked pair may
  // open at once).
  StartMode(t, ir.y, "transition", config_, "after impact");
  y_ = ir.y;
}

template <class Mech>
void Simulator<Mech>::RunRest() {
  // Criterion while at rest: the smallest corner force of the faces (linear in xg'', yg'').
  // The last few values (a check starts where the last one ended).
  std::array<std::pair<double, double>, 4> memo;
  memo.fill({-kInf, 0.0});
  int next_memo = 0;
  // The first time a corner force at rest was not finite (an absurd base acceleration), and
  // its value; -1: none.
  double bad_t = -1.0, bad_value = 0.0;
  const Y still{};
  auto margin = [&](double t) {
    for (const auto& [tm, m] : memo) {
      if (tm == t) return m;
    }
    Margins cm = mech_.Evaluate(rest_, still, Xg(t), Yg(t));
    // Sliding from rest: the friction margin too (concave as the face's between samples).
    cm.face = std::min(cm.face, SlipMargin(cm));
    if (!std::isfinite(cm.face)) {
      if (bad_t < 0.0) {
        bad_t = t;
        bad_value = cm.face;
      }
    } else {
      NoteNormalForces(cm);
    }
    memo[next_memo] = {t, cm.face};
    next_memo = (next_memo + 1) % static_cast<int>(memo.size());
    return cm.face;
  };
  const double motion_end = motion_.end_s();
  y_ = Y{};
  while (!done_) {
    const double t0 = t_;
    if (t0 >= motion_end && margin(t0) >= 0.0) {
      // Nothing will move again: the blocks stay at rest to the end of the run.
      result_.trajectory.Append(t0, t_end_, rest_, Dense{}, kCap);
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
      t_start = SwitchTime(t_start, t_neg, rest_, [](double) { return Y{}; });
      t1 = t_start;
    }
    if (bad_t >= 0.0) {
      // The blocks are at rest at t0, the last finite state.
      StopNonFinite({"normal force at rest", bad_value}, bad_t, Y{});
      EndTrajectory();
      return;
    }
    result_.trajectory.Append(t0, t1, rest_, Dense{}, kCap);
    EmitSamplesUntil(t1, false);
    t_ = t1;
    if (t_start >= 0.0) {
      StartMode(t_, Y{}, "initiation", rest_, "");
      if (!config_.at_rest() || done_) return;
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

template <class Mech>
typename Simulator<Mech>::Step Simulator<Mech>::AdvanceOneStep(bool rk4, const Y& f0,
                                                               double* h_taken) {
  Summary& sum = result_.summary;
  // The next breakpoint of the base motion: the same until t_ reaches it.
  if (!(t_ >= break_from_ && t_ < break_at_)) {
    break_at_ = motion_.next_breakpoint_after(t_);
    break_from_ = t_;
  }
  const double t_break = break_at_;
  double h = rk4 ? cfg_.step_s : std::min(h_, max_step_);
  h = std::min({h, t_break - t_, t_end_ - t_});
  if (h <= 0.0) h = std::max(t_end_ - t_, 0.0);
  const auto rhs = [this](double t, const Y& y) { return Rhs(t, y); };
  const bool dop853 = cfg_.integrator == Integrator::kDop853;
  const int active = mech_.active();
  // One attempt of step hh (built in place: a step's result is some fifty numbers).
  auto attempt = [&](double hh) {
    return rk4      ? Rk4Step(rhs, t_, y_, f0, hh)
           : dop853 ? Dop853Step(rhs, t_, y_, f0, hh, cfg_.rtol, cfg_.atol, active)
                    : Dopri5Step(rhs, t_, y_, f0, hh, cfg_.rtol, cfg_.atol, active);
  };
  Step st = attempt(h);
  if (!rk4) {
    // Step-size control as in dopri5.f and dop853.f: the error scales as h^(q + 1) with q the
    // order of the estimate the controller trusts (4 and 7), within their bounds on the ratio.
    const double expo = dop853 ? -1.0 / 8.0 : -0.2;
    const double fac_min = dop853 ? 1.0 / 3.0 : 0.2, fac_max = dop853 ? 6.0 : 5.0;
    while (!(st.err <= 1.0 || h < min_step_)) {
      ++sum.steps_rejected;
      h *= std::max(fac_min, 0.9 * std::pow(st.err, expo));
      st = attempt(h);
    }
    const double fac = st.err > 0 ? std::min(fac_max, 0.9 * std::pow(st.err, expo)) : fac_max;
    h_ = h * fac;
  }
  ++sum.steps_accepted;
  *h_taken = h;
  return st;
}

template <class Mech>
template <class Fn>
void Simulator<Mech>::Locate(StepEvent kind, int interface, const Fn& fn, double t_pos,
                             double f_pos, double t_neg, double f_neg, LocatedEvent* ev) const {
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
    ev->interface = interface;
  }
}

template <class Mech>
template <class Fy, class Ry>
void Simulator<Mech>::ConsiderCheap(StepEvent kind, int interface, const Fy& fy, const Ry& ry,
                                    double lower, const StepDense& at, double t1,
                                    bool thesis_events, LocatedEvent* ev) const {
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
  if (f_neg < 0.0) Locate(kind, interface, fn, t_, fa, t_neg, f_neg, ev);
}

template <class Mech>
typename Simulator<Mech>::LocatedEvent Simulator<Mech>::FindEvent(const StepDense& at, double t1,
                                                                  const Margins& cm1,
                                                                  bool thesis_events) {
  // Event functions, positive while nothing happens; the earliest zero is located. Besides
  // the step end, the step's interior is searched (ProbeCheap, ProbeExpensive) so that a
  // function that dips below zero and comes back within one step is not missed (the
  // thesis's scheme sees only the step end).
  LocatedEvent ev;
  // The angles' event functions cost one dense-output evaluation: checked at interior points
  // and at the minima between them (roots of their rates), unless the step's enclosure keeps
  // them positive. Each lower bound is a difference that is positive exactly when the
  // function's own floating-point value is positive wherever the enclosure holds.
  // Landings: each open interface's relative angle reaching zero (bottom first).
  for (int k = 0; k < n_; ++k) {
    if (config_[k] == Contact::kFace) continue;
    const double side = Side(config_[k]);
    // theta_k - theta_{k-1} (with theta_{k-1} = 0 on a grounded face, where [lo, hi] is
    // [0, 0]).
    const double lower = k == 0 ? (side > 0.0 ? at.lo[0] : -at.hi[0])
                                : (side > 0.0 ? at.lo[k] - at.hi[k - 1] : at.lo[k - 1] - at.hi[k]);
    ConsiderCheap(
        StepEvent::kImpact, k, [&](const Y& y) { return side * Rel(y, k); },
        [&](const Y& y) { return side * RelRate(y, k); }, lower, at, t1, thesis_events, &ev);
  }
  // Overturning: each block's |theta| reaching overturn_angle.
  const double over = cfg_.overturn_rad;
  for (int k = 0; k < n_; ++k) {
    ConsiderCheap(
        StepEvent::kOverturn, k, [&](const Y& y) { return over - std::abs(y[k]); },
        [&](const Y& y) { return y[k] < 0.0 ? y[kCap + k] : -y[kCap + k]; }, over - at.MaxAbs(k),
        at, t1, thesis_events, &ev);
  }
  // The contact margins (face corners opening: a transition; a pivot pulling: a violation)
  // cost a contact-force evaluation: checked at the midpoint and at the minimum of the
  // parabola through the values when it lies inside the step and near zero.
  if (!cm0_valid_) cm0_ = EvaluateAt(t_, at(t_));
  auto margin_of = [&](const Margins& cm) {
    const double m = cfg_.check_transitions ? std::min(cm.face, cm.point) : cm.point;
    return std::min(m, SlipMargin(cm));
  };
  {
    auto fn = [&](double t) { return margin_of(EvaluateAt(t, at(t))); };
    const double m0 = margin_of(cm0_), m1 = margin_of(cm1);
    const auto [t_neg, f_neg] =
        thesis_events ? std::pair{t1, m1} : ProbeExpensive(fn, t_, m0, t1, m1, EventTol(t1));
    if (f_neg < 0.0) Locate(StepEvent::kMargin, 0, fn, t_, m0, t_neg, f_neg, &ev);
  }
  if (thesis_events && ev.which != StepEvent::kNone) {
    // The thesis's scheme: the event is seen at the step end, pre-impact rates are the
    // previous step's.
    ev.t = ev.t_hi = t1;
  }
  return ev;
}

template <class Mech>
void Simulator<Mech>::RecordStep(const StepDense& at, const Dense& dense, double t_seg_end,
                                 const Y& y_end, const Margins& cm_end) {
  result_.trajectory.Append(t_, t_seg_end, config_, dense, kCap);
  EmitSamplesUntil(t_seg_end, false);
  // Peaks: |theta| extremes sit where the rate vanishes inside the step, or at its ends. No
  // state of the step can raise a peak when the step's enclosure stays within all of them.
  bool within_peaks = true;
  for (int k = 0; k < n_ && within_peaks; ++k) {
    within_peaks = at.MaxAbs(k) <= fig_.peak_theta_rad[k];
  }
  const int searched = within_peaks ? 0 : n_;
  for (int k = 0; k < searched; ++k) {
    auto rate = [&](double t) { return at(t)[kCap + k]; };
    const double ra = rate(t_), rb = rate(t_seg_end);
    if (ra * rb < 0.0) {
      const auto br = BrentBracket(rate, t_, t_seg_end, ra, rb, EventTol(t_seg_end));
      Track(br.first, at(br.first));
    }
  }
  Track(t_seg_end, y_end);
  // Friction needed and normal forces along the solution (at step ends).
  for (int k = 0; k < n_; ++k) {
    fig_.friction_required[k] = std::max(fig_.friction_required[k], cm_end.mu[k]);
  }
  NoteNormalForces(cm_end);
}

template <class Mech>
bool Simulator<Mech>::EventCascade(double t_ev) {
  if (std::abs(t_ev - last_event_t_) <= EventTol(t_ev)) {
    if (++same_time_events_ > 20) return true;
  } else {
    same_time_events_ = 0;
  }
  last_event_t_ = t_ev;
  return false;
}

template <class Mech>
void Simulator<Mech>::HandleEvent(const LocatedEvent& ev, const StepDense& at, double t1, Y y) {
  Summary& sum = result_.summary;
  t_ = ev.t;
  switch (ev.which) {
    case StepEvent::kImpact: {
      // The landing interface's gap is exactly zero; the blocks above it that rest on their
      // faces land with it (those that rock keep their angles).
      y = mech_.Land(config_, y, ev.interface);
      DoImpact(t_, y, ev.interface);
      break;
    }
    case StepEvent::kOverturn: {
      // The block tilted furthest (the lowest of equals).
      int block = 0;
      for (int k = 1; k < n_; ++k) {
        if (std::abs(y[k]) > std::abs(y[block])) block = k;
      }
      sum.overturn_block = block + 1;
      sum.overturn_t_s = t_;
      StopWith("overturn", y, "block " + std::to_string(block + 1), RunStatus::kOverturned);
      break;
    }
    case StepEvent::kMargin: {
      // Just past the located root: the smaller of the two margins is the one that crossed.
      const Margins cmh = EvaluateAt(ev.t_hi, at(ev.t_hi));
      int k = 0;
      const double slip = SlipMargin(cmh, &k);
      // The located root's far side has the crossing margin at or below zero: a friction
      // margin of exactly zero there is the crossing one when it is the smallest (taking it for
      // a face opening found the same configuration again, at the same instant, for ever).
      if (slip <= 0.0 && slip <= cmh.point && (!cfg_.check_transitions || slip <= cmh.face)) {
        // A contact's friction is exhausted: the unilateral model goes on from just past it.
        t_ = ev.t_hi;
        y_ = at(ev.t_hi);
        HandOver(t_, y_, "block " + std::to_string(k + 1) + " slips");
      } else if (cfg_.check_transitions && cmh.face <= cmh.point) {
        // A face force has turned tensile: the face opens.
        t_ = SwitchTime(ev.t_hi, t1, config_, [&](double t) { return at(t); });
        const Y yh = at(t_);
        y_ = yh;
        StartMode(t_, yh, "transition", config_, "face opens");
      } else if (unilateral_) {
        t_ = ev.t_hi;
        y_ = at(ev.t_hi);
        HandOver(t_, y_, "a pivot would pull (lift-off)");
      } else {
        sum.status_detail = "tensile normal force at a pivot (uplift); " + unilateral_why_;
        StopWith("assumption_violated", y, sum.status_detail, RunStatus::kAssumptionViolated);
      }
      break;
    }
    case StepEvent::kNone:
      break;
  }
  if (done_ && !handed_over_) EndTrajectory();
}

template <class Mech>
bool Simulator<Mech>::ChainImpactForbidden(const Configuration& before, const Y& pre,
                                           const typename Mech::Impact& ir, int interface,
                                           std::string* why) const {
  std::array<double, kCap> theta{}, w0{}, w1{};
  double scale = 0.0;
  for (int i = 0; i < n_; ++i) {
    theta[i] = pre[i];
    w0[i] = pre[kCap + i];
    w1[i] = ir.y[kCap + i];
    scale += std::abs(w0[i]);
  }
  // Impulses are judged against the stack's momentum scale at the impact: its mass times the
  // sum of the rates times its height.
  double mass = 0.0, height = 0.0;
  for (const BlockDef& b : scene_.blocks) {
    mass += b.mass_kg;
    height += b.height_m;
  }
  const std::vector<InterfaceImpulse> p =
      ChainImpactImpulses(scene_, before, ir.config, theta.data(), w0.data(), w1.data());
  std::string cone;
  const int k = InterfaceOutsideCone(scene_, p, mass * scale * height, &cone);
  if (k < 0 && ir.admissible) return false;
  *why = k >= 0
             ? "at the " + InterfaceName(k, n_) + " impact, " + cone
             : "the " + InterfaceName(interface, n_) + " impact has no admissible no-slip outcome";
  return true;
}

template <class Mech>
void Simulator<Mech>::HandOver(double t, const Y& y, const std::string& reason,
                               int impact_interface) {
  // The chain's figures go to the summary, which the unilateral model carries on.
  FlushFigures();
  handed_over_ = true;
  Summary& sum = result_.summary;
  sum.rhs_evaluations += rhs_count_;
  rhs_count_ = 0;
  UnilateralStart start;
  start.t_s = t;
  start.config = config_;
  start.reason = reason;
  start.impact_interface = impact_interface;
  for (int i = 0; i < n_; ++i) {
    start.theta_rad.push_back(y[i]);
    start.omega_radps.push_back(y[kCap + i]);
  }
  const UnilateralSteps steps{t_end_, max_step_, min_step_, std::min(h_, max_step_), event_tol_};
  const UnilateralEnd end =
      ContinueUnilateral(scene_, motion_, start, steps, &result_, &next_sample_);
  config_ = end.config;
  unilateral_at_rest_ = end.at_rest;
  t_ = std::max(t_, result_.trajectory.end_s());
  done_ = true;
}

template <class Mech>
void Simulator<Mech>::EndTrajectory() {
  // The run stops at t_: the trajectory ends there.
  Dense last;
  last.c[0] = y_;
  result_.trajectory.Append(t_, t_, config_, last, kCap);
  const double stop = t_;
  t_end_ = stop;
  EmitSamplesUntil(stop, true);
}

template <class Mech>
typename Simulator<Mech>::NonFinite Simulator<Mech>::NonFiniteState(const Y& y) const {
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(y[i])) return {"theta" + std::to_string(i + 1), y[i]};
  }
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(y[kCap + i])) return {"omega" + std::to_string(i + 1), y[kCap + i]};
  }
  return {};
}

template <class Mech>
typename Simulator<Mech>::NonFinite Simulator<Mech>::NonFiniteStep(const StepDense& at, const Y& y1,
                                                                   const Margins& cm1) const {
  for (const Y* y : {&y1, &at.lo, &at.hi}) {
    if (NonFinite nf = NonFiniteState(*y); nf.found()) return nf;
  }
  if (const double e = mech_.Energy(config_, y1); !std::isfinite(e)) return {"energy", e};
  for (const double m : {cm1.face, cm1.point}) {
    if (!std::isfinite(m)) return {"contact force", m};
  }
  return {};
}

template <class Mech>
void Simulator<Mech>::StopNonFinite(const NonFinite& nf, double t_bad, const Y& last) {
  Summary& sum = result_.summary;
  sum.non_finite_quantity = nf.quantity;
  sum.non_finite_value = NonFiniteValueText(nf.value);
  sum.non_finite_t_s = t_bad;
  sum.non_finite_last_t_s = t_;
  sum.status_detail =
      nf.quantity + " is " + sum.non_finite_value + " at t = " + MessageTimeText(t_bad) +
      " s; the run stops at its last finite state, t = " + MessageTimeText(t_) + " s";
  StopWith("non_finite", last, sum.status_detail, RunStatus::kNonFinite);
}

template <class Mech>
void Simulator<Mech>::RunMoving() {
  const bool thesis_events = cfg_.events == EventScheme::kThesis;
  const bool rk4 = cfg_.integrator == Integrator::kRk4 || thesis_events;
  Y f0 = Rhs(t_, y_);
  cm0_valid_ = false;
  while (!done_) {
    double h = 0.0;
    const Step st = AdvanceOneStep(rk4, f0, &h);
    const double t1 = t_ + h;
    const Y y1 = Project(st.y1);
    const StepDense at(*this, st, t_, y_);
    // The last stage f(t1, y1) holds the configuration's accelerations at the step end: the
    // contact margins there reuse them (y1 is already on the constraints, so Project keeps it).
    const Margins cm1 = y1 == st.y1 ? mech_.EvaluateWithRhs(config_, y1, st.f1, Xg(t1), Yg(t1))
                                    : EvaluateAt(t1, y1);
    // A step that reaches a value that is not finite is not recorded: the run ends at its
    // start, the last finite state.
    if (!StepFinite(at, y1, cm1)) {
      if (const NonFinite nf = NonFiniteStep(at, y1, cm1); nf.found()) {
        StopNonFinite(nf, t1, y_);
        EndTrajectory();
        return;
      }
    }
    const LocatedEvent ev = FindEvent(at, t1, cm1, thesis_events);
    if (ev.which != StepEvent::kNone && !std::isfinite(ev.t)) {
      StopNonFinite({"event time", ev.t}, t1, y_);
      EndTrajectory();
      return;
    }
    const bool none = ev.which == StepEvent::kNone;
    const double t_seg_end = none ? t1 : ev.t;
    const Y y_end = none ? y1 : at(ev.t);
    RecordStep(at, st.dense, t_seg_end, y_end, none ? cm1 : EvaluateAt(t_seg_end, y_end));
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
    Y y = y_end;
    if (thesis_events) {
      for (size_t i = 0; i < kCap; ++i) y[kCap + i] = y_[kCap + i];
    }
    HandleEvent(ev, at, t1, y);
    // After an event the caller restarts integration (new configuration, new first stage).
    return;
  }
}

template <class Mech>
Result Simulator<Mech>::Run() {
  t_end_ = scene_.run.duration_s;
  Y y = mech_.Initial(scene_.initial);
  Track(0.0, y);
  for (int i = 0; i < n_; ++i) {
    if (std::abs(y[i]) >= cfg_.overturn_rad) {
      throw SceneError(scene_.path.string() + ": initial angle beyond model.overturn_angle");
    }
  }
  config_ = rest_;
  // The initial configuration: an interface with a gap or a rate is open on that side; closed
  // ones stay closed unless the forces open them.
  const double xg0 = Xg(0.0), yg0 = Yg(0.0);
  const Selection sel = mech_.Select(y, xg0, yg0);
  y_ = y;
  if (!sel.consistent) {
    // No configuration is consistent: an uplift, unless some contact forces are not finite
    // (an absurd base acceleration at t = 0, for which no comparison of forces holds).
    double bad_value = 0.0;
    const bool finite = !mech_.NonFiniteForces(y, xg0, yg0, &bad_value);
    if (finite && unilateral_) {
      HandOver(0.0, y, "the initial state satisfies no contact conditions of rocking");
    } else if (finite) {
      result_.summary.status = RunStatus::kAssumptionViolated;
      result_.summary.status_detail = std::string("the initial state satisfies no ") +
                                      (n_ <= 2 ? "mode's" : "configuration's") +
                                      " contact conditions";
      if (!sel.note.empty()) result_.summary.status_detail += "; " + sel.note;
      Dense seg;
      seg.c[0] = y_;
      result_.trajectory.Append(0.0, 0.0, rest_, seg, kCap);
      t_end_ = 0.0;
      EmitSamplesUntil(0.0, true);
      return TakeResult();
    }
    if (!finite) {
      StopNonFinite({"contact force", bad_value}, 0.0, y);
      EndTrajectory();
    }
  } else {
    config_ = sel.config;
    if (finite_friction_) {
      const int k = SlippingInterface(mech_.Evaluate(config_, y, xg0, yg0));
      if (k >= 0) HandOverOrStop(0.0, y, "block " + std::to_string(k + 1) + " slips");
    }
  }
  if (!done_ && cfg_.formulation == Formulation::kUnilateral) {
    if (!unilateral_)
      throw SceneError(scene_.path.string() + ": model.formulation: " + unilateral_why_);
    HandOver(0.0, y, "model.formulation = unilateral");
  }
  if (!done_ && !config_.at_rest() && AtRestState(y)) {
    // Motion starts at t = 0 from rest.
    Event ev = NewEvent(0.0, "initiation", rest_, config_, Y{}, Y{});
    ev.energy_before_j = ev.energy_after_j = mech_.Energy(rest_, y);
    AddEvent(std::move(ev));
    ++result_.summary.initiations;
  }
  while (!done_ && t_ < t_end_) {
    if (config_.at_rest()) {
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
  if (result_.summary.status == RunStatus::kCompleted &&
      (handed_over_ ? unilateral_at_rest_ : config_.at_rest()) && t_ >= motion_.end_s()) {
    result_.summary.status = RunStatus::kAtRest;
  }
  result_.summary.rhs_evaluations += rhs_count_;
  return TakeResult();
}

template <class Mech>
Result Run(const Scene& scene, const GroundMotion& motion) {
  Simulator<Mech> sim(scene, motion);
  return sim.Run();
}

}  // namespace

bool UsesThesisEquations(const Scene& scene) {
  const Formulation f = scene.model.formulation;
  return f == Formulation::kThesis || (f == Formulation::kAuto && scene.block_count() <= 2);
}

Result Simulate(const Scene& scene, const GroundMotion& motion) {
  // The scene's rules first (the same for every engine): its messages name the key and limit.
  ValidateScene(scene);
  const int n = scene.block_count();
  if (scene.has_finite_friction()) {
    std::string why;
    if (!UnilateralApplies(scene, &why)) {
      throw SceneError(scene.path.string() + ": block" + std::to_string(n) +
                       ".friction: a finite friction needs the unilateral model, but " + why);
    }
  }
  if (UsesThesisEquations(scene)) return Run<ThesisMechanics>(scene, motion);
  // The chain's state holds the smallest power of two of blocks that fits the stack.
  if (n <= 2) return Run<ChainMechanics<2>>(scene, motion);
  if (n <= 4) return Run<ChainMechanics<4>>(scene, motion);
  if (n <= 8) return Run<ChainMechanics<8>>(scene, motion);
  if (n <= 16) return Run<ChainMechanics<16>>(scene, motion);
  if (n <= 32) return Run<ChainMechanics<32>>(scene, motion);
  return Run<ChainMechanics<64>>(scene, motion);
}

}  // namespace rockbench::reference
