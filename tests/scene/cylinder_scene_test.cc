// The cylinder's scene vocabulary (issue 41): its [[block]] table, [base.transverse], a
// harmonic's phase, its [initial] keys and model.landing_clearance_rel; what the reader and
// ValidateScene refuse and why; what its columns mean (scene/cylinder_state.h) and its history
// files, written and read back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "scene/body_kind.h"
#include "scene/cylinder_state.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

using testing_util::ErrorOf;
constexpr double kPi = std::numbers::pi;

// Lines 1-5: the cylinder.
const std::string kCylinder =
    "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\nheight = 1.5\ndensity = 2000\n";

std::string ParseError(const std::string& text) {
  return ErrorOf([&] { ParseScene(text, "c.toml"); });
}

TEST(CylinderScene, ReadsTheCylinderItsMotionAndItsState) {
  const Scene s = ParseScene(kCylinder +
                                 "[initial]\ntilt = [0.05]\nazimuth = [1.2]\ntilt_rate = [0.1]\n"
                                 "azimuth_rate = [2]\nspin_rate = [-0.5]\n"
                                 "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.2\n"
                                 "frequency_hz = 2\n[base.transverse]\nkind = \"harmonic\"\n"
                                 "amplitude_g = 0.2\nfrequency_hz = 2\nphase_deg = 90\n"
                                 "[model]\nlanding_clearance_rel = 1e-3\n",
                             "c.toml");
  ASSERT_TRUE(s.three_dimensional());
  const BlockDef& b = s.blocks[0];
  EXPECT_EQ(b.diameter_m, 0.5);
  EXPECT_EQ(b.width_m, 0.5);
  EXPECT_EQ(b.depth_m, 0.5);
  // m = rho pi D^2 H / 4.
  EXPECT_NEAR(b.mass_kg, 2000.0 * kPi * 0.25 * 0.25 * 1.5, 1e-12);
  EXPECT_EQ(s.initial.tilt_rad[0], 0.05);
  EXPECT_EQ(s.initial.azimuth_rad[0], 1.2);
  EXPECT_EQ(s.initial.tilt_rate_radps[0], 0.1);
  EXPECT_EQ(s.initial.azimuth_rate_radps[0], 2.0);
  EXPECT_EQ(s.initial.spin_rate_radps[0], -0.5);
  EXPECT_EQ(s.model.landing_clearance_rel, 1e-3);
  ASSERT_TRUE(s.transverse.has_value());
  EXPECT_EQ(s.transverse->phase_deg, 90.0);
  // A rotating field: x = A sin(w t), y = A sin(w t + 90 deg) = A cos(w t), |a| = A throughout.
  const GroundMotion m = GroundMotion::FromScene(s);
  const double a = 0.2 * kStandardGravity_mps2;
  for (const double t : {0.0, 0.03, 0.11, 0.4}) {
    EXPECT_NEAR(m.xg_mps2(t), a * std::sin(4 * kPi * t), 1e-12);
    EXPECT_NEAR(m.transverse_mps2(t), a * std::cos(4 * kPi * t), 1e-12);
    EXPECT_NEAR(std::hypot(m.xg_mps2(t), m.transverse_mps2(t)), a, 1e-12);
  }
  // The peak of a phased harmonic: its first crest, a quarter period less the phase.
  EXPECT_NEAR(m.transverse()->info().peak_t_s, 0.0, 1e-15);
  EXPECT_NEAR(m.horizontal()->info().peak_t_s, 0.125, 1e-15);
  EXPECT_NO_THROW(ValidateScene(s));
}

// A short window that ends before the first crest: the peak is at an end of the window.
TEST(CylinderScene, PhasedHarmonicPeakInAShortWindow) {
  const Scene s =
      ParseScene(kCylinder +
                     "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 1\nfrequency_hz = 1\n"
                     "phase_deg = 30\nduration_s = 0.1\n",
                 "c.toml");
  const GroundMotion motion = GroundMotion::FromScene(s);
  const MotionInfo& i = motion.horizontal()->info();
  // sin(30 deg) = 0.5 at the start, sin(30 + 36 deg) = 0.9135 at the end; the crest at 60 deg
  // (t = 1/6 s) is outside.
  EXPECT_NEAR(i.peak_g, std::sin(66 * kPi / 180), 1e-12);
  EXPECT_NEAR(i.peak_t_s, 0.1, 1e-15);
}

TEST(CylinderScene, RefusesWhatACylinderDoesNotTake) {
  EXPECT_EQ(ParseError("[[block]]\nshape = \"cylinder\"\nwidth = 1\ndiameter = 0.5\nheight = 1\n"
                       "density = 1\n"),
            "c.toml:3: block1.width: not used by shape = \"cylinder\" (give its diameter)");
  EXPECT_EQ(ParseError("[[block]]\nshape = \"cylinder\"\nheight = 1\ndensity = 1\n"),
            "c.toml:1: block1.diameter: missing; expected a positive number (m)");
  EXPECT_EQ(ParseError("[[block]]\nwidth = 1\ndiameter = 0.5\nheight = 1\ndensity = 1\n"),
            "c.toml:3: block1.diameter: only for shape = \"cylinder\" (a block's size is its "
            "width, height and depth)");
  EXPECT_EQ(ParseError(kCylinder + kCylinder),
            "c.toml:6: block2: a cylinder stands alone: the 3-D model is one cylinder on its base "
            "(docs/three-d.md), got a second body");
  EXPECT_EQ(ParseError("[[block]]\nwidth = 1\nheight = 2\ndensity = 1\n[base.transverse]\n"
                       "kind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 1\n"),
            "c.toml:5: base.transverse: only for bodies rocking in 3-D (shape = \"cylinder\"): a "
            "block rocks in the x-z plane under [base.horizontal] and [base.vertical]");
  EXPECT_EQ(ParseError(kCylinder + "[initial]\ntheta = [0.1]\n"),
            "c.toml:7: initial.theta: unknown key (expected one of: tilt, azimuth, tilt_rate, "
            "azimuth_rate, spin_rate)");
  EXPECT_EQ(ParseError("[[block]]\nwidth = 1\nheight = 2\ndensity = 1\n[initial]\ntilt = [0.1]\n"),
            "c.toml:6: initial.tilt: unknown key (expected one of: theta1, theta2, omega1, "
            "omega2, theta, omega)");
  EXPECT_EQ(ParseError(kCylinder + "[initial]\ntilt = [-0.1]\n"),
            "c.toml:7: initial.tilt: entry 1: expected a tilt >= 0 (rad; the azimuth gives its "
            "direction), got -0.1");
  EXPECT_EQ(ParseError(kCylinder + "[initial]\ntilt = [1.6]\n"),
            "c.toml:7: initial.tilt: expected a tilt below model.overturn_angle "
            "(1.5707963267948966 rad; the cylinder would have overturned), got 1.6");
  EXPECT_EQ(ParseError(kCylinder + "[initial]\nazimuth = [0.1, 0.2]\n"),
            "c.toml:7: initial.azimuth: expected an array of 1 numbers (rad, one per body), got 2 "
            "entries");
  EXPECT_EQ(ParseError(kCylinder + "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.1\n"
                                   "frequency_hz = 1\nphase_deg = 10\n"),
            "c.toml:10: base.horizontal.phase_deg: only for kind = \"harmonic\"");
  EXPECT_EQ(ParseError("[[block]]\nwidth = 1\nheight = 2\ndensity = 1\n[model]\n"
                       "landing_clearance_rel = 1e-3\n"),
            "c.toml:6: model.landing_clearance_rel: only for a cylinder (shape = \"cylinder\"): a "
            "block lands at theta = 0");
  EXPECT_EQ(ParseError(kCylinder + "[model]\nlanding_clearance_rel = 0.6\n"),
            "c.toml:7: model.landing_clearance_rel: expected a clearance relative to the "
            "diameter from 0 to 0.5, got 0.6");
}

// A scene built in code gets the same checks.
TEST(CylinderScene, ValidateSceneChecksACylinderBuiltInCode) {
  Scene s = ParseScene(kCylinder, "c.toml");
  s.initial.tilt_rad[0] = -0.1;
  EXPECT_EQ(ErrorOf([&] { ValidateScene(s); }),
            "c.toml: initial.tilt: expected a tilt >= 0 and below model.overturn_angle "
            "(1.5707963267948966 rad), got -0.1");
  s = ParseScene(kCylinder, "c.toml");
  s.blocks.push_back(s.blocks[0]);
  EXPECT_EQ(ErrorOf([&] { ValidateScene(s); }),
            "c.toml: block2: a cylinder stands alone: the 3-D model is one cylinder on its base, "
            "got 2 bodies");
  Scene block = ParseScene("[[block]]\nwidth = 1\nheight = 2\ndensity = 1\n", "b.toml");
  block.initial.spin_rate_radps[0] = 1.0;
  EXPECT_EQ(ErrorOf([&] { ValidateScene(block); }),
            "b.toml: initial.tilt: only for a cylinder (shape = \"cylinder\"); a block's state is "
            "theta and omega");
}

// The columns' meaning: a state's rotation and angular velocity read back as the same state;
// the start pose rolls without slip (the material contact point is still) with the contact on
// the base below the lean.
TEST(CylinderState, RoundTripAndRollingStartPose) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    CylinderState s;
    s.tilt_rad = 0.01 + 1.5 * u(rng);
    s.azimuth_rad = -3.0 + 6.0 * u(rng);
    s.spin_rad = -3.0 + 6.0 * u(rng);
    s.tilt_rate_radps = 2 * u(rng) - 1;
    s.azimuth_rate_radps = 4 * u(rng) - 2;
    s.spin_rate_radps = 4 * u(rng) - 2;
    const CylinderState b = CylinderStateOf(CylinderRotation(s), CylinderAngularVelocity(s));
    ASSERT_NEAR(b.tilt_rad, s.tilt_rad, 1e-13);
    ASSERT_NEAR(b.azimuth_rad, s.azimuth_rad, 1e-12);
    ASSERT_NEAR(b.spin_rad, s.spin_rad, 1e-12);
    ASSERT_NEAR(b.tilt_rate_radps, s.tilt_rate_radps, 1e-13);
    // The azimuth rate is omega . e1 / sin(tilt): its error grows as 1 / sin(tilt).
    ASSERT_NEAR(b.azimuth_rate_radps, s.azimuth_rate_radps, 1e-13 / std::sin(s.tilt_rad));
    ASSERT_NEAR(b.spin_rate_radps, s.spin_rate_radps, 1e-12 / std::sin(s.tilt_rad));
    // The contact point (the lowest rim point) is on the base and does not move.
    const double r = 0.25, h = 0.75;
    const Vec3d c = CylinderCentre(s, r, h), v = CylinderCentreVelocity(s, r, h);
    const Vec3d w = CylinderAngularVelocity(s);
    const Mat3d q = CylinderRotation(s);
    const double sk = std::hypot(q[2], q[5]);
    const Vec3d e1{q[8] * q[2] / sk, q[8] * q[5] / sk, -sk};
    Vec3d lever;
    for (int j = 0; j < 3; ++j) lever[j] = -h * q[3 * j + 2] + r * e1[j];
    ASSERT_NEAR(c[2] + lever[2], 0.0, 1e-14);
    ASSERT_NEAR(c[0] + lever[0], r * std::cos(s.azimuth_rad), 1e-14);
    ASSERT_NEAR(c[1] + lever[1], r * std::sin(s.azimuth_rad), 1e-14);
    const Vec3d slip{v[0] + w[1] * lever[2] - w[2] * lever[1],
                     v[1] + w[2] * lever[0] - w[0] * lever[2],
                     v[2] + w[0] * lever[1] - w[1] * lever[0]};
    for (double x : slip) ASSERT_NEAR(x, 0.0, 1e-13);
  }
  // Unwrapping: a state near the previous one keeps its turn count.
  CylinderState prev;
  prev.tilt_rad = 0.1;
  prev.azimuth_rad = 7.0;
  CylinderState s = prev;
  s.azimuth_rad = 7.05;
  EXPECT_NEAR(CylinderStateOf(CylinderRotation(s), {0, 0, 0}, &prev).azimuth_rad, 7.05, 1e-12);
}

class CylinderFiles : public testing_util::ScratchDirTest {};

// history.csv and events.csv of a cylinder: the columns, its modes named rest and rim,
// read back byte for byte.
TEST_F(CylinderFiles, HistoryColumnsAndModes) {
  History h;
  h.blocks = 1;
  h.shape = std::string(kCylinderShape);
  for (int i = 0; i < 3; ++i) {
    Sample s(1, CylinderKind());
    s.t_s = 0.01 * i;
    for (size_t q = 0; q < s.state.size(); ++q) s.state[q][0] = 0.1 * static_cast<double>(q + i);
    s.mode.set(0, i == 0 ? Contact::kFace : Contact::kRight);
    h.samples.push_back(s);
  }
  Event e(1);
  e.t_s = 0.01;
  e.kind = "initiation";
  e.mode_after.set(0, Contact::kRight);
  h.events.push_back(e);
  const std::string csv = HistoryToCsv(h);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "t,tilt1,azimuth1,spin1,tilt_x1,tilt_y1,tilt_rate1,azimuth_rate1,spin_rate1,mode");
  EXPECT_NE(csv.find(",rest\n"), std::string::npos);
  EXPECT_NE(csv.find(",rim\n"), std::string::npos);
  const std::string events = EventsToCsv(h);
  EXPECT_EQ(events.substr(0, events.find('\n')),
            "t,kind,mode_before,mode_after,tilt_rate1_before,tilt_rate1_after,energy_before_j,"
            "energy_after_j,note");
  EXPECT_NE(events.find(",initiation,rest,rim,"), std::string::npos);
  const auto path = dir_ / "history.csv";
  WriteFileAtomic(path, csv);
  const History back = ReadHistoryCsv(path);
  EXPECT_EQ(back.shape, "cylinder");
  EXPECT_EQ(HistoryToCsv(back), csv);
}

}  // namespace
}  // namespace rockbench
