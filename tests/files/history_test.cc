// History and event CSV files, reading them back, and atomic writes.
#include "scene/history.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/outcome.h"
#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "scene/body_kind.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

class HistoryTest : public testing_util::ScratchDirTest {
 protected:
  static std::string Slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

// A configuration of `blocks` interfaces from an index: every mode of the thesis for one or
// two blocks (rest, 3a and 3b for one), letters beyond.
Configuration ConfigurationFor(int blocks, int i) {
  if (blocks == 1)
    return ConfigurationOf(i % 3 == 0 ? Mode::kRest : (i % 3 == 1 ? Mode::k3a : Mode::k3b), 1);
  if (blocks == 2) return ConfigurationOf(static_cast<Mode>(i % 9), 2);
  Configuration c(blocks);
  for (int k = 0; k < blocks; ++k) c.set(k, static_cast<Contact>((i / (k + 1) + k) % 3));
  return c;
}

// A deterministic history of `blocks` blocks with irrational-looking values of both signs and
// all modes.
History MakeHistory(int blocks, int n) {
  History h;
  h.blocks = blocks;
  for (int i = 0; i < n; ++i) {
    Sample s(blocks);
    s.t_s = 0.005 * i + (i % 7 == 3 ? 1.234567e-4 : 0.0);  // some event times between outputs
    s.theta_rad[0] = 0.15 * std::cos(0.37 * i) * std::exp(-0.01 * i);
    s.omega_radps[0] = -1.7 * std::sin(0.37 * i + 0.2);
    for (int k = 1; k < blocks; ++k) {
      s.theta_rad[k] = 1e-7 * k * std::sin(1.3 * i + k);
      s.omega_radps[k] = 3.0e5 * std::cos(0.11 * i - k);
    }
    s.mode = ConfigurationFor(blocks, i);
    h.samples.push_back(s);
  }
  return h;
}

// A sample of two blocks.
Sample TwoBlockSample(double t, double th1, double th2, double w1, double w2, Mode mode) {
  Sample s(2);
  s.t_s = t;
  s.theta_rad = {th1, th2};
  s.omega_radps = {w1, w2};
  s.mode = ConfigurationOf(mode, 2);
  return s;
}

TEST_F(HistoryTest, Headers) {
  EXPECT_EQ(HistoryCsvHeader(2), "t,theta1,theta2,omega1,omega2,mode");
  EXPECT_EQ(HistoryCsvHeader(1), "t,theta1,omega1,mode");
  EXPECT_EQ(HistoryCsvHeader(3), "t,theta1,theta2,theta3,omega1,omega2,omega3,mode");
}

TEST_F(HistoryTest, ExactFormatOfARow) {
  History h;
  h.samples.push_back(TwoBlockSample(0.005, 0.15, -0.0625, 1.5, -2.0, Mode::k1a));
  EXPECT_EQ(HistoryToCsv(h),
            "t,theta1,theta2,omega1,omega2,mode\n"
            "0.005000000,1.500000000000e-01,-6.250000000000e-02,1.500000000000e+00,"
            "-2.000000000000e+00,1a\n");
  History one;
  one.blocks = 1;
  Sample s(1);
  s.t_s = 0.005;
  s.theta_rad[0] = 0.15;
  s.omega_radps[0] = 1.5;
  s.mode = ConfigurationOf(Mode::k3a, 1);
  one.samples.push_back(s);
  EXPECT_EQ(HistoryToCsv(one),
            "t,theta1,omega1,mode\n"
            "0.005000000,1.500000000000e-01,1.500000000000e+00,3a\n");
  // Three blocks: every angle, then every rate, and the configuration's letters.
  History three;
  three.blocks = 3;
  Sample t(3);
  t.t_s = 0.25;
  t.theta_rad = {0.0, 0.5, -0.25};
  t.omega_radps = {0.0, 1.0, 2.0};
  t.mode.set(1, Contact::kRight);
  t.mode.set(2, Contact::kLeft);
  three.samples.push_back(t);
  EXPECT_EQ(HistoryToCsv(three),
            "t,theta1,theta2,theta3,omega1,omega2,omega3,mode\n"
            "0.250000000,0.000000000000e+00,5.000000000000e-01,-2.500000000000e-01,"
            "0.000000000000e+00,1.000000000000e+00,2.000000000000e+00,frl\n");
}

TEST_F(HistoryTest, ASampleOfAnotherBlockCountIsAnError) {
  History h;
  h.blocks = 3;
  h.samples.push_back(Sample(2));
  EXPECT_THROW(HistoryToCsv(h), std::logic_error);
}

// Round trip: what is read back equals what was written to the printed precision: t to
// 0.5e-9 s (9 decimals), the states to half a unit in the 13th significant digit.
void ExpectRoundTrip(const History& in, const History& out) {
  ASSERT_EQ(out.blocks, in.blocks);
  ASSERT_EQ(out.samples.size(), in.samples.size());
  const auto near = [](double a, double b) {
    return std::abs(a - b) <= 0.5e-12 * std::abs(a) * 1.0000001 + 1e-300;
  };
  for (size_t i = 0; i < in.samples.size(); ++i) {
    const Sample& a = in.samples[i];
    const Sample& b = out.samples[i];
    ASSERT_EQ(b.blocks(), in.blocks) << i;
    ASSERT_EQ(b.omega_radps.size(), static_cast<size_t>(in.blocks)) << i;
    EXPECT_NEAR(b.t_s, a.t_s, 0.5e-9 + 1e-15) << i;
    for (int k = 0; k < in.blocks; ++k) {
      EXPECT_TRUE(near(a.theta_rad[k], b.theta_rad[k])) << i << " " << k << " " << a.theta_rad[k];
      EXPECT_TRUE(near(a.omega_radps[k], b.omega_radps[k])) << i << " " << k;
    }
    EXPECT_EQ(b.mode, a.mode) << i;
  }
}

TEST_F(HistoryTest, RoundTripTwoBlocks) {
  const History h = MakeHistory(2, 500);
  const fs::path p = dir_ / "run" / "reference" / "history.csv";
  WriteFileAtomic(p, HistoryToCsv(h));
  const History back = ReadHistoryCsv(p);
  ExpectRoundTrip(h, back);
  // Writing what was read gives the same bytes: the format is a fixed point.
  EXPECT_EQ(HistoryToCsv(back), Slurp(p));
}

TEST_F(HistoryTest, RoundTripOneBlockWithCrLf) {
  const History h = MakeHistory(1, 200);
  std::string text = HistoryToCsv(h);
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const fs::path p = dir_ / "history.csv";
  WriteFileAtomic(p, crlf);
  ExpectRoundTrip(h, ReadHistoryCsv(p));
}

// Every block count reads back what was written, and writes the same bytes again.
TEST_F(HistoryTest, RoundTripOneTwoThreeAndSixBlocks) {
  for (const int blocks : {1, 2, 3, 6}) {
    SCOPED_TRACE(blocks);
    const History h = MakeHistory(blocks, 120);
    const fs::path p = dir_ / ("history" + std::to_string(blocks) + ".csv");
    WriteFileAtomic(p, HistoryToCsv(h));
    const History back = ReadHistoryCsv(p);
    ExpectRoundTrip(h, back);
    EXPECT_EQ(HistoryToCsv(back), Slurp(p));
  }
}

TEST_F(HistoryTest, ReadErrorsNameFileAndLine) {
  const auto expect_error = [&](const std::string& text, const std::string& where,
                                const std::string& piece) {
    const fs::path p = dir_ / "bad.csv";
    WriteFileAtomic(p, text);
    try {
      ReadHistoryCsv(p);
      ADD_FAILURE() << "no error for " << text;
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(p.string() + where, 0), 0u) << msg;
      EXPECT_NE(msg.find(piece), std::string::npos) << msg;
    }
  };
  expect_error("time,angle\n", ":1:", "header");
  expect_error("", ":1:", "empty");
  expect_error("t,theta1,omega1,mode\n0.0,1e-3,2e-3,rest\n0.1,abc,2e-3,rest\n", ":3:", "column 2");
  expect_error("t,theta1,omega1,mode\n0.0,1e-3,2e-3,5c\n", ":2:", "mode");
  expect_error("t,theta1,omega1,mode\n0.0,1e-3,rest\n", ":2:", "4 columns");
  expect_error("t,theta1,theta2,omega1,omega2,mode\n0.0,1,2,3,4,1a,extra\n", ":2:", "6 columns");
  expect_error("t,theta1,omega1,mode\n0.0,,2e-3,rest\n", ":2:", "column 2");
  // A single block has no mode with block 2 rocking.
  expect_error("t,theta1,omega1,mode\n0.0,1e-3,2e-3,1a\n", ":2:", "mode");
  // N blocks: the header's own columns, N letters of f, r or l.
  expect_error("t,theta1,theta2,theta3,omega1,omega3,omega2,mode\n", ":1:", "header");
  expect_error("t,theta1,theta2,theta3,omega1,omega2,omega3,mode\n0,1,2,3,4,5,6,fr\n",
               ":2:", "configuration");
  expect_error("t,theta1,theta2,theta3,omega1,omega2,omega3,mode\n0,1,2,3,4,5,rest\n",
               ":2:", "8 columns");
  try {
    ReadHistoryCsv(dir_ / "none.csv");
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("none.csv"), std::string::npos);
  }
}

TEST_F(HistoryTest, EventsCsv) {
  History h;
  Event e(2);
  e.t_s = 1.25;
  e.kind = "ground_impact";
  e.mode_before = ConfigurationOf(Mode::k1a, 2);
  e.mode_after = ConfigurationOf(Mode::k2b, 2);
  e.omega_before_radps = {-0.5, 0.25};
  e.omega_after_radps = {0.125, -1.0};
  e.energy_before_j = 1000.0;
  e.energy_after_j = 750.5;
  e.note = "inadmissible: a, b\nc";
  h.events.push_back(e);
  EXPECT_EQ(EventsToCsv(h),
            "t,kind,mode_before,mode_after,omega1_before,omega2_before,omega1_after,omega2_after,"
            "energy_before_j,energy_after_j,note\n"
            "1.250000000,ground_impact,1a,2b,-5.000000000000e-01,2.500000000000e-01,"
            "1.250000000000e-01,-1.000000000000e+00,1.000000000000e+03,7.505000000000e+02,"
            "inadmissible: a; b c\n");
  // One block keeps the two-block columns, its omega2 written as 0.
  History one;
  one.blocks = 1;
  Event f(1);
  f.t_s = 0.5;
  f.kind = "overturn";
  f.mode_before = f.mode_after = ConfigurationOf(Mode::k3a, 1);
  f.omega_before_radps = f.omega_after_radps = {2.0};
  one.events.push_back(f);
  EXPECT_EQ(EventsToCsv(one),
            "t,kind,mode_before,mode_after,omega1_before,omega2_before,omega1_after,omega2_after,"
            "energy_before_j,energy_after_j,note\n"
            "0.500000000,overturn,3a,3a,2.000000000000e+00,0.000000000000e+00,2.000000000000e+00,"
            "0.000000000000e+00,0.000000000000e+00,0.000000000000e+00,\n");
  // Three blocks: every block's rate before, then after.
  History three;
  three.blocks = 3;
  Event g(3);
  g.t_s = 2.0;
  g.kind = "interface_impact";
  g.mode_after.set(2, Contact::kRight);
  g.omega_before_radps = {0.0, 0.0, -1.0};
  g.omega_after_radps = {0.0, 0.0, 0.5};
  three.events.push_back(g);
  EXPECT_EQ(EventsToCsv(three),
            "t,kind,mode_before,mode_after,omega1_before,omega2_before,omega3_before,"
            "omega1_after,omega2_after,omega3_after,energy_before_j,energy_after_j,note\n"
            "2.000000000,interface_impact,fff,ffr,0.000000000000e+00,0.000000000000e+00,"
            "-1.000000000000e+00,0.000000000000e+00,0.000000000000e+00,5.000000000000e-01,"
            "0.000000000000e+00,0.000000000000e+00,\n");
}

// `blocks` events of every kind of configuration and rates of both signs.
std::vector<Event> MakeEvents(int blocks, int n) {
  std::vector<Event> out;
  for (int i = 0; i < n; ++i) {
    Event e(blocks);
    e.t_s = 0.359512345 + 0.25 * i;
    e.kind = i % 2 == 0 ? "ground_impact" : "transition";
    e.mode_before = ConfigurationFor(blocks, i);
    e.mode_after = ConfigurationFor(blocks, i + 1);
    for (int k = 0; k < blocks; ++k) {
      e.omega_before_radps[k] = -0.123456789012 * (k + 1) * (i % 3 - 1);
      e.omega_after_radps[k] = 0.5 * std::sin(1.7 * i + k);
    }
    e.energy_before_j = 7315.47 + i;
    e.energy_after_j = 7000.25 + i;
    e.note = i % 3 == 0 ? "" : "a note";
    out.push_back(std::move(e));
  }
  return out;
}

// events.csv of 1, 2, 3 and 6 blocks reads back what EventsToCsv wrote (rates to 13 significant
// digits) and writes the same bytes again.
TEST_F(HistoryTest, EventsCsvRoundTripOneTwoThreeAndSixBlocks) {
  for (const int blocks : {1, 2, 3, 6}) {
    SCOPED_TRACE(blocks);
    History h;
    h.blocks = blocks;
    h.events = MakeEvents(blocks, 12);
    const auto path = Write("events" + std::to_string(blocks) + ".csv", EventsToCsv(h));
    // One and two blocks share a header: the reader is told the count (two when it is not).
    const std::vector<Event> back = ReadEventsCsv(path, blocks <= 2 ? blocks : 0);
    ASSERT_EQ(back.size(), h.events.size());
    for (size_t i = 0; i < back.size(); ++i) {
      const Event& a = h.events[i];
      const Event& b = back[i];
      ASSERT_EQ(b.blocks(), blocks);
      ASSERT_EQ(b.omega_after_radps.size(), static_cast<size_t>(blocks));
      EXPECT_EQ(b.t_s, a.t_s);
      EXPECT_EQ(b.kind, a.kind);
      EXPECT_EQ(b.mode_before, a.mode_before) << i;
      EXPECT_EQ(b.mode_after, a.mode_after) << i;
      for (int k = 0; k < blocks; ++k) {
        // To half a unit in the 13th significant digit.
        for (const auto* v : {&a.omega_before_radps, &a.omega_after_radps}) {
          const double x = (*v)[k];
          const double y =
              (v == &a.omega_before_radps ? b.omega_before_radps : b.omega_after_radps)[k];
          EXPECT_NEAR(y, x, 0.5e-12 * std::abs(x) * 1.0000001 + 1e-300) << i << " " << k;
        }
      }
      EXPECT_EQ(b.energy_before_j, a.energy_before_j);
      EXPECT_EQ(b.note, a.note);
    }
    History again;
    again.blocks = blocks;
    again.events = back;
    EXPECT_EQ(EventsToCsv(again), EventsToCsv(h));
  }
  // An N-block file read as another count is refused.
  History h;
  h.blocks = 3;
  h.events = MakeEvents(3, 2);
  const auto path = Write("events3.csv", EventsToCsv(h));
  EXPECT_THROW(ReadEventsCsv(path, 4), std::runtime_error);
  EXPECT_THROW(ReadEventsCsv(path, 2), std::runtime_error);
}

// events.csv reads back what EventsToCsv wrote (values with 13 significant digits, the note
// with its commas and line breaks replaced), and a bad line is named.
TEST_F(HistoryTest, EventsCsvRoundTripAndErrors) {
  History h;
  Event a(2);
  a.t_s = 0.359512345;
  a.kind = "transition";
  a.mode_before = ConfigurationOf(Mode::k3a, 2);
  a.mode_after = ConfigurationOf(Mode::k1a, 2);
  a.omega_before_radps = a.omega_after_radps = {-0.123456789012, 0.5};
  a.energy_before_j = a.energy_after_j = 7315.47;
  Event b = a;
  b.t_s = 1.0;
  b.kind = "ground_impact";
  b.note = "";
  h.events = {a, b};
  const auto path = Write("events.csv", EventsToCsv(h));
  const std::vector<Event> back = ReadEventsCsv(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].t_s, a.t_s);
  EXPECT_EQ(back[0].kind, "transition");
  EXPECT_EQ(back[0].mode_before, ConfigurationOf(Mode::k3a, 2));
  EXPECT_EQ(back[0].mode_after, ConfigurationOf(Mode::k1a, 2));
  EXPECT_DOUBLE_EQ(back[0].omega_before_radps[0], a.omega_before_radps[0]);
  EXPECT_EQ(back[0].energy_after_j, 7315.47);
  EXPECT_EQ(back[1].note, "");
  EXPECT_EQ(HistoryToCsv(History{2, {}, back}), HistoryToCsv(h));  // events do not print
  EXPECT_EQ(EventsToCsv(History{2, {}, back}), EventsToCsv(h));

  const std::string header = EventsToCsv(History{});
  const auto expect_error = [&](const std::string& text, const std::string& what) {
    const auto p = Write("bad.csv", text);
    try {
      ReadEventsCsv(p);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error("", "bad.csv:1: empty file");
  expect_error("t,kind\n", "bad.csv:1: expected the header");
  expect_error(header + "1.0,ground_impact,1a,2b,0,0,0,0,0,0\n", "bad.csv:2: expected 11 columns");
  expect_error(header + "1.0,ground_impact,1a,9z,0,0,0,0,0,0,\n", "bad.csv:2: mode_after");
  expect_error(header + "1.0,ground_impact,1a,2b,0,nan,0,0,0,0,\n", "bad.csv:2: omega2_before");
}

// A cylinder's events.csv (written here by hand, in EventsToCsv's number formats) is read from
// its header: its modes by the cylinder's names, its tilt rates as the events' rates; writing the
// events back gives the same bytes. Told the wrong kind or count, or given a bad cell, the
// reader says so.
TEST_F(HistoryTest, ACylindersEventsCsvIsReadFromItsHeader) {
  const std::string text =
      "t,kind,mode_before,mode_after,tilt_rate1_before,tilt_rate1_after,energy_before_j,"
      "energy_after_j,note\n"
      "0.250000000,initiation,rest,rim,0.000000000000e+00,1.500000000000e-01,"
      "1.250000000000e+01,1.250000000000e+01,\n"
      "1.120700000,overturn,rim,rim,-2.000000000000e+00,-2.125000000000e+00,"
      "3.000000000000e+01,2.950000000000e+01,past atan(D/H)\n";
  const auto path = Write("cylinder_events.csv", text);
  const std::vector<Event> back = ReadEventsCsv(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].blocks(), 1);
  EXPECT_EQ(back[0].t_s, 0.25);
  EXPECT_EQ(back[0].kind, "initiation");
  EXPECT_EQ(back[0].mode_before[0], Contact::kFace);
  EXPECT_EQ(back[0].mode_after[0], Contact::kRight);
  EXPECT_EQ(back[0].omega_before_radps[0], 0.0);
  EXPECT_EQ(back[0].omega_after_radps[0], 0.15);
  EXPECT_EQ(back[0].energy_before_j, 12.5);
  EXPECT_EQ(back[0].note, "");
  EXPECT_EQ(back[1].t_s, 1.1207);
  EXPECT_EQ(back[1].kind, "overturn");
  EXPECT_EQ(back[1].mode_before[0], Contact::kRight);
  EXPECT_EQ(back[1].omega_before_radps[0], -2.0);
  EXPECT_EQ(back[1].omega_after_radps[0], -2.125);
  EXPECT_EQ(back[1].energy_after_j, 29.5);
  EXPECT_EQ(back[1].note, "past atan(D/H)");
  History h;
  h.blocks = 1;
  h.shape = std::string(kCylinderShape);
  h.events = back;
  EXPECT_EQ(EventsToCsv(h), text);
  // Told its kind and count, it reads the same; told another, it refuses.
  EXPECT_EQ(ReadEventsCsv(path, 1, kCylinderShape).size(), 2u);
  EXPECT_THROW(ReadEventsCsv(path, 2), std::runtime_error);
  EXPECT_THROW(ReadEventsCsv(path, 1, "block"), std::runtime_error);
  History planar;
  planar.events = {Event(2)};
  const auto planar_path = Write("planar_events.csv", EventsToCsv(planar));
  try {
    ReadEventsCsv(planar_path, 0, kCylinderShape);
    ADD_FAILURE() << "a planar events file read as a cylinder's";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("planar_events.csv:1: expected the events of cylinder"),
              std::string::npos)
        << e.what();
  }
  const std::string header = text.substr(0, text.find('\n') + 1);
  const auto expect_error = [&](const std::string& bad, const std::string& what) {
    const auto p = Write("bad_cylinder.csv", bad);
    try {
      ReadEventsCsv(p, 1, kCylinderShape);
      ADD_FAILURE() << "no error for: " << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error("t,kind\n", "bad_cylinder.csv:1: expected the header '" +
                               header.substr(0, header.size() - 1) + "'");
  expect_error(header + "1.0,overturn,rim,rim,0,0,0,0\n", "bad_cylinder.csv:2: expected 9 columns");
  expect_error(header + "1.0,overturn,rim,3a,0,0,0,0,\n", "bad_cylinder.csv:2: mode_after");
  expect_error(header + "1.0,overturn,rim,rim,0,nan,0,0,\n",
               "bad_cylinder.csv:2: tilt_rate1_after");
}

TEST_F(HistoryTest, WriteFileAtomicReplacesAndLeavesNoTemporary) {
  const fs::path p = dir_ / "a" / "b" / "out.txt";
  WriteFileAtomic(p, "first\n");
  EXPECT_EQ(Slurp(p), "first\n");
  const char kBinary[] = "second\0with nul\n";
  const std::string binary(kBinary, sizeof kBinary - 1);
  WriteFileAtomic(p, binary);
  EXPECT_EQ(Slurp(p), binary);
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(p.parent_path())) {
    ++entries;
    EXPECT_EQ(entry.path().filename(), "out.txt");
  }
  EXPECT_EQ(entries, 1);
  // A folder in the way of the file: an error naming the path.
  fs::create_directories(dir_ / "dir_target");
  EXPECT_THROW(WriteFileAtomic(dir_ / "dir_target", "x"), std::runtime_error);
}

// An impact event's kind names its interface (InterfaceName + "_impact"), for every stack
// height; other kinds, and names no stack writes, are no impact.
TEST(ImpactInterface, IsTheInverseOfTheImpactKindsNames) {
  for (const int blocks : {1, 2, 3, 10, 64}) {
    for (int k = 0; k < blocks; ++k) {
      EXPECT_EQ(ImpactInterface(InterfaceName(k, blocks) + "_impact"), k) << blocks << " " << k;
    }
  }
  for (const char* kind : {"transition", "initiation", "rest", "overturn", "interface1_impact",
                           "interface0_impact", "interface_2_impact", "interfacex_impact",
                           "interface2", "ground", "_impact", "interface2_impactx"}) {
    EXPECT_EQ(ImpactInterface(kind), -1) << kind;
  }
}

}  // namespace
}  // namespace rockbench
