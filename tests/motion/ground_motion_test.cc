// Base motion: units and scale, piecewise-linear records, breakpoints, analytic kinds, padding.
#include "motion/ground_motion.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "tests/common/analytic_motion.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;
const fs::path kRecords = fs::path(ROCKBENCH_SOURCE_DIR) / "records";
const fs::path kRinaldi228 = kRecords / "northridge1994_rinaldi_receiving_sta_228.AT2";

class GroundMotionTest : public testing_util::ScratchDirTest {};

MotionDef FileDef(const fs::path& file) {
  MotionDef d;
  d.key = "base.horizontal";
  d.kind = MotionKind::kFile;
  d.file = file;
  d.file_as_written = file.filename().string();
  return d;
}

TEST_F(GroundMotionTest, UnitsAndScale) {
  // One-column file, values 1, -2, 4; each unit and the scale multiply them.
  const fs::path p = Write("one.txt", "1\n-2\n4\n");
  const double g = kStandardGravity_mps2;
  struct Case {
    AccelUnits units;
    double to_mps2;
  };
  for (const Case& c :
       {Case{AccelUnits::kG, g}, Case{AccelUnits::kMps2, 1.0}, Case{AccelUnits::kCmps2, 0.01}}) {
    MotionDef d = FileDef(p);
    d.units = c.units;
    d.units_given = true;
    d.dt_s = 0.1;
    d.scale = 0.5;
    const MotionComponent m = MotionComponent::FromDef(d);
    ASSERT_EQ(m.samples_mps2().size(), 3u);
    EXPECT_DOUBLE_EQ(m.samples_mps2()[1], -2.0 * c.to_mps2 * 0.5);
    EXPECT_DOUBLE_EQ(m.accel_mps2(0.2), 4.0 * c.to_mps2 * 0.5);
    EXPECT_DOUBLE_EQ(m.info().peak_g, 4.0 * c.to_mps2 * 0.5 / g);
    EXPECT_DOUBLE_EQ(m.info().peak_t_s, 0.2);
    EXPECT_EQ(m.info().format, "plain-1col");
  }
}

TEST_F(GroundMotionTest, PlainFileWithoutUnitsIsAnError) {
  MotionDef d = FileDef(Write("one.txt", "1\n2\n"));
  d.dt_s = 0.1;
  EXPECT_THROW(MotionComponent::FromDef(d), SceneError);
}

TEST_F(GroundMotionTest, At2InGAndConflictingUnits) {
  MotionDef d = FileDef(kRinaldi228);
  d.scale = 0.5;
  const MotionComponent m = MotionComponent::FromDef(d);
  const RecordData raw = ReadAt2(kRinaldi228);
  ASSERT_EQ(m.samples_mps2().size(), raw.values.size());
  for (size_t i = 0; i < raw.values.size(); ++i) {
    ASSERT_DOUBLE_EQ(m.samples_mps2()[i], raw.values[i] * kStandardGravity_mps2 * 0.5);
  }
  // MotionInfo: SOURCES.md gives PGA 0.8741 g; the scale halves it.
  const MotionInfo& info = m.info();
  EXPECT_EQ(info.source, "northridge1994_rinaldi_receiving_sta_228.AT2");
  EXPECT_EQ(info.format, "AT2");
  EXPECT_EQ(info.npts, 1991);
  EXPECT_EQ(info.dt_s, 0.01);
  EXPECT_NEAR(info.duration_s, 19.9, 1e-12);
  EXPECT_NEAR(info.peak_g, 0.5 * 0.8741, 0.5 * 0.5e-4);
  const auto peak_at =
      std::max_element(raw.values.begin(), raw.values.end(),
                       [](double a, double b) { return std::abs(a) < std::abs(b); });
  EXPECT_DOUBLE_EQ(info.peak_t_s, 0.01 * static_cast<double>(peak_at - raw.values.begin()));
  // Units given as g: fine; as m/s2 against a header in g: an error naming the header line.
  d.units_given = true;
  d.units = AccelUnits::kG;
  EXPECT_NO_THROW(MotionComponent::FromDef(d));
  d.units = AccelUnits::kMps2;
  const std::string msg = testing_util::ErrorOf([&] { MotionComponent::FromDef(d); });
  EXPECT_NE(msg.find(kRinaldi228.string() + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("UNITS OF G"), std::string::npos) << msg;
}

TEST_F(GroundMotionTest, PiecewiseLinearAndZeroOutside) {
  const std::vector<double> a = {0.0, 1.0, 3.0, -1.0};
  const double t0 = 0.5, dt = 0.1;
  const MotionComponent m = MotionComponent::FromSamples(a, dt, t0, "test");
  // At the sample times t0 + i dt: the samples, exactly.
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(m.accel_mps2(t0 + static_cast<double>(i) * dt), a[i]) << i;
  }
  // Between samples: linear (1e-12 allows for rounding of the fractions).
  EXPECT_NEAR(m.accel_mps2(0.55), 0.5, 1e-12);
  EXPECT_NEAR(m.accel_mps2(0.625), 1.0 + 0.25 * 2.0, 1e-12);
  EXPECT_NEAR(m.accel_mps2(0.79), 3.0 + 0.9 * (-4.0), 1e-12);
  // Zero before the first and after the last sample.
  EXPECT_EQ(m.accel_mps2(0.0), 0.0);
  EXPECT_EQ(m.accel_mps2(std::nextafter(t0, 0.0)), 0.0);
  EXPECT_EQ(m.accel_mps2(std::nextafter(m.end_s(), 10.0)), 0.0);
  EXPECT_EQ(m.accel_mps2(5.0), 0.0);
  EXPECT_DOUBLE_EQ(m.end_s(), 0.8);
  EXPECT_EQ(m.info().format, "samples");
  EXPECT_DOUBLE_EQ(m.info().peak_g, 3.0 / kStandardGravity_mps2);
  EXPECT_DOUBLE_EQ(m.info().peak_t_s, 0.7);
}

// piece_at serves an integrator that asks for many times inside one sample interval: its
// piece must give accel_mps2's value bit for bit wherever it holds t (the reference's outputs
// rest on that), at sample times, between them, at both ends of the record and at times whose
// index arithmetic rounds to the neighbouring interval (dt = 0.01 is not a binary fraction).
TEST_F(GroundMotionTest, PieceAtGivesAccelBitForBit) {
  std::vector<double> a;
  for (int i = 0; i < 200; ++i) a.push_back(std::sin(0.37 * i) + 0.01 * i);
  const double t0 = 0.3, dt = 0.01;
  const MotionComponent m = MotionComponent::FromSamples(a, dt, t0, "test");
  const double t_last = t0 + 199 * dt;
  std::vector<double> times = {t0, t_last, std::nextafter(t_last, 0.0)};
  for (int i = 0; i < 200; ++i) {
    const double ti = t0 + i * dt;
    times.insert(times.end(), {ti, std::nextafter(ti, 0.0), std::nextafter(ti, 1e9), ti + 0.37 * dt,
                               ti + 0.5 * dt});
  }
  int held = 0;
  for (const double t : times) {
    const MotionComponent::LinearPiece piece = m.piece_at(t);
    if (!(t >= t0 && t <= t_last)) {
      EXPECT_FALSE(piece.valid) << t;
      continue;
    }
    ASSERT_TRUE(piece.Holds(t)) << t;
    EXPECT_EQ(piece.At(t), m.accel_mps2(t)) << t;
    // Every other time the same piece holds gets the same value too.
    for (const double u : {piece.t_lo, piece.t_hi, 0.5 * (piece.t_lo + piece.t_hi)}) {
      EXPECT_EQ(piece.At(u), m.accel_mps2(u)) << u;
    }
    ++held;
  }
  EXPECT_GT(held, 900);
  // Outside the samples, and for analytic kinds, there is no piece.
  EXPECT_FALSE(m.piece_at(std::nextafter(t0, 0.0)).valid);
  EXPECT_FALSE(m.piece_at(std::nextafter(t_last, 1e9)).valid);
  MotionDef sine;
  sine.kind = MotionKind::kSinePulse;
  sine.amplitude_g = 0.3;
  sine.frequency_hz = 2.0;
  EXPECT_FALSE(MotionComponent::FromDef(sine).piece_at(0.1).valid);
}

TEST_F(GroundMotionTest, RecordAtEverySampleTimeIsTheSample) {
  MotionDef d = FileDef(kRinaldi228);
  d.start_s = 1.5;
  const MotionComponent m = MotionComponent::FromDef(d);
  const auto& s = m.samples_mps2();
  EXPECT_EQ(m.t0_s(), 1.5);
  for (size_t i = 0; i < s.size(); ++i) {
    const double t = m.t0_s() + static_cast<double>(i) * m.dt_s();
    ASSERT_EQ(m.accel_mps2(t), s[i]) << i;
    // Half-way: the mean of the neighbours (1e-12 relative: rounding of t and the fraction).
    if (i + 1 < s.size()) {
      const double mid = m.accel_mps2(t + 0.5 * m.dt_s());
      ASSERT_NEAR(mid, 0.5 * (s[i] + s[i + 1]),
                  1e-12 * (std::abs(s[i]) + std::abs(s[i + 1])) + 1e-15);
    }
  }
  EXPECT_EQ(m.accel_mps2(1.4999), 0.0);
}

TEST_F(GroundMotionTest, TwoColumnFileStartsAtItsOwnTimePlusStart) {
  MotionDef d = FileDef(Write("two.txt", "t a\n2.0 1\n2.5 2\n3.0 3\n"));
  d.units = AccelUnits::kMps2;
  d.units_given = true;
  d.start_s = 1.0;
  const MotionComponent m = MotionComponent::FromDef(d);
  EXPECT_EQ(m.t0_s(), 3.0);
  EXPECT_EQ(m.accel_mps2(3.0), 1.0);
  EXPECT_EQ(m.accel_mps2(4.0), 3.0);
  EXPECT_EQ(m.accel_mps2(2.9), 0.0);
  EXPECT_EQ(m.next_breakpoint_after(0.0), 3.0);
  EXPECT_EQ(m.end_s(), 4.0);
}

TEST_F(GroundMotionTest, RecordBreakpoints) {
  const MotionComponent m = MotionComponent::FromSamples({1.0, 2.0, 3.0, 4.0}, 0.25, 1.0, "test");
  EXPECT_EQ(m.next_breakpoint_after(-3.0), 1.0);
  EXPECT_EQ(m.next_breakpoint_after(std::nextafter(1.0, 0.0)), 1.0);
  EXPECT_EQ(m.next_breakpoint_after(1.0), 1.25);  // strictly after
  EXPECT_EQ(m.next_breakpoint_after(1.3), 1.5);
  EXPECT_EQ(m.next_breakpoint_after(1.5), 1.75);
  EXPECT_EQ(m.next_breakpoint_after(1.74), 1.75);
  EXPECT_EQ(m.next_breakpoint_after(1.75), kInf);
  EXPECT_EQ(m.next_breakpoint_after(9.0), kInf);
}

TEST_F(GroundMotionTest, WalkingBreakpointsVisitsEverySampleOfARecord) {
  // 0.01 s steps do not add up exactly in binary: each breakpoint must still be strictly later
  // and be the next sample time.
  MotionDef d = FileDef(kRinaldi228);
  d.start_s = 0.3;
  const MotionComponent m = MotionComponent::FromDef(d);
  double t = -1.0;
  size_t count = 0;
  for (double next = m.next_breakpoint_after(t); std::isfinite(next);
       next = m.next_breakpoint_after(t)) {
    ASSERT_GT(next, t);
    ASSERT_EQ(next, m.t0_s() + static_cast<double>(count) * m.dt_s()) << count;
    t = next;
    ++count;
  }
  EXPECT_EQ(count, m.samples_mps2().size());
  EXPECT_EQ(t, m.end_s());
}

// Formulas of the README, written out independently of the implementation.
double Expected(MotionKind kind, double a_mps2, double f, double t0, double length, double t) {
  // Closed window [t0, t0 + length], compared in absolute time as the README states it.
  if (!(t >= t0 && t <= t0 + length)) return 0.0;
  const double tau = t - t0;
  switch (kind) {
    case MotionKind::kHarmonic:
    case MotionKind::kSinePulse:
      return a_mps2 * std::sin(2 * kPi * f * tau);
    case MotionKind::kCosinePulse:
      return a_mps2 * std::cos(2 * kPi * f * tau);
    case MotionKind::kRectangularPulse:
      return a_mps2;
    case MotionKind::kRicker: {
      const double s = tau - 1 / f;
      return a_mps2 * (1 - 2 * kPi * kPi * f * f * s * s) * std::exp(-kPi * kPi * f * f * s * s);
    }
    case MotionKind::kFile:
    case MotionKind::kKanaiTajimi:  // sampled: synthetic_motion_test.cc
      break;
  }
  return 0.0;
}

TEST_F(GroundMotionTest, AnalyticKindsFollowTheirFormulas) {
  const double g = kStandardGravity_mps2, amp = 0.3, f = 2.0, t0 = 0.7, scale = 1.5;
  struct Case {
    MotionKind kind;
    double duration;  // as given in the scene
    double length;    // active window
  };
  const std::vector<Case> cases = {
      {MotionKind::kHarmonic, 1.3, 1.3},         {MotionKind::kHarmonic, kInf, kInf},
      {MotionKind::kSinePulse, kInf, 1 / f},     {MotionKind::kCosinePulse, kInf, 1 / f},
      {MotionKind::kRectangularPulse, 0.8, 0.8}, {MotionKind::kRicker, kInf, 2 / f}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(MotionKindName(c.kind)) + " length " + std::to_string(c.length));
    MotionDef d = testing_util::AnalyticMotion(c.kind, amp, f, t0, c.duration);
    d.scale = scale;
    const MotionComponent m = MotionComponent::FromDef(d);
    const double a = amp * scale * g;
    const double end = t0 + c.length;
    EXPECT_EQ(m.end_s(), end);
    EXPECT_EQ(m.info().format, "analytic");
    EXPECT_EQ(m.info().source, MotionKindName(c.kind));
    EXPECT_EQ(m.info().npts, 0);
    // Before the start: zero; at the start and at the end (closed window): the formula.
    EXPECT_EQ(m.accel_mps2(t0 - 1e-9), 0.0);
    EXPECT_EQ(m.accel_mps2(0.0), 0.0);
    EXPECT_NEAR(m.accel_mps2(t0), Expected(c.kind, a, f, t0, c.length, t0), 1e-12);
    if (std::isfinite(end)) {
      EXPECT_NEAR(m.accel_mps2(end), Expected(c.kind, a, f, t0, c.length, end), 1e-12);
      EXPECT_EQ(m.accel_mps2(end + 1e-9), 0.0);
      EXPECT_EQ(m.accel_mps2(end + 10.0), 0.0);
    }
    // Inside: a spread of times (1e-12 m/s^2: same formula, rounding only).
    for (double frac : {0.05, 0.125, 0.25, 0.3, 0.5, 0.61, 0.75, 0.99}) {
      const double span = std::isfinite(c.length) ? c.length : 3.0;
      const double t = t0 + frac * span;
      EXPECT_NEAR(m.accel_mps2(t), Expected(c.kind, a, f, t0, c.length, t), 1e-12) << t;
    }
    // Breakpoints: the start, then the end (none for a never-ending harmonic).
    EXPECT_EQ(m.next_breakpoint_after(0.0), t0);
    EXPECT_EQ(m.next_breakpoint_after(t0), end);
    EXPECT_EQ(m.next_breakpoint_after(t0 + 0.01), end);
    if (std::isfinite(end)) {
      EXPECT_EQ(m.next_breakpoint_after(end), kInf);
    }
    // The peak in MotionInfo (exact) against dense sampling of the window: 1e5 samples put the
    // sampled peak within (2 pi f dt)^2 / 2 ~ 1e-8 relative of the true one.
    const double span = std::isfinite(c.length) ? c.length : 2.0 / f;
    double peak = 0.0;
    for (int i = 0; i <= 100000; ++i) {
      peak = std::max(peak, std::abs(m.accel_mps2(t0 + span * i / 100000.0)));
    }
    EXPECT_NEAR(m.info().peak_g, peak / g, 1e-7 * amp * scale);
    EXPECT_GE(m.info().peak_t_s, t0);
    EXPECT_NEAR(std::abs(m.accel_mps2(m.info().peak_t_s)) / g, m.info().peak_g, 1e-12);
  }
}

TEST_F(GroundMotionTest, RickerPeakIsAgAtT0PlusOneOverF) {
  const double g = kStandardGravity_mps2, amp = -0.45, f = 1.6, t0 = 0.25;
  const MotionComponent m =
      MotionComponent::FromDef(testing_util::AnalyticMotion(MotionKind::kRicker, amp, f, t0));
  EXPECT_DOUBLE_EQ(m.accel_mps2(t0 + 1 / f), amp * g);
  EXPECT_DOUBLE_EQ(m.info().peak_t_s, t0 + 1 / f);
  EXPECT_DOUBLE_EQ(m.info().peak_g, 0.45);
  // Symmetric about the peak (rounding of the two times only).
  EXPECT_NEAR(m.accel_mps2(t0 + 1 / f - 0.2), m.accel_mps2(t0 + 1 / f + 0.2), 1e-12);
}

TEST_F(GroundMotionTest, ShortHarmonicPeakIsAtItsEnd) {
  // 0.1 s of a 2 Hz sine stops before the crest at 0.125 s: peak sin(2 pi 2 0.1) = 0.951.
  const MotionComponent m = MotionComponent::FromDef(
      testing_util::AnalyticMotion(MotionKind::kHarmonic, 1.0, 2.0, 0.0, 0.1));
  EXPECT_NEAR(m.info().peak_g, std::sin(2 * kPi * 0.2), 1e-15);
  EXPECT_DOUBLE_EQ(m.info().peak_t_s, 0.1);
}

TEST_F(GroundMotionTest, PadsTheShorterOfTwoRecords) {
  const fs::path h = Write("h.txt", "1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n");
  const fs::path v = Write("v.txt", "1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n12\n13\n14\n15\n");
  Scene scene;
  scene.blocks = {BlockDef{1.0, 2.0, 1.0, 100.0, 0.0}};
  scene.horizontal = FileDef(h);
  scene.horizontal->units = AccelUnits::kMps2;
  scene.horizontal->units_given = true;
  scene.horizontal->dt_s = 0.01;
  scene.vertical = *scene.horizontal;
  scene.vertical->key = "base.vertical";
  scene.vertical->file = v;
  const GroundMotion gm = GroundMotion::FromScene(scene);
  ASSERT_TRUE(gm.has_horizontal() && gm.has_vertical());
  EXPECT_EQ(gm.horizontal()->samples_mps2().size(), 15u);
  EXPECT_EQ(gm.horizontal()->info().padded_samples, 5);
  EXPECT_EQ(gm.horizontal()->info().npts, 10);  // as read
  EXPECT_EQ(gm.vertical()->info().padded_samples, 0);
  EXPECT_DOUBLE_EQ(gm.horizontal()->end_s(), gm.vertical()->end_s());
  EXPECT_NEAR(gm.xg_mps2(0.09), 10.0, 1e-12);
  EXPECT_NEAR(gm.xg_mps2(0.095), 5.0, 1e-12);  // ramps down to the first padded zero
  EXPECT_EQ(gm.xg_mps2(0.12), 0.0);
  EXPECT_NEAR(gm.yg_mps2(0.12), 13.0, 1e-12);
  EXPECT_DOUBLE_EQ(gm.end_s(), 0.14);
}

TEST_F(GroundMotionTest, PadsShippedRecordsOfDifferentLengths) {
  // Rinaldi 228 (1991 samples at 0.01 s, 19.90 s) with Kobe KJMA UP (7500 at 0.02 s, 149.98 s):
  // the horizontal gets zeros up to 149.98 s, i.e. 14999 samples in all.
  Scene scene;
  scene.blocks = {BlockDef{1.0, 2.0, 1.0, 100.0, 0.0}};
  scene.horizontal = FileDef(kRinaldi228);
  scene.vertical = FileDef(kRecords / "kobe1995_kjma_UP.AT2");
  scene.vertical->key = "base.vertical";
  const GroundMotion gm = GroundMotion::FromScene(scene);
  EXPECT_EQ(gm.horizontal()->info().padded_samples, 14999 - 1991);
  EXPECT_EQ(gm.vertical()->info().padded_samples, 0);
  EXPECT_NEAR(gm.horizontal()->end_s(), 149.98, 1e-9);
  EXPECT_EQ(gm.xg_mps2(100.0), 0.0);
  EXPECT_NE(gm.yg_mps2(100.0), 0.0);
  EXPECT_NEAR(gm.end_s(), 149.98, 1e-9);
}

TEST_F(GroundMotionTest, CombinedBreakpointsAndEmptyMotion) {
  GroundMotion none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.end_s(), 0.0);
  EXPECT_EQ(none.next_breakpoint_after(0.0), kInf);
  EXPECT_EQ(none.xg_mps2(1.0), 0.0);
  EXPECT_EQ(none.yg_mps2(1.0), 0.0);

  GroundMotion gm;
  gm.set_horizontal(MotionComponent::FromSamples({1.0, 2.0, 3.0}, 0.5, 0.0, "h"));
  gm.set_vertical(MotionComponent::FromDef(
      testing_util::AnalyticMotion(MotionKind::kRectangularPulse, 0.1, 0.0, 0.2, 0.6)));
  EXPECT_EQ(gm.next_breakpoint_after(0.0), 0.2);        // pulse start
  EXPECT_EQ(gm.next_breakpoint_after(0.2), 0.5);        // sample
  EXPECT_EQ(gm.next_breakpoint_after(0.5), 0.2 + 0.6);  // pulse end
  EXPECT_EQ(gm.next_breakpoint_after(0.2 + 0.6), 1.0);  // last sample
  EXPECT_EQ(gm.next_breakpoint_after(1.0), kInf);
  EXPECT_EQ(gm.end_s(), 1.0);
  EXPECT_DOUBLE_EQ(gm.yg_mps2(0.5), 0.1 * kStandardGravity_mps2);
}

TEST_F(GroundMotionTest, FromSamplesRejectsBadInput) {
  EXPECT_THROW(MotionComponent::FromSamples({}, 0.1, 0.0, "x"), SceneError);
  EXPECT_THROW(MotionComponent::FromSamples({1.0}, 0.0, 0.0, "x"), SceneError);
  EXPECT_THROW(MotionComponent::FromSamples({1.0, NAN}, 0.1, 0.0, "x"), SceneError);
}

// The units an AT2 header declares decide the conversion; the scene's units must agree, and
// acceleration in units other than g is read only when the scene says which.
TEST_F(GroundMotionTest, At2HeaderUnitsDecideTheConversion) {
  const auto at2 = [&](const std::string& name, const std::string& units_line) {
    return Write(name, "PEER NGA STRONG MOTION DATABASE RECORD\nSomewhere, 1/1/2000, X, 0\n" +
                           units_line +
                           "\nNPTS=    3, DT=   .0100 SEC,\n  .1000000E+03"
                           "  -.2000000E+03   .5000000E+02\n");
  };
  const std::vector<double> raw = {100.0, -200.0, 50.0};
  const auto expect_error = [](const MotionDef& d, const std::vector<std::string>& pieces) {
    const std::string msg = testing_util::ErrorOf([&] { MotionComponent::FromDef(d); });
    for (const auto& piece : pieces) {
      EXPECT_NE(msg.find(piece), std::string::npos) << "'" << piece << "' not in: " << msg;
    }
  };
  struct Case {
    const char* units_line;
    AccelUnits units;
    double to_mps2;
  };
  for (const Case& c :
       {Case{"ACCELERATION TIME SERIES IN UNITS OF CM/S/S", AccelUnits::kCmps2, 0.01},
        Case{"ACCELERATION TIME SERIES IN UNITS OF GAL", AccelUnits::kCmps2, 0.01},
        Case{"ACCELERATION TIME SERIES IN UNITS OF M/S2", AccelUnits::kMps2, 1.0}}) {
    SCOPED_TRACE(c.units_line);
    const fs::path p = at2("cms.AT2", c.units_line);
    MotionDef d = FileDef(p);
    const std::string units = "\"" + std::string(AccelUnitsName(c.units)) + "\"";
    // No units in the scene: refused (read as g it would be 981 or 9.8 times too strong).
    expect_error(d, {p.string() + ":3:", std::string("\"") + c.units_line + "\"",
                     "base.horizontal.units = " + units});
    // The scene says the same units: converted with them, times the scale.
    d.units_given = true;
    d.units = c.units;
    d.scale = -2.0;
    const MotionComponent m = MotionComponent::FromDef(d);
    ASSERT_EQ(m.samples_mps2().size(), raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
      EXPECT_DOUBLE_EQ(m.samples_mps2()[i], raw[i] * c.to_mps2 * -2.0) << i;
    }
    EXPECT_DOUBLE_EQ(m.info().peak_g, 200.0 * c.to_mps2 * 2.0 / kStandardGravity_mps2);
    // Other units in the scene: refused, naming both.
    for (AccelUnits other : {AccelUnits::kG, AccelUnits::kMps2, AccelUnits::kCmps2}) {
      if (other == c.units) continue;
      d.units = other;
      expect_error(d, {p.string() + ":3:", std::string("\"") + c.units_line + "\"",
                       "base.horizontal.units is \"" + std::string(AccelUnitsName(other)) + "\"",
                       "use units = " + units});
    }
  }
  // A header in g: read as g; a scene saying otherwise is refused (as before). -200 g is past
  // the physical limit (100 g, scene/limits.h): refused naming the line and the sample; scaled
  // by 0.25 it is -50 g and read.
  MotionDef g = FileDef(at2("g.AT2", "ACCELERATION TIME SERIES IN UNITS OF G"));
  expect_error(g, {"g.AT2:5: sample 2 = -200 g;", "at most 100 g"});
  g.scale = 0.25;
  EXPECT_DOUBLE_EQ(MotionComponent::FromDef(g).samples_mps2()[1], -50.0 * kStandardGravity_mps2);
  g.scale = 0.6;
  expect_error(g, {"g.AT2:5: sample 2 = -200 g times base.horizontal.scale = 0.6 is -120 g;"});
  g.scale = 1.0;
  g.units_given = true;
  g.units = AccelUnits::kCmps2;
  expect_error(g, {":3:", "\"ACCELERATION TIME SERIES IN UNITS OF G\"", "omit units or use \"g\""});
  // Velocity: refused whatever the scene says.
  MotionDef v = FileDef(at2("v.AT2", "VELOCITY TIME SERIES IN UNITS OF CM/S"));
  v.units_given = true;
  v.units = AccelUnits::kCmps2;
  expect_error(v, {":3:", "\"VELOCITY TIME SERIES IN UNITS OF CM/S\"", "reads acceleration"});
  // No units line: g unless the scene says otherwise (the header cannot contradict it).
  MotionDef none = FileDef(at2("none.AT2", "free text"));
  none.scale = 0.25;
  EXPECT_DOUBLE_EQ(MotionComponent::FromDef(none).samples_mps2()[0], 25.0 * kStandardGravity_mps2);
  none.scale = 1.0;
  none.units_given = true;
  none.units = AccelUnits::kCmps2;
  EXPECT_DOUBLE_EQ(MotionComponent::FromDef(none).samples_mps2()[0], 1.0);
}

// The unit g is standard gravity, 9.80665 m/s^2: [run] gravity (the simulation's gravitational
// acceleration) does not rescale a record in g, an analytic amplitude_g, or peak_g.
TEST_F(GroundMotionTest, RunGravityDoesNotRescaleTheBaseMotion) {
  Scene scene;
  scene.blocks = {BlockDef{1.0, 2.0, 1.0, 100.0, 0.0}};
  scene.horizontal = FileDef(kRinaldi228);
  scene.vertical = testing_util::AnalyticMotion(MotionKind::kHarmonic, 0.2, 3.0, 0.0, 1.0);
  scene.vertical->key = "base.vertical";
  scene.run.gravity_mps2 = 9.81;
  const GroundMotion earth = GroundMotion::FromScene(scene);
  scene.run.gravity_mps2 = 3.71;
  const GroundMotion mars = GroundMotion::FromScene(scene);
  const RecordData raw = ReadAt2(kRinaldi228);
  ASSERT_EQ(earth.horizontal()->samples_mps2().size(), raw.values.size());
  for (size_t i = 0; i < raw.values.size(); ++i) {
    ASSERT_EQ(earth.horizontal()->samples_mps2()[i], raw.values[i] * kStandardGravity_mps2) << i;
    ASSERT_EQ(mars.horizontal()->samples_mps2()[i], earth.horizontal()->samples_mps2()[i]) << i;
  }
  for (double t : {0.0, 0.05, 0.2, 0.5, 0.77, 1.0}) {
    EXPECT_EQ(earth.yg_mps2(t), mars.yg_mps2(t)) << t;
    // The formula with A = 0.2 x 9.80665 m/s^2 (1e-14 m/s^2: rounding of the same operations).
    EXPECT_NEAR(earth.yg_mps2(t), 0.2 * 9.80665 * std::sin(2 * kPi * 3.0 * t), 1e-14) << t;
  }
  EXPECT_EQ(earth.horizontal()->info().peak_g, mars.horizontal()->info().peak_g);
  // SOURCES.md: PGA 0.8741 g (4 decimals), the file's own number, in standard g.
  EXPECT_NEAR(earth.horizontal()->info().peak_g, 0.8741, 0.5e-4);
  EXPECT_EQ(earth.vertical()->info().peak_g, 0.2);
}

// Each sample's printed precision, converted like the sample; exact zeros for padding.
TEST_F(GroundMotionTest, SampleResolution) {
  MotionDef d = FileDef(Write("one.txt", "1.25\n-0.002\n4\n"));
  d.units = AccelUnits::kCmps2;
  d.units_given = true;
  d.dt_s = 0.1;
  d.scale = -2.0;
  MotionComponent m = MotionComponent::FromDef(d);
  // One unit of the last digit (0.01, 0.001, 1) in cm/s^2, times 0.01 and |scale|.
  ASSERT_EQ(m.sample_resolution_mps2().size(), 3u);
  EXPECT_DOUBLE_EQ(m.sample_resolution_mps2()[0], 0.01 * 0.01 * 2.0);
  EXPECT_DOUBLE_EQ(m.sample_resolution_mps2()[1], 0.001 * 0.01 * 2.0);
  EXPECT_DOUBLE_EQ(m.sample_resolution_mps2()[2], 1.0 * 0.01 * 2.0);
  m.pad_to(0.45);
  ASSERT_EQ(m.samples_mps2().size(), 6u);
  ASSERT_EQ(m.sample_resolution_mps2().size(), 6u);
  for (size_t i = 3; i < 6; ++i) EXPECT_EQ(m.sample_resolution_mps2()[i], 0.0) << i;
  // A shipped AT2 record in g: E15.7 values, e.g. -.2556093E-02 g, known to 1e-9 g.
  const MotionComponent rinaldi = MotionComponent::FromDef(FileDef(kRinaldi228));
  ASSERT_EQ(rinaldi.sample_resolution_mps2().size(), rinaldi.samples_mps2().size());
  EXPECT_DOUBLE_EQ(rinaldi.sample_resolution_mps2()[0], 1e-9 * kStandardGravity_mps2);
  // Analytic kinds: none; FromSamples: as given.
  EXPECT_TRUE(
      MotionComponent::FromDef(testing_util::AnalyticMotion(MotionKind::kSinePulse, 0.1, 1.0, 0.0))
          .sample_resolution_mps2()
          .empty());
  EXPECT_TRUE(
      MotionComponent::FromSamples({1.0, 2.0}, 0.1, 0.0, "s").sample_resolution_mps2().empty());
  EXPECT_EQ(
      MotionComponent::FromSamples({1.0, 2.0}, 0.1, 0.0, "s", {0.5, 0.25}).sample_resolution_mps2(),
      (std::vector<double>{0.5, 0.25}));
  EXPECT_THROW(MotionComponent::FromSamples({1.0, 2.0}, 0.1, 0.0, "s", {0.5}), SceneError);
  EXPECT_THROW(MotionComponent::FromSamples({1.0, 2.0}, 0.1, 0.0, "s", {0.5, -1.0}), SceneError);
  EXPECT_THROW(MotionComponent::FromSamples({1.0, 2.0}, 0.1, 0.0, "s", {0.5, NAN}), SceneError);
}

TEST_F(GroundMotionTest, ScaledCopies) {
  const MotionComponent rec =
      MotionComponent::FromSamples({1.0, -3.0, 2.0}, 0.1, 0.5, "rec", {0.01, 0.02, 0.04});
  const MotionComponent half = rec.Scaled(-0.5);
  EXPECT_EQ(half.samples_mps2(), (std::vector<double>{-0.5, 1.5, -1.0}));
  EXPECT_EQ(half.sample_resolution_mps2(), (std::vector<double>{0.005, 0.01, 0.02}));
  EXPECT_DOUBLE_EQ(half.info().peak_g, 1.5 / kStandardGravity_mps2);
  EXPECT_DOUBLE_EQ(half.info().peak_t_s, 0.6);
  EXPECT_EQ(half.info().source, "rec");
  EXPECT_EQ(half.t0_s(), 0.5);
  EXPECT_EQ(half.dt_s(), 0.1);
  EXPECT_EQ(half.accel_mps2(0.65), -0.5 * rec.accel_mps2(0.65));
  EXPECT_EQ(rec.samples_mps2()[1], -3.0);  // the original is untouched
  // Analytic: the amplitude, everywhere; the exact peak follows.
  const MotionComponent pulse =
      MotionComponent::FromDef(testing_util::AnalyticMotion(MotionKind::kRicker, 0.3, 2.0, 0.1));
  const MotionComponent more = pulse.Scaled(1.01);
  // The amplitude is scaled before the shape multiplies it: equal to an ulp or two.
  for (double t : {0.1, 0.3, 0.6, 0.9}) {
    EXPECT_DOUBLE_EQ(more.accel_mps2(t), 1.01 * pulse.accel_mps2(t)) << t;
  }
  EXPECT_DOUBLE_EQ(more.info().peak_g, 0.3 * 1.01);
  EXPECT_EQ(more.info().peak_t_s, pulse.info().peak_t_s);
  EXPECT_TRUE(more.sample_resolution_mps2().empty());
  EXPECT_DOUBLE_EQ(pulse.Scaled(-2.0).info().peak_g, 0.6);
  EXPECT_THROW(rec.Scaled(NAN), std::invalid_argument);
  EXPECT_THROW(pulse.Scaled(INFINITY), std::invalid_argument);
}

TEST_F(GroundMotionTest, WithSamplesKeepsTheRecordAndRecomputesThePeak) {
  MotionDef d = FileDef(Write("one.txt", "1.0\n-3.0\n2.0\n"));
  d.units = AccelUnits::kMps2;
  d.units_given = true;
  d.dt_s = 0.1;
  MotionComponent rec = MotionComponent::FromDef(d);
  rec.pad_to(0.4);
  const MotionComponent other = rec.WithSamples({1.0, -3.0, 4.5, 0.0, 0.0});
  EXPECT_EQ(other.samples_mps2(), (std::vector<double>{1.0, -3.0, 4.5, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(other.info().peak_g, 4.5 / kStandardGravity_mps2);
  EXPECT_DOUBLE_EQ(other.info().peak_t_s, 0.2);
  EXPECT_EQ(other.sample_resolution_mps2(), rec.sample_resolution_mps2());
  EXPECT_EQ(other.info().source, "one.txt");
  EXPECT_EQ(other.info().format, "plain-1col");
  EXPECT_EQ(other.info().npts, 3);
  EXPECT_EQ(other.info().padded_samples, 2);
  EXPECT_EQ(other.t0_s(), rec.t0_s());
  EXPECT_EQ(other.dt_s(), rec.dt_s());
  EXPECT_EQ(other.end_s(), rec.end_s());
  EXPECT_THROW(rec.WithSamples({1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(rec.WithSamples({1.0, 2.0, 3.0, 4.0, NAN}), std::invalid_argument);
  const MotionComponent pulse =
      MotionComponent::FromDef(testing_util::AnalyticMotion(MotionKind::kSinePulse, 0.3, 2.0, 0.0));
  EXPECT_THROW(pulse.WithSamples({}), std::invalid_argument);
}

}  // namespace
}  // namespace rockbench
