// `rockbench stress` as a program: isolation (a crashing or hanging case becomes a row, not the
// end of the command), the CI subset's rows from both engines, rows independent of --jobs and
// of the run (wall times excepted), atomic output, and bad options exiting 2.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"

namespace rockbench {
namespace {

using testing_util::ReadFile;
using CliRun = testing_util::ShellRun;

using testing_util::Rockbench;

using Row = std::map<std::string, std::string>;

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream ss(line);
  for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
  if (!line.empty() && line.back() == ',') f.push_back("");
  return f;
}

std::vector<Row> ReadCsv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = Split(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = Split(line);
    EXPECT_EQ(f.size(), header.size()) << line;
    Row r;
    for (size_t k = 0; k < header.size() && k < f.size(); ++k) r[header[k]] = f[k];
    rows.push_back(r);
  }
  return rows;
}

// The CSV without its wall_s column.
std::string WithoutWallTimes(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  std::getline(in, line);
  const std::vector<std::string> header = Split(line);
  const size_t wall = std::find(header.begin(), header.end(), "wall_s") - header.begin();
  in.seekg(0);
  while (std::getline(in, line)) {
    std::vector<std::string> f = Split(line);
    if (wall < f.size()) f[wall].clear();
    for (size_t k = 0; k < f.size(); ++k) out += (k ? "," : "") + f[k];
    out += "\n";
  }
  return out;
}

class StressCliTest : public testing_util::ScratchDirTest {};

TEST_F(StressCliTest, CrashAndHangBecomeRowsNotFailures) {
  const auto out = dir_ / "out";
  const CliRun r = Rockbench("stress --out " + out.string() +
                             " --case selftest/crash --case selftest/hang --case release/single");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<Row> rows = ReadCsv(ReadFile(out / "stress.csv"));
  std::map<std::string, Row> by;
  for (const Row& row : rows) by[row.at("case") + "|" + row.at("engine")] = row;
  // Catalogue order: the release cases first, the hidden self-tests last.
  ASSERT_GE(rows.size(), 4u);
  EXPECT_EQ(rows.front().at("case"), "release/single/inside_1pct");
  EXPECT_EQ(rows.back().at("case"), "selftest/hang");
  EXPECT_EQ(by.at("selftest/crash|reference").at("status"), "crash (signal 11)");
  EXPECT_EQ(by.at("selftest/crash|reference").at("finished"), "0");
  const Row& hang = by.at("selftest/hang|reference");
  EXPECT_EQ(hang.at("status"), "wall_limit");
  EXPECT_EQ(hang.at("finished"), "0");
  // Killed at its 1 s limit (RunProcess polls; generous upper end for a loaded machine).
  EXPECT_GE(std::stod(hang.at("wall_s")), 1.0);
  EXPECT_LT(std::stod(hang.at("wall_s")), 10.0);
  EXPECT_EQ(by.at("release/single/outside_1pct|reference").at("status"), "overturned");
  EXPECT_EQ(by.at("release/single/inside_1pct|reference").at("finished"), "1");
}

// The CI subset: every (case, engine) has a row with a status; the reference's rows keep its
// invariants (stress_test.cc says why these bounds); Bullet's rows carry their settings,
// violations and agreement.
TEST_F(StressCliTest, QuickSubsetGivesARowPerCaseAndEngine) {
  const auto out = dir_ / "quick";
  const CliRun r = Rockbench("stress --quick --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CliRun list = Rockbench("stress --list --quick");
  ASSERT_EQ(list.exit_code, 0);
  const std::vector<Row> rows = ReadCsv(ReadFile(out / "stress.csv"));
  int expected = 0;
  std::istringstream ls(list.output);
  for (std::string line; std::getline(ls, line);) {
    std::istringstream f(line);
    std::string name, engines;
    f >> name >> engines;
    expected += 1 + static_cast<int>(std::count(engines.begin(), engines.end(), ','));
  }
  EXPECT_EQ(static_cast<int>(rows.size()), expected);
  int bullet_rows = 0;
  for (const Row& row : rows) {
    const std::string what = row.at("case") + " " + row.at("engine");
    EXPECT_FALSE(row.at("status").empty()) << what;
    if (row.at("engine") == "reference") {
      EXPECT_EQ(row.at("finished"), "1") << what;
      EXPECT_EQ(row.at("nan"), "0") << what;
      if (!row.at("max_energy_gain_rel").empty()) {
        EXPECT_LE(std::stod(row.at("max_energy_gain_rel")), 1e-9) << what;
      }
      EXPECT_LT(std::stoi(row.at("events")), 10000) << what;
      if (!row.at("min_event_gap_s").empty()) {
        EXPECT_GT(std::stod(row.at("min_event_gap_s")), 0.0);
      }
    } else {
      ++bullet_rows;
      EXPECT_FALSE(row.at("dt_s").empty()) << what;
      EXPECT_FALSE(row.at("violations").empty()) << what;
      EXPECT_NE(row.at("status").rfind("crash", 0), 0u) << what;
      EXPECT_NE(row.at("status"), "wall_limit") << what;
      if (row.at("finished") == "1") {
        EXPECT_FALSE(row.at("theta1_max_abs_error_rad").empty());
      }
    }
  }
  EXPECT_GT(bullet_rows, 0);
  // Nothing but stress.csv in the folder (no temporary files left).
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(out)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST_F(StressCliTest, RowsDoNotDependOnJobsOrTheRun) {
  const std::string cases =
      " --case uplift/top --case release/single --case mass_ratio/m2_over_m1=0.001";
  ASSERT_EQ(Rockbench("stress --jobs 1 --out " + (dir_ / "a").string() + cases).exit_code, 0);
  ASSERT_EQ(Rockbench("stress --jobs 3 --out " + (dir_ / "b").string() + cases).exit_code, 0);
  const std::string a = ReadFile(dir_ / "a" / "stress.csv");
  EXPECT_EQ(WithoutWallTimes(a), WithoutWallTimes(ReadFile(dir_ / "b" / "stress.csv")));
  EXPECT_GT(ReadCsv(a).size(), 4u);
}

TEST_F(StressCliTest, BadOptionsExitTwo) {
  const std::string out = " --out " + (dir_ / "x").string();
  CliRun r = Rockbench("stress" + out + " --case no_such_case");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("'no_such_case'"), std::string::npos) << r.output;
  r = Rockbench("stress" + out + " --jobs 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--jobs"), std::string::npos) << r.output;
  r = Rockbench("stress --quick");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
  r = Rockbench("stress --run-case no/such --engine reference");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no/such"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x" / "stress.csv"));
}

}  // namespace
}  // namespace rockbench
