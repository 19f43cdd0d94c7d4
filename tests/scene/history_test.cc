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

// A deterministic history with irrational-looking values of both signs and all modes.
History MakeHistory(bool two_blocks, int n) {
  History h;
  h.two_blocks = two_blocks;
  for (int i = 0; i < n; ++i) {
    Sample s;
    s.t_s = 0.005 * i + (i % 7 == 3 ? 1.234567e-4 : 0.0);  // some event times between outputs
    s.theta1_rad = 0.15 * std::cos(0.37 * i) * std::exp(-0.01 * i);
    s.omega1_radps = -1.7 * std::sin(0.37 * i + 0.2);
    if (two_blocks) {
      s.theta2_rad = 1e-7 * std::sin(1.3 * i);
      s.omega2_radps = 3.0e5 * std::cos(0.11 * i);
    }
    s.mode = static_cast<Mode>(i % 9);
    if (!two_blocks) s.mode = i % 3 == 0 ? Mode::kRest : (i % 3 == 1 ? Mode::k3a : Mode::k3b);
    h.samples.push_back(s);
  }
  return h;
}

TEST_F(HistoryTest, Headers) {
  EXPECT_EQ(HistoryCsvHeader(true), "t,theta1,theta2,omega1,omega2,mode");
  EXPECT_EQ(HistoryCsvHeader(false), "t,theta1,omega1,mode");
}

TEST_F(HistoryTest, ExactFormatOfARow) {
  History h;
  h.samples.push_back({0.005, 0.15, -0.0625, 1.5, -2.0, Mode::k1a});
  EXPECT_EQ(HistoryToCsv(h),
            "t,theta1,theta2,omega1,omega2,mode\n"
            "0.005000000,1.500000000000e-01,-6.250000000000e-02,1.500000000000e+00,"
            "-2.000000000000e+00,1a\n");
  h.two_blocks = false;
  EXPECT_EQ(HistoryToCsv(h),
            "t,theta1,omega1,mode\n"
            "0.005000000,1.500000000000e-01,1.500000000000e+00,1a\n");
}

// Round trip: what is read back equals what was written to the printed precision: t to
// 0.5e-9 s (9 decimals), the states to half a unit in the 13th significant digit.
void ExpectRoundTrip(const History& in, const History& out) {
  ASSERT_EQ(out.two_blocks, in.two_blocks);
  ASSERT_EQ(out.samples.size(), in.samples.size());
  const auto near = [](double a, double b) {
    return std::abs(a - b) <= 0.5e-12 * std::abs(a) * 1.0000001 + 1e-300;
  };
  for (size_t i = 0; i < in.samples.size(); ++i) {
    const Sample& a = in.samples[i];
    const Sample& b = out.samples[i];
    EXPECT_NEAR(b.t_s, a.t_s, 0.5e-9 + 1e-15) << i;
    EXPECT_TRUE(near(a.theta1_rad, b.theta1_rad)) << i << " " << a.theta1_rad;
    EXPECT_TRUE(near(a.omega1_radps, b.omega1_radps)) << i;
    if (in.two_blocks) {
      EXPECT_TRUE(near(a.theta2_rad, b.theta2_rad)) << i;
      EXPECT_TRUE(near(a.omega2_radps, b.omega2_radps)) << i;
    } else {
      EXPECT_EQ(b.theta2_rad, 0.0);
      EXPECT_EQ(b.omega2_radps, 0.0);
    }
    EXPECT_EQ(b.mode, a.mode) << i;
  }
}

TEST_F(HistoryTest, RoundTripTwoBlocks) {
  const History h = MakeHistory(true, 500);
  const fs::path p = dir_ / "run" / "reference" / "history.csv";
  WriteFileAtomic(p, HistoryToCsv(h));
  const History back = ReadHistoryCsv(p);
  ExpectRoundTrip(h, back);
  // Writing what was read gives the same bytes: the format is a fixed point.
  EXPECT_EQ(HistoryToCsv(back), Slurp(p));
}

TEST_F(HistoryTest, RoundTripOneBlockWithCrLf) {
  const History h = MakeHistory(false, 200);
  std::string text = HistoryToCsv(h);
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const fs::path p = dir_ / "history.csv";
  WriteFileAtomic(p, crlf);
  ExpectRoundTrip(h, ReadHistoryCsv(p));
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
  try {
    ReadHistoryCsv(dir_ / "none.csv");
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("none.csv"), std::string::npos);
  }
}

TEST_F(HistoryTest, EventsCsv) {
  History h;
  Event e;
  e.t_s = 1.25;
  e.kind = "ground_impact";
  e.mode_before = Mode::k1a;
  e.mode_after = Mode::k2b;
  e.omega1_before = -0.5;
  e.omega2_before = 0.25;
  e.omega1_after = 0.125;
  e.omega2_after = -1.0;
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
}

// events.csv reads back what EventsToCsv wrote (values with 13 significant digits, the note
// with its commas and line breaks replaced), and a bad line is named.
TEST_F(HistoryTest, EventsCsvRoundTripAndErrors) {
  History h;
  Event a;
  a.t_s = 0.359512345;
  a.kind = "transition";
  a.mode_before = Mode::k3a;
  a.mode_after = Mode::k1a;
  a.omega1_before = a.omega1_after = -0.123456789012;
  a.omega2_before = a.omega2_after = 0.5;
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
  EXPECT_EQ(back[0].mode_before, Mode::k3a);
  EXPECT_EQ(back[0].mode_after, Mode::k1a);
  EXPECT_DOUBLE_EQ(back[0].omega1_before, a.omega1_before);
  EXPECT_EQ(back[0].energy_after_j, 7315.47);
  EXPECT_EQ(back[1].note, "");
  EXPECT_EQ(HistoryToCsv(History{true, {}, back}), HistoryToCsv(h));  // events do not print
  EXPECT_EQ(EventsToCsv(History{true, {}, back}), EventsToCsv(h));

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

}  // namespace
}  // namespace rockbench
