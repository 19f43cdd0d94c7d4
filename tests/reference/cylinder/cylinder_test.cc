// The cylinder reference (reference/cylinder/, reference/cylinder_run.h) against what must hold
// (issue 41): an independent second formulation (cylinder_world_frame.h: world frame, quaternion,
// the contact force solved for; no Euler-angle equations), the planar limit with impacts (an
// independent planar integrator written here), energy conservation, rotation invariance, the
// onset threshold, the landing rule and its planar coefficient, and the model's boundaries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/cylinder/cylinder_model.h"
#include "reference/cylinder_run.h"
#include "reference/cylinder/cylinder_world_frame.h"
#include "reference/integration/integrator.h"
#include "scene/body_kind.h"
#include "scene/scene.h"

namespace rockbench::reference::cylinder {
namespace {

constexpr double kPi = std::numbers::pi;
namespace oracle = rockbench::reference::test;

// The slender cylinder of docs/cylinder-3d.md section 6: D = 0.5 m, H = 1.5 m, 2500 kg/m^3.
constexpr double kD = 0.5, kH = 1.5, kRho = 2500.0, kG = 9.81;

CylinderBody Body(double d = kD, double h = kH, double rho = kRho, double g = kG) {
  const double m = rho * kPi * 0.25 * d * d * h;
  return MakeCylinderBody(d, h, m, g);
}

oracle::CylinderBody OracleBody(double d = kD, double h = kH, double rho = kRho) {
  return oracle::SolidCylinder(d, h, rho);
}

// A cylinder scene: the body above, `rest` TOML appended (initial state, base, run, model).
Scene CylinderScene(const std::string& rest, double d = kD, double h = kH) {
  const std::string text = "[[block]]\nshape = \"cylinder\"\ndiameter = " + ShortestText(d) +
                           "\nheight = " + ShortestText(h) + "\ndensity = " + ShortestText(kRho) +
                           "\n" + rest;
  return ParseScene(text, "cylinder.toml");
}

CylinderResult RunScene(const Scene& scene) {
  return SimulateCylinder(scene, GroundMotion::FromScene(scene));
}

// The value of a history's quantity at every row, with the row times.
std::vector<std::pair<double, double>> Column(const History& h, const std::string& stem) {
  StateQuantityReader read(h, stem);
  std::vector<std::pair<double, double>> out;
  for (const Sample& s : h.samples) out.push_back({s.t_s, read(s, 1)});
  return out;
}

// The angular acceleration (world) of ZYZ angles, rates and their accelerations:
// omega = phi' z + theta' e2 + psi' k, differentiated with e2' = phi' z x e2, k' = omega x k.
Eigen::Vector3d AngularAcceleration(double th, double ph, double thd, double phd, double psd,
                                    double thdd, double phdd, double psdd) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d e2(-std::sin(ph), std::cos(ph), 0.0);
  const Eigen::Vector3d k(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  const Eigen::Vector3d omega = phd * z + thd * e2 + psd * k;
  return phdd * z + thdd * e2 + thd * phd * z.cross(e2) + psdd * k + psd * omega.cross(k);
}

// The model's accelerations and contact force equal the world-frame formulation's at random
// states, bodies and base accelerations (both exact: agreement to roundoff; 1e-11 of the scale
// leaves three orders of magnitude for the 1/sin(theta) at theta >= 0.01).
TEST(CylinderModel, EqualsTheWorldFrameFormulationPointwise) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  double worst_accel = 0.0, worst_force = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double d = 0.1 + 1.9 * u(rng), h = 0.1 + 3.9 * u(rng), rho = 500 + 7500 * u(rng);
    const CylinderBody body = Body(d, h, rho);
    const oracle::CylinderBody ob = OracleBody(d, h, rho);
    const double th = 0.01 + 1.49 * u(rng), ph = 2 * kPi * u(rng), ps = 2 * kPi * u(rng);
    const double thd = 3 * n(rng), phd = 3 * n(rng), psd = 3 * n(rng);
    const BaseAccel a{5 * n(rng), 5 * n(rng), 5 * n(rng)};
    RimState s;
    s.theta = th;
    s.theta_dot = thd;
    s.phi_dot = phd;
    s.psi_dot = psd;
    s.cos_phi = std::cos(ph);
    s.sin_phi = std::sin(ph);
    const RimDynamics dyn = Dynamics(body, s, a);
    const oracle::CylinderDerivative o =
        oracle::Derivative(ob, oracle::FromTiltAzimuthSpin(th, ph, ps, thd, phd, psd), a, kG);
    const Eigen::Vector3d alpha =
        AngularAcceleration(th, ph, thd, phd, psd, dyn.theta_ddot, dyn.phi_ddot, dyn.psi_ddot);
    const double accel_scale = std::max(1.0, o.angular_acceleration_rps2.norm());
    worst_accel = std::max(worst_accel, (alpha - o.angular_acceleration_rps2).norm() / accel_scale);
    const Eigen::Vector3d f(dyn.force_n[0], dyn.force_n[1], dyn.force_n[2]);
    const double force_scale = std::max(body.mass_kg * kG, o.contact_force_N.norm());
    worst_force = std::max(worst_force, (f - o.contact_force_N).norm() / force_scale);
  }
  std::printf("measured: pointwise, angular acceleration %.2g, contact force %.2g (relative)\n",
              worst_accel, worst_force);
  EXPECT_LT(worst_accel, 1e-11);
  EXPECT_LT(worst_force, 1e-11);
}

// The world-frame formulation integrated on its own (DOP853, the same controller as the
// reference's, tight tolerances), sampled at the output times.
std::vector<oracle::TiltAzimuthSpin> IntegrateOracle(const oracle::CylinderBody& body,
                                                     const oracle::CylinderState& y0,
                                                     const GroundMotion& motion, double t_end,
                                                     double dt_out) {
  using Y = VecN<7>;
  const auto rhs = [&](double t, const Y& y) {
    const std::array<double, 3> a{motion.xg_mps2(t), motion.transverse_mps2(t), motion.yg_mps2(t)};
    return oracle::Derivative(body, y, a, kG).dstate;
  };
  std::vector<oracle::TiltAzimuthSpin> out{oracle::ToTiltAzimuthSpin(y0)};
  Y y = y0;
  double t = 0.0, h = 1e-4;
  long next = 1;
  while (t < t_end) {
    const double hh = std::min(h, t_end - t);
    StepResultN<7> st = Dop853Step(rhs, t, y, rhs(t, y), hh, 1e-13, 1e-15);
    if (st.err > 1.0) {
      h = hh * std::max(1.0 / 3.0, 0.9 * std::pow(st.err, -1.0 / 8.0));
      continue;
    }
    const double t1 = hh == t_end - t ? t_end : t + hh;
    while (next * dt_out <= t1 * (1 + 1e-12)) {
      out.push_back(oracle::ToTiltAzimuthSpin(st.dense.At(next * dt_out)));
      ++next;
    }
    t = t1;
    y = st.y1;
    h = hh * (st.err > 0 ? std::min(6.0, 0.9 * std::pow(st.err, -1.0 / 8.0)) : 6.0);
  }
  return out;
}

// Seconds of wobbling, free and forced: the reference's tilt vector equals the world-frame
// formulation's to 1e-10 rad (the figure; both integrate at relative tolerance 1e-12 or
// tighter, and docs/cylinder-3d.md section 6 measured 4.6e-13 in theta between the two
// formulations).
TEST(CylinderRun, EqualsTheWorldFrameFormulationOverSecondsOfWobbling) {
  struct Case {
    double phi_rate;
    std::string base;
  };
  const std::vector<Case> cases = {
      {1.0, ""},
      {3.0, ""},
      {6.0, ""},
      {2.0,
       "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.05\nfrequency_hz = 1.3\n"
       "[base.transverse]\nkind = \"harmonic\"\namplitude_g = 0.04\nfrequency_hz = 1.1\n"
       "phase_deg = 90\n"},
  };
  for (const Case& c : cases) {
    const Scene scene = CylinderScene(
        "[initial]\ntilt = [0.1]\nazimuth_rate = [" + ShortestText(c.phi_rate) + "]\n" + c.base +
        "[run]\nduration = 4\noutput_interval = 0.01\n[model]\nintegrator = \"dop853\"\n"
        "rtol = 1e-13\natol = 1e-15\n");
    const CylinderResult r = RunScene(scene);
    ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.status_detail;
    ASSERT_EQ(r.summary.landings, 0);
    const auto ref_x = Column(r.history, "tilt_x"), ref_y = Column(r.history, "tilt_y");
    const std::vector<oracle::TiltAzimuthSpin> o = IntegrateOracle(
        OracleBody(), oracle::FromTiltAzimuthSpin(0.1, 0.0, 0.0, 0.0, c.phi_rate, 0.0),
        GroundMotion::FromScene(scene), 4.0, 0.01);
    ASSERT_EQ(o.size(), ref_x.size());
    double worst = 0.0;
    for (size_t i = 0; i < o.size(); ++i) {
      worst = std::max(worst, std::hypot(ref_x[i].second - o[i].tilt_x_rad(),
                                         ref_y[i].second - o[i].tilt_y_rad()));
    }
    std::printf("measured: phi0' = %g%s, max |tilt vector difference| %.2g rad over 4 s\n",
                c.phi_rate, c.base.empty() ? "" : " (forced)", worst);
    EXPECT_LT(worst, 1e-10) << "phi0' = " << c.phi_rate;
  }
}

// Free rolling on a fixed base conserves energy (the rolling contact does no work): drift below
// 1e-10 of the energy over 4 s at rtol 1e-12 (docs/cylinder-3d.md measured 5e-13).
TEST(CylinderRun, FreeRollingConservesEnergy) {
  const CylinderBody body = Body();
  for (const double phi_rate : {1.0, 3.0, 6.0}) {
    const Scene scene =
        CylinderScene("[initial]\ntilt = [0.1]\nazimuth_rate = [" + ShortestText(phi_rate) +
                      "]\nspin_rate = [0.5]\n" + "[run]\nduration = 4\n");
    const CylinderResult r = RunScene(scene);
    ASSERT_EQ(r.summary.landings, 0);
    StateQuantityReader tilt(r.history, "tilt"), tilt_rate(r.history, "tilt_rate"),
        azimuth_rate(r.history, "azimuth_rate"), spin_rate(r.history, "spin_rate");
    double e0 = 0.0, worst = 0.0;
    for (const Sample& s : r.history.samples) {
      RimState st;
      st.theta = tilt(s, 1);
      st.theta_dot = tilt_rate(s, 1);
      st.phi_dot = azimuth_rate(s, 1);
      st.psi_dot = spin_rate(s, 1);
      const double e = Energy(body, st);
      if (&s == &r.history.samples.front()) e0 = e;
      worst = std::max(worst, std::abs(e - e0));
    }
    std::printf("measured: phi0' = %g, energy drift %.2g of the energy over 4 s\n", phi_rate,
                worst / e0);
    EXPECT_LT(worst, 1e-10 * e0) << phi_rate;
  }
}

// An independent planar rocking body with the cylinder's mass, pivot inertia and critical angle:
// x'' = (m R_c / I_O) [(g + a_z) sin(x - S alpha) - a_x cos(x - S alpha)], S = sgn x, and at
// x = 0 the rate times e = 1 - 2 m R^2 / I_O (docs/cylinder-3d.md section 4.1 and 5). DOP853 with
// its impacts located by bisection on the dense output.
std::vector<double> PlanarBody(const CylinderBody& body, double x0, const GroundMotion& motion,
                               double t_end, double dt_out, std::vector<double>* impacts) {
  using Y = VecN<2>;
  const double rc = std::hypot(body.radius_m, body.half_height_m);
  const double io = body.pivot_inertia_kgm2(), alpha = body.critical_angle_rad();
  const double e = 1.0 - 2.0 * body.mass_kg * body.radius_m * body.radius_m / io;
  double side = x0 > 0 ? 1.0 : -1.0;
  const auto rhs = [&](double t, const Y& y) {
    const double a = motion.xg_mps2(t), az = motion.yg_mps2(t);
    return Y{y[1], body.mass_kg * rc / io *
                       ((body.gravity_mps2 + az) * std::sin(y[0] - side * alpha) -
                        a * std::cos(y[0] - side * alpha))};
  };
  std::vector<double> out{x0};
  Y y{x0, 0.0};
  double t = 0.0, h = 1e-4;
  long next = 1;
  while (t < t_end) {
    const double hh = std::min({h, t_end - t, motion.next_breakpoint_after(t) - t});
    StepResultN<2> st = Dop853Step(rhs, t, y, rhs(t, y), hh, 1e-13, 1e-15);
    if (st.err > 1.0) {
      h = hh * std::max(1.0 / 3.0, 0.9 * std::pow(st.err, -1.0 / 8.0));
      continue;
    }
    double t1 = t + hh;
    bool impact = side * st.y1[0] <= 0.0;
    if (impact) {
      double lo = t, hi = t1;
      for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        (side * st.dense.At(mid)[0] > 0.0 ? lo : hi) = mid;
      }
      t1 = hi;
    }
    while (next * dt_out < t1 || (!impact && next * dt_out <= t1 * (1 + 1e-12))) {
      out.push_back(st.dense.At(next * dt_out)[0]);
      ++next;
    }
    const Y at = st.dense.At(t1);
    y = impact ? Y{0.0, e * at[1]} : st.y1;
    if (impact) {
      impacts->push_back(t1);
      side = -side;
      h = 1e-6;
    } else {
      h = hh * (st.err > 0 ? std::min(6.0, 0.9 * std::pow(st.err, -1.0 / 8.0)) : 6.0);
    }
    t = t1;
  }
  return out;
}

// The planar limit, impacts included: uniaxial motion and no azimuthal rate give the planar
// body's tilt with the cylinder's mass, pivot inertia and critical angle (1e-10 rad; docs
// section 6 measured 3.2e-12 over 18 landings), its landings at the same times, and the
// azimuth's sine exactly 0 through every landing's half-turn.
TEST(CylinderRun, PlanarLimitIsThePlanarBodyWithImpacts) {
  const Scene scene = CylinderScene(
      "[initial]\ntilt = [0.1]\n[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.25\n"
      "frequency_hz = 1.5\n[run]\nduration = 6\ngravity = 9.81\n[model]\nintegrator = "
      "\"dop853\"\nrtol = 1e-13\natol = 1e-15\n");
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const CylinderResult r = SimulateCylinder(scene, motion);
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.status_detail;
  EXPECT_TRUE(r.summary.planar);
  EXPECT_EQ(r.summary.landing_tilt_rad, 0.0);
  std::vector<double> impacts;
  const std::vector<double> planar = PlanarBody(Body(), 0.1, motion, 6.0, 0.01, &impacts);
  ASSERT_GE(impacts.size(), 10u);
  // The landings, in order, at the planar body's impact times.
  std::vector<double> landings;
  for (const Event& e : r.history.events) {
    if (e.kind == "ground_impact") landings.push_back(e.t_s);
  }
  ASSERT_EQ(landings.size(), impacts.size());
  double worst_t = 0.0;
  for (size_t i = 0; i < impacts.size(); ++i) {
    EXPECT_NEAR(landings[i], impacts[i], 1e-9) << i;
    worst_t = std::max(worst_t, std::abs(landings[i] - impacts[i]));
  }
  // The rows at output times (every event row is at another time).
  StateQuantityReader tilt_x(r.history, "tilt_x"), tilt_y(r.history, "tilt_y");
  double worst = 0.0;
  size_t matched = 0;
  for (const Sample& s : r.history.samples) {
    EXPECT_EQ(tilt_y(s, 1), 0.0);
    const double k = std::round(s.t_s / 0.01);
    if (std::abs(s.t_s - k * 0.01) > 1e-12 || k >= static_cast<double>(planar.size())) continue;
    if (s.t_s != k * 0.01) continue;
    worst = std::max(worst, std::abs(tilt_x(s, 1) - planar[static_cast<size_t>(k)]));
    ++matched;
  }
  std::printf("measured: planar limit, %zu landings within %.2g s, max |tilt_x - planar| %.2g rad\n",
              impacts.size(), worst_t, worst);
  EXPECT_GE(matched, 600u);
  EXPECT_LT(worst, 1e-10);
}

// The landing's planar coefficient: 1 - 2 m R^2 / I_O = 0.849056603774 for D = 0.5 m, H = 1.5 m
// (docs/cylinder-3d.md section 5: I_O = 0.828125 m, 2 m R^2 = 0.125 m), and every event's
// rate ratio in the planar run equals it to roundoff.
TEST(CylinderModel, PlanarLandingCoefficient) {
  const CylinderBody body = Body();
  EXPECT_NEAR(PlanarRestitution(body), 1.0 - 0.125 / 0.828125, 1e-15);
  EXPECT_NEAR(PlanarRestitution(body), 0.849056603774, 1e-12);
  RimState s;
  s.theta_dot = -0.3;
  const Landing l = Land(body, s);
  EXPECT_NEAR(l.theta_dot, 0.3 * PlanarRestitution(body), 1e-15);
  EXPECT_EQ(l.axial_rate, 0.0);
  // A squat cylinder (2 m R^2 > I_O) lands flat: e < 0.
  EXPECT_LT(PlanarRestitution(Body(2.0, 0.5)), 0.0);
}

// The landing never adds energy (1e5 random bodies and pre-impact rates; docs section 5
// measured a loss of at least 6.2e-4 of the kinetic energy), and keeps the angular momentum
// about the new contact point about the vertical and the horizontal normal to the diameter,
// computed here from the world-frame formulation's inertia.
TEST(CylinderModel, LandingKeepsItsMomentaAndLosesEnergy) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 100000; ++i) {
    const double d = 0.1 + 1.9 * u(rng), h = 0.1 + 3.9 * u(rng);
    const CylinderBody body = Body(d, h);
    RimState s;
    s.theta = 0.0;
    s.theta_dot = -std::abs(n(rng)) - 1e-3;
    s.phi_dot = n(rng);  // at theta = 0, w1 = -phi' sin theta = 0
    s.psi_dot = n(rng);
    const Landing l = Land(body, s);
    ASSERT_GE(l.energy_lost_j, -1e-12 * body.mass_kg) << i;
    // About the new contact P' (old frame: e1 toward P, so P' is at -R e1 from the foot):
    // L' = I_G w + m r' x v_G, r' = G - P' = (R, 0, h). Before, the centre moves with the
    // rolling about P (v_G = w x r, r = G - P = (-R, 0, h)); after, about P' (v_G = w x r').
    const double m = body.mass_kg, r = body.radius_m, hh = body.half_height_m;
    const double it = body.inertia_transverse_kgm2(), ia = body.inertia_axial_kgm2();
    const Eigen::Vector3d rp(r, 0.0, hh), rold(-r, 0.0, hh);
    const auto about_new = [&](const Eigen::Vector3d& w, const Eigen::Vector3d& pivot_to_g) {
      const Eigen::Vector3d ig(it * w.x(), it * w.y(), ia * w.z());
      return Eigen::Vector3d(ig + m * rp.cross(w.cross(pivot_to_g)));
    };
    const Eigen::Vector3d before =
        about_new(Eigen::Vector3d(0.0, s.theta_dot, s.psi_dot + s.phi_dot), rold);
    // After: w2+ = -theta'+ (the new frame's e2 is the old one reversed), w1+ = 0.
    const Eigen::Vector3d after = about_new(Eigen::Vector3d(0.0, -l.theta_dot, l.axial_rate), rp);
    // Roundoff of the terms (the momenta are differences of terms up to I_O |w|): 1e-13 of
    // their size is some 500 ulps.
    const double terms =
        body.pivot_inertia_kgm2() * (std::abs(s.theta_dot) + std::abs(s.psi_dot + s.phi_dot));
    ASSERT_NEAR(after.y(), before.y(), 1e-13 * terms) << i;
    ASSERT_NEAR(after.z(), before.z(), 1e-13 * terms) << i;
  }
}

// Rotating the ground motion and the initial azimuth by beta rotates the azimuth by beta and
// leaves tilt and spin (1e-10 rad over 3 s; docs section 6 measured 9.4e-12).
TEST(CylinderRun, RotatingTheGroundMotionRotatesTheAzimuth) {
  const double beta = 0.7;
  const auto scene_at = [&](double b) {
    // a = A (cos b, sin b) sin(2 pi f t) + a transverse harmonic rotated with it.
    const double a1 = 0.06, a2 = 0.04;
    const std::string base =
        "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = " +
        ShortestText(a1 * std::cos(b) - a2 * std::sin(b)) +
        "\nfrequency_hz = 1.3\n[base.transverse]\nkind = \"harmonic\"\namplitude_g = " +
        ShortestText(a1 * std::sin(b) + a2 * std::cos(b)) + "\nfrequency_hz = 1.3\n";
    return CylinderScene("[initial]\ntilt = [0.08]\nazimuth = [" + ShortestText(0.3 + b) +
                         "]\ntilt_rate = [0.1]\nazimuth_rate = [1.5]\nspin_rate = [0.4]\n" + base +
                         "[run]\nduration = 3\n");
  };
  const CylinderResult a = RunScene(scene_at(0.0)), b = RunScene(scene_at(beta));
  ASSERT_EQ(a.summary.landings, 0);
  ASSERT_EQ(b.summary.landings, 0);
  const auto ta = Column(a.history, "tilt"), tb = Column(b.history, "tilt");
  const auto pa = Column(a.history, "azimuth"), pb = Column(b.history, "azimuth");
  const auto sa = Column(a.history, "spin"), sb = Column(b.history, "spin");
  ASSERT_EQ(ta.size(), tb.size());
  double worst_tilt = 0.0, worst_azimuth = 0.0, worst_spin = 0.0;
  for (size_t i = 0; i < ta.size(); ++i) {
    worst_tilt = std::max(worst_tilt, std::abs(ta[i].second - tb[i].second));
    worst_azimuth = std::max(worst_azimuth, std::abs(pb[i].second - pa[i].second - beta));
    worst_spin = std::max(worst_spin, std::abs(sa[i].second - sb[i].second));
  }
  std::printf("measured: rotation by 0.7 rad, tilt %.2g, azimuth - 0.7 %.2g, spin %.2g rad\n",
              worst_tilt, worst_azimuth, worst_spin);
  EXPECT_LT(worst_tilt, 1e-10);
  EXPECT_LT(worst_azimuth, 1e-10);
  EXPECT_LT(worst_spin, 1e-10);
}

// Onset from rest under a constant field a (a rectangular pulse): the cylinder tips when
// a > (D / H)(g + a_z), at the pulse's start, its top leaning against the field; below, it
// stays on its face (docs section 4.4). g is standard gravity so that amplitude_g is a / g.
TEST(CylinderRun, OnsetThresholdAndDirectionFromRest) {
  const auto run = [](double ax_g, double ay_g) {
    std::string base;
    if (ax_g != 0.0) {
      base +=
          "[base.horizontal]\nkind = \"rectangular_pulse\"\namplitude_g = " + ShortestText(ax_g) +
          "\nduration_s = 0.3\nstart_s = 0.1\n";
    }
    if (ay_g != 0.0) {
      base +=
          "[base.transverse]\nkind = \"rectangular_pulse\"\namplitude_g = " + ShortestText(ay_g) +
          "\nduration_s = 0.3\nstart_s = 0.1\n";
    }
    return RunScene(CylinderScene(base + "[run]\nduration = 0.5\ngravity = 9.80665\n"));
  };
  const double threshold = kD / kH;
  const CylinderResult below = run(threshold * (1 - 1e-9), 0.0);
  EXPECT_EQ(below.summary.initiations, 0);
  EXPECT_EQ(below.summary.peak_tilt_rad, 0.0);
  const CylinderResult above = run(threshold * (1 + 1e-3), 0.0);
  ASSERT_EQ(above.summary.initiations, 1);
  EXPECT_NEAR(above.history.events.front().t_s, 0.1, 1e-12);
  EXPECT_TRUE(above.summary.planar);
  // +x field: the top leans toward -x (azimuth pi, at the initiation's row), tilt_y exactly 0.
  StateQuantityReader az(above.history, "azimuth"), ty(above.history, "tilt_y");
  const auto at_initiation = [&](const CylinderResult& r) {
    for (const Sample& s : r.history.samples) {
      if (s.t_s == r.history.events.front().t_s) return az(s, 1);
    }
    return -100.0;
  };
  EXPECT_NEAR(at_initiation(above), kPi, 1e-15);
  for (const Sample& s : above.history.samples) EXPECT_EQ(ty(s, 1), 0.0);
  // A diagonal field of the same magnitude tips toward atan2(-a_y, -a_x).
  const double c = std::cos(0.4), s = std::sin(0.4);
  const CylinderResult diagonal = run(threshold * (1 + 1e-3) * c, threshold * (1 + 1e-3) * s);
  ASSERT_EQ(diagonal.summary.initiations, 1);
  EXPECT_NEAR(at_initiation(diagonal), std::atan2(-s, -c), 1e-9);
  const CylinderResult diagonal_below = run(threshold * (1 - 1e-6) * c, threshold * (1 - 1e-6) * s);
  EXPECT_EQ(diagonal_below.summary.initiations, 0);
}

// A pass near upright: the exact rim model rolls round it (K = phi' sin^2 theta is kept and the
// tilt turns at about K / |theta'|), so whether it lands is the landing rule's. With phi0' =
// 1e-3 rad/s from theta0 = 0.1 the tilt turns at 1.32e-5 rad (docs section 5's table): a landing
// clearance of 1e-6 (tilt 1e-6) lets it roll round with no loss, one of 1e-4 lands it.
TEST(CylinderRun, LandingClearanceDecidesAPassNearUpright) {
  const auto run = [](double clearance) {
    return RunScene(
        CylinderScene("[initial]\ntilt = [0.1]\nazimuth_rate = [1e-3]\n[run]\nduration = 1.2\n"
                      "[model]\nlanding_clearance_rel = " +
                      ShortestText(clearance) + "\n"));
  };
  const CylinderResult rolls = run(1e-6);
  EXPECT_EQ(rolls.summary.landings, 0);
  EXPECT_FALSE(rolls.summary.planar);
  ASSERT_GE(rolls.summary.passes, 1);
  std::printf("measured: pass near upright, min tilt %.4g rad, peak after %.10g rad\n",
              rolls.summary.min_pass_tilt_rad, rolls.summary.peak_tilt_rad);
  EXPECT_NEAR(rolls.summary.min_pass_tilt_rad, 1.32e-5, 0.02e-5);
  EXPECT_NEAR(rolls.summary.peak_tilt_rad, 0.1, 1e-9);
  const CylinderResult lands = run(1e-4);
  EXPECT_GE(lands.summary.landings, 1);
  EXPECT_EQ(lands.history.events.front().note, "landed at the clearance tilt");
}

// A rebound that turns back within the landing clearance rests: its face never left the base
// by more than the clearance (without the rule it would wobble below the landing tilt, never
// crossing it again). Released at 0.012 rad with an azimuth rate (not planar) and a clearance of
// 0.01 (landing tilt 0.0100002 rad): it lands once, rebounds by e and turns back below 0.01.
TEST(CylinderRun, AReboundWithinTheClearanceRests) {
  const CylinderResult r = RunScene(CylinderScene(
      "[initial]\ntilt = [0.012]\nazimuth_rate = [0.2]\n[run]\nduration = 3\n"
      "[model]\nlanding_clearance_rel = 0.01\n"));
  ASSERT_EQ(r.summary.status, RunStatus::kAtRest) << r.summary.status_detail;
  EXPECT_EQ(r.summary.landings, 1);
  EXPECT_EQ(r.summary.rests, 1);
  ASSERT_EQ(r.history.events.size(), 2u);
  EXPECT_EQ(r.history.events[1].kind, "rest");
  EXPECT_EQ(r.history.events[1].note, "the rebound turned back within the landing clearance");
  EXPECT_LE(r.summary.peak_tilt_rad, 0.012 + 1e-12);
}

// Overturn: released beyond the critical angle with no field, the cylinder falls toward its
// azimuth and the run says when and where.
TEST(CylinderRun, OverturnSaysTheTimeAndTheAzimuth) {
  const CylinderResult r =
      RunScene(CylinderScene("[initial]\ntilt = [0.33]\nazimuth = [2.0]\n[run]\nduration = 5\n"));
  ASSERT_EQ(r.summary.status, RunStatus::kOverturned) << r.summary.status_detail;
  ASSERT_TRUE(r.summary.overturn_t_s.has_value());
  EXPECT_NEAR(r.summary.overturn_azimuth_rad, 2.0, 1e-12);
  EXPECT_GT(*r.summary.overturn_t_s, 0.0);
  EXPECT_EQ(r.history.events.back().kind, "overturn");
}

// The boundaries: a vertical field below -g lifts the cylinder off its face, a field beyond the
// friction slides it (mu g < (D / H) g: it slides before it tips); each a stated status.
TEST(CylinderRun, LiftOffAndSlipEndTheModel) {
  const CylinderResult lift = RunScene(CylinderScene(
      "[base.vertical]\nkind = \"rectangular_pulse\"\namplitude_g = -1.2\nduration_s = 0.2\n"
      "start_s = 0.1\n[run]\nduration = 0.5\n"));
  EXPECT_EQ(lift.summary.status, RunStatus::kAssumptionViolated);
  EXPECT_NE(lift.summary.status_detail.find("lift-off"), std::string::npos);
  const std::string slide_scene =
      "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\nheight = 1.5\ndensity = 2500\n"
      "friction = 0.2\n[base.horizontal]\nkind = \"rectangular_pulse\"\namplitude_g = 0.25\n"
      "duration_s = 0.2\nstart_s = 0.1\n[run]\nduration = 0.5\n";
  const CylinderResult slide = RunScene(ParseScene(slide_scene, "slide.toml"));
  EXPECT_EQ(slide.summary.status, RunStatus::kAssumptionViolated);
  EXPECT_NE(slide.summary.status_detail.find("slip"), std::string::npos);
  EXPECT_NEAR(slide.history.events.back().t_s, 0.1, 1e-12);
}

}  // namespace
}  // namespace rockbench::reference::cylinder
