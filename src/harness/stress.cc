// The stress catalogue, its runs (one child process per case and engine) and stress.csv.
#include "harness/stress.h"

#include <fnmatch.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <thread>

#include "engines/common/monitor.h"
#include "harness/compare.h"
#include "harness/engine_registry.h"
#include "harness/engines.h"
#include "harness/wall_clock.h"
#include "reference/geometry.h"
#include "reference/kinematics.h"
#include "reference/simulate.h"
#include "reference/transitions.h"
#include "scene/ground_motion.h"
#include "util/subprocess.h"

namespace rockbench {
namespace {

constexpr double kDensity_kgpm3 = 2500.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

BlockDef Block(double width_m, double height_m, double depth_m = 1.0) {
  BlockDef b;
  b.width_m = width_m;
  b.height_m = height_m;
  b.depth_m = depth_m;
  b.density_kgpm3 = kDensity_kgpm3;
  b.mass_kg = kDensity_kgpm3 * width_m * height_m * depth_m;
  return b;
}

Scene BaseScene(double duration_s) {
  Scene s;
  s.run.duration_s = duration_s;
  s.run.output_interval_s = 0.01;
  return s;
}

Scene StackScene(double B1, double H1, double B2, double H2, double duration_s) {
  Scene s = BaseScene(duration_s);
  s.block1 = Block(B1, H1);
  s.block2 = Block(B2, H2);
  return s;
}

Scene SingleScene(double B, double H, double duration_s) {
  Scene s = BaseScene(duration_s);
  s.block1 = Block(B, H);
  return s;
}

// The stack's slenderness angle (rad): its mass centre above block 1's base corner.
double StackThetaC(const Scene& s) {
  return reference::MakeGeometry(s).theta_c;
}

// Released from rest with both blocks tilted by `theta_rad` (the stack leaning as one).
void Release(Scene& s, double theta_rad) {
  s.initial.theta1_rad = theta_rad;
  if (s.two_blocks()) s.initial.theta2_rad = theta_rad;
}

MotionDef Motion(const char* key, MotionKind kind, double amplitude_g, double frequency_hz,
                 double duration_s, double start_s) {
  MotionDef m;
  m.key = key;
  m.kind = kind;
  m.amplitude_g = amplitude_g;
  m.frequency_hz = frequency_hz;
  if (duration_s > 0.0) m.duration_s = duration_s;
  m.start_s = start_s;
  return m;
}

std::string Num(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

StressCase Case(std::string name, std::string description, Scene scene, bool quick) {
  StressCase c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.scene = std::move(scene);
  c.scene.title = c.name;
  c.quick = quick;
  return c;
}

// CSV-safe free text: no commas, no line breaks.
std::string Clean(std::string s) {
  for (char& ch : s) {
    if (ch == ',') ch = ';';
    if (ch == '\n' || ch == '\r' || ch == '"') ch = ' ';
  }
  return s;
}

bool Finite(double v) {
  return std::isfinite(v);
}

bool HistoryHasNonFinite(const History& h) {
  for (const Sample& s : h.samples) {
    if (!Finite(s.t_s) || !Finite(s.theta1_rad) || !Finite(s.theta2_rad) ||
        !Finite(s.omega1_radps) || !Finite(s.omega2_radps)) {
      return true;
    }
  }
  for (const Event& e : h.events) {
    for (double v : {e.t_s, e.omega1_before, e.omega2_before, e.omega1_after, e.omega2_after,
                     e.energy_before_j, e.energy_after_j}) {
      if (!Finite(v)) return true;
    }
  }
  return false;
}

bool IsImpact(const Event& e) {
  return e.kind == "ground_impact" || e.kind == "interface_impact";
}

// Event count, impact count and the smallest time between consecutive impacts.
void CountEvents(const History& h, StressRow* row) {
  row->events = static_cast<int>(h.events.size());
  double last = kNaN;
  for (const Event& e : h.events) {
    if (!IsImpact(e)) continue;
    ++row->impacts;
    if (!std::isnan(last)) {
      const double gap = e.t_s - last;
      if (row->min_event_gap_s < 0.0 || gap < row->min_event_gap_s) row->min_event_gap_s = gap;
    }
    last = e.t_s;
  }
}

// Kinetic energy (base frame) of a state moving in `mode`, J: sum of m v_G^2 / 2 + I_G w^2 / 2,
// computed directly (not as total minus potential energy, which would cancel digits).
double KineticEnergy(const reference::Geometry& geo, Mode mode, reference::State s) {
  if (!geo.two_blocks) {
    s.theta2 = s.theta1;
    s.omega2 = s.omega1;
  }
  const reference::BodyVelocities v = reference::Velocities(geo, mode, s);
  const double m[2] = {geo.block1.m, geo.block2.m};
  const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
  double ke = 0.0;
  for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
    ke += 0.5 * m[b] * reference::Dot(v.vG[b], v.vG[b]) + 0.5 * IG[b] * v.w[b] * v.w[b];
  }
  return ke;
}

// Linear interpolation of a history's angles at t (clamped to its ends).
Sample AnglesAt(const History& h, double t) {
  if (h.samples.empty()) return Sample{};
  auto it = std::lower_bound(h.samples.begin(), h.samples.end(), t,
                             [](const Sample& s, double tt) { return s.t_s < tt; });
  if (it == h.samples.begin()) return h.samples.front();
  if (it == h.samples.end()) return h.samples.back();
  const Sample& b = *it;
  const Sample& a = *(it - 1);
  const double w = b.t_s > a.t_s ? (t - a.t_s) / (b.t_s - a.t_s) : 1.0;
  Sample s = b;
  s.theta1_rad = a.theta1_rad + w * (b.theta1_rad - a.theta1_rad);
  s.theta2_rad = a.theta2_rad + w * (b.theta2_rad - a.theta2_rad);
  return s;
}

// Keeps the largest gain (a NaN, once seen, stays: it must show).
void RecordGain(double gain, StressRow* row) {
  const double cur = row->max_energy_gain_rel;
  if (row->energy_impacts == 0 || (!std::isnan(cur) && (std::isnan(gain) || gain > cur))) {
    row->max_energy_gain_rel = gain;
  }
  ++row->energy_impacts;
}

StressRow RunReference(const StressCase& c, StressRow row) {
  const GroundMotion motion = GroundMotion::FromScene(c.scene);
  const auto start = std::chrono::steady_clock::now();
  const reference::Result r = reference::Simulate(c.scene, motion);
  row.wall_s = SecondsSince(start);
  const reference::Summary& s = r.summary;
  row.status = s.status;
  row.detail = s.status_detail;
  row.finished = true;
  row.peak_theta1_rad = s.peak_theta1_rad;
  row.peak_theta2_rad = s.peak_theta2_rad;
  row.nan =
      HistoryHasNonFinite(r.history) || !Finite(s.peak_theta1_rad) || !Finite(s.peak_theta2_rad);
  CountEvents(r.history, &row);
  // Energy across each impact: the configuration does not jump, so E_after - E_before is the
  // change of kinetic energy, computed directly at the impact's angles (the post-event state of
  // the dense solution) with the rates the event records before and after.
  const reference::Geometry geo = reference::MakeGeometry(c.scene);
  for (const Event& e : r.history.events) {
    if (!IsImpact(e)) continue;
    const Sample at = r.trajectory.At(e.t_s);
    const double ke_before = KineticEnergy(
        geo, e.mode_before, {at.theta1_rad, at.theta2_rad, e.omega1_before, e.omega2_before});
    const double ke_after = KineticEnergy(
        geo, e.mode_after, {at.theta1_rad, at.theta2_rad, e.omega1_after, e.omega2_after});
    if (!(ke_before > 0.0)) continue;
    RecordGain((ke_after - ke_before) / ke_before, &row);
  }
  if (s.impacts_energy_gain > 0) {
    row.detail += (row.detail.empty() ? "" : "; ") + std::to_string(s.impacts_energy_gain) +
                  " impacts flagged ENERGY GAIN by the model";
  }
  return row;
}

// The engines' monitor resolves tilts above MonitorConfig::angle_enter_rad (1e-5 rad); a block
// tilted by a small angle a holds about M g b1 a of potential energy, so impacts with less
// kinetic energy than M g b1 1e-5 are below what the monitor can see and are left out.
const double kEngineResolvedTilt_rad = MonitorConfig{}.angle_enter_rad;

StressRow RunEngineCase(const StressCase& c, const std::string& engine, StressRow row) {
  const GroundMotion motion = GroundMotion::FromScene(c.scene);
  const EngineRun run = RunEngine(engine, c.scene, motion);
  row.wall_s = run.wall_s;
  const RunOutcome& o = run.outcome;
  row.status = o.status.empty() ? "unknown" : o.status;
  row.detail = run.summary.value("status_detail", "");
  row.finished = row.status == "completed" || row.status == "overturned" ||
                 row.status == "at_rest" || row.status == "assumption_violated";
  row.peak_theta1_rad = o.peak_theta1_rad;
  row.peak_theta2_rad = o.peak_theta2_rad;
  row.nan = HistoryHasNonFinite(run.history) || row.detail.find("non-finite") != std::string::npos;
  CountEvents(run.history, &row);
  std::string flags;
  for (const std::string& f : o.violations) flags += (flags.empty() ? "" : ";") + f;
  row.violations = flags.empty() ? "none" : flags;
  // Energy across each impact: the monitor records E = kinetic (base frame) + potential one
  // step before the crossing step and one step after it; the scale is the kinetic energy
  // before, from the recorded rates at the impact's angles (history interpolated).
  const reference::Geometry geo = reference::MakeGeometry(c.scene);
  const double floor_j = geo.M * geo.g * geo.block1.b * kEngineResolvedTilt_rad;
  for (const Event& e : run.history.events) {
    if (!IsImpact(e)) continue;
    const Sample at = AnglesAt(run.history, e.t_s);
    const double ke_before = KineticEnergy(
        geo, e.mode_before, {at.theta1_rad, at.theta2_rad, e.omega1_before, e.omega2_before});
    if (!(ke_before > floor_j)) continue;
    RecordGain((e.energy_after_j - e.energy_before_j) / ke_before, &row);
  }
  // Agreement with the reference on the same scene.
  const reference::Result ref = reference::Simulate(c.scene, motion);
  const EngineAgreement a = CompareWithReference(c.scene, ref, run);
  row.has_agreement = true;
  row.theta1_max_abs_error_rad = a.theta1.max_abs_error_rad;
  row.theta1_peak_rel_error = a.theta1.peak_rel_error;
  if (a.theta2) {
    row.theta2_max_abs_error_rad = a.theta2->max_abs_error_rad;
    row.theta2_peak_rel_error = a.theta2->peak_rel_error;
  }
  row.impacts_matched = a.impacts.matched;
  row.reference_impacts = a.impacts.reference_impacts;
  return row;
}

void SetSettings(const StressCase& c, const std::string& engine, StressRow* row) {
  const Engine* e = FindEngine(engine);
  if (e == nullptr) return;
  row->has_settings = true;
  try {
    row->dt_s = ResolveEngineSettings(c.scene, e->settings_schema()).Number("time_step");
  } catch (const std::exception&) {
    row->dt_s = 0.0;  // the run reports the bad setting
  }
  if (c.setting) {
    for (const auto& [key, value] : c.setting->settings) {
      if (key == "time_step") continue;
      std::string text = SettingText(value);
      std::erase(text, '"');
      row->settings += (row->settings.empty() ? "" : ";") + key + "=" + text;
    }
  }
}

// --- The catalogue -------------------------------------------------------------------------

void AddSlenderness(std::vector<StressCase>& cat) {
  // Free rocking from half the stack's slenderness angle, 5 s: the impact cascade at every
  // slenderness (Housner's e -> 1 for slender blocks: many impacts; e < 0 below H/B = 0.7).
  for (double x : {0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 20.0}) {
    Scene s = StackScene(1.25, 1.25, 1.0, x * 1.0, 5.0);
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("slenderness2/h_over_b=" + Num("%g", x),
                       "block 2 H2/B2 = " + Num("%g", x) +
                           " on the thesis's block 1; free rocking from half the stack's "
                           "slenderness angle",
                       s, x == 0.5 || x == 20.0));
  }
  for (double x : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    Scene s = StackScene(1.25, x * 1.25, 1.0, 2.5, 5.0);
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("slenderness1/h_over_b=" + Num("%g", x),
                       "block 1 H1/B1 = " + Num("%g", x) +
                           " under the thesis's block 2; free rocking from half the stack's "
                           "slenderness angle",
                       s, x == 0.5 || x == 10.0));
  }
}

void AddMassRatio(std::vector<StressCase>& cat) {
  for (double x : {1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 5.0);
    s.block2->density_kgpm3 = 0.0;
    s.block2->mass_kg = x * s.block1.mass_kg;
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("mass_ratio/m2_over_m1=" + Num("%g", x),
                       "thesis geometry with m2/m1 = " + Num("%g", x) +
                           "; free rocking from half the stack's slenderness angle",
                       s, x == 1e-3 || x == 1e3));
  }
}

// The size cases' pulse: one sine cycle of 1 g at 2 Hz (2.8 times the thesis stack's uplift
// acceleration 0.351 g, 4 times the single block's 0.25 g).
constexpr double kSizePulse_g = 1.0;
constexpr double kSizePulse_hz = 2.0;

void AddSize(std::vector<StressCase>& cat) {
  // The thesis's proportions scaled so that block 1 is `b1` wide (depth scaled too).
  for (double b1 : {0.01, 0.1, 1.0, 10.0, 50.0}) {
    const double k = b1 / 1.25;
    Scene s = BaseScene(5.0);
    s.block1 = Block(1.25 * k, 1.25 * k, k);
    s.block2 = Block(1.0 * k, 2.5 * k, k);
    s.horizontal =
        Motion("base.horizontal", MotionKind::kSinePulse, kSizePulse_g, kSizePulse_hz, 0, 0.1);
    cat.push_back(Case("size/stack/b1=" + Num("%g", b1) + "m",
                       "thesis proportions, block 1 " + Num("%g", b1) +
                           " m wide, one sine pulse 1 g 2 Hz: Housner's scale effect",
                       s, b1 == 0.01 || b1 == 50.0));
  }
  // Housner's single block, H/B = 4, B = b.
  for (double b : {0.01, 0.1, 1.0, 10.0, 50.0}) {
    Scene s = BaseScene(5.0);
    s.block1 = Block(b, 4.0 * b, b);
    s.horizontal =
        Motion("base.horizontal", MotionKind::kSinePulse, kSizePulse_g, kSizePulse_hz, 0, 0.1);
    cat.push_back(Case("size/single/b=" + Num("%g", b) + "m",
                       "single block H/B = 4, " + Num("%g", b) +
                           " m wide, one sine pulse 1 g 2 Hz: Housner's scale effect",
                       s, b == 0.1 || b == 50.0));
  }
}

void AddUplift(std::vector<StressCase>& cat) {
  // A rectangular pulse of 0.99 and 1.01 times the threshold from 0.1 s to 1.1 s. The stack
  // cases use the thesis's geometry (the stack opens first: 0.351 g against block 2's 0.4 g);
  // the top cases a slender block 2 (0.25 g) on the same block 1 (the stack opens at 0.50 g).
  struct Geo {
    const char* name;
    UpliftKind kind;
    Scene scene;
  };
  const Geo geos[] = {{"stack", UpliftKind::kStack, StackScene(1.25, 1.25, 1.0, 2.5, 3.0)},
                      {"top", UpliftKind::kTop, StackScene(1.25, 1.25, 0.5, 2.0, 3.0)}};
  for (const Geo& g : geos) {
    // The threshold is in m/s^2 (the scene's gravity); amplitude_g is in standard g.
    const double a_g = UpliftThreshold_mps2(g.scene, g.kind) / kStandardGravity_mps2;
    for (const auto& [label, factor] : {std::pair{"below_1pct", 0.99}, {"above_1pct", 1.01}}) {
      Scene s = g.scene;
      s.horizontal =
          Motion("base.horizontal", MotionKind::kRectangularPulse, factor * a_g, 0.0, 1.0, 0.1);
      cat.push_back(Case(std::string("uplift/") + g.name + "/" + label,
                         Num("%.2f", factor) + " x the " +
                             (g.kind == UpliftKind::kStack ? "stack's" : "block 2's") +
                             " uplift acceleration " + Num("%.6f", a_g) +
                             " g (bisection on the reference's contact rule) for 1 s",
                         s, true));
    }
  }
  // Strong pulses up to 5 g on the thesis's geometry.
  for (double a : {1.0, 2.0, 5.0}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
    s.horizontal = Motion("base.horizontal", MotionKind::kSinePulse, a, 5.0, 0, 0.1);
    cat.push_back(Case("accel/sine_pulse/a=" + Num("%g", a) + "g",
                       "thesis geometry, one sine pulse of " + Num("%g", a) + " g at 5 Hz", s,
                       a == 5.0));
  }
  // Harmonic excitation from 0.5 to 50 Hz at 1.5 times the stack's uplift acceleration.
  const Scene thesis = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
  const double a_stack_g = UpliftThreshold_mps2(thesis, UpliftKind::kStack) / kStandardGravity_mps2;
  for (double f : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0}) {
    Scene s = thesis;
    s.horizontal = Motion("base.horizontal", MotionKind::kHarmonic, 1.5 * a_stack_g, f, 3.0, 0.0);
    cat.push_back(Case("harmonic/f=" + Num("%g", f) + "Hz",
                       "thesis geometry, harmonic 1.5 x the stack's uplift acceleration at " +
                           Num("%g", f) + " Hz for 3 s",
                       s, f == 50.0));
  }
}

void AddRelease(std::vector<StressCase>& cat) {
  for (const auto& [label, factor] : {std::pair{"inside_1pct", 0.99}, {"outside_1pct", 1.01}}) {
    Scene s = SingleScene(1.0, 4.0, 4.0);
    Release(s, factor * StackThetaC(s));
    cat.push_back(
        Case(std::string("release/single/") + label,
             "Housner block B = 1 m H = 4 m released from " + Num("%.2f", factor) + " x theta_c", s,
             true));
  }
  for (const auto& [label, factor] : {std::pair{"inside_1pct", 0.99}, {"outside_1pct", 1.01}}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 4.0);
    Release(s, factor * StackThetaC(s));
    cat.push_back(Case(std::string("release/stack/") + label,
                       "thesis stack released leaning as one from " + Num("%.2f", factor) +
                           " x the stack's slenderness angle",
                       s, true));
  }
}

void AddCascade(std::vector<StressCase>& cat) {
  {
    // At rest after 90 impacts at 11.23 s.
    Scene s = SingleScene(1.0, 4.0, 12.0);
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("cascade/single/until_rest",
                       "Housner block B = 1 m H = 4 m from theta_c / 2 until it comes to rest", s,
                       true));
  }
  {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 20.0);
    Release(s, 0.15);
    cat.push_back(Case("cascade/stack/until_rest",
                       "the thesis's free-rocking example (6.3.1) for 20 s, until rest", s, false));
  }
  {
    // The stack settles from 0.15 rad at 4.97 s (cascade/stack/until_rest); the pulse at 6 s
    // then restarts it from rest.
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 12.0);
    Release(s, 0.15);
    s.horizontal = Motion("base.horizontal", MotionKind::kSinePulse, 0.6, 2.0, 0, 6.0);
    cat.push_back(Case("restart/stack/pulse_after_rest",
                       "the thesis's free rocking until rest, then a 0.6 g 2 Hz sine pulse at "
                       "6 s restarts the stack",
                       s, true));
  }
}

void AddVertical(std::vector<StressCase>& cat) {
  // At rest: a downward vertical pulse from 0.2 s to 0.7 s (nothing else).
  for (double a : {-0.9, -0.99, -1.01, -1.5}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 2.0);
    s.vertical = Motion("base.vertical", MotionKind::kRectangularPulse, a, 0.0, 0.5, 0.2);
    cat.push_back(
        Case("vertical/at_rest/yg=" + Num("%g", a) + "g",
             "thesis stack at rest, vertical base acceleration " + Num("%g", a) + " g for 0.5 s", s,
             a == -0.99 || a == -1.01));
  }
  // Rocking: the thesis's free rocking with a downward pulse from 0.2 s to 0.5 s.
  for (double a : {-0.5, -1.01}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 2.0);
    Release(s, 0.15);
    s.vertical = Motion("base.vertical", MotionKind::kRectangularPulse, a, 0.0, 0.3, 0.2);
    cat.push_back(
        Case("vertical/rocking/yg=" + Num("%g", a) + "g",
             "thesis free rocking, vertical base acceleration " + Num("%g", a) + " g for 0.3 s", s,
             false));
  }
}

// Every engine's settings cases (Engine::StressGrid) on the thesis's free rocking, 3 s.
void AddEngineSettings(std::vector<StressCase>& cat) {
  for (const std::string& name : BuiltEngineNames()) {
    const Engine* engine = FindEngine(name);
    for (const SweepSetting& st : engine->StressGrid()) {
      Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
      Release(s, 0.15);
      for (const auto& [key, value] : st.settings) SetEngineSetting(s, name, key, value);
      StressCase c = Case(name + "_dt/" + st.id,
                          st.family + ", dt " + st.label + " s, on the thesis's free rocking (3 s)",
                          s, st.quick);
      c.engines = {name};
      c.setting = st;
      c.wall_limit_s = st.time_step_s < 5e-5 ? 300.0 : 60.0;
      cat.push_back(std::move(c));
    }
  }
}

}  // namespace

double UpliftThreshold_mps2(const Scene& scene, UpliftKind kind) {
  if (kind == UpliftKind::kTop && !scene.two_blocks()) {
    throw SceneError("uplift threshold of block 2 on block 1: the scene has one block");
  }
  const reference::Geometry geo = reference::MakeGeometry(scene);
  // Smaller corner force of the face in question at rest under a constant xg'' = a (N).
  auto corner = [&](double a) {
    const reference::ContactMargins m = reference::EvaluateContacts(
        geo, Mode::kRest, reference::State{}, a, 0.0, scene.model.equations);
    const reference::Reactions& r = m.reactions;
    return kind == UpliftKind::kStack ? std::min(r.ground_left, r.ground_right)
                                      : std::min(r.interface_left, r.interface_right);
  };
  double lo = 0.0, hi = geo.g;
  if (!(corner(lo) > 0.0)) throw SceneError("uplift threshold: the face is open at rest");
  while (corner(hi) >= 0.0) {
    hi *= 2.0;
    if (hi > 1e6 * geo.g) throw SceneError("uplift threshold: no opening below 1e6 g");
  }
  while (hi - lo > 1e-13 * hi) {
    const double mid = 0.5 * (lo + hi);
    (corner(mid) >= 0.0 ? lo : hi) = mid;
  }
  return hi;
}

Scene ThesisStackScene() {
  return StackScene(1.25, 1.25, 1.0, 2.5, 5.0);
}

std::vector<StressCase> StressCatalogue() {
  std::vector<StressCase> cat;
  AddSlenderness(cat);
  AddMassRatio(cat);
  AddSize(cat);
  AddUplift(cat);
  AddRelease(cat);
  AddCascade(cat);
  AddVertical(cat);
  AddEngineSettings(cat);
  for (StressCase& c : cat) {
    if (!c.engines.empty()) continue;
    c.engines = {"reference"};
    for (const std::string& name : BuiltEngineNames()) c.engines.push_back(name);
  }
  // Hidden self-tests of the isolation.
  StressCase crash = Case("selftest/crash", "the child kills itself with SIGSEGV", Scene{}, false);
  crash.scene = SingleScene(1.0, 4.0, 1.0);
  crash.engines = {"reference"};
  crash.hidden = true;
  crash.self_test = StressSelfTest::kCrash;
  crash.wall_limit_s = 30.0;
  cat.push_back(crash);
  StressCase hang = crash;
  hang.name = "selftest/hang";
  hang.description = "the child sleeps forever (wall limit 1 s)";
  hang.self_test = StressSelfTest::kHang;
  hang.wall_limit_s = 1.0;
  cat.push_back(hang);
  return cat;
}

std::vector<StressCase> SelectStressCases(const std::vector<StressCase>& catalogue,
                                          const std::vector<std::string>& patterns, bool quick) {
  auto matches = [](const std::string& pattern, const StressCase& c) {
    if (c.hidden && pattern.rfind("selftest", 0) != 0) return false;
    return c.name.rfind(pattern, 0) == 0 || ::fnmatch(pattern.c_str(), c.name.c_str(), 0) == 0;
  };
  for (const std::string& p : patterns) {
    if (std::none_of(catalogue.begin(), catalogue.end(),
                     [&](const StressCase& c) { return matches(p, c); })) {
      throw SceneError("--case '" + p +
                       "': selects no case (a name prefix or a glob; see rockbench stress --list)");
    }
  }
  std::vector<StressCase> out;
  for (const StressCase& c : catalogue) {
    bool take = patterns.empty() ? !c.hidden : false;
    for (const std::string& p : patterns) take = take || matches(p, c);
    if (take && quick && !c.quick && !c.hidden) take = false;
    if (take) out.push_back(c);
  }
  return out;
}

StressRow RunStressCaseHere(const StressCase& c, const std::string& engine) {
  StressRow row;
  row.case_name = c.name;
  row.engine = engine;
  SetSettings(c, engine, &row);
  if (c.self_test == StressSelfTest::kCrash) {
    // No core file for a deliberate crash, and the default action (a sanitizer's handler
    // would turn the signal into an exit status).
    const rlimit none{0, 0};
    ::setrlimit(RLIMIT_CORE, &none);
    std::fflush(nullptr);
    std::signal(SIGSEGV, SIG_DFL);
    std::raise(SIGSEGV);
  }
  if (c.self_test == StressSelfTest::kHang) {
    while (true) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  try {
    if (engine == "reference") return RunReference(c, row);
    return RunEngineCase(c, engine, row);
  } catch (const std::exception& e) {
    row.finished = false;
    row.status = "error";
    row.detail = e.what();
    return row;
  }
}

nlohmann::json StressRowToJson(const StressRow& r) {
  // Non-finite numbers become null (JSON has no NaN) and come back as NaN.
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json j;
  j["case"] = r.case_name;
  j["engine"] = r.engine;
  j["finished"] = r.finished;
  j["status"] = r.status;
  j["detail"] = r.detail;
  j["nan"] = r.nan;
  j["max_energy_gain_rel"] = num(r.max_energy_gain_rel);
  j["energy_impacts"] = r.energy_impacts;
  j["events"] = r.events;
  j["impacts"] = r.impacts;
  j["min_event_gap_s"] = num(r.min_event_gap_s);
  j["wall_s"] = num(r.wall_s);
  j["peak_theta1_rad"] = num(r.peak_theta1_rad);
  j["peak_theta2_rad"] = num(r.peak_theta2_rad);
  j["has_settings"] = r.has_settings;
  j["dt_s"] = r.dt_s;
  j["settings"] = r.settings;
  j["violations"] = r.violations;
  j["has_agreement"] = r.has_agreement;
  j["theta1_max_abs_error_rad"] = num(r.theta1_max_abs_error_rad);
  j["theta1_peak_rel_error"] = num(r.theta1_peak_rel_error);
  j["theta2_max_abs_error_rad"] = num(r.theta2_max_abs_error_rad);
  j["theta2_peak_rel_error"] = num(r.theta2_peak_rel_error);
  j["impacts_matched"] = r.impacts_matched;
  j["reference_impacts"] = r.reference_impacts;
  return j;
}

StressRow StressRowFromJson(const nlohmann::json& j) {
  auto num = [&](const char* key) {
    const nlohmann::json& v = j.at(key);
    return v.is_null() ? kNaN : v.get<double>();
  };
  StressRow r;
  r.case_name = j.at("case").get<std::string>();
  r.engine = j.at("engine").get<std::string>();
  r.finished = j.at("finished").get<bool>();
  r.status = j.at("status").get<std::string>();
  r.detail = j.at("detail").get<std::string>();
  r.nan = j.at("nan").get<bool>();
  r.max_energy_gain_rel = num("max_energy_gain_rel");
  r.energy_impacts = j.at("energy_impacts").get<int>();
  r.events = j.at("events").get<int>();
  r.impacts = j.at("impacts").get<int>();
  r.min_event_gap_s = num("min_event_gap_s");
  r.wall_s = num("wall_s");
  r.peak_theta1_rad = num("peak_theta1_rad");
  r.peak_theta2_rad = num("peak_theta2_rad");
  r.has_settings = j.at("has_settings").get<bool>();
  r.dt_s = j.at("dt_s").get<double>();
  r.settings = j.at("settings").get<std::string>();
  r.violations = j.at("violations").get<std::string>();
  r.has_agreement = j.at("has_agreement").get<bool>();
  r.theta1_max_abs_error_rad = num("theta1_max_abs_error_rad");
  r.theta1_peak_rel_error = num("theta1_peak_rel_error");
  r.theta2_max_abs_error_rad = num("theta2_max_abs_error_rad");
  r.theta2_peak_rel_error = num("theta2_peak_rel_error");
  r.impacts_matched = j.at("impacts_matched").get<int>();
  r.reference_impacts = j.at("reference_impacts").get<int>();
  return r;
}

namespace {

// The row of a child that ended without printing one (crash, wall limit, error exit).
StressRow ChildRow(const StressCase& c, const std::string& engine, const ProcessResult& p) {
  StressRow row;
  row.case_name = c.name;
  row.engine = engine;
  SetSettings(c, engine, &row);
  row.wall_s = p.wall_s;
  if (!p.started) {
    row.status = "error";
    row.detail = "cannot start the child: " + p.start_error;
    return row;
  }
  if (p.timed_out) {
    row.status = "wall_limit";
    row.detail = "killed after the case's wall-clock limit of " + Num("%g", c.wall_limit_s) + " s";
    return row;
  }
  if (p.signal != 0) {
    row.status = "crash (signal " + std::to_string(p.signal) + ")";
    row.detail = std::string("the child died of ") + strsignal(p.signal);
    return row;
  }
  // The last non-empty line of stdout is the row.
  std::string line;
  const size_t end = p.out.find_last_not_of("\n\r ");
  if (end != std::string::npos) {
    const size_t nl = p.out.find_last_of('\n', end);
    const size_t begin = nl == std::string::npos ? 0 : nl + 1;
    line = p.out.substr(begin, end + 1 - begin);
  }
  if (p.exit_code == 0 && !line.empty()) {
    try {
      StressRow r = StressRowFromJson(nlohmann::json::parse(line));
      if (r.case_name == c.name && r.engine == engine) return r;
    } catch (const std::exception&) {
    }
  }
  row.status = "error (exit " + std::to_string(p.exit_code) + ")";
  std::string err = p.err;
  while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
  const size_t nl = err.find_last_of('\n');
  row.detail =
      "no row from the child" +
      (err.empty() ? std::string() : ": " + err.substr(nl == std::string::npos ? 0 : nl + 1));
  return row;
}

}  // namespace

std::vector<StressRow> RunStress(const std::vector<StressCase>& cases,
                                 const StressRunOptions& options, const StressProgress& progress) {
  if (options.jobs < 0) throw SceneError("--jobs: expected 1 or more");
  const std::filesystem::path exe =
      options.executable.empty() ? SelfExecutable() : options.executable;
  struct Task {
    const StressCase* c;
    std::string engine;
  };
  std::vector<Task> tasks;
  for (const StressCase& c : cases) {
    for (const std::string& e : c.engines) tasks.push_back({&c, e});
  }
  std::vector<StressRow> rows(tasks.size());
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::mutex mu;
  int done = 0;
  auto worker = [&] {
    while (true) {
      const size_t k = next++;
      if (k >= tasks.size()) return;
      const Task& t = tasks[k];
      ProcessOptions po;
      po.timeout_s = t.c->wall_limit_s;
      const ProcessResult p =
          RunProcess({exe.string(), "stress", "--run-case", t.c->name, "--engine", t.engine}, po);
      rows[k] = ChildRow(*t.c, t.engine, p);
      std::lock_guard<std::mutex> lock(mu);
      ++done;
      if (progress) progress(done, static_cast<int>(tasks.size()), rows[k]);
    }
  };
  std::vector<std::thread> pool;
  const int n = std::min<int>(jobs, static_cast<int>(std::max<size_t>(1, tasks.size())));
  for (int i = 0; i < n; ++i) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  return rows;
}

std::string StressCsv(const std::vector<StressRow>& rows) {
  std::string out =
      "case,engine,finished,status,nan,max_energy_gain_rel,energy_impacts,events,impacts,"
      "min_event_gap_s,wall_s,peak_theta1_rad,peak_theta2_rad,dt_s,settings,"
      "violations,theta1_max_abs_error_rad,theta1_peak_rel_error,theta2_max_abs_error_rad,"
      "theta2_peak_rel_error,impacts_matched,reference_impacts,detail\n";
  auto g = [](double v) { return Num("%.6g", v); };
  for (const StressRow& r : rows) {
    const bool ran = r.finished || r.status == "blow_up" || r.status == "error";
    out += Clean(r.case_name) + "," + r.engine + "," + (r.finished ? "1" : "0") + "," +
           Clean(r.status) + "," + (r.nan ? "1" : "0") + ",";
    out += (r.energy_impacts > 0 ? Num("%.3e", r.max_energy_gain_rel) : "") + "," +
           std::to_string(r.energy_impacts) + ",";
    out += std::to_string(r.events) + "," + std::to_string(r.impacts) + ",";
    out += (r.min_event_gap_s >= 0.0 ? Num("%.6e", r.min_event_gap_s) : "") + ",";
    out += Num("%.4f", r.wall_s) + ",";
    out += (ran ? g(r.peak_theta1_rad) : "") + "," + (ran ? g(r.peak_theta2_rad) : "") + ",";
    out +=
        (r.has_settings ? Num("%.6g", r.dt_s) + "," + Clean(r.settings) + "," + Clean(r.violations)
                        : ",,") +
        ",";
    if (r.has_agreement) {
      out += g(r.theta1_max_abs_error_rad) + "," + g(r.theta1_peak_rel_error) + "," +
             g(r.theta2_max_abs_error_rad) + "," + g(r.theta2_peak_rel_error) + "," +
             std::to_string(r.impacts_matched) + "," + std::to_string(r.reference_impacts);
    } else {
      out += ",,,,,";
    }
    out += "," + Clean(r.detail) + "\n";
  }
  return out;
}

}  // namespace rockbench
