// The unilateral model (reference/unilateral.h, unilateral_run.h; issue 24): sliding, lift-off
// and their transitions against closed forms, the complementarity solver's statements, energy,
// and the pivot chain where both models hold.
#include "reference/unilateral/unilateral.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "common/rectangular_pulse.h"
#include "motion/ground_motion.h"
#include "reference/benchmarks/sliding_forms.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace rockbench::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kG = kStandardGravity_mps2;

// One block of width B, height H and 1000 kg, friction mu, on a base with the given horizontal
// rectangular pulse (amplitude a_g in g, from t0 for pulse_s).
Scene BlockUnderPulse(double B, double H, double mu, double a_g, double t0, double pulse_s,
                      double duration_s) {
  Scene s;
  BlockDef b;
  b.width_m = B;
  b.height_m = H;
  b.mass_kg = 1000.0;
  b.friction = mu;
  s.blocks = {b};
  s.run.duration_s = duration_s;
  s.run.gravity_mps2 = kG;
  s.compare.members = 0;
  s.horizontal = RectangularPulseDef(a_g, pulse_s, t0);
  return s;
}

bool HasNote(const History& h, const std::string& text) {
  for (const Event& e : h.events) {
    if (e.note.find(text) != std::string::npos) return true;
  }
  return false;
}

// From rest under a step of acceleration a (a rectangular pulse): nothing below min(mu, B/H) g;
// above it the block slides when mu < B/H (a > mu g) and rocks when B/H < mu (a > (B/H) g)
// (thesis ch. 3 after Shenton 1996: at the onset of sliding the corner forces stay compressive
// exactly when mu < b/h; at the onset of rocking the pivot needs a friction coefficient a/g =
// b/h). Checked 1% each side of the threshold over a grid of slenderness and friction.
TEST(UnilateralRun, SlideOrRockFromRestFollowsTheClosedCriteria) {
  const double t0 = 0.1;
  for (const double ratio : {0.25, 0.5, 1.0, 2.0}) {  // B/H
    for (const double mu : {0.1, 0.3, 0.6, 1.2}) {
      const double threshold_g = std::min(mu, ratio);
      for (const double f : {0.99, 1.01}) {
        const Scene s = BlockUnderPulse(ratio, 1.0, mu, f * threshold_g, t0, 0.05, 0.2);
        const Result r = Simulate(s, GroundMotion::FromScene(s));
        const Summary& sum = r.summary;
        SCOPED_TRACE("B/H " + std::to_string(ratio) + " mu " + std::to_string(mu) + " a/g " +
                     std::to_string(f * threshold_g));
        if (f < 1.0) {
          EXPECT_FALSE(sum.unilateral_from_s.has_value());
          EXPECT_EQ(sum.initiations, 0);
          EXPECT_EQ(sum.peak_theta_rad[0], 0.0);
          continue;
        }
        if (mu < ratio) {
          // Slides at the pulse's start, on its face.
          ASSERT_TRUE(sum.unilateral_from_s.has_value());
          EXPECT_NEAR(*sum.unilateral_from_s, t0, 1e-12);
          EXPECT_TRUE(HasNote(r.history, "block 1 sticks on its face -> slips left on its face"));
          EXPECT_EQ(sum.initiations, 0);
        } else {
          // Rocks (the chain's initiation at the pulse's start) and does not slide then.
          EXPECT_EQ(sum.initiations, 1);
          ASSERT_FALSE(r.history.events.empty());
          EXPECT_EQ(r.history.events[0].kind, "initiation");
          EXPECT_NEAR(r.history.events[0].t_s, t0, 1e-12);
          EXPECT_TRUE(!sum.unilateral_from_s || *sum.unilateral_from_s > t0);
        }
      }
    }
  }
}

// Newmark's sliding block: a squat block (B/H = 2 > mu) under a rectangular pulse slides and
// sticks again when and where the rigid-plastic closed form says. The stick time is an event
// located to 1e-12 sqrt(R/g); the slip is integrated by dopri5 at rtol 1e-12: measured 2.0e-10
// relative (2.0e-11 at rtol 1e-13 and with dop853: the integration's error, converging), so
// 1e-9. Friction's work is mu m g |u| (one direction of slip; Simpson's rule per step, exact
// for the piecewise-linear slip rate: the same 1e-9).
TEST(UnilateralRun, NewmarkSlidingBlockUnderAPulse) {
  const double mu = 0.2, a_g = 0.5, t0 = 0.1, pulse = 0.4;
  const Scene s = BlockUnderPulse(2.0, 1.0, mu, a_g, t0, pulse, 2.0);
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  const benchmarks::SlidingPulse cf = benchmarks::SlidingBlockUnderPulse(a_g * kG, pulse, mu, kG);
  double stick_t = -1.0, episode_j = -1.0;
  for (const Event& e : r.history.events) {
    if (e.note.find("slip stops") == std::string::npos) continue;
    stick_t = e.t_s;
    // The episode's energy audit: what friction dissipated while the block slipped.
    const size_t at = e.note.find("slip dissipated ");
    if (at != std::string::npos) episode_j = std::stod(e.note.substr(at + 16));
  }
  EXPECT_NEAR(stick_t - t0, cf.stick_t_s, 1e-9);
  ASSERT_TRUE(r.history.slip_and_lift);
  const Sample& last = r.history.samples.back();
  EXPECT_NEAR(last.u_m[0], cf.slip_m, 1e-9 * std::abs(cf.slip_m));
  EXPECT_EQ(last.z_m[0], 0.0);
  EXPECT_EQ(r.summary.status, RunStatus::kAtRest);
  EXPECT_NEAR(r.summary.friction_work_j, mu * 1000.0 * kG * std::abs(cf.slip_m),
              1e-9 * mu * 1000.0 * kG * std::abs(cf.slip_m));
  // One episode: its audit (printed to 6 digits) is the whole work.
  EXPECT_NEAR(episode_j, r.summary.friction_work_j, 1e-5 * r.summary.friction_work_j);
  // The peak slip rate, at the pulse's end: the slope of u there (u is quadratic on each side,
  // so the centred difference over +-1 ms carries an error of the rate's jump in slope times
  // 1e-3 / 2 = 4.9e-3 m/s at most; one-sided differences of 1e-6 s: 5e-6 m/s).
  const double h = 1e-6;
  const double rate =
      (r.trajectory.At(t0 + pulse).u_m[0] - r.trajectory.At(t0 + pulse - h).u_m[0]) / h;
  EXPECT_NEAR(rate, cf.peak_slip_rate_mps, 1e-5);
}

// Lift-off under a vertical sine of amplitude (1 + eps) g: the block leaves the base at the
// first instant the base falls faster than gravity, flies, and lands at the closed form's time
// (both corners at once: the plastic impact stops it). Times are events located to
// 1e-12 sqrt(R/g) on a flight integrated at rtol 1e-12: 1e-9 s.
TEST(UnilateralRun, LiftOffUnderAVerticalSine) {
  const double eps = 0.2, f_hz = 2.0;
  Scene s;
  BlockDef b;
  b.width_m = 1.0;
  b.height_m = 1.0;
  b.mass_kg = 1000.0;
  s.blocks = {b};
  s.run.duration_s = 0.45;
  s.run.gravity_mps2 = kG;
  s.compare.members = 0;
  MotionDef d;
  d.key = "base.vertical";
  d.kind = MotionKind::kHarmonic;
  d.amplitude_g = 1.0 + eps;
  d.scale = -1.0;
  d.frequency_hz = f_hz;
  s.vertical = d;
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  const benchmarks::LiftOff cf = benchmarks::LiftOffUnderVerticalSine(eps, 2 * M_PI * f_hz, kG);
  ASSERT_TRUE(r.summary.unilateral_from_s.has_value());
  EXPECT_NEAR(*r.summary.unilateral_from_s, cf.off_t_s, 1e-9);
  double land_t = -1.0;
  for (const Event& e : r.history.events) {
    if (e.kind == "ground_impact" && land_t < 0.0) land_t = e.t_s;
  }
  EXPECT_NEAR(land_t, cf.land_t_s, 1e-9);
  // The height in flight: z1 along the trajectory against the closed form.
  for (int i = 1; i < 10; ++i) {
    const double t = cf.off_t_s + (cf.land_t_s - cf.off_t_s) * i / 10.0;
    EXPECT_NEAR(r.trajectory.At(t).z_m[0], benchmarks::FlightHeight_m(t, eps, 2 * M_PI * f_hz, kG),
                1e-10)
        << t;
  }
  EXPECT_EQ(r.summary.lift_offs, 1);
  EXPECT_EQ(r.summary.impacts_energy_gain, 0);
}

// Where both hold (infinite friction, no lift-off), the unilateral model in maximal
// coordinates from t = 0 (model.formulation = "unilateral") follows the pivot chain: the same
// events, and angles that differ by the two integrations' errors (rtol 1e-12 on different
// coordinates, impacts located to 1e-12 sqrt(R/g) on each). Measured on these scenes over their
// whole runs: 3.2e-9 rad (Housner, 4 impacts), 9e-10 (the thesis's free rocking, 600 impacts
// to rest), 5.3e-9 (harmonic, 730 impacts), 5.5e-8 (Rinaldi 228 to block 2's overturn); 1e-6
// rad leaves a factor 20.
TEST(UnilateralRun, InfiniteFrictionFollowsTheChain) {
  for (const char* name :
       {"housner_free_rocking", "thesis_free_rocking", "harmonic", "thesis_rinaldi228"}) {
    SCOPED_TRACE(name);
    Scene chain = LoadScene(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/" + name + ".toml");
    chain.compare.members = 0;
    Scene uni = chain;
    uni.model.formulation = Formulation::kUnilateral;
    const GroundMotion gm = GroundMotion::FromScene(chain);
    const Result a = Simulate(chain, gm), b = Simulate(uni, gm);
    EXPECT_EQ(a.summary.status, b.summary.status);
    // The cascades to rest end by the same rest rule (the chain's on relative rates,
    // rest_rate_rel sqrt(g / R_k); the unilateral model's on the separation speed that rate
    // gives, UnilateralStack::RestSpeed), but the last impacts, at rates of 1e-7 rad/s, come
    // from two integrations and differ by a few (5% bounds them).
    EXPECT_NEAR(a.summary.impacts(), b.summary.impacts(), 0.05 * a.summary.impacts() + 0.5);
    EXPECT_EQ(b.summary.impacts_energy_gain, 0);
    double worst = 0.0;
    for (double t = 0.0; t <= a.trajectory.end_s(); t += 0.01) {
      const Sample x = a.trajectory.At(t), y = b.trajectory.At(t);
      for (int i = 0; i < x.blocks(); ++i) {
        worst = std::max(worst, std::abs(x.theta_rad[i] - y.theta_rad[i]));
      }
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_NEAR(a.trajectory.end_s(), b.trajectory.end_s(), 1e-6);
  }
}

// A slender block (b = 0.1 m, h = 1 m) tilted 0.05 rad onto its right corner, slipping right:
// with mu = 20 the normal row of its contact problem is negative (m A = 1 - d_x (mu |d_y| -
// d_x) / (I / m) = 1 - 0.04996 (20.07 - 0.05) / 0.3367 = -1.97 < 0, Painleve's condition), so
// Coulomb's law has no solution when the free normal acceleration pushes the corner down (no
// spin: -g) and two when it lifts it (a spin with omega^2 |d_y| = 25.1 m/s^2 > g): both are
// stated, never chosen silently. With mu = 0.5 the row is positive (m A = 0.93) and the solution
// unique.
TEST(UnilateralStack, PainleveCasesAreStated) {
  const double b = 0.1, h = 1.0, m = 100.0;
  for (const double mu : {20.0, 0.5}) {
    UnilateralBlock blk{b, h, m, m * (b * b + h * h) / 3.0, mu};
    const UnilateralStack stack({blk}, 9.81);
    for (const double omega : {0.0, 5.0}) {
      SCOPED_TRACE("mu " + std::to_string(mu) + " omega " + std::to_string(omega));
      // Tilted right by 0.05 rad, its right corner at the origin; the corner slides right at
      // 1 m/s with no normal rate.
      const double th = 0.05, c = std::cos(th), s = std::sin(th);
      const double dx = b * c - h * s, dy = -b * s - h * c;  // corner - mass centre
      double q[3] = {-dx, -dy, th};
      double v[3] = {1.0 - omega * dy, omega * dx, omega};
      const auto slot = stack.Slots(0, q, v)[0];
      ASSERT_NEAR(slot.gap_m, 0.0, 1e-15);
      ASSERT_NEAR(slot.gap_rate_mps, 0.0, 1e-15);
      ASSERT_GT(slot.slip_rate_mps, 0.5);
      ContactMode hint(1);
      hint.closed[0] = {true, false};
      hint.slip[0] = Slip::kRight;
      const ModeSolution sol = stack.Solve(q, v, 0.0, 0.0, hint, 1e-12, 1e-12);
      EXPECT_TRUE(sol.exhaustive);
      if (mu < 1.0) {
        EXPECT_TRUE(sol.found);
        EXPECT_EQ(sol.solutions, 1);
      } else if (omega == 0.0) {
        EXPECT_FALSE(sol.found);
        EXPECT_NE(sol.note.find("Painleve: no solution"), std::string::npos) << sol.note;
      } else {
        EXPECT_TRUE(sol.found);
        EXPECT_EQ(sol.solutions, 2);
        EXPECT_NE(sol.note.find("Painleve: several solutions"), std::string::npos) << sol.note;
      }
    }
  }
}

// A plastic impact with Coulomb friction never adds energy: random stacks of one to three
// blocks placed on random pivots (every pivot at a zero gap), random velocities, random
// friction (0 to 1.5, or infinite). The kinetic energy after is at most the energy before
// (rounding: 1e-12 of it). With infinite friction the impact is the chain's (the post-impact
// velocities conserve the generalized momenta; checked against the chain in
// InfiniteFrictionFollowsTheChain).
// Interface k's random contact (face, right or left corner, a third each) into *c, and block
// k's angle on it: a tilt of up to 0.2 rad the pivot's way relative to `below`, block k - 1's
// angle (none on the face), rad.
double RandomPivot(int k, double below, std::mt19937_64& rng, Configuration* c) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r = u(rng);
  c->set(k, r < 0.33 ? Contact::kFace : r < 0.66 ? Contact::kRight : Contact::kLeft);
  const double rel =
      (*c)[k] == Contact::kFace ? 0.0 : ((*c)[k] == Contact::kRight ? 1 : -1) * 0.2 * u(rng);
  return below + rel;
}

TEST(UnilateralStack, ImpactsNeverAddEnergy) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int solved = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 3;
    std::vector<UnilateralBlock> blocks;
    double width = 1.0 + u(rng);
    for (int i = 0; i < n; ++i) {
      width *= 0.6 + 0.4 * u(rng);
      const double bh = width / 2, hh = 0.3 + u(rng);
      const double mass = 100.0 + 1000.0 * u(rng);
      const double mu = u(rng) < 0.25 ? kInf : 1.5 * u(rng);
      blocks.push_back({bh, hh, mass, mass * (bh * bh + hh * hh) / 3.0, mu});
    }
    const UnilateralStack stack(blocks, 9.81);
    Configuration c(n);
    std::vector<double> th(n), om(n, 0.0);
    double below = 0.0;
    for (int k = 0; k < n; ++k) {
      th[k] = RandomPivot(k, below, rng, &c);
      below = th[k];
    }
    std::vector<double> q(3 * n), v(3 * n);
    stack.FromChain(c, th.data(), om.data(), q.data(), v.data());
    for (double& x : v) x = 2.0 * u(rng) - 1.0;
    double ke_before = 0.0, ke_after = 0.0;
    const ModeSolution sol = stack.SolveImpact(q.data(), v.data(), ContactMode(n), 1e-9, 0.0);
    if (!sol.found) continue;
    ++solved;
    for (int i = 0; i < n; ++i) {
      const UnilateralBlock& B = blocks[i];
      for (int j = 0; j < 3; ++j) {
        const double w = j == 2 ? B.inertia_kgm2 : B.mass_kg;
        ke_before += 0.5 * w * v[3 * i + j] * v[3 * i + j];
        ke_after += 0.5 * w * sol.result[3 * i + j] * sol.result[3 * i + j];
      }
    }
    EXPECT_LE(ke_after, ke_before * (1.0 + 1e-12)) << trial;
  }
  // Most random impacts have an outcome (those without are Painleve's: stated, not checked).
  EXPECT_GT(solved, 250);
}

// A random stack of n blocks on random pivots (every pivot at a zero gap), for the solver
// comparisons: widths shrinking upwards, masses 100 to 1100 kg, friction 0 to 1.5 or infinite.
struct RandomStack {
  std::vector<UnilateralBlock> blocks;
  std::vector<double> q, v;
};
RandomStack MakeRandomStack(int n, std::mt19937_64& rng, bool chain_rates) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomStack out;
  double width = 1.0 + u(rng);
  for (int i = 0; i < n; ++i) {
    width *= 0.6 + 0.4 * u(rng);
    const double bh = width / 2, hh = 0.3 + u(rng);
    const double mass = 100.0 + 1000.0 * u(rng);
    const double r = u(rng);
    const double mu = r < 0.2 ? kInf : r < 0.3 ? 0.0 : 1.5 * u(rng);
    out.blocks.push_back({bh, hh, mass, mass * (bh * bh + hh * hh) / 3.0, mu});
  }
  const UnilateralStack stack(out.blocks, 9.81);
  Configuration c(n);
  std::vector<double> th(n), om(n);
  double below = 0.0;
  for (int k = 0; k < n; ++k) {
    th[k] = RandomPivot(k, below, rng, &c);
    below = th[k];
    om[k] = c[k] == Contact::kFace && k == 0 ? 0.0 : 2.0 * u(rng) - 1.0;
  }
  out.q.resize(3 * n);
  out.v.resize(3 * n);
  // The chain's rates keep every pivot at rest (zero normal and slip rates: static friction).
  stack.FromChain(c, th.data(), om.data(), out.q.data(), out.v.data());
  if (!chain_rates) {
    for (double& x : out.v) x = 2.0 * u(rng) - 1.0;
  }
  return out;
}

// Lemke's method (the path of problems above the enumeration's limit: exhaustive_limit 0)
// against the enumeration of every contact state (the model's former solver, kept for small
// problems), on random states of one to three blocks under random base accelerations: where the
// enumeration finds exactly one motion, Lemke's path finds the same (1e-6 g and 1e-6 g / L: the
// enumeration's own measure of one motion, SameMotion). Impacts likewise, from random
// velocities. Lemke's path must also find a state in (nearly) every case the enumeration does:
// it may only end on a ray where the LCP has no solution or a degenerate one.
TEST(UnilateralStack, LemkeAgreesWithTheEnumeration) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int compared = 0, impacts = 0, lemke_used = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 1 + trial % 3;
    const bool impact = trial % 2 == 1;
    const RandomStack rs = MakeRandomStack(n, rng, !impact);
    const UnilateralStack stack(rs.blocks, 9.81);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ModeSolution all, lemke;
    if (impact) {
      all = stack.SolveImpact(rs.q.data(), rs.v.data(), ContactMode(n), 1e-9, 0.0, 1000000);
      lemke = stack.SolveImpact(rs.q.data(), rs.v.data(), ContactMode(n), 1e-9, 0.0, 0);
    } else {
      const double xg = 9.81 * (2.0 * u(rng) - 1.0), yg = 9.81 * (0.5 * u(rng) - 0.25);
      all = stack.Solve(rs.q.data(), rs.v.data(), xg, yg, ContactMode(n), 1e-9, 1e-9, 1000000);
      lemke = stack.Solve(rs.q.data(), rs.v.data(), xg, yg, ContactMode(n), 1e-9, 1e-9, 0);
    }
    ASSERT_TRUE(all.exhaustive);
    // Lemke's path counts no solutions (a fallback enumeration that ends below its cap has
    // tried every state, and says so).
    if (lemke.method == "lemke" || lemke.method == "preferred") {
      EXPECT_FALSE(lemke.exhaustive);
    }
    if (!all.found || all.solutions != 1) continue;
    ASSERT_TRUE(lemke.found) << lemke.note;
    if (lemke.method == "lemke") ++lemke_used;
    double scale = 9.81;
    if (impact) {
      scale = 0.0;
      for (int i = 0; i < 3 * n; ++i) {
        scale = std::max(scale, std::abs(rs.v[i]) * (i % 3 == 2 ? stack.length_scale_m() : 1.0));
      }
      ++impacts;
    }
    for (int i = 0; i < 3 * n; ++i) {
      const double tol = 1e-6 * scale / (i % 3 == 2 ? stack.length_scale_m() : 1.0);
      EXPECT_NEAR(lemke.result[i], all.result[i], tol) << i << " " << lemke.method;
    }
    ++compared;
  }
  // Most random states have one motion; Lemke itself (not the preferred state) decides many.
  EXPECT_GT(compared, 400);
  EXPECT_GT(impacts, 200);
  EXPECT_GT(lemke_used, 200);
}

// The thesis's stack (block 1 1.25 x 1.25 m, block 2 1.0 x 2.5 m, 2500 kg/m^3, infinite
// friction) under one cycle of a 1.2 g, 0.75 Hz sine: block 2 falls over. At 1.2348 s the
// chain's interface pivot would pull while it still carries 1.1e4 N of tangential force, so
// that no state of stick or open exists (the enumeration proves it; the run stopped there
// before). Any finite friction slips first, and as mu grows the overturn converges (measured
// with this model: 1.37377 s at mu = 1, 1.37193 at 10, 1.371660 at 100, 1.3716284 at 1e4):
// the limit slip of infinite friction must reach it, to the convergence of that sequence
// (1e-4 s: 1e2 to 1e4 moved it 3.2e-5 s).
TEST(UnilateralRun, InfiniteFrictionOverturnsThroughTheLimitSlip) {
  auto scene = [](double mu) {
    Scene s;
    BlockDef b1, b2;
    b1.width_m = 1.25;
    b1.height_m = 1.25;
    b1.mass_kg = 2500.0 * 1.25 * 1.25;
    b1.friction = mu;
    b2.width_m = 1.0;
    b2.height_m = 2.5;
    b2.mass_kg = 2500.0 * 2.5;
    b2.friction = mu;
    s.blocks = {b1, b2};
    s.run.duration_s = 3.0;
    s.run.gravity_mps2 = 9.81;
    s.compare.members = 0;
    MotionDef d;
    d.key = "base.horizontal";
    d.kind = MotionKind::kSinePulse;
    d.amplitude_g = 1.2;
    d.frequency_hz = 0.75;
    s.horizontal = d;
    return s;
  };
  const Scene inf = scene(kInf), big = scene(1e4);
  const Result a = Simulate(inf, GroundMotion::FromScene(inf));
  const Result b = Simulate(big, GroundMotion::FromScene(big));
  ASSERT_EQ(a.summary.status, RunStatus::kOverturned) << a.summary.status_detail;
  EXPECT_EQ(a.summary.overturn_block, 2);
  ASSERT_EQ(b.summary.status, RunStatus::kOverturned);
  EXPECT_NEAR(a.summary.overturn_t_s, b.summary.overturn_t_s, 1e-4);
  EXPECT_TRUE(HasNote(a.history, "block 2 sticks on its left corner -> slips left on its left"));
}

// Two blocks, one 1e12 times heavier than the other (1e3 and 1e15 kg, the scene's limits),
// from t = 0 in the unilateral model, at rest and under a small pulse: the run does not stop
// (its mode's equations were singular to the solver's tolerance: the Schur complement's
// condition number is about the mass ratio). At rest nothing moves: the angles stay zero to
// rounding (1e-12 rad).
TEST(UnilateralRun, AMassRatioOf1e12IsRegular) {
  for (const int heavy : {0, 1}) {
    for (const double a_g : {0.0, 0.05}) {
      SCOPED_TRACE("heavy block " + std::to_string(heavy + 1) + " pulse " + std::to_string(a_g));
      Scene s;
      BlockDef b1, b2;
      b1.width_m = 1.25;
      b1.height_m = 1.25;
      b1.mass_kg = 1e3;
      b2.width_m = 1.0;
      b2.height_m = 2.5;
      b2.mass_kg = 1e3;
      (heavy == 0 ? b1 : b2).mass_kg = 1e15;
      s.blocks = {b1, b2};
      s.run.duration_s = 1.0;
      s.run.gravity_mps2 = kG;
      s.compare.members = 0;
      s.model.formulation = Formulation::kUnilateral;
      if (a_g > 0.0) s.horizontal = RectangularPulseDef(a_g, 0.2, 0.1);
      const Result r = Simulate(s, GroundMotion::FromScene(s));
      EXPECT_NE(r.summary.status, RunStatus::kAssumptionViolated) << r.summary.status_detail;
      EXPECT_NEAR(r.trajectory.end_s(), 1.0, 1e-12);
      if (a_g == 0.0) {
        EXPECT_LT(std::abs(r.summary.peak_theta_rad[0]), 1e-12);
        EXPECT_LT(std::abs(r.summary.peak_theta_rad[1]), 1e-12);
      }
    }
  }
}

// Twenty wide blocks (4 m x 0.2 m: the stack is 4 m tall and as wide, so it slides rather than
// rocks, mu = 0.3 < b / h_G = 1) with friction 0.3 on the ground and 0.8 between blocks, under
// a rectangular pulse of 0.5 g for 0.3 s: the stack slides on the ground as one body (each
// interface above needs |T| / N = 0.3 < 0.8) and sticks again where Newmark's closed form for
// one block says. The stick time is an event (1e-9 s, as NewmarkSlidingBlockUnderPulse); the
// slip is integrated in 60 coordinates with the drift projected every step (measured 2e-11
// relative; 1e-9).
TEST(UnilateralRun, TwentyBlocksSlideAsOne) {
  const double mu = 0.3, a_g = 0.5, t0 = 0.1, pulse = 0.3;
  Scene s;
  for (int i = 0; i < 20; ++i) {
    BlockDef b;
    b.width_m = 4.0;
    b.height_m = 0.2;
    b.mass_kg = 2500.0 * 4.0 * 0.2;
    b.friction = i == 0 ? mu : 0.8;
    s.blocks.push_back(b);
  }
  s.run.duration_s = 1.0;
  s.run.gravity_mps2 = kG;
  s.compare.members = 0;
  s.horizontal = RectangularPulseDef(a_g, pulse, t0);
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  const benchmarks::SlidingPulse cf = benchmarks::SlidingBlockUnderPulse(a_g * kG, pulse, mu, kG);
  EXPECT_EQ(r.summary.status, RunStatus::kAtRest) << r.summary.status_detail;
  double stick_t = -1.0;
  for (const Event& e : r.history.events) {
    if (e.note.find("slip stops") != std::string::npos) stick_t = e.t_s;
  }
  EXPECT_NEAR(stick_t - t0, cf.stick_t_s, 1e-9);
  ASSERT_TRUE(r.history.slip_and_lift);
  const Sample& last = r.history.samples.back();
  EXPECT_NEAR(last.u_m[0], cf.slip_m, 1e-9 * std::abs(cf.slip_m));
  for (int k = 1; k < 20; ++k) EXPECT_LT(std::abs(last.u_m[k]), 1e-9) << k;
}

}  // namespace
}  // namespace rockbench::reference
