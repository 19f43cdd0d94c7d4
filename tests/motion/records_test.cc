// Record readers: every shipped record against records/SOURCES.md, every AT2 header variant, and
// malformed files (errors must name the file and the line).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

const fs::path kRecords = fs::path(ROCKBENCH_SOURCE_DIR) / "records";

// One row of the table in records/SOURCES.md.
struct Shipped {
  const char* file;
  const char* format;  // "AT2", "plain-2col", "plain-1col"
  int npts;
  double dt_s;
  double peak_file_units;  // "peak (file units)" column, 4 decimals
  double dt_scene_s;       // dt for one-column files (from the script that uses the file)
};

const std::vector<Shipped> kShipped = {
    {"christchurch2011_hvsc_UP_plain_t_ms2.txt", "plain-2col", 5401, 0.005, 21.3966, 0.0},
    {"imperialvalley1940_elcentro_array9_180_PEER2000.AT2", "AT2", 4000, 0.01, 0.3129, 0.0},
    {"kobe1995_kjma_000.AT2", "AT2", 7500, 0.02, 0.8342, 0.0},
    {"kobe1995_kjma_090.AT2", "AT2", 7500, 0.02, 0.6297, 0.0},
    {"kobe1995_kjma_UP.AT2", "AT2", 7500, 0.02, 0.3389, 0.0},
    {"northridge1994_arleta_nordhoff_fire_sta_360.AT2", "AT2", 2000, 0.02, 0.3081, 0.0},
    {"northridge1994_castaic_old_ridge_route_090_plain_t_g.txt", "plain-2col", 3989, 0.01, 0.5683,
     0.0},
    {"northridge1994_rinaldi_receiving_sta_228.AT2", "AT2", 1991, 0.01, 0.8741, 0.0},
    {"northridge1994_rinaldi_receiving_sta_318.AT2", "AT2", 1991, 0.01, 0.4723, 0.0},
    {"northridge1994_rinaldi_receiving_sta_UP.AT2", "AT2", 1991, 0.01, 0.9582, 0.0},
    {"northridge1994_sylmar_converter_sta_052.AT2", "AT2", 8773, 0.005, 0.6230, 0.0},
    {"northridge1994_sylmar_converter_sta_142.AT2", "AT2", 8773, 0.005, 0.9234, 0.0},
    {"tabas1978_FN_plain_g_dt0p02.txt", "plain-1col", 2500, 0.02, 0.8999, 0.02},
};

RecordData ReadShipped(const Shipped& s) {
  const fs::path p = kRecords / s.file;
  return std::string(s.format) == "AT2" ? ReadAt2(p) : ReadPlain(p, s.dt_scene_s);
}

TEST(ShippedRecords, EveryFileIsListed) {
  // A record added to records/ without a row here (and in SOURCES.md) fails.
  std::set<std::string> listed;
  for (const auto& s : kShipped) listed.insert(s.file);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kRecords)) {
    const std::string name = entry.path().filename().string();
    if (name == "SOURCES.md") continue;
    ++files;
    EXPECT_TRUE(listed.count(name)) << name << " has no row in records_test.cc";
  }
  EXPECT_EQ(files, static_cast<int>(kShipped.size()));
}

TEST(ShippedRecords, NptsDtAndPeakMatchSources) {
  for (const auto& s : kShipped) {
    SCOPED_TRACE(s.file);
    const RecordData r = ReadShipped(s);
    EXPECT_EQ(r.format, s.format);
    EXPECT_EQ(static_cast<int>(r.values.size()), s.npts);
    // The dt of two-column files is the mean step of the time column: equal up to rounding.
    EXPECT_NEAR(r.dt_s, s.dt_s, 1e-12);
    double peak = 0.0;
    for (double v : r.values) peak = std::max(peak, std::abs(v));
    // SOURCES.md gives the peak to 4 decimals: within half a unit of the last digit.
    EXPECT_NEAR(peak, s.peak_file_units, 0.5e-4 + 1e-12);
    if (std::string(s.format) == "AT2") {
      EXPECT_EQ(r.header_units, AccelUnits::kG);
      EXPECT_GT(r.units_line, 0);
      EXPECT_EQ(r.t0_s, 0.0);
    }
  }
}

TEST(ShippedRecords, ChristchurchPgaInG) {
  // SOURCES.md: 21.3966 m/s^2 is PGA 2.182 g (3 decimals), i.e. with standard gravity 9.80665.
  MotionDef def;
  def.key = "base.vertical";
  def.file = kRecords / "christchurch2011_hvsc_UP_plain_t_ms2.txt";
  def.units = AccelUnits::kMps2;
  def.units_given = true;
  const MotionComponent c = MotionComponent::FromDef(def);
  EXPECT_NEAR(c.info().peak_g, 2.182, 0.5e-3);
  EXPECT_EQ(c.info().format, "plain-2col");
  EXPECT_EQ(c.info().npts, 5401);
  EXPECT_NEAR(c.info().duration_s, 27.0, 1e-9);
}

// Writes synthetic files into a fresh temporary folder.
class RecordFiles : public testing_util::ScratchDirTest {
 protected:
  // Expects `fn` to throw a SceneError whose message contains every piece.
  template <typename Fn>
  static void ExpectError(Fn fn, const std::vector<std::string>& pieces) {
    const std::string msg = testing_util::ErrorOf([&] { fn(); });
    for (const auto& piece : pieces) {
      EXPECT_NE(msg.find(piece), std::string::npos) << "'" << piece << "' not in: " << msg;
    }
  }

  fs::path dir_;
};

// Ten values 0.1, -0.2, ..., as a list of tokens in the given format.
const std::vector<double> kTen = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7, -0.8, 0.9, -1.0};

void ExpectTen(const RecordData& r, double dt) {
  EXPECT_EQ(r.format, "AT2");
  EXPECT_EQ(r.dt_s, dt);
  ASSERT_EQ(r.values.size(), kTen.size());
  for (size_t i = 0; i < kTen.size(); ++i) EXPECT_DOUBLE_EQ(r.values[i], kTen[i]) << i;
}

TEST_F(RecordFiles, Pre2000PeaWithCrCrLfAndBlankLines) {
  const std::string text =
      "PACIFIC ENGINEERING AND ANALYSIS STRONG-MOTION DATA\r\r\n"
      "NORTHRIDGE 01/17/94 1231, ARLETA, 360                 \r\r\n"
      "ACCELERATION TIME HISTORY IN UNITS OF G\r\r\n"
      "NPTS=    10, DT= .02000 SEC\r\r\n"
      "   .1000000E+00  -.2000000E+00   .3000000E+00  -.4000000E+00   .5000000E+00\r\r\n"
      "\r\r\n"
      "  -.6000000E+00   .7000000E+00  -.8000000E+00   .9000000E+00  -.1000000E+01\r\r\n";
  const RecordData r = ReadAt2(Write("pea.AT2", text));
  ExpectTen(r, 0.02);
  EXPECT_EQ(r.header_units, AccelUnits::kG);
  EXPECT_EQ(r.units_line, 3);
  EXPECT_EQ(r.units_text, "ACCELERATION TIME HISTORY IN UNITS OF G");
}

TEST_F(RecordFiles, Peer2000LowercaseDtWithoutSec) {
  const std::string text =
      "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY CDMG.\n"
      "CHI-CHI 09/20/99, CHY080, N\n"
      "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.05 Hz LP=50.0 Hz\n"
      "NPTS=  10, dt=  .00500\n"
      "   .1000000E+00  -.2000000E+00   .3000000E+00  -.4000000E+00   .5000000E+00\n"
      "  -.6000000E+00   .7000000E+00  -.8000000E+00   .9000000E+00  -.1000000E+01\n";
  ExpectTen(ReadAt2(Write("lower.AT2", text)), 0.005);
}

TEST_F(RecordFiles, NumbersFirstTrailerAfterSixHeaderLines) {
  const std::string text =
      "line 1\nline 2\nline 3\nline 4\nline 5\nACCELERATION IN UNITS OF G\n"
      "10 0.00500 NPTS, DT\n"
      "0.1 -0.2 0.3 -0.4 0.5 -0.6 0.7 -0.8\n"
      "0.9 -1.0\n";
  const RecordData r = ReadAt2(Write("trailer.at2", text));
  ExpectTen(r, 0.005);
  EXPECT_EQ(r.units_line, 6);
}

TEST_F(RecordFiles, NgaWest2TrailingCommaAndFilterPoles) {
  const std::string values =
      "  .1000000E+00  -.2000000E+00   .3000000E+00  -.4000000E+00   .5000000E+00\n"
      "  -.6000000E+00   .7000000E+00  -.8000000E+00   .9000000E+00  -.1000000E+01\n";
  const std::string head =
      "PEER NGA STRONG MOTION DATABASE RECORD\nNorthridge-01, 1/17/1994, Rinaldi, 228\n"
      "ACCELERATION TIME SERIES IN UNITS OF G\n";
  ExpectTen(ReadAt2(Write("a.AT2", head + "NPTS=   10, DT=   .0100 SEC,\n" + values)), 0.01);
  ExpectTen(
      ReadAt2(Write("b.AT2", head +
                                 "NPTS=   10, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 "
                                 "POLE @      .05000\n" +
                                 values)),
      0.01);
  // Re-spaced by hand (Kobe files): spaces around '=' and before the commas.
  ExpectTen(ReadAt2(Write("c.AT2", head + "NPTS =   10 , DT =   .020 SEC ,      \n" + values)),
            0.02);
  // Newer RSNs: "0.01" and values with a leading digit.
  ExpectTen(ReadAt2(Write("d.AT2", head + "NPTS=   10, DT=    0.01 SEC\n" +
                                       " 1.0000000E-01 -2.0000000E-01  3.0000000E-01 "
                                       "-4.0000000E-01  5.0000000E-01\n"
                                       "-6.0000000E-01  7.0000000E-01 -8.0000000E-01 "
                                       " 9.0000000E-01 -1.0000000E+00\n")),
            0.01);
}

TEST_F(RecordFiles, PseudoAt2EightPerLineShortLastLine) {
  const std::string text =
      "El Centro\nPeknold version\nunits of g\nNPTS=  10, DT= .02000 SEC\n"
      "   0.10000  -0.20000   0.30000  -0.40000   0.50000  -0.60000   0.70000  -0.80000\n"
      "   0.90000  -1.00000\n";
  const RecordData r = ReadAt2(Write("peknold.AT2", text));
  ExpectTen(r, 0.02);
  EXPECT_EQ(r.header_units, AccelUnits::kG);  // "units of g": case-insensitive
}

TEST_F(RecordFiles, At2AccelerationInCmPerS2WithoutUnitsOf) {
  const std::string text = "x\ny\nACCELERATION IN CM/S/S\nNPTS= 2, DT= 0.01 SEC\n1 2\n";
  const RecordData r = ReadAt2(Write("cms.AT2", text));
  EXPECT_EQ(r.header_units, AccelUnits::kCmps2);
  EXPECT_EQ(r.units_line, 3);
  EXPECT_EQ(r.values, (std::vector<double>{1.0, 2.0}));
}

// Every spelling of the units line: the units the reader finds (the values are not touched:
// conversion is MotionComponent's, see ground_motion_test.cc).
TEST_F(RecordFiles, At2HeaderUnitsSpellings) {
  struct Case {
    const char* line;
    AccelUnits units;
  };
  const std::vector<Case> cases = {
      {"ACCELERATION TIME SERIES IN UNITS OF G", AccelUnits::kG},
      {"ACCELERATION TIME HISTORY IN UNITS OF G", AccelUnits::kG},
      {"ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=15.0 Hz",
       AccelUnits::kG},
      {"Acceleration time series in units of g,", AccelUnits::kG},
      {"ACCELERATION TIME SERIES IN UNITS OF CM/S/S", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF CM/S^2", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF CM/S2", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF cm/sec**2", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF GAL", AccelUnits::kCmps2},
      {"ACCELERATION IN CM/SEC2", AccelUnits::kCmps2},
      {"ACCELERATION TIME SERIES IN UNITS OF M/S/S", AccelUnits::kMps2},
      {"ACCELERATION TIME SERIES IN UNITS OF M/S2", AccelUnits::kMps2},
      {"ACCELERATION TIME SERIES IN UNITS OF M/S^2.", AccelUnits::kMps2},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const RecordData r = ReadAt2(
        Write("u.AT2",
              std::string("PEER NGA STRONG MOTION DATABASE RECORD\nSomewhere, 1/1/2000, X, 0\n") +
                  c.line + "\nNPTS=    2, DT=   .0100 SEC,\n  .1000000E+00  -.2000000E+00\n"));
    EXPECT_EQ(r.header_units, c.units);
    EXPECT_EQ(r.units_line, 3);
    EXPECT_EQ(r.units_text, c.line);
    EXPECT_EQ(r.values, (std::vector<double>{0.1, -0.2}));
  }
}

// A header without a units line (free text, e.g. the pseudo-AT2 files of SOURCES.md) declares
// nothing: the scene's units decide, g by default (MotionComponent::FromDef).
TEST_F(RecordFiles, At2WithoutUnitsLineDeclaresNothing) {
  const RecordData r =
      ReadAt2(Write("free.AT2",
                    "El Centro\nPeknold version\nACCELERATION TIME SERIES\nNPTS= 2, DT= .02\n"
                    "0.1 0.2\n"));
  EXPECT_FALSE(r.header_units.has_value());
  EXPECT_EQ(r.units_line, 0);
}

// Velocity and displacement files (PEER's .VT2 and .DT2 share the AT2 layout) and units the
// reader does not know are refused at the header line, quoting it and saying what is expected.
TEST_F(RecordFiles, At2RefusesVelocityDisplacementAndUnknownUnits) {
  struct Case {
    const char* line;
    std::vector<std::string> pieces;
  };
  const std::vector<Case> cases = {
      {"VELOCITY TIME SERIES IN UNITS OF CM/S", {"reads acceleration", ".VT2"}},
      {"VELOCITY TIME HISTORY IN UNITS OF CM/SEC", {"reads acceleration"}},
      {"DISPLACEMENT TIME SERIES IN UNITS OF CM", {"reads acceleration", ".DT2"}},
      {"DISPLACEMENT TIME SERIES", {"reads acceleration"}},
      {"TIME SERIES IN UNITS OF CM/S", {"velocity unit", "reads acceleration"}},
      {"ACCELERATION TIME SERIES IN UNITS OF CM", {"length", "reads acceleration"}},
      {"ACCELERATION TIME SERIES IN UNITS OF FT/S/S", {"does not read", "CM/S/S", "M/S/S", "G"}},
      {"ACCELERATION TIME SERIES IN UNITS OF KM/H", {"unknown units \"KM/H\"", "CM/S/S"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const fs::path p =
        Write("v.AT2", std::string("PEER NGA STRONG MOTION DATABASE RECORD\nX, 1/1/2000\n") +
                           c.line + "\nNPTS=    2, DT=   .0100 SEC,\n  .1000000E+00  .2E+00\n");
    std::vector<std::string> pieces = c.pieces;
    pieces.push_back(p.string() + ":3:");
    pieces.push_back(std::string("\"") + c.line + "\"");
    ExpectError([&] { ReadAt2(p); }, pieces);
  }
}

// One unit of the last printed digit, in the file's units, for each notation the records use.
TEST(PrintedResolution, TokenRule) {
  EXPECT_EQ(PrintedResolution("-.1234567E-02"), 1e-9);  // AT2, E15.7
  EXPECT_EQ(PrintedResolution(".1297983E-02"), 1e-9);
  EXPECT_EQ(PrintedResolution("-1.2727865E-09"), 1e-16);  // NGA-West2, leading digit
  EXPECT_EQ(PrintedResolution("-1.65951E-03"), 1e-8);
  EXPECT_EQ(PrintedResolution("0.039111"), 1e-6);              // tabas, F
  EXPECT_EQ(PrintedResolution("-0.0248394791700000"), 1e-16);  // trailing zeros are printed
  EXPECT_EQ(PrintedResolution("0.10000"), 1e-5);
  EXPECT_EQ(PrintedResolution("12"), 1.0);
  EXPECT_EQ(PrintedResolution("12."), 1.0);
  EXPECT_EQ(PrintedResolution("+3"), 1.0);
  EXPECT_EQ(PrintedResolution("1.5e3"), 100.0);
  EXPECT_EQ(PrintedResolution("1E+05"), 1e5);
  EXPECT_EQ(PrintedResolution("-.5"), 0.1);
  EXPECT_EQ(PrintedResolution("0"), 1.0);
  EXPECT_EQ(PrintedResolution("0.0000000E+00"), 1e-7);
  for (const char* bad : {"", "-", ".", "e5", "1e", "1e+", "1.2.3", "0x10", "nan", "inf", "1,5"}) {
    EXPECT_TRUE(std::isnan(PrintedResolution(bad))) << "'" << bad << "'";
  }
}

TEST_F(RecordFiles, ResolutionOfEachSample) {
  // AT2: E15.7 values (1e-7 of the mantissa) with varying exponents, and a short F value.
  const RecordData at2 =
      ReadAt2(Write("res.AT2",
                    "a\nb\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    4, DT=   .0100 SEC,\n"
                    "  -.1234567E-02   .7654321E+00  1.0000000E-04\n 0.25\n"));
  EXPECT_EQ(at2.values, (std::vector<double>{-.1234567E-02, .7654321E+00, 1e-4, 0.25}));
  EXPECT_EQ(at2.resolution, (std::vector<double>{1e-9, 1e-7, 1e-11, 1e-2}));
  // Plain: the acceleration column (not the time column) sets the resolution.
  const RecordData two = ReadPlain(Write("res.txt", "t a\n0.000 1.5e3\n0.010 -0.03\n0.020 7\n"), 0);
  EXPECT_EQ(two.resolution, (std::vector<double>{100.0, 0.01, 1.0}));
  const RecordData one = ReadPlain(Write("one.txt", "0.039111\n-0.0248394791700000\n"), 0.02);
  EXPECT_EQ(one.resolution, (std::vector<double>{1e-6, 1e-16}));
}

TEST(ShippedRecords, ResolutionMatchesThePrintedDigits) {
  // Every shipped record: one resolution per value, and the value is a whole number of
  // resolution units. Both are the doubles nearest to decimals, so the quotient is within a few
  // ulps of that whole number (8 eps relative).
  for (const auto& s : kShipped) {
    SCOPED_TRACE(s.file);
    const RecordData r = ReadShipped(s);
    ASSERT_EQ(r.resolution.size(), r.values.size());
    for (size_t i = 0; i < r.values.size(); ++i) {
      ASSERT_GT(r.resolution[i], 0.0) << i;
      const double units = r.values[i] / r.resolution[i];
      ASSERT_NEAR(units, std::round(units),
                  8 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(units)))
          << i;
    }
  }
  const RecordData tabas = ReadShipped(kShipped.back());
  EXPECT_EQ(tabas.resolution.front(), 1e-6);  // "     0.039111"
  const RecordData christchurch = ReadShipped(kShipped.front());
  EXPECT_EQ(christchurch.resolution.front(), 1e-16);  // "-0.0248394791700000"
  const RecordData rinaldi = ReadShipped(kShipped[7]);
  EXPECT_EQ(rinaldi.resolution.front(), 1e-9);  // "-.2556093E-02"
}

TEST_F(RecordFiles, At2Truncated) {
  const std::string text =
      "a\nb\nUNITS OF G\nNPTS=  10, DT= .01 SEC\n0.1 0.2 0.3 0.4 0.5\n0.6 0.7 0.8 0.9\n";
  const fs::path p = Write("trunc.AT2", text);
  // The file ends on line 6 after 9 values; the header on line 4 says 10.
  ExpectError([&] { ReadAt2(p); }, {p.string() + ":6:", "read 9 values", "NPTS = 10", "line 4"});
}

TEST_F(RecordFiles, At2TooManyValues) {
  const std::string text = "a\nb\nc\nNPTS= 3, DT= .01 SEC\n0.1 0.2\n0.3 0.4\n";
  const fs::path p = Write("many.AT2", text);
  ExpectError([&] { ReadAt2(p); }, {p.string() + ":6:", "more values than NPTS = 3"});
}

TEST_F(RecordFiles, At2NanInfAndTextTokens) {
  const std::string head = "a\nb\nc\nNPTS= 4, DT= .01 SEC\n0.1 0.2\n";
  const fs::path nan = Write("nan.AT2", head + "NaN 0.4\n");
  ExpectError([&] { ReadAt2(nan); }, {nan.string() + ":6:", "finite", "NaN"});
  const fs::path inf = Write("inf.AT2", head + "0.3 inf\n");
  ExpectError([&] { ReadAt2(inf); }, {inf.string() + ":6:", "finite", "inf"});
  const fs::path text = Write("text.AT2", head + "0.3 0.4x\n");
  ExpectError([&] { ReadAt2(text); }, {text.string() + ":6:", "expected a number", "0.4x"});
}

TEST_F(RecordFiles, At2BadHeaders) {
  const fs::path none = Write("none.AT2", "a\nb\nc\n0.1 0.2 0.3\n");
  ExpectError([&] { ReadAt2(none); }, {none.string(), "NPTS"});
  const fs::path no_dt = Write("nodt.AT2", "a\nb\nc\nNPTS= 3, SEC\n0.1 0.2 0.3\n");
  ExpectError([&] { ReadAt2(no_dt); }, {no_dt.string() + ":4:", "NPTS and DT"});
  const fs::path zero_dt = Write("zerodt.AT2", "a\nb\nc\nNPTS= 3, DT= 0.0 SEC\n0.1 0.2 0.3\n");
  ExpectError([&] { ReadAt2(zero_dt); }, {zero_dt.string() + ":4:", "positive DT"});
  const fs::path zero_n = Write("zeron.AT2", "a\nb\nc\nNPTS= 0, DT= 0.01 SEC\n");
  ExpectError([&] { ReadAt2(zero_n); },
              {zero_n.string() + ":4:", "NPTS as a positive whole number"});
  ExpectError([&] { ReadAt2(dir_ / "missing.AT2"); },
              {(dir_ / "missing.AT2").string(), "no such record file"});
}

TEST_F(RecordFiles, PlainTwoColumnsWithHeaderTabsCommas) {
  const RecordData tabs =
      ReadPlain(Write("t.txt", "Time[s]\tAccel[g]\n\n1.00\t0.5\n1.01\t-0.25\r\n1.02\t0.125"), 0.0);
  EXPECT_EQ(tabs.format, "plain-2col");
  EXPECT_EQ(tabs.t0_s, 1.0);
  EXPECT_NEAR(tabs.dt_s, 0.01, 1e-15);
  EXPECT_EQ(tabs.values, (std::vector<double>{0.5, -0.25, 0.125}));
  const RecordData commas = ReadPlain(Write("c.csv", "t,a\n0,1\n0.5,2\n1.0,+3\n"), 0.0);
  EXPECT_EQ(commas.dt_s, 0.5);
  EXPECT_EQ(commas.values, (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST_F(RecordFiles, PlainOneColumnUsesSceneDt) {
  const fs::path p = Write("one.txt", "# accel in g\n  0.1\n -0.2\n  0.3\n");
  const RecordData r = ReadPlain(p, 0.02);
  EXPECT_EQ(r.format, "plain-1col");
  EXPECT_EQ(r.dt_s, 0.02);
  EXPECT_EQ(r.t0_s, 0.0);
  EXPECT_EQ(r.values, (std::vector<double>{0.1, -0.2, 0.3}));
  ExpectError([&] { ReadPlain(p, 0.0); }, {p.string(), "dt"});
}

TEST_F(RecordFiles, PlainMalformed) {
  // Non-uniform time column: the step ending on line 4 is 0.02 instead of 0.0133.
  const fs::path uneven = Write("uneven.txt", "t a\n0.00 1\n0.01 2\n0.03 3\n0.04 4\n");
  ExpectError([&] { ReadPlain(uneven, 0.0); }, {uneven.string() + ":4:", "uniformly spaced"});
  const fs::path backwards = Write("back.txt", "1.0 1\n0.5 2\n");
  ExpectError([&] { ReadPlain(backwards, 0.0); }, {backwards.string() + ":2:", "increase"});
  const fs::path cols = Write("cols.txt", "0 1\n0.1 2 3\n");
  ExpectError([&] { ReadPlain(cols, 0.0); }, {cols.string() + ":2:", "column"});
  const fs::path three = Write("three.txt", "0 1 2\n");
  ExpectError([&] { ReadPlain(three, 0.0); }, {three.string() + ":1:", "2 columns"});
  const fs::path text = Write("text.txt", "0 1\n0.1 2\nend of data\n");
  ExpectError([&] { ReadPlain(text, 0.0); }, {text.string() + ":3:", "expected a number"});
  const fs::path nan = Write("nan.txt", "0.1\nnan\n");
  ExpectError([&] { ReadPlain(nan, 0.01); }, {nan.string() + ":2:", "finite"});
  const fs::path empty = Write("empty.txt", "header only\n\n");
  ExpectError([&] { ReadPlain(empty, 0.01); }, {empty.string(), "no numeric data"});
  const fs::path with_dt = Write("twodt.txt", "0 1\n0.1 2\n");
  ExpectError([&] { ReadPlain(with_dt, 0.1); }, {with_dt.string(), "time column"});
  const fs::path one_row = Write("onerow.txt", "0 1\n");
  ExpectError([&] { ReadPlain(one_row, 0.0); }, {one_row.string() + ":1:", "2 rows"});
}

}  // namespace
}  // namespace rockbench
