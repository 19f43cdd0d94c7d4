#include "engines/common/monitor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine/non_finite.h"

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
// they are; then block 2's, and so on up the stack; then the ground's (kinematic drive).
NonFiniteField FirstNonFinite(const StepReadout& s) {
  // The common case first, without a string: a sum is finite when every term is (a finite sum
  // that overflows is sorted out below).
  auto sum = [](const BodyReadout& b) {
    return b.x_m + b.y_m + b.cos_phi + b.sin_phi + b.vx_mps + b.vy_mps + b.w_radps;
  };
  double all = 0.0;
  for (const BodyReadout& b : s.blocks) all += sum(b);
  if (std::isfinite(all + s.ground_x_m + s.ground_y_m + s.ground_vx_mps + s.ground_vy_mps)) {
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
  for (size_t k = 0; k < s.blocks.size(); ++k) {
    if (NonFiniteField f = body(s.blocks[k], static_cast<int>(k) + 1); !f.name.empty()) return f;
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
  in_meta_.blocks = input.blocks;
  in_meta_.initial = input.initial;
  in_meta_.run = input.run;
  in_meta_.time_step_s = input.time_step_s;
  in_meta_.drive_kind = input.drive_kind;
  in_meta_.kinematic_highpass_hz = input.kinematic_highpass_hz;
  in_meta_.overturn_rad = input.overturn_rad;
  in_meta_.stop_at_rest_after_s = input.stop_at_rest_after_s;
  in_meta_.steps = input.steps;
  in_meta_.slip_and_lift = input.slip_and_lift;
  blocks_ = input.block_count();
  slip_and_lift_ = input.slip_and_lift;
  if (blocks_ < 1 || blocks_ > kMaxBlocks) {
    throw std::invalid_argument(std::string("Monitor: ") + std::to_string(blocks_) +
                                " blocks; expected 1 to " + std::to_string(kMaxBlocks));
  }
  const size_t n = static_cast<size_t>(blocks_);
  last_ = Sample(blocks_, slip_and_lift_);
  prev_ = Derived(blocks_, slip_and_lift_);
  g_ = input.run.gravity_mps2;
  dt_ = input.time_step_s;
  out_dt_ = input.run.output_interval_s;
  b_.resize(n);
  h_.resize(n);
  m_.resize(n);
  props_.resize(n);
  significant_m_.assign(n, 0.0);
  for (size_t k = 0; k < n; ++k) {
    const BlockDef& def = input.blocks[k];
    b_[k] = 0.5 * def.width_m;
    h_[k] = 0.5 * def.height_m;
    m_[k] = def.mass_kg;
    props_[k] = MakeBlockProps(def.width_m, def.height_m, m_[k]);
    const double tipping = m_[k] * g_ * (std::hypot(b_[k], h_[k]) - h_[k]);
    tipping_energy_j_ = k == 0 ? tipping : tipping_energy_j_ + tipping;
    // alpha B per block: a corner moved by d tilts the block by d / B.
    significant_m_[k] = cfg_.significant_critical_fraction * props_[k].theta_c * 2.0 * b_[k];
  }
  hysteresis_.assign(n, Side{});
  phi_.assign(n, 0.0);
  landings_.assign(n, Landing{});
  abs_prev_.assign(n, 0.0);
  offset_prev_.assign(n, 0.0);
  side_now_.assign(n, 0);
  pivot_side_.assign(n, 0);
  peak_.assign(n, 0.0);
  peak_t_.assign(n, 0.0);
  impacts_at_.assign(n, 0);
  contacts_.assign(n, ContactWatch{});
  history_.blocks = blocks_;
  history_.slip_and_lift = slip_and_lift_;
}

void Monitor::CheckBodies(const StepReadout& s) const {
  if (s.blocks.size() != static_cast<size_t>(blocks_)) {
    throw std::invalid_argument(std::string("Monitor: the engine read ") +
                                std::to_string(s.blocks.size()) + " bodies for a stack of " +
                                std::to_string(blocks_) + " blocks");
  }
}

void Monitor::SlipAndLift(int k, double x, double y, double c, double sn, double xs, double ys,
                          double cs, double ss, double hs, Derived* d) const {
  // The support's top face: its middle point, unit normal nL and tangent tL (the reference's
  // (sin thL, cos thL) and (cos thL, -sin thL) with thL = -phi of the support).
  const double tx = xs - ss * hs, ty = ys + cs * hs;
  const double nx = -ss, ny = cs, tlx = cs, tly = ss;
  // Block k's base corners, local (+-b, -h) turned by its CCW angle, relative to that point.
  const double b = b_[k], h = h_[k];
  const double rx = x + c * b + sn * h - tx, ry = y + sn * b - c * h - ty;
  const double lx = x - c * b + sn * h - tx, ly = y - sn * b - c * h - ty;
  Sample& smp = d->sample;
  smp.z_m[k] = std::min(rx * nx + ry * ny, lx * nx + ly * ny);
  // The corner on the side of the relative tilt, from where it stood at rest (centred).
  const double rel = smp.theta_rad[k] - (k == 0 ? 0.0 : smp.theta_rad[k - 1]);
  smp.u_m[k] = rel >= 0.0 ? rx * tlx + ry * tly - b : lx * tlx + ly * tly + b;
}

Monitor::Derived Monitor::Derive(const StepReadout& s) {
  Derived d(blocks_, slip_and_lift_);
  d.sample.t_s = s.t_s;
  // The support of the block being read (the block below), in the base frame.
  double xs = 0.0, ys = 0.0, cs = 1.0, ss = 0.0, hs = 0.0, bs = 0.0;
  for (int k = 0; k < blocks_; ++k) {
    const BodyReadout& r = s.blocks[k];
    // Unwrapped CCW angles; the thesis's theta is -phi.
    phi_[k] += std::remainder(std::atan2(r.sin_phi, r.cos_phi) - phi_[k], 2.0 * std::numbers::pi);
    d.sample.theta_rad[k] = -phi_[k];
    d.sample.omega_radps[k] = -r.w_radps;
    // Base frame.
    const double x = r.x_m - s.ground_x_m, y = r.y_m - s.ground_y_m;
    const double vx = r.vx_mps - s.ground_vx_mps, vy = r.vy_mps - s.ground_vy_mps;
    const double c = r.cos_phi, sn = r.sin_phi;
    const double b = b_[k], h = h_[k];
    if (k == 0) {
      // Lowest corner of block 1 above the ground (bottom corners at local (+-b1, -h1)).
      // Corner heights: y = y1 + sin(phi) lx + cos(phi) ly for local (lx, ly) = (+-b1, +-h1); the
      // top corners matter for a block lying on its side.
      const double yl = y - sn * b - c * h;
      const double yr = y + sn * b - c * h;
      const double yl_top = y - sn * b + c * h;
      const double yr_top = y + sn * b + c * h;
      d.gap_m[0] = std::min(std::min(yl, yr), std::min(yl_top, yr_top));
      d.energy_j = BlockEnergy_j(props_[0], g_, {{x, y}, {vx, vy}, r.w_radps});
    } else {
      d.energy_j += BlockEnergy_j(props_[k], g_, {{x, y}, {vx, vy}, r.w_radps});
      // Block k's bottom corners in block k - 1's frame: gap above its top face (y = h_(k-1)).
      // The lowest corner's height gives lift (as for block 1). Below the face's line only a
      // corner over the face penetrates it: one that has slid past the face's edge hangs beside
      // the block below, not in it (issue 24: a top block sliding off, tipping over the edge).
      double gap = 1e300, gap_over = 1e300;
      for (int j = -1; j <= 1; j += 2) {
        const double px = x + c * (j * b) + sn * h;  // local (j b, -h)
        const double py = y + sn * (j * b) - c * h;
        const double dx = px - xs, dy = py - ys;
        const double lx = cs * dx + ss * dy;
        const double ly = -ss * dx + cs * dy;
        gap = std::min(gap, ly - hs);
        if (std::abs(lx) <= bs * (1.0 + 1e-9)) gap_over = std::min(gap_over, ly - hs);
      }
      d.gap_m[k] = gap >= 0.0 ? gap : std::min(0.0, gap_over);
      // The middle of the base, local (0, -h), along the support's top face.
      const double mx = x + sn * h - xs, my = y - c * h - ys;
      d.base_offset_m[k] = cs * mx + ss * my;
    }
    if (slip_and_lift_) SlipAndLift(k, x, y, c, sn, xs, ys, cs, ss, hs, &d);
    xs = x, ys = y, cs = c, ss = sn, hs = h, bs = b;
  }
  return d;
}

void Monitor::Pivots(const StepReadout& s, Derived* d, int* sides) const {
  const Sample& cur = d->sample;
  double xs = 0.0, ys = 0.0, cs = 1.0, ss = 0.0;  // the support, in the base frame
  for (int k = 0; k < blocks_; ++k) {
    const BodyReadout& r = s.blocks[k];
    const double c = r.cos_phi, sn = r.sin_phi;
    const double x = r.x_m - s.ground_x_m, y = r.y_m - s.ground_y_m;
    const int side = TiltSide(cur, k);
    sides[k] = side;
    if (k == 0) {
      // Block 1's pivot: bottom corner (side1 b1, -h1) in its frame (bottom centre when flat).
      d->pivot_x_m[0] = x + c * (side * b_[0]) + sn * h_[0];
    } else {
      // Block k's pivot (side b_k, -h_k) in its frame, expressed in block k - 1's frame.
      const double px = x + c * (side * b_[k]) + sn * h_[k];
      const double py = y + sn * (side * b_[k]) - c * h_[k];
      const double dx = px - xs, dy = py - ys;
      d->pivot_x_m[k] = cs * dx + ss * dy;
    }
    xs = x, ys = y, cs = c, ss = sn;
  }
}

int Monitor::TiltSide(const Sample& s, int k) const {
  // The reference's rule (scene/mode.h TiltContact), with the angle's side from the
  // hysteresis and the flat band's rate threshold of MonitorConfig.
  const double rate = k == 0 ? s.omega_radps[0] : s.omega_radps[k] - s.omega_radps[k - 1];
  return SideOfContact(TiltContact(ContactOfSide(hysteresis_[k].side), rate, cfg_.rate_tol_radps));
}

Configuration Monitor::InferMode(const Sample& s) const {
  Configuration c(blocks_);
  for (int k = 0; k < blocks_; ++k) c.set(k, ContactOfSide(TiltSide(s, k)));
  return c;
}

void Monitor::Record(const Sample& s) {
  history_.samples.push_back(s);
}

void Monitor::PushEvent(Event e) {
  history_.events.push_back(std::move(e));
}

void Monitor::Start(const StepReadout& s) {
  CheckBodies(s);
  if (const NonFiniteField f = FirstNonFinite(s); !f.name.empty()) {
    // Not even the initial state is finite: no sample, and no step will be read.
    last_.t_s = end_t_s_ = s.t_s;
    last_recorded_ = true;
    StopNonFinite(f.name, NonFiniteValueText(f.value), s.t_s, 0);
    return;
  }
  for (int k = 0; k < blocks_; ++k) {
    phi_[k] = std::atan2(s.blocks[k].sin_phi, s.blocks[k].cos_phi);
  }
  Derived d = Derive(s);
  for (int k = 0; k < blocks_; ++k) {
    const double rel =
        k == 0 ? d.sample.theta_rad[0] : d.sample.theta_rad[k] - d.sample.theta_rad[k - 1];
    hysteresis_[k].side = std::abs(rel) > cfg_.angle_enter_rad ? Sign(rel) : 0;
    hysteresis_[k].prev = rel;
    peak_[k] = std::abs(d.sample.theta_rad[k]);
  }
  d.sample.mode = InferMode(d.sample);
  Pivots(s, &d, pivot_side_.data());
  prev_ = d;
  last_ = d.sample;
  energy_min_free_j_ = d.energy_j;
  Record(d.sample);
  last_recorded_ = true;
  next_out_ = 1;
}

bool Monitor::Step(std::int64_t n, const StepReadout& s) {
  if (status_ == RunStatus::kNonFinite) return false;
  CheckBodies(s);
  steps_done_ = n;
  if (!s.engine_fault.empty()) {
    StopNonFinite("the engine's next state", "not finite", s.t_s, n, s.engine_fault);
    return false;
  }
  if (const NonFiniteField f = FirstNonFinite(s); !f.name.empty()) {
    StopNonFinite(f.name, NonFiniteValueText(f.value), s.t_s, n);
    return false;
  }
  Derived d = Derive(s);
  if (!std::isfinite(d.energy_j)) {
    StopNonFinite("energy", NonFiniteValueText(d.energy_j), s.t_s, n);
    return false;
  }
  Sample& cur = d.sample;
  const double t_prev = prev_.sample.t_s, t = cur.t_s;
  // |theta| of every block before this step (prev_ is overwritten before the overturn check).
  for (int k = 0; k < blocks_; ++k) {
    abs_prev_[k] = std::abs(prev_.sample.theta_rad[k]);
    offset_prev_[k] = std::abs(prev_.base_offset_m[k]);
  }

  DetectLandings(cur, t_prev);
  cur.mode = InferMode(cur);
  CompletePendingImpacts(d);
  OpenImpacts();
  RecordModeChange(d);

  MeasureContacts(s, &d);
  MeasurePeaksAndEnergy(d, s.base_accelerating);

  prev_ = d;
  last_ = cur;
  last_recorded_ = false;
  end_t_s_ = t;

  RecordOutput(cur, t);
  const bool stopped = Stopped(d, t_prev);
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
      quantity + " is " + value + " at t = " + MessageTimeText(t_s) + " s (step " +
      std::to_string(n) + (why.empty() ? std::string() : ": " + why) + ")" +
      (any_finite
           ? "; the run stops at its last finite state, t = " + MessageTimeText(last_.t_s) + " s"
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
  bool slip = false, uplift = false, penetration = false;
  for (int k = 0; k < blocks_; ++k) {
    const ContactWatch& c = contacts_[k];
    slip = slip || c.slip_m > cfg_.slip_flag_rel * 2.0 * b_[k];
    uplift = uplift || c.uplift_episodes > 0;
    penetration = penetration || c.penetration_max_m > cfg_.penetration_flag_m;
  }
  return {slip, uplift, penetration,
          energy_gain_max_j_ > cfg_.energy_growth_flag_rel * tipping_energy_j_,
          status_ == RunStatus::kBlowUp || status_ == RunStatus::kNonFinite};
}

std::array<bool, std::size(kViolationFlags)> Monitor::RaisedSignificantly() const {
  bool uplift = false, penetration = false;
  for (int k = 0; k < blocks_; ++k) {
    uplift = uplift || contacts_[k].uplift_max_m > significant_m_[k];
    penetration = penetration || contacts_[k].penetration_max_m > significant_m_[k];
  }
  const auto raised = Raised();
  // Slip is judged as flagged (slip_flag_rel of the width): it tilts nothing, and a converged
  // engine's accumulated contact jitter reaches 0.3 mm over Rinaldi 228 (ODE, MuJoCo).
  return {raised[0], uplift, penetration, raised[3], raised[4]};
}

void Monitor::NoteOnsets(double t_s) {
  const auto raised = Raised();
  const auto significant = RaisedSignificantly();
  for (size_t i = 0; i < raised.size(); ++i) {
    if (raised[i] && std::isnan(onset_t_s_[i])) onset_t_s_[i] = t_s;
    if (significant[i] && std::isnan(significant_t_s_[i])) significant_t_s_[i] = t_s;
  }
}

void Monitor::DetectLandings(const Sample& cur, double t_prev) {
  // Impacts: a tilted block lands on its support (interface k: block k's angle relative to
  // block k - 1, block 1's on the ground).
  landings_t_prev_ = t_prev;
  for (int k = 0; k < blocks_; ++k) {
    Landing& l = landings_[k];
    Side& h = hysteresis_[k];
    l = Landing{};
    l.angle = k == 0 ? cur.theta_rad[0] : cur.theta_rad[k] - cur.theta_rad[k - 1];
    l.angle_prev = h.prev;
    l.side_before = h.side;
    l.landed = UpdateSide(&h.side, h.prev, l.angle, t_prev, cur.t_s, cfg_.angle_enter_rad,
                          cfg_.angle_leave_rad, &l.t_s, &l.crossed);
    h.prev = l.angle;
  }
}

void Monitor::CompletePendingImpacts(const Derived& d) {
  // Pending impacts: Bullet resolves a contact in the step after the one that brought the
  // corner into the support, so an impact is complete one step after its angle crossed zero
  // (or after kImpactWaitSteps steps if it landed without crossing).
  constexpr int kImpactWaitSteps = 10;
  const Sample& cur = d.sample;
  const Sample& prev = prev_.sample;
  for (size_t k = 0; k < pending_.size();) {
    PendingImpact& p = pending_[k];
    const Landing& l = landings_[p.interface];
    const double angle = l.angle;
    const double angle_prev = l.angle_prev;
    bool done = false;
    if (p.crossed) {
      done = true;
    } else if (p.side * angle <= 0.0) {
      p.crossed = true;
      p.event.t_s = CrossingTime(angle_prev, angle, landings_t_prev_, cur.t_s);
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

void Monitor::OpenImpacts() {
  const Sample& prev = prev_.sample;
  // Interfaces from the bottom: the ground's impact first, as the two-block monitor.
  for (int k = 0; k < blocks_; ++k) {
    const Landing& l = landings_[k];
    if (!l.landed) continue;
    ++impacts_at_[k];
    PendingImpact p(blocks_);
    p.interface = k;
    p.side = l.side_before;
    p.crossed = l.crossed;
    p.event.t_s = l.t_s;
    // "ground_impact", "interface_impact" (two blocks), "interface3_impact" (block 3 on
    // block 2 of three or more): the reference's kinds.
    p.event.kind = InterfaceName(k, blocks_) + "_impact";
    p.event.mode_before = prev.mode;
    // The state before the crossing step is before the contact impulse: Bullet applies it in
    // the step that crosses (a speculative contact already in the manifold) or in the next one
    // (a contact found penetrating), so the step after the crossing is after it.
    p.event.omega_before_radps = prev.omega_radps;
    p.event.energy_before_j = prev_.energy_j;
    pending_.push_back(std::move(p));
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
  Pivots(s, d_ptr, side_now_.data());
  for (int k = 0; k < blocks_; ++k) {
    ContactWatch& c = contacts_[k];
    const int side = side_now_[k];
    if (side == pivot_side_[k] && d.gap_m[k] < cfg_.uplift_tol_m) {
      c.slip_m += std::abs(d.pivot_x_m[k] - prev_.pivot_x_m[k]);
    }
    c.drift_max_m = std::max(c.drift_max_m, std::abs(d.pivot_x_m[k] - side * b_[k]));
    pivot_side_[k] = side;
  }
  // Uplift and penetration.
  for (int k = 0; k < blocks_; ++k) {
    ContactWatch& c = contacts_[k];
    const bool up = d.gap_m[k] > cfg_.uplift_tol_m;
    if (up) {
      c.uplift_s += dt_;
      c.uplift_max_m = std::max(c.uplift_max_m, d.gap_m[k]);
      if (!c.airborne) ++c.uplift_episodes;
    }
    c.airborne = up;
    c.penetration_max_m = std::max(c.penetration_max_m, -d.gap_m[k]);
  }
  out_of_plane_m_ = std::max(out_of_plane_m_, s.out_of_plane_m);
  out_of_plane_rad_ = std::max(out_of_plane_rad_, s.out_of_plane_rad);
}

void Monitor::MeasurePeaksAndEnergy(const Derived& d, bool base_accelerating) {
  const Sample& cur = d.sample;
  const double t = cur.t_s;
  // Peaks.
  for (int k = 0; k < blocks_; ++k) {
    const double a = std::abs(cur.theta_rad[k]);
    if (a > peak_[k]) {
      peak_[k] = a;
      peak_t_[k] = t;
    }
    max_rate_radps_ = std::max(max_rate_radps_, std::abs(cur.omega_radps[k]));
  }

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

bool Monitor::Stopped(const Derived& d, double t_prev) {
  const Sample& cur = d.sample;
  const double t = cur.t_s;
  // Stops: overturn, blow-up. A block overturns when |theta| reaches the model's overturn angle
  // (model.overturn_angle, the reference's definition, no slack). The crossing time is
  // interpolated linearly between the step's two ends, the same way for every block: Bullet turns
  // each body at a constant rate within a step, so this is Bullet's own crossing. If several
  // cross in one step, the first to cross overturned (ties: the lowest, as the reference).
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
  for (int k = 0; k < blocks_; ++k) crossed(k + 1, abs_prev_[k], std::abs(cur.theta_rad[k]));
  // A block whose base no longer overlaps its support's top face has left it (block 1 never:
  // the ground is infinite). If it did so before any overturn in the step, the run ends there.
  int off_block = 0;
  double t_off = 0.0;
  for (int k = 1; k < blocks_; ++k) {
    const double reach = b_[k] + b_[k - 1], off = std::abs(d.base_offset_m[k]);
    if (!(off > reach)) continue;
    const double when = CrossingTime(reach - offset_prev_[k], reach - off, t_prev, t);
    if (off_block == 0 || when < t_off) {
      off_block = k + 1;
      t_off = when;
    }
  }
  // The event that ends the run at t_end (kind, the block it names).
  auto end_event = [&](const char* kind, double t_end, int block) {
    Event e(blocks_);
    e.t_s = t_end;
    e.kind = kind;
    e.mode_before = e.mode_after = cur.mode;
    e.omega_before_radps = e.omega_after_radps = cur.omega_radps;
    e.energy_before_j = e.energy_after_j = d.energy_j;
    e.note = "block " + std::to_string(block);
    PushEvent(std::move(e));
  };
  if (off_block != 0 && (over_block == 0 || t_off <= t_over)) {
    status_ = RunStatus::kLeftSupport;
    left_support_block_ = off_block;
    left_support_t_s_ = t_off;
    status_detail_ = "block " + std::to_string(off_block) + " slid off its support (its base " +
                     "no longer overlaps block " + std::to_string(off_block - 1) + "'s top face)";
    end_event("left_support", t_off, off_block);
    return true;
  }
  if (over_block != 0) {
    status_ = RunStatus::kOverturned;
    overturn_block_ = over_block;
    overturn_t_s_ = t_over;
    status_detail_ = "block " + std::to_string(over_block) +
                     " reached |theta| = " + std::to_string(over) + " rad (model.overturn_angle)";
    end_event("overturn", t_over, over_block);
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
  o.left_support_block = left_support_block_;
  if (left_support_block_ != 0) o.left_support_t_s = left_support_t_s_;
  o.end_t_s = end_t_s_;
  o.peak_theta_rad = peak_;
  o.peak_theta_t_s = peak_t_;
  o.impacts_at = impacts_at_;
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
  // Same shape as the reference's part of summary.json (run/summary.cc): per block theta1 ..
  // thetaN; per interface "ground", then "interface" (two blocks) or "interface2" ..
  // "interfaceN" (three or more).
  int total = 0;
  for (int k = 0; k < blocks_; ++k) {
    j["peaks"][std::string("theta") + std::to_string(k + 1)] = {{"abs_rad", peak_[k]},
                                                                {"t_s", peak_t_[k]}};
    total += impacts_at_[k];
  }
  j["impacts"] = {{"total", total}, {"ground", impacts_at_[0]}};
  if (blocks_ <= 2) {
    j["impacts"]["interface"] = blocks_ == 2 ? impacts_at_[1] : 0;
  } else {
    for (int k = 1; k < blocks_; ++k) j["impacts"][InterfaceName(k, blocks_)] = impacts_at_[k];
  }
  j["transitions"] = transitions_;
  j["initiations"] = initiations_;
  j["rests"] = rests_;
  if (overturn_block_ != 0) {
    j["overturn"] = {{"block", overturn_block_}, {"t_s", overturn_t_s_}};
  } else {
    j["overturn"] = nullptr;
  }
  // A block that slid off its support (null: none), as the reference's summary.
  if (left_support_block_ != 0) {
    j["left_support"] = {{"block", left_support_block_}, {"t_s", left_support_t_s_}};
  } else {
    j["left_support"] = nullptr;
  }
  json fin;
  fin["t_s"] = last_.t_s;
  for (int k = 0; k < blocks_; ++k) {
    fin[std::string("theta") + std::to_string(k + 1) + "_rad"] = last_.theta_rad[k];
    fin[std::string("omega") + std::to_string(k + 1) + "_radps"] = last_.omega_radps[k];
  }
  fin["mode"] = ConfigurationName(last_.mode);
  j["final"] = fin;

  json v;
  for (int k = 0; k < blocks_; ++k) {
    const ContactWatch& c = contacts_[k];
    const std::string name = InterfaceName(k, blocks_);
    v["slip_" + name + "_m"] = c.slip_m;
    v["drift_" + name + "_max_m"] = c.drift_max_m;
    v["uplift_" + name + "_s"] = c.uplift_s;
    v["uplift_" + name + "_max_m"] = c.uplift_max_m;
    v["uplift_" + name + "_episodes"] = c.uplift_episodes;
    v["penetration_" + name + "_max_m"] = c.penetration_max_m;
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
  // Per block; one block writes a second entry 0, as it always has.
  if (blocks_ == 1) {
    v["significant_displacement_m"] = {significant_m_[0], 0.0};
  } else {
    v["significant_displacement_m"] = significant_m_;
  }
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
