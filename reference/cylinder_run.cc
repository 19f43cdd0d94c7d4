#include "reference/cylinder_run.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

#include "reference/integration/integrator.h"
#include "scene/body_kind.h"
#include "scene/cylinder_state.h"

namespace rockbench::reference::cylinder {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The planar model's event width, relative to the time scale (simulate.cc kEventTolRel).
constexpr double kEventTolRel = 1e-12;
// Event functions are sampled at this many points of every step (a sign change between two
// is located by Brent's method).
constexpr int kEventSamples = 8;
// The forces' margins (lift-off, slip) are sampled at every this many event samples.
constexpr int kForceSampleEvery = 4;
// The longest step, in time scales: at least kEventSamples event samples per quarter T.
constexpr double kMaxStepRel = 0.25;
// The first step after a start from upright, in time scales; the controller grows it.
constexpr double kUprightStepRel = 1e-6;
// A step below this, in time scales, stops the run (a pass too close to upright to integrate).
constexpr double kMinStepRel = 1e-14;
// The tilt an onset from rest starts from, rad (Onset).
constexpr double kOnsetTilt_rad = 1e-12;
// A local minimum of the tilt below this fraction of the critical angle is a pass near upright.
constexpr double kPassTiltRel = 0.01;

// The integrated state on the rim: the tilt vector (u, v) = theta (cos, sin) of the azimuth
// measured from the segment's reference azimuth, the total turn chi = azimuth + spin, the
// tilt vector's velocity and the axial rate w3 = psi' + phi' cos theta. Unlike the angles, these
// have regular equations through upright (where the azimuth has no value and its rate grows as
// 1 / theta^2 in a pass near upright): onsets, landings and passes integrate smoothly.
using Y = VecN<6>;
enum : size_t { kU, kV, kChi, kUDot, kVDot, kW3 };

// cos and sin of an angle, exact at multiples of pi/2 (within 1e-12 of one), so that a planar
// motion's transverse arm is exactly 0.
std::pair<double, double> CosSin(double angle_rad) {
  const double quarters = angle_rad / (0.5 * kPi);
  const double k = std::round(quarters);
  if (std::abs(quarters - k) < 1e-12) {
    const long m = ((static_cast<long>(k) % 4) + 4) % 4;
    static constexpr double kCos[4] = {1.0, 0.0, -1.0, 0.0};
    static constexpr double kSin[4] = {0.0, 1.0, 0.0, -1.0};
    return {kCos[m], kSin[m]};
  }
  return {std::cos(angle_rad), std::sin(angle_rad)};
}

class Run {
 public:
  Run(const Scene& scene, const GroundMotion& motion)
      : scene_(scene),
        motion_(motion),
        cfg_(scene.model),
        body_(BodyOf(scene)),
        t_scale_(body_.time_scale_s()),
        t_end_(scene.run.duration_s),
        event_tol_(kEventTolRel * t_scale_),
        rest_rate_(
            cfg_.rest_rate_rel *
            std::sqrt(body_.gravity_mps2 / std::hypot(body_.radius_m, body_.half_height_m))) {
    result_.history.blocks = 1;
    result_.history.shape = std::string(kCylinderShape);
    CylinderSummary& s = result_.summary;
    s.min_normal_rel = kInf;
    s.min_pass_tilt_rad = kInf;
  }

  CylinderResult Go() {
    const InitialState& in = scene_.initial;
    const double tilt0 = in.tilt_rad[0], rate0 = in.tilt_rate_radps[0];
    const double azimuth0 = in.azimuth_rad[0];
    // A motion that keeps one vertical plane exactly: no azimuth or spin rate, no transverse
    // field, and the lean along the field's line (or no field, or an onset, which leans
    // against it).
    const auto [c0, s0] = CosSin(azimuth0);
    CylinderSummary& sum = result_.summary;
    sum.planar = !motion_.has_transverse() && in.azimuth_rate_radps[0] == 0.0 &&
                 in.spin_rate_radps[0] == 0.0 &&
                 (!motion_.has_horizontal() || s0 == 0.0 || (tilt0 == 0.0 && rate0 == 0.0));
    sum.landing_tilt_rad = sum.planar ? 0.0 : std::asin(cfg_.landing_clearance_rel);
    azimuth_ref_ = azimuth0;
    last_azimuth_ = azimuth0;
    cos_ref_ = c0;
    sin_ref_ = s0;
    psi_ = 0.0;
    if (tilt0 == 0.0 && rate0 == 0.0) {
      on_rim_ = false;
    } else {
      // Upright with a negative tilt rate: the tilt vector moves away from the azimuth (the
      // same motion about the opposite rim point); the azimuth rate has no meaning there.
      on_rim_ = true;
      y_ = {tilt0,
            0.0,
            azimuth0,
            rate0,
            tilt0 * in.azimuth_rate_radps[0],
            in.spin_rate_radps[0] + in.azimuth_rate_radps[0] * std::cos(tilt0)};
      h_ = (tilt0 == 0.0 ? kUprightStepRel : 1e-3) * t_scale_;
    }
    Emit(0.0);
    next_output_ = 1;
    while (!done_) {
      if (on_rim_) {
        RimStep();
      } else {
        RestStep();
      }
    }
    sum.end_s = t_;
    if (sum.min_normal_rel == kInf) sum.min_normal_rel = 0.0;
    if (sum.min_pass_tilt_rad == kInf) sum.min_pass_tilt_rad = 0.0;
    return std::move(result_);
  }

 private:
  BaseAccel Accel(double t) const {
    return {motion_.xg_mps2(t), motion_.transverse_mps2(t), motion_.yg_mps2(t)};
  }
  // The polar view of a tilt vector state: the rim state (its azimuth's cosine and sine from
  // the reference's and the vector's direction), the direction in the reference's frame, and
  // the tilt vector's speed across its direction, theta phi' (each quantity divides by theta
  // once at most, so that nothing underflows to 0/0 just off upright).
  struct Polar {
    RimState rim;
    double dir_cos = 1.0, dir_sin = 0.0, across = 0.0;
  };
  Polar PolarOf(const Y& y) const {
    Polar p;
    RimState& s = p.rim;
    const double u = y[kU], v = y[kV], ud = y[kUDot], vd = y[kVDot];
    s.theta = std::hypot(u, v);
    if (s.theta > 0.0) {
      p.dir_cos = u / s.theta;
      p.dir_sin = v / s.theta;
      s.theta_dot = p.dir_cos * ud + p.dir_sin * vd;
      p.across = p.dir_cos * vd - p.dir_sin * ud;
      s.phi_dot = p.across / s.theta;
    } else if (const double speed = std::hypot(ud, vd); speed > 0.0) {
      // Upright: the direction is the velocity's.
      p.dir_cos = ud / speed;
      p.dir_sin = vd / speed;
      s.theta_dot = speed;
    }
    s.psi_dot = y[kW3] - s.phi_dot * std::cos(s.theta);
    s.cos_phi = cos_ref_ * p.dir_cos - sin_ref_ * p.dir_sin;
    s.sin_phi = sin_ref_ * p.dir_cos + cos_ref_ * p.dir_sin;
    return p;
  }
  RimState StateOf(const Y& y) const { return PolarOf(y).rim; }

  // The tilt vector's equations from the rim's: radial theta'' - theta phi'^2, tangential
  // theta phi'' + 2 theta' phi', turned into the reference's frame; chi' = w3 + phi' (1 - cos).
  Y Rhs(double t, const Y& y) const {
    const Polar p = PolarOf(y);
    const RimState& s = p.rim;
    const RimDynamics d = Dynamics(body_, s, Accel(t));
    double radial = d.theta_ddot, tangential = d.theta_phi_ddot, turn = 0.0;
    if (s.theta > 0.0) {
      radial -= p.across * s.phi_dot;
      tangential += 2.0 * s.theta_dot * s.phi_dot;
      // phi' (1 - cos theta) = across (2 sin^2(theta / 2) / theta).
      const double half = std::sin(0.5 * s.theta);
      turn = p.across * 2.0 * half * (half / s.theta);
    }
    return {y[kUDot],
            y[kVDot],
            y[kW3] + turn,
            radial * p.dir_cos - tangential * p.dir_sin,
            radial * p.dir_sin + tangential * p.dir_cos,
            d.axial_rate_dot};
  }

  // The azimuth of a state, continuous with the last row's (the last's when upright).
  double AzimuthOf(const Y& y) const {
    if (y[kU] == 0.0 && y[kV] == 0.0) return last_azimuth_;
    const double a = azimuth_ref_ + std::atan2(y[kV], y[kU]);
    return a + 2.0 * kPi * std::round((last_azimuth_ - a) / (2.0 * kPi));
  }

  // The history's row of an integrated state (on the rim) or of the rest (upright, still).
  Sample RowOf(double t, const Y* y) const {
    Sample out(1, CylinderKind());
    out.t_s = t;
    CylinderState cs;
    cs.azimuth_rad = azimuth_ref_;
    cs.spin_rad = psi_;
    double tilt_x = 0.0, tilt_y = 0.0;
    if (y != nullptr) {
      const RimState s = StateOf(*y);
      cs.tilt_rad = s.theta;
      cs.azimuth_rad = AzimuthOf(*y);
      cs.spin_rad = (*y)[kChi] - cs.azimuth_rad;
      cs.tilt_rate_radps = s.theta_dot;
      cs.azimuth_rate_radps = s.phi_dot;
      cs.spin_rate_radps = s.psi_dot;
      // The tilt vector in the world, exact on the reference's cosine and sine.
      tilt_x = (*y)[kU] * cos_ref_ - (*y)[kV] * sin_ref_;
      tilt_y = (*y)[kU] * sin_ref_ + (*y)[kV] * cos_ref_;
      out.mode.set(0, Contact::kRight);
    }
    const double values[8] = {
        cs.tilt_rad, cs.azimuth_rad,     cs.spin_rad,           tilt_x,
        tilt_y,      cs.tilt_rate_radps, cs.azimuth_rate_radps, cs.spin_rate_radps};
    for (int q = 0; q < 8; ++q) out.state[static_cast<size_t>(q)][0] = values[q];
    return out;
  }

  void Emit(double t, const Y* y = nullptr) {
    Sample row = RowOf(t, on_rim_ ? (y != nullptr ? y : &y_) : nullptr);
    const double tilt = row.state[0][0];
    last_azimuth_ = row.state[1][0];
    CylinderSummary& sum = result_.summary;
    if (tilt > sum.peak_tilt_rad) {
      sum.peak_tilt_rad = tilt;
      sum.peak_tilt_t_s = t;
    }
    result_.history.samples.push_back(std::move(row));
  }

  double OutputTime(long i) const { return static_cast<double>(i) * scene_.run.output_interval_s; }

  // Output rows at the output times in (t_, t_to] (t_to included when `inclusive`).
  template <class At>
  void EmitUntil(double t_to, bool inclusive, const At& at) {
    for (;;) {
      const double to = OutputTime(next_output_);
      if (to > t_end_ * (1.0 + 1e-12)) return;
      if (inclusive ? to > t_to : to >= t_to) return;
      const Y y = at(to);
      Emit(to, &y);
      ++next_output_;
    }
  }

  void AddEvent(double t, const char* kind, Contact before, Contact after, double rate_before,
                double rate_after, double energy_before, double energy_after, std::string note) {
    Event e(1);
    e.t_s = t;
    e.kind = kind;
    e.mode_before.set(0, before);
    e.mode_after.set(0, after);
    e.omega_before_radps[0] = rate_before;
    e.omega_after_radps[0] = rate_after;
    e.energy_before_j = energy_before;
    e.energy_after_j = energy_after;
    e.note = std::move(note);
    result_.history.events.push_back(std::move(e));
  }

  void Stop(RunStatus status, std::string detail) {
    result_.summary.status = status;
    result_.summary.status_detail = std::move(detail);
    done_ = true;
  }

  // One step on the rim, its events located on the dense output.
  void RimStep() {
    CylinderSummary& sum = result_.summary;
    if (!(t_ >= break_from_ && t_ < break_at_)) {
      break_at_ = motion_.next_breakpoint_after(t_);
      break_from_ = t_;
    }
    const bool rk4 = cfg_.integrator == Integrator::kRk4;
    const bool dop853 = cfg_.integrator == Integrator::kDop853;
    double h = rk4 ? cfg_.step_s : std::min(h_, kMaxStepRel * t_scale_);
    h = std::min({h, break_at_ - t_, t_end_ - t_});
    const auto rhs = [this](double t, const Y& y) { return Rhs(t, y); };
    // First same as last: the previous step's f(t1, y1) when nothing changed the state since.
    const Y f0 = continued_ ? f1_ : Rhs(t_, y_);
    auto attempt = [&](double hh) {
      return rk4      ? Rk4Step(rhs, t_, y_, f0, hh)
             : dop853 ? Dop853Step(rhs, t_, y_, f0, hh, cfg_.rtol, cfg_.atol)
                      : Dopri5Step(rhs, t_, y_, f0, hh, cfg_.rtol, cfg_.atol);
    };
    StepResultN<6> st = attempt(h);
    // A step that ends on a breakpoint or the end ends there exactly.
    const auto step_end = [&](double hh) {
      return hh == break_at_ - t_ ? break_at_ : hh == t_end_ - t_ ? t_end_ : t_ + hh;
    };
    if (!rk4) {
      // dopri5.f's and dop853.f's step-size control (as simulate.cc).
      const double expo = dop853 ? -1.0 / 8.0 : -0.2;
      const double fac_min = dop853 ? 1.0 / 3.0 : 0.2, fac_max = dop853 ? 6.0 : 5.0;
      while (!(st.err <= 1.0) && h >= kMinStepRel * t_scale_) {
        ++sum.steps_rejected;
        h *= std::max(fac_min, 0.9 * std::pow(st.err, expo));
        st = attempt(h);
      }
      if (h < kMinStepRel * t_scale_) {
        Stop(RunStatus::kAssumptionViolated,
             "the step fell below 1e-14 time scales at tilt " +
                 std::to_string(std::hypot(y_[kU], y_[kV])) +
                 " rad (a pass too close to upright for model.landing_clearance_rel)");
        return;
      }
      const double fac = st.err > 0 ? std::min(fac_max, 0.9 * std::pow(st.err, expo)) : fac_max;
      h_ = h * fac;
    }
    ++sum.steps_accepted;
    for (double v : st.y1) {
      if (!std::isfinite(v)) {
        Stop(RunStatus::kNonFinite,
             "the state stopped being finite at t = " + std::to_string(step_end(h)) + " s");
        return;
      }
    }
    const DenseStepN<6>& dense = st.dense;
    const double t0 = t_, t1 = step_end(h);
    // The event functions, > 0 while the motion stays in the model.
    const double theta_land = sum.landing_tilt_rad;
    const double mu = scene_.blocks[0].friction;
    const double weight = body_.mass_kg * body_.gravity_mps2;
    enum Kind { kLand, kOverturn, kApex, kLift, kSlip, kKinds };
    RimDynamics solved;
    double solved_t = std::numeric_limits<double>::quiet_NaN();
    const auto g = [&](int kind, double t) {
      const Y y = dense.At(t);
      switch (kind) {
        case kLand:
          // A planar motion lands at u = 0 (v stays 0), any other at the clearance tilt.
          return sum.planar ? y[kU] : std::hypot(y[kU], y[kV]) - theta_land;
        case kOverturn:
          return cfg_.overturn_rad - std::hypot(y[kU], y[kV]);
        case kApex:
          // A rebound whose apex stays within the landing clearance (its tilt rate turning
          // down below the landing tilt): the face never left the base.
          if (sum.planar || std::hypot(y[kU], y[kV]) >= theta_land) return 1.0;
          return StateOf(y).theta_dot;
        default: {
          // Lift-off and slip at one time share one solve.
          if (t != solved_t) {
            solved = Dynamics(body_, StateOf(y), Accel(t));
            solved_t = t;
          }
          const RimDynamics& d = solved;
          if (kind == kLift) return d.force_n[2] / weight;
          return (mu * d.force_n[2] - std::hypot(d.force_n[0], d.force_n[1])) / weight;
        }
      }
    };
    const bool check_slip = std::isfinite(mu);
    double first_t = kInf;
    int first_kind = -1;
    double first_lo = 0.0;
    // The forces' margins (a solve of the rim's equations each) at every kForceSampleEvery-th
    // sample, from the previous step's end when the state continues it.
    double prev[kKinds];
    for (int k = 0; k < kKinds; ++k) {
      if (k == kSlip && !check_slip) {
        prev[k] = 1.0;
      } else {
        prev[k] = continued_ && k >= kLift ? force_margin_[k - kLift] : g(k, t0);
      }
    }
    for (int i = 1; i <= kEventSamples && first_kind < 0; ++i) {
      const double ti = i == kEventSamples ? t1 : t0 + h * i / kEventSamples;
      for (int k = 0; k < kKinds; ++k) {
        if (k == kSlip && !check_slip) continue;
        if (k >= kLift && i % kForceSampleEvery != 0) continue;
        const double ti_prev = t0 + h * (i - (k >= kLift ? kForceSampleEvery : 1)) / kEventSamples;
        const double gi = g(k, ti);
        // A landing or an overturn crosses from > 0 to <= 0; a force from >= 0 to < 0.
        const bool crossed =
            k <= kApex ? (prev[k] > 0.0 && gi <= 0.0 &&
                          (k != kApex ||
                           std::hypot(dense.At(ti_prev)[kU], dense.At(ti_prev)[kV]) < theta_land))
                       : (prev[k] >= 0.0 && gi < 0.0);
        if (crossed && ti < first_t) {
          const auto fn = [&](double t) { return g(k, t); };
          const auto br = BrentBracket(fn, ti_prev, ti, prev[k], gi, event_tol_);
          if (br.second < first_t) {
            first_t = br.second;
            first_lo = br.first;
            first_kind = k;
          }
        }
        prev[k] = gi;
      }
    }
    const double t_stop = first_kind >= 0 ? first_t : t1;
    EmitUntil(t_stop, first_kind < 0, [&](double t) { return dense.At(t); });
    // Step-end figures: the friction the rolling needs, the normal force, passes near upright.
    const Y y_end = first_kind >= 0 ? dense.At(first_lo) : st.y1;
    {
      const double t_end_of_step = first_kind >= 0 ? first_lo : t1;
      const RimDynamics d = t_end_of_step == solved_t
                                ? solved
                                : Dynamics(body_, StateOf(y_end), Accel(t_end_of_step));
      sum.friction_needed = std::max(sum.friction_needed, d.friction_needed());
      sum.min_normal_rel = std::min(sum.min_normal_rel, d.force_n[2] / weight);
      const RimState before = StateOf(y_), after = StateOf(y_end);
      if (before.theta_dot < 0.0 && after.theta_dot >= 0.0 &&
          after.theta < kPassTiltRel * body_.critical_angle_rad()) {
        ++sum.passes;
        sum.min_pass_tilt_rad = std::min(sum.min_pass_tilt_rad, after.theta);
      }
      if (after.theta > sum.peak_tilt_rad) {
        sum.peak_tilt_rad = after.theta;
        sum.peak_tilt_t_s = first_kind >= 0 ? first_lo : t1;
      }
    }
    continued_ = first_kind < 0;
    if (continued_) {
      f1_ = st.f1;
      force_margin_[0] = prev[kLift];
      force_margin_[1] = prev[kSlip];
    }
    if (first_kind < 0) {
      t_ = t1;
      y_ = st.y1;
      if (t_ >= t_end_) Finish();
      return;
    }
    t_ = first_t;
    // A landing's state is the one still on the lean's side (the bracket's other end, within
    // the event width): its tilt rate points down toward upright.
    y_ = dense.At(first_kind == kLand ? first_lo : first_t);
    // A lift-off beyond the critical angle with the tilt still rising is the fall's: the rim
    // lets go of the base as the cylinder topples (gravity no longer restores it).
    const RimState at_event = StateOf(y_);
    const bool falling = first_kind == kLift && at_event.theta > body_.critical_angle_rad() &&
                         at_event.theta_dot > 0.0;
    if (first_kind == kOverturn || falling) {
      const RimState s = StateOf(y_);
      sum.overturn_t_s = t_;
      sum.overturn_azimuth_rad = WrappedAzimuth_rad(std::atan2(s.sin_phi, s.cos_phi));
      EmitEvent();
      const double e = Energy(body_, s);
      std::string note = "azimuth " + std::to_string(sum.overturn_azimuth_rad) + " rad";
      if (falling) {
        note += "; the rim lifted off at tilt " + std::to_string(at_event.theta) +
                " rad beyond the critical angle " + std::to_string(body_.critical_angle_rad()) +
                " rad while tilting away: counted as the overturn";
      }
      AddEvent(t_, "overturn", Contact::kRight, Contact::kRight, at_event.theta_dot,
               at_event.theta_dot, e, e, note);
      Stop(RunStatus::kOverturned, "");
      return;
    }
    switch (first_kind) {
      case kLand:
        Landed();
        return;
      case kApex:
        RestsWithinClearance();
        return;
      default: {
        EmitEvent();
        const double e = Energy(body_, StateOf(y_));
        const std::string why =
            first_kind == kLift ? "lift-off: the rim's normal force would pull"
                                : "slip: the rolling needs more friction than block1.friction = " +
                                      std::to_string(mu);
        AddEvent(t_, "assumption_violated", Contact::kRight, Contact::kRight, at_event.theta_dot,
                 at_event.theta_dot, e, e, why);
        Stop(RunStatus::kAssumptionViolated, why + " at t = " + std::to_string(t_) + " s");
        return;
      }
    }
  }

  // A landing: the plastic impact of the face, then rest or rocking on the opposite rim point.
  void Landed() {
    CylinderSummary& sum = result_.summary;
    const RimState pre = StateOf(y_);
    const Landing l = Land(body_, pre);
    ++sum.landings;
    const double e_before = Energy(body_, pre);
    const double phi_pre = AzimuthOf(y_);
    const double chi = y_[kChi];
    if (l.theta_dot <= rest_rate_) {
      ComeToRest("ground_impact", "rest");
      return;
    }
    // The half-turn of the azimuth, exact on its cosine and sine; the column's value within
    // (-pi, pi] (a planar rocking's lean alternates between two azimuths, not a drift).
    azimuth_ref_ = WrappedAzimuth_rad(phi_pre + kPi);
    last_azimuth_ = azimuth_ref_;
    cos_ref_ = -pre.cos_phi;
    sin_ref_ = -pre.sin_phi;
    // Upright, the tilt vector leaving toward the new azimuth.
    y_ = {0.0, 0.0, chi, l.theta_dot, 0.0, l.axial_rate};
    const double e_after = Energy(body_, StateOf(y_));
    AddEvent(t_, "ground_impact", Contact::kRight, Contact::kRight, pre.theta_dot, l.theta_dot,
             e_before, e_after, pre.theta > 0.0 ? "landed at the clearance tilt" : "");
    EmitEvent();
    h_ = kUprightStepRel * t_scale_;
  }

  // A rebound that turns back within the landing clearance: the cylinder rests on its face (its
  // spin held by the face's friction, as after a landing that rests).
  void RestsWithinClearance() {
    ComeToRest("rest", "the rebound turned back within the landing clearance");
  }

  // From the rim at y_ to rest on the face, keeping the azimuth and the spin (the face's
  // friction holds the spin too), with an event of `kind` and `note`.
  void ComeToRest(const char* kind, const char* note) {
    const RimState pre = StateOf(y_);
    const double phi = AzimuthOf(y_);
    ++result_.summary.rests;
    on_rim_ = false;
    azimuth_ref_ = phi;
    cos_ref_ = pre.cos_phi;
    sin_ref_ = pre.sin_phi;
    psi_ = y_[kChi] - phi;
    AddEvent(t_, kind, Contact::kRight, Contact::kFace, pre.theta_dot, 0.0, Energy(body_, pre),
             Energy(body_, RimState{}), note);
    EmitEvent();
  }

  // At rest on the face until the field tips it (OnsetMargin > 0), lifts it or slides it.
  void RestStep() {
    if (t_ >= t_end_) {
      Finish();
      return;
    }
    // After the motion has ended the cylinder rests for good.
    if (t_ >= motion_.end_s()) {
      EmitUntil(t_end_, true, [&](double) { return Y{}; });
      t_ = t_end_;
      Stop(RunStatus::kAtRest, "");
      return;
    }
    if (!(t_ >= break_from_ && t_ < break_at_)) {
      break_at_ = motion_.next_breakpoint_after(t_);
      break_from_ = t_;
    }
    // Scan the margins at a fraction of the time scale (an analytic field's shortest period is
    // far longer; a record is straight between its breakpoints).
    const double t1 = std::min({break_at_, t_end_, t_ + 0.05 * t_scale_});
    const double mu = scene_.blocks[0].friction;
    const auto margin = [&](double t) { return OnsetMargin(body_, Accel(t)); };
    const auto lift = [&](double t) { return body_.gravity_mps2 + Accel(t)[2]; };
    const auto slip = [&](double t) {
      const BaseAccel a = Accel(t);
      return mu * (body_.gravity_mps2 + a[2]) - std::hypot(a[0], a[1]);
    };
    double t_prev = t_;
    for (int i = 1; i <= kEventSamples; ++i) {
      const double ti = i == kEventSamples ? t1 : t_ + (t1 - t_) * i / kEventSamples;
      // The boundaries first: lift-off and slip at rest end the model as on the rim.
      if (!(lift(ti) > 0.0) || (std::isfinite(mu) && slip(ti) < 0.0)) {
        const bool lifts = !(lift(ti) > 0.0);
        const auto fn =
            lifts ? std::function<double(double)>(lift) : std::function<double(double)>(slip);
        const auto br = BrentBracket(fn, t_prev, ti, fn(t_prev), fn(ti), event_tol_);
        EmitUntil(br.second, false, [&](double) { return Y{}; });
        t_ = br.second;
        EmitEvent();
        const std::string why = lifts ? "lift-off at rest: the vertical field exceeds gravity"
                                      : "slip at rest: the field needs more friction than "
                                        "block1.friction = " +
                                            std::to_string(mu);
        AddEvent(t_, "assumption_violated", Contact::kFace, Contact::kFace, 0.0, 0.0, 0.0, 0.0,
                 why);
        Stop(RunStatus::kAssumptionViolated, why + " at t = " + std::to_string(t_) + " s");
        return;
      }
      if (margin(ti) > 0.0) {
        const auto br = BrentBracket(margin, t_prev, ti, margin(t_prev), margin(ti), event_tol_);
        EmitUntil(br.second, false, [&](double) { return Y{}; });
        t_ = br.second;
        Onset();
        return;
      }
      t_prev = ti;
    }
    EmitUntil(t1, false, [&](double) { return Y{}; });
    t_ = t1;
  }

  // The field tips the cylinder about the rim point away from it: its top leans against it.
  void Onset() {
    CylinderSummary& sum = result_.summary;
    ++sum.initiations;
    const BaseAccel a = Accel(t_);
    const double ah = std::hypot(a[0], a[1]);
    const double previous = azimuth_ref_;
    cos_ref_ = -a[0] / ah;
    sin_ref_ = -a[1] / ah;
    azimuth_ref_ = std::atan2(sin_ref_, cos_ref_);
    // Continuous with the azimuth the rest kept: the same direction within a half-turn.
    azimuth_ref_ += 2.0 * kPi * std::round((previous - azimuth_ref_) / (2.0 * kPi));
    last_azimuth_ = azimuth_ref_;
    on_rim_ = true;
    // The rim model has no direction at upright and no rate at the onset: it starts at a tilt
    // of kOnsetTilt_rad toward the azimuth, still, where the restoring moment has its direction
    // (an offset far below any tolerance; from exactly upright the integrator's stages would
    // turn the azimuth by the roundoff of an acceleration that is itself ~0 at the onset).
    y_ = {kOnsetTilt_rad, 0.0, azimuth_ref_ + psi_, 0.0, 0.0, 0.0};
    h_ = kUprightStepRel * t_scale_;
    AddEvent(t_, "initiation", Contact::kFace, Contact::kRight, 0.0, 0.0, 0.0, 0.0, "");
    EmitEvent();
  }

  // The row of an event's time (the state after it); an output time there is this row.
  void EmitEvent() {
    if (OutputTime(next_output_) == t_) ++next_output_;
    Emit(t_);
  }

  void Finish() {
    EmitUntil(t_end_, true, [&](double) { return y_; });
    t_ = t_end_;
    Stop(RunStatus::kCompleted, "");
  }

  const Scene& scene_;
  const GroundMotion& motion_;
  const ModelConfig cfg_;
  const CylinderBody body_;
  const double t_scale_, t_end_, event_tol_, rest_rate_;
  CylinderResult result_;
  bool on_rim_ = false, done_ = false;
  double t_ = 0.0, h_ = 0.0;
  Y y_{};
  double azimuth_ref_ = 0.0, cos_ref_ = 1.0, sin_ref_ = 0.0, psi_ = 0.0;
  double last_azimuth_ = 0.0;  // the last row's azimuth (the unwrapping's anchor)
  // Whether y_ is the last step's end, unchanged: then f1_ is f(t_, y_) and force_margin_ the
  // lift-off and slip margins there.
  bool continued_ = false;
  Y f1_{};
  double force_margin_[2] = {1.0, 1.0};
  long next_output_ = 0;
  double break_from_ = -kInf, break_at_ = -kInf;
};

}  // namespace

CylinderBody BodyOf(const Scene& scene) {
  const BlockDef& b = scene.blocks.at(0);
  return MakeCylinderBody(b.diameter_m, b.height_m, b.mass_kg, scene.run.gravity_mps2);
}

CylinderResult SimulateCylinder(const Scene& scene, const GroundMotion& motion) {
  return Run(scene, motion).Go();
}

}  // namespace rockbench::reference::cylinder
