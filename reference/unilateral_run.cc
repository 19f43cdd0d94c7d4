#include "reference/unilateral_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "engine/outcome.h"
#include "reference/integration/integrator.h"
#include "reference/unilateral/unilateral.h"

namespace rockbench::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Relative tolerances of the contact conditions and events: forces to 1e-9 of the weight,
// gaps to 1e-10 of the largest half-diagonal, rates to 1e-9 of sqrt(g L).
constexpr double kForceTolRel = 1e-9;
constexpr double kGapTolRel = 1e-10;
constexpr double kRateTolRel = 1e-9;

// A trajectory segment's state read as a sample.
class View : public StateView {
 public:
  explicit View(const UnilateralStack& stack) : stack_(stack) {}
  int components() const override { return 6 * stack_.size(); }
  void Fill(const double* state, Sample* out) const override {
    const int n = stack_.size();
    const double* q = state;
    const double* v = state + 3 * n;
    for (int i = 0; i < n; ++i) {
      out->theta_rad[i] = q[3 * i + 2];
      out->omega_radps[i] = v[3 * i + 2];
      if (out->u_m.size() == static_cast<size_t>(n)) {
        double u = 0.0, z = 0.0;
        stack_.SlipAndLift(i, q, &u, &z);
        out->u_m[i] = u;
        out->z_m[i] = z;
      }
    }
  }

 private:
  UnilateralStack stack_;
};

const char* SlipText(Slip s) {
  return s == Slip::kStick ? "sticks" : s == Slip::kRight ? "slips right" : "slips left";
}

// One interface's contact state in words: "sticks on its face", "slips right on its right
// corner", "flies".
std::string StateText(const ContactMode& m, int k) {
  if (!m.any_closed(k)) return "flies";
  const char* where = m.closed[k][0] && m.closed[k][1] ? "its face"
                      : m.closed[k][0]                 ? "its right corner"
                                                       : "its left corner";
  return std::string(SlipText(m.slip[k])) + " on " + where;
}

// The driver for stacks of at most kCap blocks: its state arrays have that many blocks' room
// (a stack of two does not step, zero and copy twenty blocks' arrays).
template <int kCap>
class Runner {
  // The state: q (3 per block) from 0, v from kSecond, padded with zeros to kState.
  static constexpr size_t kSecond = 3 * static_cast<size_t>(kCap);
  static constexpr size_t kState = 2 * kSecond;
  using Y = VecN<kState>;
  using Dense = DenseStepN<kState>;
  using Step = StepResultN<kState>;

 public:
  Runner(const Scene& scene, const GroundMotion& motion, const UnilateralStart& start,
         const UnilateralSteps& steps, Result* result, long* next_sample)
      : scene_(scene),
        motion_(motion),
        stack_(UnilateralStack::OfScene(scene)),
        n_(stack_.size()),
        steps_(steps),
        r_(result),
        next_sample_(next_sample),
        mode_(n_),
        slip_armed_(static_cast<size_t>(n_), false),
        impact_interface_(start.impact_interface) {
    const double L = stack_.length_scale_m();
    gap_tol_ = kGapTolRel * L;
    rate_tol_ = kRateTolRel * std::sqrt(stack_.g_mps2() * L);
    force_tol_ = kForceTolRel * stack_.weight_n();
    t_ = start.t_s;
    stack_.FromChain(start.config, start.theta_rad.data(), start.omega_radps.data(), y_.data(),
                     y_.data() + kSecond);
    view_ = std::make_shared<View>(stack_);
    r_->trajectory.SetStateView(view_);
    config_ = start.config;
    h_ = steps.first_step_s;
  }

  UnilateralEnd Go(const std::string& reason);

 private:
  const double* Q(const Y& y) const { return y.data(); }
  const double* V(const Y& y) const { return y.data() + kSecond; }
  double Xg(double t) const { return motion_.xg_mps2(t); }
  double Yg(double t) const { return motion_.yg_mps2(t); }

  Y Rhs(double t, const Y& y) const {
    Y f{};
    std::array<double, kSecond> acc{};
    if (!stack_.Accelerations(mode_, Q(y), V(y), Xg(t), Yg(t), acc.data())) {
      acc.fill(std::numeric_limits<double>::quiet_NaN());
    }
    for (int i = 0; i < 3 * n_; ++i) {
      f[i] = y[kSecond + i];
      f[kSecond + i] = acc[i];
    }
    ++r_->summary.rhs_evaluations;
    return f;
  }

  // Event functions, positive while nothing happens (each with its tolerance added, so that a
  // located root is just past the condition's own tolerance).
  enum class Kind { kLanding, kLift, kCone, kSlipStop, kEdge, kOverturn };
  struct EventFn {
    Kind kind;
    int k = 0, j = 0;
  };
  double Value(const EventFn& e, double t, const Y& y) const;
  std::vector<EventFn> Functions() const;

  // Go's parts, each false when the run stopped (stated): the hand-over from the chain (the
  // mode, or the impact, at t_), one accepted step from t_ (h its size), a finite end state,
  // the step's earliest event (its index in fns, -1: none; *t_ev its instant), the segment up
  // to t_seg recorded (friction's work, the trajectory, samples, peaks), the event at t_seg
  // handled, and the end (the last sample, at rest or not).
  bool HandOver(const std::string& reason);
  bool AcceptedStep(double t_break, const Y& f0, Step* st, double* h);
  bool FiniteEnd(const Y& y1, double t1);
  int EarliestEvent(const std::vector<EventFn>& fns, double t1, const Dense& dense,
                    double* t_ev) const;
  void RecordSegment(const Dense& dense, double t_seg, const Y& y_end);
  bool AtEvent(const EventFn& e, double t_seg, const Y& y_end);
  UnilateralEnd Finish();
  // The state at t in the step from t_ (y_ itself at t_).
  Y At(const Dense& dense, double t) const { return t == t_ ? y_ : dense.At(t); }

  // The contact state from (t, y) on, from its complementarity problem; false: none (the run
  // stops, stated).
  bool NewMode(double t, const Y& y, const char* kind, const std::string& why);
  // The impact of a slot of interface k landing at (t_, y_): its outcome, event and the mode
  // after it; false: the run stopped.
  bool Impact(int k);
  void AddEvent(double t, const std::string& kind, const Configuration& before,
                const Configuration& after, const Y& pre, const Y& post, const std::string& note);
  void Stop(double t, const Y& y, RunStatus status, const std::string& kind,
            const std::string& detail);
  void Emit(double t_end, bool inclusive);
  void Track(double t, const Y& y);
  void NoteForces(const Y& y, double t);
  std::string Changes(const ContactMode& before, const ContactMode& after) const;
  std::string EpisodeAudit(const ContactMode& before);
  // Friction's power, W (>= 0), and per interface (with `per`).
  // The contact forces of the current mode at (t, y) (null: its equations are singular), kept
  // for the last instant asked.
  const ModeSolution* Forces(double t, const Y& y) const;
  double FrictionPower(double t, const Y& y, std::array<double, kCap>* per = nullptr) const;
  // Interface k's slip rate at its first closed slot of the current mode, m/s.
  double SlipRate(int k, const Y& y) const {
    const auto s = stack_.Slots(k, Q(y), V(y), &mode_);
    return (mode_.closed[k][0] ? s[0] : s[1]).slip_rate_mps;
  }
  // Arms the slip-stop event of every slipping interface whose rate in its slip's direction
  // exceeds the rate tolerance at y; with `reset` (a new mode), disarms the others.
  void ArmSlipStops(const Y& y, bool reset) {
    for (int k = 0; k < n_; ++k) {
      const bool slips = mode_.any_closed(k) && mode_.slip[k] != Slip::kStick;
      if (!slips) {
        slip_armed_[k] = false;
        continue;
      }
      const bool beyond = static_cast<int>(mode_.slip[k]) * SlipRate(k, y) > rate_tol_;
      slip_armed_[k] = beyond || (!reset && slip_armed_[k]);
    }
  }
  // The stack with its friction changed to mu (every interface's with `every`, else only the
  // infinite ones), built once into *cache: the fallbacks of an impact with no Coulomb outcome.
  const UnilateralStack& StackWithFriction(std::optional<UnilateralStack>* cache, bool every,
                                           double mu) {
    if (!*cache) {
      std::vector<UnilateralBlock> blocks;
      for (int i = 0; i < n_; ++i) {
        UnilateralBlock b = stack_.block(i);
        if (every || std::isinf(b.friction)) b.friction = mu;
        blocks.push_back(b);
      }
      cache->emplace(std::move(blocks), stack_.g_mps2());
    }
    return **cache;
  }
  bool HasClosed() const {
    for (int k = 0; k < n_; ++k) {
      if (mode_.any_closed(k)) return true;
    }
    return false;
  }

  const Scene& scene_;
  const GroundMotion& motion_;
  const UnilateralStack stack_;
  const int n_;
  UnilateralSteps steps_;
  Result* r_;
  long* next_sample_;
  std::shared_ptr<View> view_;
  ContactMode mode_;
  Configuration config_;
  double t_ = 0.0, h_ = 0.0;
  Y y_{};
  double gap_tol_ = 0.0, rate_tol_ = 0.0, force_tol_ = 0.0;
  bool done_ = false;
  std::optional<UnilateralStack> frictionless_, limit_;
  // Per interface: its slip-stop event is armed (see Value, kSlipStop).
  std::vector<bool> slip_armed_;
  // >= 0: handed over at an impact of this interface (UnilateralStart::impact_interface).
  int impact_interface_ = -1;
  // Forces' last solve: its instant, state and mode, and what it gave.
  mutable struct {
    bool valid = false, solved = false;
    double t = 0.0;
    Y y{};
    ContactMode mode;
    ModeSolution forces;
  } memo_;
  // Friction's work at each interface since its slip began, J (the episode's energy audit).
  std::array<double, kCap> episode_work_j_{};
  int same_time_events_ = 0;
  double last_event_t_ = -1.0;
};

template <int kCap>
std::vector<typename Runner<kCap>::EventFn> Runner<kCap>::Functions() const {
  std::vector<EventFn> out;
  for (int k = 0; k < n_; ++k) {
    const bool closed = mode_.any_closed(k);
    for (int j = 0; j < 2; ++j) {
      if (mode_.closed[k][j]) {
        out.push_back({Kind::kLift, k, j});
        if (k > 0) out.push_back({Kind::kEdge, k, j});
      } else {
        out.push_back({Kind::kLanding, k, j});
      }
    }
    const double mu = stack_.block(k).friction;
    // A sticking interface of finite friction may reach its cone; a slipping one, whatever its
    // friction (infinite friction's limit slip included), may stop.
    if (closed && mu > 0.0 && mode_.slip[k] != Slip::kStick) {
      out.push_back({Kind::kSlipStop, k, 0});
    } else if (closed && mu > 0.0 && std::isfinite(mu)) {
      out.push_back({Kind::kCone, k, 0});
    }
  }
  for (int i = 0; i < n_; ++i) out.push_back({Kind::kOverturn, i, 0});
  return out;
}

template <int kCap>
double Runner<kCap>::Value(const EventFn& e, double t, const Y& y) const {
  const double L = stack_.length_scale_m();
  switch (e.kind) {
    case Kind::kOverturn:
      return scene_.model.overturn_rad - std::abs(y[3 * e.k + 2]);
    case Kind::kLanding: {
      const SlotKinematics s = stack_.Slots(e.k, Q(y), V(y))[e.j];
      // An empty slot cannot land; its value stays positive.
      if (!s.exists) return 1.0;
      // Approaching faster than the rate tolerance: the root where the gap is zero. (A root
      // inside the face would be put back on it after the impact, adding m g times that depth
      // per landing: a cascade then never came to rest, docs/sliding.md.)
      if (s.gap_rate_mps < -rate_tol_) return s.gap_m / L;
      // Else not approaching: no landing. A slot that has just opened has a gap and a rate of
      // rounding's size, of either sign; a corner that stops within the gap tolerance of its
      // face lands when it comes back faster than the rate tolerance.
      return std::max(s.gap_m, 0.5 * gap_tol_) / L;
    }
    case Kind::kEdge: {
      // The closed point's face ends under it: the block's corner passes its support's edge,
      // or (the support's corner) leaves the block's base or comes back under the block's
      // corner. Continuous: the mode keeps its point past the edge.
      const SlotKinematics s = stack_.Slots(e.k, Q(y), V(y), &mode_)[e.j];
      const double edge = stack_.block(e.k - 1).b_m * (1.0 + 1e-9), bU = stack_.block(e.k).b_m;
      return s.upper_corner ? (edge - std::abs(s.xi_upper_corner_m)) / L
                            : std::min(bU - std::abs(s.xi_support_corner_m),
                                       std::abs(s.xi_upper_corner_m) - edge) /
                                  L;
    }
    case Kind::kLift:
    case Kind::kCone: {
      const ModeSolution* forces = Forces(t, y);
      if (forces == nullptr) return -1.0;
      const ModeSolution& f = *forces;
      // Roots at twice the contact conditions' tolerance: past them, so that the mode that
      // ends is no longer consistent where the next is sought.
      if (e.kind == Kind::kLift) {
        return (f.slot_normal[e.k][e.j] + 2.0 * force_tol_) / stack_.weight_n();
      }
      const double mu = stack_.block(e.k).friction;
      return (mu * f.normal[e.k] - std::abs(f.tangential[e.k]) + 2.0 * force_tol_) /
             stack_.weight_n();
    }
    case Kind::kSlipStop: {
      // The slip rate in the slip's direction. A slip that began within the rate tolerance of
      // zero (a slip from rest, its acceleration pointing its way) is armed once its rate
      // exceeds that tolerance; until then it ends only when its rate falls the tolerance the
      // other way, so that the rounding of a rate of ~1e-18 m/s at its first instant is not
      // taken for its end (which gave the same mode again, at the same instant, for ever).
      const double rate = static_cast<int>(mode_.slip[e.k]) * SlipRate(e.k, y);
      return (slip_armed_[e.k] ? rate : rate + rate_tol_) / std::sqrt(stack_.g_mps2() * L);
    }
  }
  return 1.0;
}

template <int kCap>
const ModeSolution* Runner<kCap>::Forces(double t, const Y& y) const {
  // The event functions of every closed slot and interface, friction's power and the
  // summary's forces all ask at the same step end: one solve serves them.
  if (!(memo_.valid && memo_.t == t && memo_.y == y && memo_.mode == mode_)) {
    std::array<double, kSecond> acc{};
    memo_.solved = stack_.Accelerations(mode_, Q(y), V(y), Xg(t), Yg(t), acc.data(), &memo_.forces);
    memo_.t = t;
    memo_.y = y;
    memo_.mode = mode_;
    memo_.valid = true;
  }
  return memo_.solved ? &memo_.forces : nullptr;
}

template <int kCap>
double Runner<kCap>::FrictionPower(double t, const Y& y, std::array<double, kCap>* per) const {
  double p = 0.0;
  if (per != nullptr) per->fill(0.0);
  bool any = false;
  for (int k = 0; k < n_; ++k) any = any || (mode_.any_closed(k) && mode_.slip[k] != Slip::kStick);
  if (!any) return 0.0;
  const ModeSolution* forces = Forces(t, y);
  if (forces == nullptr) return 0.0;
  const ModeSolution& f = *forces;
  for (int k = 0; k < n_; ++k) {
    if (!mode_.any_closed(k) || mode_.slip[k] == Slip::kStick) continue;
    const auto s = stack_.Slots(k, Q(y), V(y), &mode_);
    const SlotKinematics& ref = mode_.closed[k][0] ? s[0] : s[1];
    // The friction force times the slip rate: -T v_t >= 0 when T opposes the slip.
    const double pk = -f.tangential[k] * ref.slip_rate_mps;
    p += pk;
    if (per != nullptr) (*per)[k] = pk;
  }
  return p;
}

template <int kCap>
void Runner<kCap>::Track(double t, const Y& y) {
  Summary& sum = r_->summary;
  for (int i = 0; i < n_; ++i) {
    const double a = std::abs(y[3 * i + 2]);
    if (a > sum.peak_theta_rad[i]) {
      sum.peak_theta_rad[i] = a;
      sum.peak_theta_t_s[i] = t;
    }
  }
}

template <int kCap>
void Runner<kCap>::NoteForces(const Y& y, double t) {
  const ModeSolution* forces = Forces(t, y);
  if (forces == nullptr) return;
  const ModeSolution& f = *forces;
  Summary& sum = r_->summary;
  for (int k = 0; k < n_; ++k) {
    if (!mode_.any_closed(k)) continue;
    sum.min_normal_n[k] = std::min(sum.min_normal_n[k], f.normal[k]);
    if (mode_.slip[k] == Slip::kStick && f.normal[k] > 0.0) {
      sum.friction_required[k] =
          std::max(sum.friction_required[k], std::abs(f.tangential[k]) / f.normal[k]);
    }
  }
}

template <int kCap>
void Runner<kCap>::Emit(double t_end, bool inclusive) {
  EmitTrajectorySamples(r_->trajectory, scene_.run.output_interval_s, steps_.t_end_s, t_end,
                        inclusive, next_sample_, &r_->history.samples);
}

template <int kCap>
void Runner<kCap>::AddEvent(double t, const std::string& kind, const Configuration& before,
                            const Configuration& after, const Y& pre, const Y& post,
                            const std::string& note) {
  // Block i's rate: the third of its three velocities (x, y, phi).
  Event ev = ModeChangeEvent(n_, t, kind, before, after, pre.data() + kSecond + 2,
                             post.data() + kSecond + 2, 3);
  ev.energy_before_j = stack_.Energy(Q(pre), V(pre));
  ev.energy_after_j = stack_.Energy(Q(post), V(post));
  ev.note = note;
  r_->history.events.push_back(std::move(ev));
}

template <int kCap>
void Runner<kCap>::Stop(double t, const Y& y, RunStatus status, const std::string& kind,
                        const std::string& detail) {
  AddEvent(t, kind, config_, config_, y, y, detail);
  Summary& sum = r_->summary;
  if (sum.status == RunStatus::kCompleted) sum.status = status;
  if (status != RunStatus::kOverturned) sum.status_detail = detail;
  Dense last;
  last.c[0] = y;
  r_->trajectory.AppendState(t, t, config_, last, kSecond);
  Emit(t, true);
  t_ = t;
  y_ = y;
  done_ = true;
}

template <int kCap>
std::string Runner<kCap>::EpisodeAudit(const ContactMode& before) {
  // Each interface whose slip ends here: the energy friction dissipated over the episode.
  std::string out;
  for (int k = 0; k < n_; ++k) {
    const bool slipped = before.any_closed(k) && before.slip[k] != Slip::kStick;
    const bool slips = mode_.any_closed(k) && mode_.slip[k] == before.slip[k];
    if (!slipped || slips) continue;
    char buf[96];
    std::snprintf(buf, sizeof buf, "; block %d's slip dissipated %.6g J", k + 1,
                  episode_work_j_[k]);
    out += buf;
    episode_work_j_[k] = 0.0;
  }
  return out;
}

template <int kCap>
std::string Runner<kCap>::Changes(const ContactMode& before, const ContactMode& after) const {
  std::string out;
  for (int k = 0; k < n_; ++k) {
    const std::string a = StateText(before, k), b = StateText(after, k);
    if (a == b) continue;
    if (!out.empty()) out += "; ";
    out += "block " + std::to_string(k + 1) + " " + a + " -> " + b;
  }
  return out;
}

template <int kCap>
bool Runner<kCap>::NewMode(double t, const Y& y, const char* kind, const std::string& why) {
  const ModeSolution sol = stack_.Solve(Q(y), V(y), Xg(t), Yg(t), mode_, gap_tol_, rate_tol_);
  Summary& sum = r_->summary;
  if (!sol.found) {
    config_ = stack_.ConfigurationOf(mode_, Q(y));
    Stop(t, y, RunStatus::kAssumptionViolated, "assumption_violated",
         "no contact state at t = " + std::to_string(t) + " s: " + sol.note);
    return false;
  }
  if (sol.solutions > 1 && !sum.undetermined_from_s) {
    sum.undetermined_from_s = t;
    sum.undetermined_detail = "the contact state at t = " + std::to_string(t) + " s: " + sol.note;
  }
  const ContactMode before = mode_;
  const Configuration config_before = config_;
  mode_ = sol.mode;
  config_ = stack_.ConfigurationOf(mode_, Q(y));
  ArmSlipStops(y, true);
  if (kind[0] == '\0' || (before == mode_ && why.find("edge") == std::string::npos &&
                          why.find("base end") == std::string::npos)) {
    return true;
  }
  for (int k = 0; k < n_; ++k) {
    if (before.any_closed(k) && !mode_.any_closed(k)) ++sum.lift_offs;
    if (mode_.any_closed(k) && mode_.slip[k] != Slip::kStick &&
        (!before.any_closed(k) || before.slip[k] == Slip::kStick)) {
      ++sum.slip_starts;
    }
  }
  {
    std::string note = Changes(before, mode_);
    if (!why.empty()) note = why + (note.empty() ? "" : ": " + note);
    note += EpisodeAudit(before);
    if (sol.solutions > 1) note += " (" + sol.note + ")";
    AddEvent(t, kind, config_before, config_, y, y, note);
    ++sum.transitions;
  }
  return true;
}

template <int kCap>
bool Runner<kCap>::Impact(int k) {
  Summary& sum = r_->summary;
  ModeSolution imp = stack_.SolveImpact(Q(y_), V(y_), mode_, gap_tol_, scene_.model.rest_rate_rel);
  // Its outcome from `alt` instead, where Coulomb's law gives none: the note says which, the
  // contacts that close stick until the next mode decides, and `decided` says whether the
  // model's limit decides it (else the impact is undetermined).
  bool took_fallback = false;
  auto fall_back = [&](const UnilateralStack& alt, const std::string& what, bool decided) {
    const ModeSolution o =
        alt.SolveImpact(Q(y_), V(y_), mode_, gap_tol_, scene_.model.rest_rate_rel);
    if (!o.found) return;
    const std::string why = imp.note;
    imp = o;
    imp.found = decided;
    imp.note = why + what;
    for (int i = 0; i < n_; ++i) {
      if (!decided || std::isinf(stack_.block(i).friction)) imp.mode.slip[i] = Slip::kStick;
    }
    took_fallback = true;
  };
  bool infinite = false;
  for (int i = 0; i < n_; ++i) infinite = infinite || std::isinf(stack_.block(i).friction);
  // At infinite friction no sticking outcome may exist (the sticking impulse would pull): the
  // outcome is then the limit of Coulomb's as the friction grows, taken at mu = 1e4 (as the
  // contact problem's limit slip, docs/sliding.md). Decided by that limit, and said.
  if (!imp.found && infinite) {
    fall_back(StackWithFriction(&limit_, false, 1e4),
              " at infinite friction; the limit of Coulomb's outcome (mu = 1e4) follows", true);
  }
  // Still none (a sticking impulse that would pull, with no slip to take its place): the model
  // does not decide this impact (stated below). Leaving the velocities as they were would drive
  // the corner on into its face and land it again at the same instant for ever; the rule takes
  // the frictionless plastic outcome instead (the kinetic-energy projection onto the unilateral
  // constraints, a convex problem that always has its one solution), which stops every approach
  // and never adds energy.
  if (!imp.found) {
    fall_back(StackWithFriction(&frictionless_, true, 0.0), "; the frictionless outcome follows",
              false);
  }
  Y post = y_;
  for (int i = 0; i < 3 * n_; ++i) post[kSecond + i] = imp.result[i];
  if ((!imp.found || imp.solutions > 1) && !sum.undetermined_from_s) {
    sum.undetermined_from_s = t_;
    sum.undetermined_detail =
        "the " + InterfaceName(k, n_) + " impact at t = " + std::to_string(t_) + " s: " + imp.note;
  }
  if (!imp.found) ++sum.impacts_inadmissible;
  if (imp.solutions > 1) ++sum.impacts_ambiguous;
  const Configuration before = config_;
  const ContactMode mode_before = mode_;
  if (imp.found || took_fallback) mode_ = imp.mode;
  // A slip that the impact starts is a slip start.
  for (int i = 0; i < n_; ++i) {
    if (mode_.any_closed(i) && mode_.slip[i] != Slip::kStick &&
        (!mode_before.any_closed(i) || mode_before.slip[i] == Slip::kStick)) {
      ++sum.slip_starts;
    }
  }
  config_ = stack_.ConfigurationOf(mode_, Q(post));
  std::string note = Changes(mode_before, mode_) + EpisodeAudit(mode_before);
  if (!imp.note.empty()) note += (note.empty() ? "" : "; ") + imp.note;
  const double e0 = stack_.Energy(Q(y_), V(y_)), e1 = stack_.Energy(Q(post), V(post));
  if (e1 - e0 > 1e-9 * std::abs(e0) + 1e-12) {
    ++sum.impacts_energy_gain;
    note += " ENERGY GAIN";
  }
  AddEvent(t_, InterfaceName(k, n_) + "_impact", before, config_, y_, post, note);
  ++sum.impacts_at[k];
  y_ = post;
  return NewMode(t_, y_, "transition", "after impact");
}

template <int kCap>
bool Runner<kCap>::HandOver(const std::string& reason) {
  Summary& sum = r_->summary;
  sum.unilateral_from_s = t_;
  sum.unilateral_reason = reason;
  // The contact state at the hand-over: every slot at a zero gap may close.
  ContactMode chain(n_);
  for (int k = 0; k < n_; ++k) {
    chain.closed[k] = {config_[k] != Contact::kLeft, config_[k] != Contact::kRight};
  }
  mode_ = chain;
  if (impact_interface_ >= 0) {
    // Handed over at an impact: the chain's pivots closed and sticking just before it, the
    // impact resolved here (Coulomb at the impulse level), then the mode after it.
    AddEvent(t_, "transition", config_, config_, y_, y_, "unilateral model from here: " + reason);
    ++sum.transitions;
    return Impact(impact_interface_);
  }
  if (!NewMode(t_, y_, "", "")) return false;
  std::string note = "unilateral model from here: " + reason;
  const std::string ch = Changes(chain, mode_);
  if (!ch.empty()) note += ": " + ch;
  AddEvent(t_, "transition", config_, config_, y_, y_, note);
  ++sum.transitions;
  for (int k = 0; k < n_; ++k) {
    if (mode_.any_closed(k) && mode_.slip[k] != Slip::kStick) ++sum.slip_starts;
    if (!mode_.any_closed(k)) ++sum.lift_offs;
  }
  return true;
}

template <int kCap>
bool Runner<kCap>::AcceptedStep(double t_break, const Y& f0, Step* st, double* h) {
  Summary& sum = r_->summary;
  const bool dop853 = scene_.model.integrator == Integrator::kDop853;
  const double rtol = scene_.model.rtol, atol = scene_.model.atol;
  const int active = 6 * n_;
  while (true) {
    *h = std::min({h_, steps_.max_step_s, t_break - t_});
    if (t_break - t_ - *h < steps_.min_step_s) *h = t_break - t_;
    auto rhs = [&](double t, const Y& y) { return Rhs(t, y); };
    *st = dop853 ? Dop853Step(rhs, t_, y_, f0, *h, rtol, atol, active)
                 : Dopri5Step(rhs, t_, y_, f0, *h, rtol, atol, active);
    // A step whose error or end state is not finite is rejected (and shrunk).
    bool finite = std::isfinite(st->err);
    for (size_t i = 0; i < kState && finite; ++i) finite = std::isfinite(st->y1[i]);
    const double err = finite ? st->err : 1e10;
    const double order = dop853 ? 8.0 : 5.0;
    const double grow = err == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(err, -1.0 / order), 0.2, 5.0);
    if (err <= 1.0) {
      ++sum.steps_accepted;
      h_ = *h * grow;
      return true;
    }
    ++sum.steps_rejected;
    h_ = *h * grow;
    if (h_ < steps_.min_step_s) {
      Stop(t_, y_, RunStatus::kAssumptionViolated, "assumption_violated",
           "the unilateral model's step fell below its smallest at t = " + std::to_string(t_) +
               " s");
      return false;
    }
  }
}

template <int kCap>
bool Runner<kCap>::FiniteEnd(const Y& y1, double t1) {
  Summary& sum = r_->summary;
  for (size_t i = 0; i < kState; ++i) {
    if (!std::isfinite(y1[i])) {
      sum.non_finite_quantity = "state";
      sum.non_finite_value = std::isnan(y1[i]) ? "NaN" : y1[i] > 0 ? "+inf" : "-inf";
      sum.non_finite_t_s = t1;
      sum.non_finite_last_t_s = t_;
      Stop(t_, y_, RunStatus::kNonFinite, "non_finite",
           "the unilateral model's state is not finite at t = " + std::to_string(t1) + " s");
      return false;
    }
  }
  return true;
}

template <int kCap>
int Runner<kCap>::EarliestEvent(const std::vector<EventFn>& fns, double t1, const Dense& dense,
                                double* t_ev) const {
  double t_lo = kInf;
  int which = -1;
  const Y y_mid = At(dense, 0.5 * (t_ + t1));
  for (int e = 0; e < static_cast<int>(fns.size()); ++e) {
    auto fn = [&](double t) { return Value(fns[e], t, At(dense, t)); };
    double t_neg = t1, f_neg = fn(t1);
    if (!(f_neg < 0.0) && fns[e].kind == Kind::kLanding) {
      const double fm = Value(fns[e], 0.5 * (t_ + t1), y_mid);
      if (fm < 0.0) {
        t_neg = 0.5 * (t_ + t1);
        f_neg = fm;
      }
    }
    if (!(f_neg < 0.0)) continue;
    double f_a = fn(t_);
    if (!(f_a >= 0.0)) {
      // Already past its tolerance at the step's start: at once.
      if (t_ < t_lo) {
        t_lo = t_;
        *t_ev = t_;
        which = e;
      }
      continue;
    }
    const auto br = BrentBracket(fn, t_, t_neg, f_a, f_neg, steps_.event_tol_s);
    if (br.first < t_lo) {
      t_lo = br.first;
      *t_ev = br.second;
      which = e;
    }
  }
  return which;
}

template <int kCap>
void Runner<kCap>::RecordSegment(const Dense& dense, double t_seg, const Y& y_end) {
  Summary& sum = r_->summary;
  // Friction's work over the segment (Simpson's rule).
  {
    const double tm = 0.5 * (t_ + t_seg);
    std::array<double, kCap> p0{}, pm{}, p1{};
    const double p = (FrictionPower(t_, y_, &p0) + 4.0 * FrictionPower(tm, At(dense, tm), &pm) +
                      FrictionPower(t_seg, y_end, &p1)) /
                     6.0;
    sum.friction_work_j += std::max(0.0, p * (t_seg - t_));
    for (int k = 0; k < n_; ++k) {
      episode_work_j_[k] += std::max(0.0, (p0[k] + 4.0 * pm[k] + p1[k]) / 6.0 * (t_seg - t_));
    }
  }
  r_->trajectory.AppendState(t_, t_seg, config_, dense, kSecond);
  Emit(t_seg, false);
  // Peaks: the extremes of each angle inside the segment, and its end.
  for (int i = 0; i < n_; ++i) {
    auto rate = [&](double t) { return At(dense, t)[kSecond + 3 * i + 2]; };
    const double ra = rate(t_), rb = rate(t_seg);
    if (ra * rb < 0.0) {
      const auto br = BrentBracket(rate, t_, t_seg, ra, rb, steps_.event_tol_s);
      Track(br.first, At(dense, br.first));
    }
  }
  Track(t_seg, y_end);
  NoteForces(y_end, t_seg);
}

template <int kCap>
bool Runner<kCap>::AtEvent(const EventFn& e, double t_seg, const Y& y_end) {
  Summary& sum = r_->summary;
  if (std::abs(t_seg - last_event_t_) <= steps_.event_tol_s) {
    if (++same_time_events_ > 20) {
      Stop(t_seg, y_end, RunStatus::kAssumptionViolated, "assumption_violated",
           "event cascade at one instant (unilateral model)");
      return false;
    }
  } else {
    same_time_events_ = 0;
  }
  last_event_t_ = t_seg;
  t_ = t_seg;
  y_ = y_end;
  switch (e.kind) {
    case Kind::kOverturn:
      config_ = stack_.ConfigurationOf(mode_, Q(y_));
      sum.overturn_block = e.k + 1;
      sum.overturn_t_s = t_;
      Stop(t_, y_, RunStatus::kOverturned, "overturn", "block " + std::to_string(e.k + 1));
      return false;
    case Kind::kLanding:
      return Impact(e.k);
    case Kind::kEdge: {
      const bool upper = !mode_.support_corner[e.k][e.j];
      const std::string corner = e.j == 0 ? "right" : "left";
      const std::string what = upper ? "block " + std::to_string(e.k + 1) + "'s " + corner +
                                           " corner passes its support's edge"
                                     : "its support's " + corner + " corner reaches block " +
                                           std::to_string(e.k + 1) + "'s base end";
      if (!stack_.Slots(e.k, Q(y_), V(y_))[e.j].exists) {
        // Past both edges: the block has left its support (an outcome of its own, not an
        // overturn: the block may still stand upright).
        config_ = stack_.ConfigurationOf(mode_, Q(y_));
        sum.left_support_block = e.k + 1;
        sum.left_support_t_s = t_;
        Stop(t_, y_, RunStatus::kLeftSupport, "left_support",
             "block " + std::to_string(e.k + 1) + " slid off its support");
        return false;
      }
      return NewMode(t_, y_, "transition", what);
    }
    case Kind::kLift:
      return NewMode(t_, y_, "transition", "contact opens");
    case Kind::kCone:
      return NewMode(t_, y_, "transition", "friction cone reached");
    case Kind::kSlipStop:
      return NewMode(t_, y_, "transition", "slip stops");
  }
  return true;
}

template <int kCap>
UnilateralEnd Runner<kCap>::Finish() {
  if (!done_) {
    Dense last;
    last.c[0] = y_;
    r_->trajectory.AppendState(t_, t_, config_, last, kSecond);
    Emit(steps_.t_end_s, true);
  }
  UnilateralEnd end{config_, false};
  bool still = true;
  for (int k = 0; k < n_ && still; ++k) {
    still = mode_.closed[k][0] && mode_.closed[k][1] && mode_.slip[k] == Slip::kStick;
  }
  for (int i = 0; i < 3 * n_ && still; ++i) still = std::abs(y_[kSecond + i]) <= rate_tol_;
  end.at_rest = still && !done_;
  return end;
}

template <int kCap>
UnilateralEnd Runner<kCap>::Go(const std::string& reason) {
  if (!HandOver(reason)) return {config_, false};
  Y f0 = Rhs(t_, y_);
  while (!done_ && t_ < steps_.t_end_s) {
    // One accepted step, cut at the base motion's next kink.
    const double t_break = std::min(motion_.next_breakpoint_after(t_), steps_.t_end_s);
    Step st;
    double h = 0.0;
    if (!AcceptedStep(t_break, f0, &st, &h)) return {config_, false};
    const double t1 = t_ + h;
    if (!FiniteEnd(st.y1, t1)) return {config_, false};
    // The earliest event in the step: every function at the step end, the landings also at
    // its middle (a corner that touches and leaves within one step).
    const std::vector<EventFn> fns = Functions();
    double t_ev = kInf;
    const int which = EarliestEvent(fns, t1, st.dense, &t_ev);
    const bool none = which < 0;
    const double t_seg = none ? t1 : t_ev;
    const Y y_end = none ? st.y1 : At(st.dense, t_seg);
    RecordSegment(st.dense, t_seg, y_end);
    if (none) {
      t_ = t1;
      y_ = st.y1;
      f0 = st.f1;
      if (HasClosed()) {
        // Back on the constraints (the drift of one step), and the next step's first stage there.
        stack_.Project(mode_, y_.data(), y_.data() + kSecond);
        f0 = Rhs(t_, y_);
        ArmSlipStops(y_, false);
      }
      continue;
    }
    if (!AtEvent(fns[which], t_seg, y_end)) return {config_, false};
    f0 = Rhs(t_, y_);
  }
  return Finish();
}

}  // namespace

bool UnilateralApplies(const Scene& scene, std::string* why) {
  std::string w;
  if (scene.block_count() > kUnilateralMaxBlocks) {
    w = "the unilateral model takes at most " + std::to_string(kUnilateralMaxBlocks) + " blocks";
  } else if (scene.model.equations != Equations::kNonlinear) {
    w = "the unilateral model runs on the nonlinear equations only";
  } else if (scene.model.events != EventScheme::kLocated) {
    w = "the unilateral model locates its events (model.events = \"located\")";
  }
  if (why != nullptr) *why = w;
  return w.empty();
}

UnilateralEnd ContinueUnilateral(const Scene& scene, const GroundMotion& motion,
                                 const UnilateralStart& start, const UnilateralSteps& steps,
                                 Result* result, long* next_sample) {
  // Two sizes of state arrays: small stacks (the common case) and the largest.
  constexpr int kSmall = 4;
  if (scene.block_count() <= kSmall) {
    Runner<kSmall> run(scene, motion, start, steps, result, next_sample);
    return run.Go(start.reason);
  }
  Runner<kUnilateralMaxBlocks> run(scene, motion, start, steps, result, next_sample);
  return run.Go(start.reason);
}

std::vector<InterfaceImpulse> ChainImpactImpulses(const Scene& scene, const Configuration& before,
                                                  const Configuration& after,
                                                  const double* theta_rad,
                                                  const double* omega_before_radps,
                                                  const double* omega_after_radps) {
  const UnilateralStack stack = UnilateralStack::OfScene(scene);
  const int n = stack.size();
  std::vector<double> q0(3 * n), v0(3 * n), q1(3 * n), v1(3 * n);
  stack.FromChain(before, theta_rad, omega_before_radps, q0.data(), v0.data());
  stack.FromChain(after, theta_rad, omega_after_radps, q1.data(), v1.data());
  std::vector<InterfaceImpulse> out(static_cast<size_t>(n));
  // Interface k's impulse on block k: the momentum blocks k..N gain, summed from the top.
  double px = 0.0, py = 0.0;
  for (int k = n - 1; k >= 0; --k) {
    const double m = stack.block(k).mass_kg;
    px += m * (v1[3 * k] - v0[3 * k]);
    py += m * (v1[3 * k + 1] - v0[3 * k + 1]);
    // The support's top face: the ground's is level; block k - 1's turns with it.
    const double th = k > 0 ? theta_rad[k - 1] : 0.0;
    const double c = std::cos(th), s = std::sin(th);
    out[k].normal_ns = px * s + py * c;
    out[k].tangential_ns = px * c - py * s;
  }
  return out;
}

int InterfaceOutsideCone(const Scene& scene, const std::vector<InterfaceImpulse>& impulses,
                         double impulse_scale_ns, std::string* why) {
  const double tol = 1e-9 * impulse_scale_ns;
  for (size_t k = 0; k < impulses.size(); ++k) {
    const double mu = scene.blocks[k].friction;
    const InterfaceImpulse& p = impulses[k];
    char buf[200];
    if (p.normal_ns < -tol) {
      std::snprintf(buf, sizeof buf, "block %zu's no-slip impact impulse pulls (P_N = %.6g N s)",
                    k + 1, p.normal_ns);
    } else if (std::isfinite(mu) && std::abs(p.tangential_ns) > mu * p.normal_ns + tol) {
      std::snprintf(buf, sizeof buf,
                    "block %zu's no-slip impact impulse leaves its friction cone (|P_T| / P_N "
                    "= %.6g > mu = %.6g)",
                    k + 1, std::abs(p.tangential_ns) / std::max(p.normal_ns, 1e-300), mu);
    } else {
      continue;
    }
    if (why != nullptr) *why = buf;
    return static_cast<int>(k);
  }
  return -1;
}

}  // namespace rockbench::reference
