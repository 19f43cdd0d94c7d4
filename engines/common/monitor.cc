#include "engines/common/monitor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace rockbench {

void ReadBaseMotion(const EngineInput& in, std::int64_t n, StepReadout* s) {
  constexpr double kBaseStillMps2 = 1e-4;
  const double dt = in.time_step_s;
  const size_t i = static_cast<size_t>(n);
  if (in.drive_kind == DriveKind::kKinematic) {
    const auto& ux = in.drive.ux_m;
    const auto& uy = in.drive.uy_m;
    s->ground_x_m = ux[i];
    s->ground_y_m = uy[i];
    // The blocks' velocities after step n are those of the step that ended at t_n.
    s->ground_vx_mps = i == 0 ? in.drive.ux0_mps : (ux[i] - ux[i - 1]) / dt;
    s->ground_vy_mps = i == 0 ? in.drive.uy0_mps : (uy[i] - uy[i - 1]) / dt;
    if (i >= 1) {
      const double prev_vx = i == 1 ? in.drive.ux0_mps : (ux[i - 1] - ux[i - 2]) / dt;
      const double prev_vy = i == 1 ? in.drive.uy0_mps : (uy[i - 1] - uy[i - 2]) / dt;
      s->base_accelerating = std::abs(s->ground_vx_mps - prev_vx) > kBaseStillMps2 * dt ||
                             std::abs(s->ground_vy_mps - prev_vy) > kBaseStillMps2 * dt;
    }
  } else if (i >= 1) {
    const double ax = in.drive.ax_mps2.empty() ? 0.0 : in.drive.ax_mps2[i - 1];
    const double ay = in.drive.ay_mps2.empty() ? 0.0 : in.drive.ay_mps2[i - 1];
    s->base_accelerating = std::abs(ax) > kBaseStillMps2 || std::abs(ay) > kBaseStillMps2;
  }
}
namespace {

int Sign(double v) {
  return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);
}

// A quantity read from the engine that is not finite: its name and value (empty name: none).
struct NonFiniteField {
  std::string name;
  double value = 0.0;
};

// The first field of a readout that is not finite, named as the thesis's quantities: block 1's
// rate is omega1 (its CCW angular velocity with the sign turned), its pose and velocity by what
// they are; then block 2's; then the ground's (kinematic drive).
NonFiniteField FirstNonFinite(const StepReadout& s, bool two_blocks) {
  // The common case first, without a string: a sum is finite when every term is (a finite sum
  // that overflows is sorted out below).
  auto sum = [](const BodyReadout& b) {
    return b.x_m + b.y_m + b.cos_phi + b.sin_phi + b.vx_mps + b.vy_mps + b.w_radps;
  };
  if (std::isfinite(sum(s.block1) + (two_blocks ? sum(s.block2) : 0.0) + s.ground_x_m +
                    s.ground_y_m + s.ground_vx_mps + s.ground_vy_mps)) {
    return {};
  }
  auto body = [](const BodyReadout& b, int k) -> NonFiniteField {
    const std::string block = "block " + std::to_string(k);
    const std::pair<const char*, double> fields[] = {
        {"position", b.x_m},        {"position", b.y_m},    {"orientation", b.cos_phi},
        {"orientation", b.sin_phi}, {"velocity", b.vx_mps}, {"velocity", b.vy_mps}};
    for (const auto& [what, v] : fields) {
      if (!std::isfinite(v)) return {block + " " + what, v};
    }
    if (!std::isfinite(b.w_radps)) return {"omega" + std::to_string(k), -b.w_radps};
    return {};
  };
  if (NonFiniteField f = body(s.block1, 1); !f.name.empty()) return f;
  if (two_blocks) {
    if (NonFiniteField f = body(s.block2, 2); !f.name.empty()) return f;
  }
  const std::pair<const char*, double> ground[] = {{"ground position", s.ground_x_m},
                                                   {"ground position", s.ground_y_m},
                                                   {"ground velocity", s.ground_vx_mps},
                                                   {"ground velocity", s.ground_vy_mps}};
  for (const auto& [what, v] : ground) {
    if (!std::isfinite(v)) return {what, v};
  }
  return {};
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

// Linear interpolation of the zero crossing of a quantity (an angle, or the overturn margin
// overturn_rad - |theta|) between two steps, clamped to the step.
double CrossingTime(double prev, double angle, double t_prev, double t) {
  const double denom = prev - angle;
  const double frac = denom != 0.0 ? std::clamp(prev / denom, 0.0, 1.0) : 1.0;
  return t_prev + frac * (t - t_prev);
}

// Hysteresis update of one tilt. Returns true when the tilted block lands (its angle crosses
// zero or falls below `leave`); *t_impact is the linearly interpolated zero crossing, or t when
// it landed without crossing.
bool UpdateSide(int* side, double prev, double angle, double t_prev, double t, double enter,
                double leave, double* t_impact, bool* crossed) {
  bool impact = false;
  *crossed = false;
  if (*side != 0) {
    const double a = *side * angle;
    if (a <= 0.0) {
      impact = true;
      *crossed = true;
      *t_impact = CrossingTime(prev, angle, t_prev, t);
    } else if (a < leave) {
      impact = true;
      *t_impact = t;
    }
    if (impact) *side = std::abs(angle) > enter ? Sign(angle) : 0;
  } else if (std::abs(angle) > enter) {
    *side = Sign(angle);
  }
  return impact;
}

// The hysteresis's side (+1 right, -1 left, 0 flat) as the contact it implies, and back.
Contact ContactOfSide(int side) {
  return side > 0 ? Contact::kRight : (side < 0 ? Contact::kLeft : Contact::kFace);
}
int SideOfContact(Contact c) {
  return c == Contact::kRight ? 1 : (c == Contact::kLeft ? -1 : 0);
}

}  // namespace

Monitor::Monitor(const EngineInput& input, MonitorConfig config) : cfg_(config) {
  in_meta_.block1 = input.block1;
  in_meta_.block2 = input.block2;
  in_meta_.initial = input.initial;
  in_meta_.run = input.run;
  in_meta_.time_step_s = input.time_step_s;
  in_meta_.drive_kind = input.drive_kind;
  in_meta_.kinematic_highpass_hz = input.kinematic_highpass_hz;
  in_meta_.overturn_rad = input.overturn_rad;
  in_meta_.stop_at_rest_after_s = input.stop_at_rest_after_s;
  in_meta_.steps = input.steps;
  two_ = input.two_blocks();
  blocks_ = two_ ? 2 : 1;
  last_ = Sample(blocks_);
  prev_ = Derived(blocks_);
  b1_ = 0.5 * input.block1.width_m;
  h1_ = 0.5 * input.block1.height_m;
  m1_ = input.block1.mass_kg;
  props1_ = MakeBlockProps(input.block1.width_m, input.block1.height_m, m1_);
  if (two_) {
    b2_ = 0.5 * input.block2->width_m;
    h2_ = 0.5 * input.block2->height_m;
    m2_ = input.block2->mass_kg;
    props2_ = MakeBlockProps(input.block2->width_m, input.block2->height_m, m2_);
  }
  g_ = input.run.gravity_mps2;
  dt_ = input.time_step_s;
  out_dt_ = input.run.output_interval_s;
  tipping_energy_j_ = m1_ * g_ * (std::hypot(b1_, h1_) - h1_);
  if (two_) tipping_energy_j_ += m2_ * g_ * (std::hypot(b2_, h2_) - h2_);
  // alpha B per block: a corner moved by d tilts the block by d / B.
  significant_m_[0] = cfg_.significant_critical_fraction * props1_.theta_c * 2.0 * b1_;
  if (two_) significant_m_[1] = cfg_.significant_critical_fraction * props2_.theta_c * 2.0 * b2_;
  history_.blocks = blocks_;
}

Monitor::Derived Monitor::Derive(const StepReadout& s) {
  Derived d(blocks_);
  const BodyReadout& r1 = s.block1;
  // Unwrapped CCW angles; the thesis's theta is -phi.
  phi1_ += std::remainder(std::atan2(r1.sin_phi, r1.cos_phi) - phi1_, 2.0 * std::numbers::pi);
  d.sample.t_s = s.t_s;
  d.sample.theta_rad[0] = -phi1_;
  d.sample.omega_radps[0] = -r1.w_radps;
  // Base frame.
  const double x1 = r1.x_m - s.ground_x_m, y1 = r1.y_m - s.ground_y_m;
  const double vx1 = r1.vx_mps - s.ground_vx_mps, vy1 = r1.vy_mps - s.ground_vy_mps;
  const double c1 = r1.cos_phi, s1 = r1.sin_phi;
  // Lowest corner of block 1 above the ground (bottom corners at local (+-b1, -h1)).
  // Corner heights: y = y1 + sin(phi) lx + cos(phi) ly for local (lx, ly) = (+-b1, +-h1); the top
  // corners matter for a block lying on its side.
  const double yl = y1 - s1 * b1_ - c1 * h1_;
  const double yr = y1 + s1 * b1_ - c1 * h1_;
  const double yl_top = y1 - s1 * b1_ + c1 * h1_;
  const double yr_top = y1 + s1 * b1_ + c1 * h1_;
  d.gap_ground_m = std::min(std::min(yl, yr), std::min(yl_top, yr_top));
  d.energy_j = BlockEnergy_j(props1_, g_, {{x1, y1}, {vx1, vy1}, r1.w_radps});
  if (two_) {
    const BodyReadout& r2 = s.block2;
    phi2_ += std::remainder(std::atan2(r2.sin_phi, r2.cos_phi) - phi2_, 2.0 * std::numbers::pi);
    d.sample.theta_rad[1] = -phi2_;
    d.sample.omega_radps[1] = -r2.w_radps;
    const double x2 = r2.x_m - s.ground_x_m, y2 = r2.y_m - s.ground_y_m;
    const double vx2 = r2.vx_mps - s.ground_vx_mps, vy2 = r2.vy_mps - s.ground_vy_mps;
    d.energy_j += BlockEnergy_j(props2_, g_, {{x2, y2}, {vx2, vy2}, r2.w_radps});
    // Block 2's bottom corners in block 1's frame: gap above block 1's top face (y = h1).
    const double c2 = r2.cos_phi, s2 = r2.sin_phi;
    double gap = 1e300;
    for (int k = -1; k <= 1; k += 2) {
      const double px = x2 + c2 * (k * b2_) + s2 * h2_;  // local (k b2, -h2)
      const double py = y2 + s2 * (k * b2_) - c2 * h2_;
      const double dx = px - x1, dy = py - y1;
      const double ly = -s1 * dx + c1 * dy;
      gap = std::min(gap, ly - h1_);
    }
    d.gap_interface_m = gap;
  }
  return d;
}

void Monitor::Pivots(const StepReadout& s, Derived* d, int* side1, int* side2) const {
  const Sample& cur = d->sample;
  const double c1 = s.block1.cos_phi, s1 = s.block1.sin_phi;
  const double x1 = s.block1.x_m - s.ground_x_m, y1 = s.block1.y_m - s.ground_y_m;
  int pivot_side2 = 0;
  TiltSides(cur, side1, &pivot_side2);
  // Block 1's pivot: bottom corner (side1 b1, -h1) in its frame (bottom centre when flat).
  d->pivot_ground_x_m = x1 + c1 * (*side1 * b1_) + s1 * h1_;
  if (!two_) return;
  *side2 = pivot_side2;
  // Block 2's pivot (side2 b2, -h2) in its frame, expressed in block 1's frame.
  const double c2 = s.block2.cos_phi, s2 = s.block2.sin_phi;
  const double x2 = s.block2.x_m - s.ground_x_m, y2 = s.block2.y_m - s.ground_y_m;
  const double px = x2 + c2 * (*side2 * b2_) + s2 * h2_;
  const double py = y2 + s2 * (*side2 * b2_) - c2 * h2_;
  const double dx = px - x1, dy = py - y1;
  d->pivot_interface_x_m = c1 * dx + s1 * dy;
}

void Monitor::TiltSides(const Sample& s, int* side1, int* side2) const {
  // The reference's rule (scene/mode.h TiltContact), with the angle's side from the
  // hysteresis and the flat band's rate threshold of MonitorConfig.
  *side1 = SideOfContact(
      TiltContact(ContactOfSide(ground_.side), s.omega_radps[0], cfg_.rate_tol_radps));
  *side2 = 0;
  if (two_) {
    *side2 = SideOfContact(TiltContact(ContactOfSide(interface_.side),
                                       s.omega_radps[1] - s.omega_radps[0], cfg_.rate_tol_radps));
  }
}

Configuration Monitor::InferMode(const Sample& s) const {
  int s1 = 0, s2 = 0;
  TiltSides(s, &s1, &s2);
  return ConfigurationOf(ModeOf({ContactOfSide(s1), ContactOfSide(s2)}, two_), blocks_);
}

void Monitor::Record(const Sample& s) {
  history_.samples.push_back(s);
}

void Monitor::PushEvent(Event e) {
  history_.events.push_back(std::move(e));
}

void Monitor::Start(const StepReadout& s) {
  if (const NonFiniteField f = FirstNonFinite(s, two_); !f.name.empty()) {
    // Not even the initial state is finite: no sample, and no step will be read.
    last_.t_s = end_t_s_ = s.t_s;
    last_recorded_ = true;
    StopNonFinite(f.name, NonFiniteText(f.value), s.t_s, 0);
    return;
  }
  const double a1 = std::atan2(s.block1.sin_phi, s.block1.cos_phi);
  phi1_ = a1;
  if (two_) phi2_ = std::atan2(s.block2.sin_phi, s.block2.cos_phi);
  Derived d = Derive(s);
  const double theta1 = d.sample.theta_rad[0];
  ground_.side = std::abs(theta1) > cfg_.angle_enter_rad ? Sign(theta1) : 0;
  ground_.prev = theta1;
  if (two_) {
    const double rel = d.sample.theta_rad[1] - theta1;
    interface_.side = std::abs(rel) > cfg_.angle_enter_rad ? Sign(rel) : 0;
    interface_.prev = rel;
  }
  d.sample.mode = InferMode(d.sample);
  Pivots(s, &d, &pivot_side1_, &pivot_side2_);
  peak1_ = std::abs(theta1);
  peak2_ = two_ ? std::abs(d.sample.theta_rad[1]) : 0.0;
  prev_ = d;
  last_ = d.sample;
  energy_min_free_j_ = d.energy_j;
  Record(d.sample);
  last_recorded_ = true;
  next_out_ = 1;
}

bool Monitor::Step(std::int64_t n, const StepReadout& s) {
  if (status_ == RunStatus::kNonFinite) return false;
  steps_done_ = n;
  if (!s.engine_fault.empty()) {
    StopNonFinite("the engine's next state", "not finite", s.t_s, n, s.engine_fault);
    return false;
  }
  if (const NonFiniteField f = FirstNonFinite(s, two_); !f.name.empty()) {
    StopNonFinite(f.name, NonFiniteText(f.value), s.t_s, n);
    return false;
  }
  Derived d = Derive(s);
  if (!std::isfinite(d.energy_j)) {
    StopNonFinite("energy", NonFiniteText(d.energy_j), s.t_s, n);
    return false;
  }
  Sample& cur = d.sample;
  const double t_prev = prev_.sample.t_s, t = cur.t_s;
  // |theta| of both blocks before this step (prev_ is overwritten before the overturn check).
  const double abs1_prev = std::abs(prev_.sample.theta_rad[0]);
  const double abs2_prev = two_ ? std::abs(prev_.sample.theta_rad[1]) : 0.0;

  const Landings landings = DetectLandings(cur, t_prev);
  cur.mode = InferMode(cur);
  CompletePendingImpacts(d, landings);
  OpenImpacts(landings);
  RecordModeChange(d);

  MeasureContacts(s, &d);
  MeasurePeaksAndEnergy(d, s.base_accelerating);

  prev_ = d;
  last_ = cur;
  last_recorded_ = false;
  end_t_s_ = t;

  RecordOutput(cur, t);
  const bool stopped = Stopped(d, t_prev, abs1_prev, abs2_prev);
  NoteOnsets(t);
  return !stopped;
}

void Monitor::StopNonFinite(const std::string& quantity, const std::string& value, double t_s,
                            std::int64_t n, const std::string& why) {
  status_ = RunStatus::kNonFinite;
  non_finite_quantity_ = quantity;
  non_finite_value_ = value;
  non_finite_t_s_ = t_s;
  const bool any_finite = !history_.samples.empty();
  status_detail_ =
      quantity + " is " + value + " at t = " + TimeText(t_s) + " s (step " + std::to_string(n) +
      (why.empty() ? std::string() : ": " + why) + ")" +
      (any_finite ? "; the run stops at its last finite state, t = " + TimeText(last_.t_s) + " s"
                  : "; no state of the run is finite");
  // The run, its history and its outcome end at the last finite state.
  end_t_s_ = last_.t_s;
  if (any_finite) {
    Event e(blocks_);
    e.t_s = last_.t_s;
    e.kind = "non_finite";
    e.mode_before = e.mode_after = last_.mode;
    e.omega_before_radps = e.omega_after_radps = last_.omega_radps;
    e.energy_before_j = e.energy_after_j = prev_.energy_j;
    e.note = status_detail_;
    PushEvent(std::move(e));
  }
  NoteOnsets(t_s);
}

std::array<bool, std::size(kViolationFlags)> Monitor::Raised() const {
  const double slip_flag1 = cfg_.slip_flag_rel * 2.0 * b1_;
  const double slip_flag2 = cfg_.slip_flag_rel * 2.0 * b2_;
  return {slip_ground_m_ > slip_flag1 || (two_ && slip_interface_m_ > slip_flag2),
          uplift_ground_episodes_ > 0 || (two_ && uplift_interface_episodes_ > 0),
          penetration_ground_max_m_ > cfg_.penetration_flag_m ||
              (two_ && penetration_interface_max_m_ > cfg_.penetration_flag_m),
          energy_gain_max_j_ > cfg_.energy_growth_flag_rel * tipping_energy_j_,
          status_ == RunStatus::kBlowUp || status_ == RunStatus::kNonFinite};
}

std::array<bool, std::size(kViolationFlags)> Monitor::RaisedSignificantly() const {
  auto over = [&](double ground_m, double interface_m) {
    return ground_m > significant_m_[0] || (two_ && interface_m > significant_m_[1]);
  };
  const auto raised = Raised();
  // Slip is judged as flagged (slip_flag_rel of the width): it tilts nothing, and a converged
  // engine's accumulated contact jitter reaches 0.3 mm over Rinaldi 228 (ODE, MuJoCo).
  return {raised[0], over(uplift_ground_max_m_, uplift_interface_max_m_),
          over(penetration_ground_max_m_, penetration_interface_max_m_), raised[3], raised[4]};
}

void Monitor::NoteOnsets(double t_s) {
  const auto raised = Raised();
  const auto significant = RaisedSignificantly();
  for (size_t i = 0; i < raised.size(); ++i) {
    if (raised[i] && std::isnan(onset_t_s_[i])) onset_t_s_[i] = t_s;
    if (significant[i] && std::isnan(significant_t_s_[i])) significant_t_s_[i] = t_s;
  }
}

Monitor::Landings Monitor::DetectLandings(const Sample& cur, double t_prev) {
  // Impacts: a tilted block lands.
  Landings l;
  l.t_prev = t_prev;
  l.rel = two_ ? cur.theta_rad[1] - cur.theta_rad[0] : 0.0;
  l.rel_prev = interface_.prev;
  l.theta1_prev = ground_.prev;
  l.side_ground = ground_.side;
  l.side_interface = interface_.side;
  l.ground = UpdateSide(&ground_.side, ground_.prev, cur.theta_rad[0], t_prev, cur.t_s,
                        cfg_.angle_enter_rad, cfg_.angle_leave_rad, &l.t_ground, &l.crossed_ground);
  ground_.prev = cur.theta_rad[0];
  if (two_) {
    l.interface =
        UpdateSide(&interface_.side, interface_.prev, l.rel, t_prev, cur.t_s, cfg_.angle_enter_rad,
                   cfg_.angle_leave_rad, &l.t_interface, &l.crossed_interface);
    interface_.prev = l.rel;
  }
  return l;
}

void Monitor::CompletePendingImpacts(const Derived& d, const Landings& l) {
  // Pending impacts: Bullet resolves a contact in the step after the one that brought the
  // corner into the support, so an impact is complete one step after its angle crossed zero
  // (or after kImpactWaitSteps steps if it landed without crossing).
  constexpr int kImpactWaitSteps = 10;
  const Sample& cur = d.sample;
  const Sample& prev = prev_.sample;
  for (size_t k = 0; k < pending_.size();) {
    PendingImpact& p = pending_[k];
    const double angle = p.interface ? l.rel : cur.theta_rad[0];
    const double angle_prev = p.interface ? l.rel_prev : l.theta1_prev;
    bool done = false;
    if (p.crossed) {
      done = true;
    } else if (p.side * angle <= 0.0) {
      p.crossed = true;
      p.event.t_s = CrossingTime(angle_prev, angle, l.t_prev, cur.t_s);
      p.event.omega_before_radps = prev.omega_radps;
      p.event.energy_before_j = prev_.energy_j;
    } else if (++p.waited >= kImpactWaitSteps) {
      done = true;
      p.event.note = "landed without crossing zero";
    }
    if (done) {
      p.event.mode_after = cur.mode;
      p.event.omega_after_radps = cur.omega_radps;
      p.event.energy_after_j = d.energy_j;
      PushEvent(std::move(p.event));
      pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(k));
      suppress_mode_events_ = 1;
    } else {
      ++k;
    }
  }
}

void Monitor::OpenImpacts(const Landings& l) {
  const Sample& prev = prev_.sample;
  auto make_impact = [&](const char* kind, bool interface, int side, double when, bool crossed) {
    PendingImpact p(blocks_);
    p.interface = interface;
    p.side = side;
    p.crossed = crossed;
    p.event.t_s = when;
    p.event.kind = kind;
    p.event.mode_before = prev.mode;
    // The state before the crossing step is before the contact impulse: Bullet applies it in
    // the step that crosses (a speculative contact already in the manifold) or in the next one
    // (a contact found penetrating), so the step after the crossing is after it.
    p.event.omega_before_radps = prev.omega_radps;
    p.event.energy_before_j = prev_.energy_j;
    pending_.push_back(std::move(p));
  };
  if (l.ground) {
    ++impacts_ground_;
    make_impact("ground_impact", false, l.side_ground, l.t_ground, l.crossed_ground);
  }
  if (l.interface) {
    ++impacts_interface_;
    make_impact("interface_impact", true, l.side_interface, l.t_interface, l.crossed_interface);
  }
}

void Monitor::RecordModeChange(const Derived& d) {
  const Sample& cur = d.sample;
  const Sample& prev = prev_.sample;
  const bool impact_busy = !pending_.empty() || suppress_mode_events_ > 0;
  // Mode changes without impact.
  if (cur.mode != prev.mode && !impact_busy) {
    Event e(blocks_);
    e.t_s = cur.t_s;
    e.mode_before = prev.mode;
    e.mode_after = cur.mode;
    e.omega_before_radps = e.omega_after_radps = cur.omega_radps;
    e.energy_before_j = prev_.energy_j;
    e.energy_after_j = d.energy_j;
    if (prev.mode.at_rest()) {
      e.kind = "initiation";
      ++initiations_;
    } else if (cur.mode.at_rest()) {
      e.kind = "rest";
      ++rests_;
    } else {
      e.kind = "transition";
      ++transitions_;
    }
    PushEvent(std::move(e));
  }
  if (suppress_mode_events_ > 0) --suppress_mode_events_;
}

void Monitor::MeasureContacts(const StepReadout& s, Derived* d_ptr) {
  const Derived& d = *d_ptr;
  // Slip: horizontal motion of the pivot point relative to the support while in contact.
  {
    int side1 = 0, side2 = 0;
    Pivots(s, d_ptr, &side1, &side2);
    if (side1 == pivot_side1_ && d.gap_ground_m < cfg_.uplift_tol_m) {
      slip_ground_m_ += std::abs(d.pivot_ground_x_m - prev_.pivot_ground_x_m);
    }
    drift_ground_max_m_ = std::max(drift_ground_max_m_, std::abs(d.pivot_ground_x_m - side1 * b1_));
    pivot_side1_ = side1;
    if (two_) {
      if (side2 == pivot_side2_ && d.gap_interface_m < cfg_.uplift_tol_m) {
        slip_interface_m_ += std::abs(d.pivot_interface_x_m - prev_.pivot_interface_x_m);
      }
      drift_interface_max_m_ =
          std::max(drift_interface_max_m_, std::abs(d.pivot_interface_x_m - side2 * b2_));
      pivot_side2_ = side2;
    }
  }
  // Uplift and penetration.
  {
    const bool up = d.gap_ground_m > cfg_.uplift_tol_m;
    if (up) {
      uplift_ground_s_ += dt_;
      uplift_ground_max_m_ = std::max(uplift_ground_max_m_, d.gap_ground_m);
      if (!airborne_ground_) ++uplift_ground_episodes_;
    }
    airborne_ground_ = up;
    penetration_ground_max_m_ = std::max(penetration_ground_max_m_, -d.gap_ground_m);
    if (two_) {
      const bool up2 = d.gap_interface_m > cfg_.uplift_tol_m;
      if (up2) {
        uplift_interface_s_ += dt_;
        uplift_interface_max_m_ = std::max(uplift_interface_max_m_, d.gap_interface_m);
        if (!airborne_interface_) ++uplift_interface_episodes_;
      }
      airborne_interface_ = up2;
      penetration_interface_max_m_ = std::max(penetration_interface_max_m_, -d.gap_interface_m);
    }
  }
  out_of_plane_m_ = std::max(out_of_plane_m_, s.out_of_plane_m);
  out_of_plane_rad_ = std::max(out_of_plane_rad_, s.out_of_plane_rad);
}

void Monitor::MeasurePeaksAndEnergy(const Derived& d, bool base_accelerating) {
  const Sample& cur = d.sample;
  const double t = cur.t_s;
  // Peaks.
  if (std::abs(cur.theta_rad[0]) > peak1_) {
    peak1_ = std::abs(cur.theta_rad[0]);
    peak1_t_ = t;
  }
  if (two_ && std::abs(cur.theta_rad[1]) > peak2_) {
    peak2_ = std::abs(cur.theta_rad[1]);
    peak2_t_ = t;
  }
  max_rate_radps_ = std::max(
      {max_rate_radps_, std::abs(cur.omega_radps[0]), two_ ? std::abs(cur.omega_radps[1]) : 0.0});

  // Energy without input must not grow.
  if (base_accelerating) {
    free_ = false;
  } else {
    if (!free_) {
      free_ = true;
      energy_min_free_j_ = std::min(prev_.energy_j, d.energy_j);
    }
    energy_min_free_j_ = std::min(energy_min_free_j_, d.energy_j);
    const double gain = d.energy_j - energy_min_free_j_;
    if (gain > energy_gain_max_j_) {
      energy_gain_max_j_ = gain;
      energy_gain_t_s_ = t;
    }
  }
}

void Monitor::RecordOutput(const Sample& cur, double t) {
  // Output sample: the step nearest to each output time (every step without an interval).
  if (!(out_dt_ > 0.0)) {
    Record(cur);
    last_recorded_ = true;
  } else if (t >= static_cast<double>(next_out_) * out_dt_ - 0.5 * dt_) {
    Record(cur);
    last_recorded_ = true;
    next_out_ = static_cast<std::int64_t>(std::floor((t + 0.5 * dt_) / out_dt_)) + 1;
  }
}

bool Monitor::Stopped(const Derived& d, double t_prev, double abs1_prev, double abs2_prev) {
  const Sample& cur = d.sample;
  const double t = cur.t_s;
  // Stops: overturn, blow-up. A block overturns when |theta| reaches the model's overturn angle
  // (model.overturn_angle, the reference's definition, no slack). The crossing time is
  // interpolated linearly between the step's two ends, the same way for both blocks: Bullet turns
  // each body at a constant rate within a step, so this is Bullet's own crossing. If both cross
  // in one step, the first to cross overturned (ties: block 1, as the reference).
  const double over = in_meta_.overturn_rad;
  int over_block = 0;
  double t_over = 0.0;
  auto crossed = [&](int block, double abs_prev, double abs_cur) {
    if (!(abs_cur >= over)) return;
    const double when = CrossingTime(over - abs_prev, over - abs_cur, t_prev, t);
    if (over_block == 0 || when < t_over) {
      over_block = block;
      t_over = when;
    }
  };
  crossed(1, abs1_prev, std::abs(cur.theta_rad[0]));
  if (two_) crossed(2, abs2_prev, std::abs(cur.theta_rad[1]));
  if (over_block != 0) {
    status_ = RunStatus::kOverturned;
    overturn_block_ = over_block;
    overturn_t_s_ = t_over;
    status_detail_ = "block " + std::to_string(over_block) +
                     " reached |theta| = " + std::to_string(over) + " rad (model.overturn_angle)";
    Event e(blocks_);
    e.t_s = t_over;
    e.kind = "overturn";
    e.mode_before = e.mode_after = cur.mode;
    e.omega_before_radps = e.omega_after_radps = cur.omega_radps;
    e.energy_before_j = e.energy_after_j = d.energy_j;
    e.note = "block " + std::to_string(over_block);
    PushEvent(std::move(e));
    return true;
  }
  // Settled: at rest once the base can no longer start rocking (ensemble members only).
  if (!cur.mode.at_rest()) {
    rest_since_s_ = -1.0;
  } else if (rest_since_s_ < 0.0) {
    rest_since_s_ = t;
  }
  if (rest_since_s_ >= 0.0 && t >= in_meta_.stop_at_rest_after_s &&
      t - rest_since_s_ >= cfg_.settled_for_s - 0.5 * dt_) {
    status_ = RunStatus::kAtRest;
    status_detail_ = "at rest after " + std::to_string(in_meta_.stop_at_rest_after_s) +
                     " s, when the base motion can no longer start rocking";
    return true;
  }
  if (max_rate_radps_ > cfg_.blow_up_rate_radps) {
    status_ = RunStatus::kBlowUp;
    status_detail_ = "|omega| above " + std::to_string(cfg_.blow_up_rate_radps) + " rad/s";
    return true;
  }
  if (energy_gain_max_j_ > cfg_.blow_up_energy_rel * tipping_energy_j_) {
    status_ = RunStatus::kBlowUp;
    status_detail_ = "energy grew without base input by more than the tipping energy";
    return true;
  }
  return false;
}

void Monitor::Finish() {
  // Impacts still waiting for their post-impact state: complete them with the last state.
  for (PendingImpact& p : pending_) {
    p.event.mode_after = last_.mode;
    p.event.omega_after_radps = last_.omega_radps;
    p.event.energy_after_j = prev_.energy_j;
    p.event.note = "run ended before the contact was resolved";
    PushEvent(std::move(p.event));
  }
  pending_.clear();
  // Impacts are pushed when complete: restore time order.
  std::stable_sort(history_.events.begin(), history_.events.end(),
                   [](const Event& a, const Event& b) { return a.t_s < b.t_s; });
  if (!last_recorded_) {
    Record(last_);
    last_recorded_ = true;
  }
}

RunOutcome Monitor::Outcome() const {
  RunOutcome o(blocks_);
  o.status = status_;
  o.overturned_block = overturn_block_;
  if (overturn_block_ != 0) o.overturn_t_s = overturn_t_s_;
  o.end_t_s = end_t_s_;
  o.peak_theta_rad[0] = peak1_, o.peak_theta_t_s[0] = peak1_t_;
  o.impacts_at[0] = impacts_ground_;
  if (two_) {
    o.peak_theta_rad[1] = peak2_, o.peak_theta_t_s[1] = peak2_t_;
    o.impacts_at[1] = impacts_interface_;
  }
  // The raised flags with their onsets; a flag first raised by this evaluation (never, in a run
  // that stepped) is dated at the run's end.
  auto list = [this](const auto& raised, const auto& onsets, std::vector<std::string>* names,
                     std::vector<double>* times) {
    for (size_t i = 0; i < std::size(kViolationFlags); ++i) {
      if (!raised[i]) continue;
      names->push_back(kViolationFlags[i]);
      times->push_back(std::isnan(onsets[i]) ? end_t_s_ : onsets[i]);
    }
  };
  list(Raised(), onset_t_s_, &o.violations, &o.violation_onsets_t_s);
  list(RaisedSignificantly(), significant_t_s_, &o.significant_violations,
       &o.significant_onsets_t_s);
  return o;
}

nlohmann::json Monitor::Summary() const {
  using nlohmann::json;
  json j;
  j["status"] = StatusText(status_);
  if (!status_detail_.empty()) j["status_detail"] = status_detail_;
  if (status_ == RunStatus::kNonFinite) {
    j["non_finite"] = {{"quantity", non_finite_quantity_},
                       {"value", non_finite_value_},
                       {"t_s", non_finite_t_s_},
                       {"last_finite_t_s", end_t_s_}};
  }
  j["end_t_s"] = end_t_s_;
  j["steps"] = steps_done_;
  // Same shape as the reference's part of summary.json (run/summary.cc).
  j["peaks"]["theta1"] = {{"abs_rad", peak1_}, {"t_s", peak1_t_}};
  if (two_) j["peaks"]["theta2"] = {{"abs_rad", peak2_}, {"t_s", peak2_t_}};
  j["impacts"] = {{"total", impacts_ground_ + impacts_interface_},
                  {"ground", impacts_ground_},
                  {"interface", impacts_interface_}};
  j["transitions"] = transitions_;
  j["initiations"] = initiations_;
  j["rests"] = rests_;
  if (overturn_block_ != 0) {
    j["overturn"] = {{"block", overturn_block_}, {"t_s", overturn_t_s_}};
  } else {
    j["overturn"] = nullptr;
  }
  json fin;
  fin["t_s"] = last_.t_s;
  fin["theta1_rad"] = last_.theta_rad[0];
  fin["omega1_radps"] = last_.omega_radps[0];
  if (two_) {
    fin["theta2_rad"] = last_.theta_rad[1];
    fin["omega2_radps"] = last_.omega_radps[1];
  }
  fin["mode"] = ConfigurationName(last_.mode);
  j["final"] = fin;

  json v;
  v["slip_ground_m"] = slip_ground_m_;
  v["drift_ground_max_m"] = drift_ground_max_m_;
  v["uplift_ground_s"] = uplift_ground_s_;
  v["uplift_ground_max_m"] = uplift_ground_max_m_;
  v["uplift_ground_episodes"] = uplift_ground_episodes_;
  v["penetration_ground_max_m"] = penetration_ground_max_m_;
  if (two_) {
    v["slip_interface_m"] = slip_interface_m_;
    v["drift_interface_max_m"] = drift_interface_max_m_;
    v["uplift_interface_s"] = uplift_interface_s_;
    v["uplift_interface_max_m"] = uplift_interface_max_m_;
    v["uplift_interface_episodes"] = uplift_interface_episodes_;
    v["penetration_interface_max_m"] = penetration_interface_max_m_;
  }
  v["energy_gain_max_j"] = energy_gain_max_j_;
  v["energy_gain_t_s"] = energy_gain_t_s_;
  v["tipping_energy_j"] = tipping_energy_j_;
  v["energy_gain_rel"] = tipping_energy_j_ > 0.0 ? energy_gain_max_j_ / tipping_energy_j_ : 0.0;
  v["out_of_plane_m"] = out_of_plane_m_;
  v["out_of_plane_rad"] = out_of_plane_rad_;
  v["max_rate_radps"] = max_rate_radps_;
  const RunOutcome outcome = Outcome();
  nlohmann::json onsets = nlohmann::json::object();
  for (const char* flag : kViolationFlags) {
    const auto it = std::find(outcome.violations.begin(), outcome.violations.end(), flag);
    v[flag] = it != outcome.violations.end();
    if (it != outcome.violations.end()) {
      onsets[flag] = outcome.violation_onsets_t_s[it - outcome.violations.begin()];
    }
  }
  v["onset_t_s"] = onsets;
  nlohmann::json significant = nlohmann::json::object();
  for (size_t i = 0; i < outcome.significant_violations.size(); ++i) {
    significant[outcome.significant_violations[i]] = outcome.significant_onsets_t_s[i];
  }
  v["significant_onset_t_s"] = significant;
  v["significant_displacement_m"] = {significant_m_[0], significant_m_[1]};
  j["violations"] = v;

  json m;
  m["angle_enter_rad"] = cfg_.angle_enter_rad;
  m["angle_leave_rad"] = cfg_.angle_leave_rad;
  m["rate_tol_radps"] = cfg_.rate_tol_radps;
  m["uplift_tol_m"] = cfg_.uplift_tol_m;
  m["slip_flag_rel"] = cfg_.slip_flag_rel;
  m["penetration_flag_m"] = cfg_.penetration_flag_m;
  m["energy_growth_flag_rel"] = cfg_.energy_growth_flag_rel;
  m["settled_for_s"] = cfg_.settled_for_s;
  if (std::isfinite(in_meta_.stop_at_rest_after_s)) {
    m["stop_at_rest_after_s"] = in_meta_.stop_at_rest_after_s;
  }
  j["monitor"] = m;
  return j;
}

}  // namespace rockbench
