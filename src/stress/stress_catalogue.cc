// The stress catalogue: the named cases (scenes, motions, wall-clock limits) in their fixed
// order, and their selection by name.
#include <fnmatch.h>

#include <cmath>
#include <numbers>

#include "motion/ground_motion.h"
#include "reference/catalogue.h"
#include "run/engine_registry.h"
#include "run/reference_engine.h"
#include "stress/stress.h"
#include "util/format.h"

namespace rockbench {
namespace {

constexpr double kDensity_kgpm3 = 2500.0;

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
  s.blocks = {Block(B1, H1), Block(B2, H2)};
  return s;
}

Scene SingleScene(double B, double H, double duration_s) {
  Scene s = BaseScene(duration_s);
  s.blocks = {Block(B, H)};
  return s;
}

// The stack's slenderness angle (rad): its mass centre above block 1's base corner.
double StackThetaC(const Scene& s) {
  return reference::CriticalAngle_rad(s);
}

// Released from rest with both blocks tilted by `theta_rad` (the stack leaning as one).
void Release(Scene& s, double theta_rad) {
  for (int k = 0; k < s.block_count(); ++k) s.initial.theta_rad[k] = theta_rad;
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

StressCase Case(std::string name, std::string description, Scene scene, bool quick) {
  StressCase c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.scene = std::move(scene);
  c.scene.title = c.name;
  c.quick = quick;
  return c;
}

// --- The catalogue -------------------------------------------------------------------------

void AddSlenderness(std::vector<StressCase>& cat) {
  // Free rocking from half the stack's slenderness angle, 5 s: the impact cascade at every
  // slenderness (Housner's e -> 1 for slender blocks: many impacts; e < 0 below H/B = 0.7).
  for (double x : {0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 20.0}) {
    Scene s = StackScene(1.25, 1.25, 1.0, x * 1.0, 5.0);
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("slenderness2/h_over_b=" + Format("%g", x),
                       "block 2 H2/B2 = " + Format("%g", x) +
                           " on the thesis's block 1; free rocking from half the stack's "
                           "slenderness angle",
                       s, x == 0.5 || x == 20.0));
  }
  for (double x : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    Scene s = StackScene(1.25, x * 1.25, 1.0, 2.5, 5.0);
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("slenderness1/h_over_b=" + Format("%g", x),
                       "block 1 H1/B1 = " + Format("%g", x) +
                           " under the thesis's block 2; free rocking from half the stack's "
                           "slenderness angle",
                       s, x == 0.5 || x == 10.0));
  }
}

void AddMassRatio(std::vector<StressCase>& cat) {
  for (double x : {1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 5.0);
    s.blocks[1].density_kgpm3 = 0.0;
    s.blocks[1].mass_kg = x * s.blocks[0].mass_kg;
    Release(s, 0.5 * StackThetaC(s));
    cat.push_back(Case("mass_ratio/m2_over_m1=" + Format("%g", x),
                       "thesis geometry with m2/m1 = " + Format("%g", x) +
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
    s.blocks = {Block(1.25 * k, 1.25 * k, k), Block(1.0 * k, 2.5 * k, k)};
    s.horizontal =
        Motion("base.horizontal", MotionKind::kSinePulse, kSizePulse_g, kSizePulse_hz, 0, 0.1);
    cat.push_back(Case("size/stack/b1=" + Format("%g", b1) + "m",
                       "thesis proportions, block 1 " + Format("%g", b1) +
                           " m wide, one sine pulse 1 g 2 Hz: Housner's scale effect",
                       s, b1 == 0.01 || b1 == 50.0));
  }
  // Housner's single block, H/B = 4, B = b.
  for (double b : {0.01, 0.1, 1.0, 10.0, 50.0}) {
    Scene s = BaseScene(5.0);
    s.blocks = {Block(b, 4.0 * b, b)};
    s.horizontal =
        Motion("base.horizontal", MotionKind::kSinePulse, kSizePulse_g, kSizePulse_hz, 0, 0.1);
    cat.push_back(Case("size/single/b=" + Format("%g", b) + "m",
                       "single block H/B = 4, " + Format("%g", b) +
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
                         Format("%.2f", factor) + " x the " +
                             (g.kind == UpliftKind::kStack ? "stack's" : "block 2's") +
                             " uplift acceleration " + Format("%.6f", a_g) +
                             " g (bisection on the reference's contact rule) for 1 s",
                         s, true));
    }
  }
  // Strong pulses up to 5 g on the thesis's geometry.
  for (double a : {1.0, 2.0, 5.0}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
    s.horizontal = Motion("base.horizontal", MotionKind::kSinePulse, a, 5.0, 0, 0.1);
    cat.push_back(Case("accel/sine_pulse/a=" + Format("%g", a) + "g",
                       "thesis geometry, one sine pulse of " + Format("%g", a) + " g at 5 Hz", s,
                       a == 5.0));
  }
  // Harmonic excitation from 0.5 to 50 Hz at 1.5 times the stack's uplift acceleration.
  const Scene thesis = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
  const double a_stack_g = UpliftThreshold_mps2(thesis, UpliftKind::kStack) / kStandardGravity_mps2;
  for (double f : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0}) {
    Scene s = thesis;
    s.horizontal = Motion("base.horizontal", MotionKind::kHarmonic, 1.5 * a_stack_g, f, 3.0, 0.0);
    cat.push_back(Case("harmonic/f=" + Format("%g", f) + "Hz",
                       "thesis geometry, harmonic 1.5 x the stack's uplift acceleration at " +
                           Format("%g", f) + " Hz for 3 s",
                       s, f == 50.0));
  }
}

void AddRelease(std::vector<StressCase>& cat) {
  for (const auto& [label, factor] : {std::pair{"inside_1pct", 0.99}, {"outside_1pct", 1.01}}) {
    Scene s = SingleScene(1.0, 4.0, 4.0);
    Release(s, factor * StackThetaC(s));
    cat.push_back(
        Case(std::string("release/single/") + label,
             "Housner block B = 1 m H = 4 m released from " + Format("%.2f", factor) + " x theta_c",
             s, true));
  }
  for (const auto& [label, factor] : {std::pair{"inside_1pct", 0.99}, {"outside_1pct", 1.01}}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 4.0);
    Release(s, factor * StackThetaC(s));
    cat.push_back(Case(std::string("release/stack/") + label,
                       "thesis stack released leaning as one from " + Format("%.2f", factor) +
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
        Case("vertical/at_rest/yg=" + Format("%g", a) + "g",
             "thesis stack at rest, vertical base acceleration " + Format("%g", a) + " g for 0.5 s",
             s, a == -0.99 || a == -1.01));
  }
  // Rocking: the thesis's free rocking with a downward pulse from 0.2 s to 0.5 s.
  for (double a : {-0.5, -1.01}) {
    Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 2.0);
    Release(s, 0.15);
    s.vertical = Motion("base.vertical", MotionKind::kRectangularPulse, a, 0.0, 0.3, 0.2);
    cat.push_back(
        Case("vertical/rocking/yg=" + Format("%g", a) + "g",
             "thesis free rocking, vertical base acceleration " + Format("%g", a) + " g for 0.3 s",
             s, false));
  }
}

// Every engine's settings cases (Engine::StressGrid) on the thesis's free rocking, 3 s.
void AddEngineSettings(std::vector<StressCase>& cat) {
  for (const std::string& name : BuiltEngineNames()) {
    const Engine* engine = FindEngine(name);
    for (const SweepSetting& st : engine->StressGrid()) {
      Scene s = StackScene(1.25, 1.25, 1.0, 2.5, 3.0);
      Release(s, 0.15);
      s = engine->SceneForSetting(s, st);
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
  if (kind == UpliftKind::kTop && scene.block_count() != 2) {
    throw SceneError("uplift threshold of block 2 on block 1: the scene has one block");
  }
  // Smaller corner force of the face in question at rest under a constant xg'' = a (N).
  const reference::RestFace face =
      kind == UpliftKind::kStack ? reference::RestFace::kGround : reference::RestFace::kInterface;
  auto corner = [&](double a) { return reference::RestCornerForce_N(scene, face, a); };
  const double g = scene.run.gravity_mps2;
  double lo = 0.0, hi = g;
  if (!(corner(lo) > 0.0)) throw SceneError("uplift threshold: the face is open at rest");
  while (corner(hi) >= 0.0) {
    hi *= 2.0;
    if (hi > 1e6 * g) throw SceneError("uplift threshold: no opening below 1e6 g");
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
    c.engines = {TheReference().name()};
    for (const std::string& name : BuiltEngineNames()) c.engines.push_back(name);
  }
  // Hidden self-tests of the isolation.
  StressCase crash = Case("selftest/crash", "the child kills itself with SIGSEGV", Scene{}, false);
  crash.scene = SingleScene(1.0, 4.0, 1.0);
  crash.engines = {TheReference().name()};
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

}  // namespace rockbench
