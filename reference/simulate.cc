// The reference model's driver: integrates the mode's equations, locates events on the dense
// output, applies impacts and transitions, and monitors the model's assumptions.
#include "reference/simulate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "reference/geometry.h"
#include "reference/impact.h"
#include "reference/kinematics.h"
#include "reference/modes.h"
#include "reference/transitions.h"

namespace rockbench::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Events are located to this width (s): the issue asks for better than 1e-10 s.
constexpr double kEventTol_s = 1e-12;
// Largest dopri5 step (s): keeps a fast double crossing of an event function from hiding
// inside one step.
constexpr double kMaxStep_s = 0.02;
// While at rest under an analytic motion, the initiation criteria are checked at least this
// often (s). Between record samples the accelerations are linear in time, so each corner force
// is linear and the smallest of them concave: checking the samples is exact.
constexpr double kRestScan_s = 1e-3;

State ToState(const Vec4& y) {
  return {y[0], y[1], y[2], y[3]};
}
Vec4 ToVec(const State& s) {
  return {s.theta1, s.theta2, s.omega1, s.omega2};
}

double Side(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

class Simulator {
 public:
  Simulator(const Scene& scene, const GroundMotion& motion)
      : scene_(scene), cfg_(scene.model), motion_(motion), geo_(MakeGeometry(scene)) {
    for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
      if (*c && (*c)->samples_mps2().empty()) analytic_motion_ = true;
    }
  }

  Result Run();

 private:
  Vec4 Rhs(double t, const Vec4& y) const {
    const auto acc = ModeAccelerations(geo_, mode_, ToState(y), motion_.xg_mps2(t),
                                       motion_.yg_mps2(t), cfg_.equations);
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

  void EmitSamplesUntil(double t_end, bool inclusive);
  void AddEvent(Event ev) { result_.history.events.push_back(std::move(ev)); }
  void Track(double t, const State& s);
  bool StartMode(double t, const State& s, const char* kind, Mode before, const std::string& note);
  // At a located switch the choice of mode can hang on rounding (a face force or an opening
  // acceleration of ~1e-16): the first time from t on (1e-12 s, doubling, up to t_max) at which
  // a mode other than `leaving` is consistent; t itself when none is found.
  template <class StateAt>
  double SwitchTime(double t, double t_max, Mode leaving, const StateAt& state_at) const {
    for (double dt = 0.0; t + dt <= t_max; dt = dt == 0.0 ? 1e-12 : 2 * dt) {
      const double tt = t + dt;
      const ModeSelection sel =
          SelectMode(geo_, state_at(tt), motion_.xg_mps2(tt), motion_.yg_mps2(tt), cfg_.equations);
      if (sel.consistent && sel.mode != leaving) return tt;
    }
    return t;
  }
  void DoImpact(double t, const State& s, ImpactKind kind);
  void RunRest();
  void RunMoving();
  double GapGround(const Vec4& y) const { return Side(ContactsOf(mode_).ground) * y[0]; }
  double GapInterface(const Vec4& y) const {
    const Contacts c = ContactsOf(mode_);
    const double rel = c.ground == Contact::kFace ? y[1] : y[1] - y[0];
    return Side(c.interface) * rel;
  }
  ContactMargins Margins(double t, const Vec4& y) const {
    return EvaluateContacts(geo_, mode_, ToState(y), motion_.xg_mps2(t), motion_.yg_mps2(t),
                            cfg_.equations);
  }
  // Records an event that ends the run at t_ in state s (no change of state).
  void StopWith(const char* kind, const State& s, const std::string& note,
                const std::string& status) {
    Event ev;
    ev.t_s = t_;
    ev.kind = kind;
    ev.mode_before = ev.mode_after = mode_;
    ev.omega1_before = ev.omega1_after = s.omega1;
    ev.omega2_before = ev.omega2_after = s.omega2;
    ev.energy_before_j = ev.energy_after_j = Energy(geo_, mode_, s);
    ev.note = note;
    AddEvent(ev);
    y_ = ToVec(s);
    Finish(status);
  }
  // Smallest normal reactions seen (summary).
  void NoteNormalForces(const Reactions& r) {
    Summary& sum = result_.summary;
    sum.min_normal_ground_n = std::min(sum.min_normal_ground_n, r.N_ground);
    if (geo_.two_blocks)
      sum.min_normal_interface_n = std::min(sum.min_normal_interface_n, r.N_interface);
  }
  void Finish(const std::string& status) {
    if (result_.summary.status == "completed") result_.summary.status = status;
    done_ = true;
  }

  const Scene& scene_;
  const ModelConfig& cfg_;
  const GroundMotion& motion_;
  const Geometry geo_;
  Result result_;
  Mode mode_ = Mode::kRest;
  double t_ = 0.0;
  Vec4 y_{};
  double t_end_ = 0.0;
  long next_sample_ = 0;
  bool done_ = false;
  bool analytic_motion_ = false;  // some component is an analytic kind (not a record)
  double h_ = 1e-3;
  mutable long rhs_count_ = 0;
  int same_time_events_ = 0;
  double last_event_t_ = -1.0;
};

void Simulator::Track(double t, const State& s) {
  Summary& sum = result_.summary;
  if (std::abs(s.theta1) > sum.peak_theta1_rad) {
    sum.peak_theta1_rad = std::abs(s.theta1);
    sum.peak_theta1_t_s = t;
  }
  if (geo_.two_blocks && std::abs(s.theta2) > sum.peak_theta2_rad) {
    sum.peak_theta2_rad = std::abs(s.theta2);
    sum.peak_theta2_t_s = t;
  }
}

void Simulator::EmitSamplesUntil(double t_end, bool inclusive) {
  const double dt = scene_.run.output_interval_s;
  auto& samples = result_.history.samples;
  while (true) {
    const double ts = next_sample_ * dt;
    if (ts > t_end_ + 1e-12 * t_end_) break;
    if (inclusive ? ts > t_end : ts >= t_end) break;
    Sample smp = result_.trajectory.At(ts);
    smp.t_s = ts;
    samples.push_back(smp);
    ++next_sample_;
  }
}

bool Simulator::StartMode(double t, const State& s, const char* kind, Mode before,
                          const std::string& note) {
  const ModeSelection sel =
      SelectMode(geo_, s, motion_.xg_mps2(t), motion_.yg_mps2(t), cfg_.equations);
  Event ev;
  ev.t_s = t;
  ev.mode_before = before;
  ev.omega1_before = s.omega1;
  ev.omega2_before = s.omega2;
  ev.omega1_after = s.omega1;
  ev.omega2_after = s.omega2;
  ev.energy_before_j = ev.energy_after_j = Energy(geo_, before, s);
  if (!sel.consistent) {
    ev.kind = "assumption_violated";
    ev.mode_after = before;
    ev.note = "no mode satisfies the contact conditions (tensile normal force: uplift)";
    result_.summary.status_detail = ev.note;
    AddEvent(ev);
    result_.summary.status = "assumption_violated";
    done_ = true;
    return false;
  }
  if (sel.mode != before) {
    ev.kind = kind;
    ev.mode_after = sel.mode;
    ev.note = note;
    if (std::string(kind) == "initiation") ++result_.summary.initiations;
    if (std::string(kind) == "transition") ++result_.summary.transitions;
    AddEvent(ev);
  }
  mode_ = sel.mode;
  return true;
}

void Simulator::DoImpact(double t, const State& pre, ImpactKind kind) {
  const Mode before = mode_;
  const ImpactResult ir = ResolveImpact(geo_, before, pre, kind, cfg_.rest_rate_radps);
  Summary& sum = result_.summary;
  Event ev;
  ev.t_s = t;
  ev.kind = kind == ImpactKind::kGround ? "ground_impact" : "interface_impact";
  ev.mode_before = before;
  ev.mode_after = ir.chosen.mode;
  ev.omega1_before = pre.omega1;
  ev.omega2_before = geo_.two_blocks ? pre.omega2 : 0.0;
  ev.omega1_after = ir.chosen.state.omega1;
  ev.omega2_after = geo_.two_blocks ? ir.chosen.state.omega2 : 0.0;
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
  (kind == ImpactKind::kGround ? sum.impacts_ground : sum.impacts_interface)++;
  AddEvent(ev);
  mode_ = ir.chosen.mode;
  // The post-impact mode must also satisfy the contact forces (a locked pair may open at once).
  StartMode(t, ir.chosen.state, "transition", mode_, "after impact");
  y_ = ToVec(ir.chosen.state);
}

void Simulator::RunRest() {
  // Criterion while at rest: the smallest corner force of the two faces (linear in xg'', yg'').
  auto margin = [&](double t) {
    const ContactMargins cm = EvaluateContacts(geo_, Mode::kRest, State{}, motion_.xg_mps2(t),
                                               motion_.yg_mps2(t), cfg_.equations);
    NoteNormalForces(cm.reactions);
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
      Finish("at_rest");
      return;
    }
    double t1 = std::min(motion_.next_breakpoint_after(t0), t_end_);
    if (analytic_motion_) t1 = std::min(t1, t0 + kRestScan_s);
    const double m1 = margin(t1);
    double t_start = -1.0;
    if (m1 < 0.0) {
      const double m0 = margin(t0);
      if (m0 < 0.0) {
        t_start = t0;
      } else {
        const auto br = BrentBracket(margin, t0, t1, m0, m1, kEventTol_s);
        t_start = br.second;
      }
      t_start = SwitchTime(t_start, t1, Mode::kRest, [](double) { return State{}; });
      t1 = t_start;
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

void Simulator::RunMoving() {
  const bool thesis_events = cfg_.events == EventScheme::kThesis;
  const bool rk4 = cfg_.integrator == Integrator::kRk4 || thesis_events;
  Vec4 f0 = Rhs(t_, y_);
  Summary& sum = result_.summary;
  while (!done_) {
    const double t_break = motion_.next_breakpoint_after(t_);
    double h = rk4 ? cfg_.step_s : std::min(h_, kMaxStep_s);
    h = std::min({h, t_break - t_, t_end_ - t_});
    if (h <= 0.0) h = std::max(t_end_ - t_, 0.0);
    StepResult st;
    if (rk4) {
      st = Rk4Step([this](double t, const Vec4& y) { return Rhs(t, y); }, t_, y_, f0, h);
    } else {
      while (true) {
        st = Dopri5Step([this](double t, const Vec4& y) { return Rhs(t, y); }, t_, y_, f0, h,
                        cfg_.rtol, cfg_.atol);
        if (st.err <= 1.0 || h < 1e-14) break;
        ++sum.steps_rejected;
        h *= std::max(0.2, 0.9 * std::pow(st.err, -0.2));
      }
      const double fac = st.err > 0 ? std::min(5.0, 0.9 * std::pow(st.err, -0.2)) : 5.0;
      h_ = h * fac;
    }
    ++sum.steps_accepted;
    const double t1 = t_ + h;
    const Vec4 y1 = Project(st.y1);
    // Event functions at the step end; the earliest triggered one is located.
    const Contacts c = ContactsOf(mode_);
    const bool ground_moves = c.ground != Contact::kFace;
    const bool interface_moves = geo_.two_blocks && c.interface != Contact::kFace;
    enum { kNone, kGroundImpact, kInterfaceImpact, kOverturn, kFace, kPoint } which = kNone;
    double t_ev = kInf, t_ev_hi = kInf;
    auto consider = [&](int kind, auto fn) {
      const double fa = fn(t_), fb = fn(t1);
      if (!(fb < 0.0)) return;
      double lo = t_, hi = t_;
      double ta = t_, fta = fa;
      if (fa == 0.0) {
        // The step starts on the event surface (a contact that just opened): the function may
        // rise before it falls. Start the search from the last positive interior sample.
        for (int k = 1; k < 16; ++k) {
          const double tk = t_ + (t1 - t_) * k / 16.0;
          const double fk = fn(tk);
          if (fk > 0.0) {
            ta = tk;
            fta = fk;
          }
        }
        // A short excursion near the start: look closer, geometrically.
        for (int k = 5; k < 48 && !(fta > 0.0); ++k) {
          const double tk = t_ + std::ldexp(t1 - t_, -k);
          const double fk = fn(tk);
          if (fk > 0.0) {
            ta = tk;
            fta = fk;
          }
        }
      }
      if (fta > 0.0) {
        const auto br = BrentBracket(fn, ta, t1, fta, fb, kEventTol_s);
        lo = br.first;
        hi = br.second;
      }
      if (lo < t_ev) {
        t_ev = lo;
        t_ev_hi = hi;
        which = static_cast<decltype(which)>(kind);
      }
    };
    const double t_step0 = t_;
    const Vec4 y_step0 = y_;
    auto at = [&](double t) { return Project(t == t_step0 ? y_step0 : st.dense.At(t)); };
    if (ground_moves) consider(kGroundImpact, [&](double t) { return GapGround(at(t)); });
    if (interface_moves) consider(kInterfaceImpact, [&](double t) { return GapInterface(at(t)); });
    const double over = cfg_.overturn_rad;
    consider(kOverturn, [&](double t) {
      const Vec4 y = at(t);
      return over - std::max(std::abs(y[0]), geo_.two_blocks ? std::abs(y[1]) : 0.0);
    });
    const ContactMargins cm1 = Margins(t1, y1);
    if (cfg_.check_transitions && cm1.face < 0.0) {
      consider(kFace, [&](double t) { return Margins(t, at(t)).face; });
    }
    if (cm1.point < 0.0) consider(kPoint, [&](double t) { return Margins(t, at(t)).point; });
    if (thesis_events && which != kNone) {
      // The thesis's scheme: the event is seen at the step end, pre-impact rates are the
      // previous step's.
      t_ev = t_ev_hi = t1;
    }
    const double t_seg_end = which == kNone ? t1 : t_ev;
    Trajectory::Segment seg{t_, t_seg_end, mode_, st.dense};
    result_.trajectory.Append(seg);
    EmitSamplesUntil(t_seg_end, false);
    // Peaks: |theta| extremes sit where the rate vanishes inside the step, or at its ends.
    for (int k = 0; k < (geo_.two_blocks ? 2 : 1); ++k) {
      auto rate = [&](double t) { return at(t)[2 + k]; };
      const double ra = rate(t_), rb = rate(t_seg_end);
      if (ra * rb < 0.0) {
        const auto br = BrentBracket(rate, t_, t_seg_end, ra, rb, kEventTol_s);
        Track(br.first, ToState(at(br.first)));
      }
    }
    const Vec4 y_end = which == kNone ? y1 : at(t_ev);
    Track(t_seg_end, ToState(y_end));
    // Friction needed and normal forces along the solution (at step ends).
    const ContactMargins& cmr = which == kNone ? cm1 : Margins(t_seg_end, y_end);
    sum.friction_required_ground = std::max(sum.friction_required_ground, cmr.mu_ground);
    sum.friction_required_interface = std::max(sum.friction_required_interface, cmr.mu_interface);
    NoteNormalForces(cmr.reactions);
    if (which == kNone) {
      t_ = t1;
      y_ = y1;
      f0 = st.f1;
      if (t_ >= t_end_) {
        EmitSamplesUntil(t_end_, true);
        done_ = true;
      }
      continue;
    }
    // Guard against an endless cascade of events at one instant.
    if (std::abs(t_ev - last_event_t_) <= 1e-12) {
      if (++same_time_events_ > 20) {
        sum.status_detail = "event cascade at one instant";
        Finish("assumption_violated");
        return;
      }
    } else {
      same_time_events_ = 0;
    }
    last_event_t_ = t_ev;
    State s = ToState(y_end);
    if (thesis_events) {
      s.omega1 = y_[2];
      s.omega2 = y_[3];
    }
    t_ = t_ev;
    switch (which) {
      case kGroundImpact:
        s.theta1 = 0.0;
        if (!interface_moves) s.theta2 = 0.0;
        DoImpact(t_, s, ImpactKind::kGround);
        break;
      case kInterfaceImpact:
        s.theta2 = ground_moves ? s.theta1 : 0.0;
        DoImpact(t_, s, ImpactKind::kInterface);
        break;
      case kOverturn: {
        const bool first = std::abs(s.theta1) >= std::abs(s.theta2) || !geo_.two_blocks;
        sum.overturn_block = first ? 1 : 2;
        sum.overturn_t_s = t_;
        StopWith("overturn", s, first ? "block 1" : "block 2", "overturned");
        break;
      }
      case kFace: {
        // Just past the located root, where the face force has turned tensile.
        t_ = SwitchTime(t_ev_hi, t1, mode_, [&](double t) { return ToState(at(t)); });
        const State sh = ToState(at(t_));
        y_ = ToVec(sh);
        StartMode(t_, sh, "transition", mode_, "face opens");
        break;
      }
      case kPoint: {
        sum.status_detail = "tensile normal force at a pivot (uplift)";
        StopWith("assumption_violated", s, sum.status_detail, "assumption_violated");
        break;
      }
      default:
        break;
    }
    if (done_) {
      // The run stops at the event: the trajectory ends there.
      Trajectory::Segment last{t_, t_, mode_, DenseStep{}};
      last.dense.c[0] = y_;
      result_.trajectory.Append(last);
      const double stop = t_;
      t_end_ = stop;
      EmitSamplesUntil(stop, true);
    }
    // After an event the caller restarts integration (new mode, new first stage).
    return;
  }
}

Result Simulator::Run() {
  ValidateScene(scene_);
  t_end_ = scene_.run.duration_s;
  const InitialState& in = scene_.initial;
  State s{in.theta1_rad, geo_.two_blocks ? in.theta2_rad : in.theta1_rad, in.omega1_radps,
          geo_.two_blocks ? in.omega2_radps : in.omega1_radps};
  result_.history.two_blocks = geo_.two_blocks;
  Track(0.0, s);
  if (std::abs(s.theta1) >= cfg_.overturn_rad || std::abs(s.theta2) >= cfg_.overturn_rad) {
    throw SceneError(scene_.path.string() + ": initial angle beyond model.overturn_angle");
  }
  mode_ = Mode::kRest;
  // The initial mode: a contact with a gap or a rate is open on that side; closed contacts
  // stay closed unless the forces open them.
  const ModeSelection sel =
      SelectMode(geo_, s, motion_.xg_mps2(0.0), motion_.yg_mps2(0.0), cfg_.equations);
  y_ = ToVec(s);
  if (!sel.consistent) {
    result_.summary.status = "assumption_violated";
    result_.summary.status_detail = "the initial state satisfies no mode's contact conditions";
    Trajectory::Segment seg{0.0, 0.0, Mode::kRest, DenseStep{}};
    seg.dense.c[0] = y_;
    result_.trajectory.Append(seg);
    t_end_ = 0.0;
    EmitSamplesUntil(0.0, true);
    return result_;
  }
  mode_ = sel.mode;
  if (mode_ != Mode::kRest && s.theta1 == 0.0 && s.theta2 == 0.0 && s.omega1 == 0.0 &&
      s.omega2 == 0.0) {
    // Motion starts at t = 0 from rest.
    Event ev;
    ev.kind = "initiation";
    ev.mode_before = Mode::kRest;
    ev.mode_after = mode_;
    ev.energy_before_j = ev.energy_after_j = Energy(geo_, Mode::kRest, s);
    AddEvent(ev);
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
    while (k < samples.size() && samples[k].t_s < ev.t_s) merged.push_back(samples[k++]);
    if (k < samples.size() && samples[k].t_s == ev.t_s) continue;
    if (!merged.empty() && merged.back().t_s == ev.t_s) continue;
    merged.push_back(result_.trajectory.At(ev.t_s));
  }
  while (k < samples.size()) merged.push_back(samples[k++]);
  samples = std::move(merged);
  if (result_.summary.status == "completed" && mode_ == Mode::kRest && t_ >= motion_.end_s()) {
    result_.summary.status = "at_rest";
  }
  result_.summary.rhs_evaluations = rhs_count_;
  return std::move(result_);
}

}  // namespace

Result Simulate(const Scene& scene, const GroundMotion& motion) {
  Simulator sim(scene, motion);
  return sim.Run();
}

}  // namespace rockbench::reference
