// `rockbench run` as a user meets it: outputs, summary keys other tools read, determinism,
// atomic writes, and clear errors with a non-zero exit for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout + stderr
};

Outcome Rockbench(const std::string& args) {
  const std::string cmd = std::string(ROCKBENCH_EXE) + " " + args + " 2>&1";
  Outcome out;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.output.append(buf, n);
  const int status = pclose(p);
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

std::string Slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path TempDir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("rockbench_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const std::string kSrc = ROCKBENCH_SOURCE_DIR;

TEST(CliRunTest, WritesHistoryEventsAndSummary) {
  const fs::path out = TempDir("ok");
  const Outcome r =
      Rockbench("run " + kSrc + "/scenes/thesis_free_rocking.toml --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("outputs in"), std::string::npos);
  const std::string hist = Slurp(out / "reference/history.csv");
  EXPECT_EQ(hist.substr(0, hist.find('\n')), "t,theta1,theta2,omega1,omega2,mode");
  EXPECT_TRUE(fs::exists(out / "reference/events.csv"));
  const auto j = nlohmann::json::parse(Slurp(out / "summary.json"));
  for (const char* key :
       {"status", "wall_s", "peaks", "impacts", "overturn", "friction_required"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_TRUE(j["peaks"]["theta1"].contains("abs_rad"));
  EXPECT_TRUE(j["peaks"]["theta2"].contains("t_s"));
  EXPECT_TRUE(j["impacts"].contains("total"));
  EXPECT_TRUE(j["friction_required"].contains("ground"));
  EXPECT_TRUE(j["friction_required"].contains("interface"));
  EXPECT_FALSE(j["base"].contains("horizontal"));  // free rocking: no base motion
  // Nothing half-written is left behind.
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
  }
  fs::remove_all(out);
}

TEST(CliRunTest, SingleBlockHistoryColumns) {
  const fs::path out = TempDir("one");
  const Outcome r =
      Rockbench("run " + kSrc + "/scenes/housner_free_rocking.toml --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string hist = Slurp(out / "reference/history.csv");
  EXPECT_EQ(hist.substr(0, hist.find('\n')), "t,theta1,omega1,mode");
  fs::remove_all(out);
}

TEST(CliRunTest, SameInputSameBytes) {
  const fs::path a = TempDir("a"), b = TempDir("b");
  const std::string scene = kSrc + "/scenes/thesis_rinaldi228.toml";
  ASSERT_EQ(Rockbench("run " + scene + " --out " + a.string()).exit_code, 0);
  ASSERT_EQ(Rockbench("run " + scene + " --out " + b.string()).exit_code, 0);
  EXPECT_EQ(Slurp(a / "reference/history.csv"), Slurp(b / "reference/history.csv"));
  EXPECT_EQ(Slurp(a / "reference/events.csv"), Slurp(b / "reference/events.csv"));
  const auto ja = nlohmann::json::parse(Slurp(a / "summary.json"));
  EXPECT_EQ(ja["base"]["horizontal"]["npts"], 1991);
  EXPECT_NEAR(ja["base"]["horizontal"]["peak_g"].get<double>(), 0.8741, 5e-5);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(CliRunTest, SetOverridesASceneValue) {
  const fs::path out = TempDir("set");
  const Outcome r =
      Rockbench("run " + kSrc + "/scenes/thesis_free_rocking.toml --set run.duration=0.5 --out " +
                out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string hist = Slurp(out / "reference/history.csv");
  EXPECT_NE(hist.find("\n0.500000000,"), std::string::npos);
  EXPECT_EQ(hist.find("\n0.505000000,"), std::string::npos);
  fs::remove_all(out);
}

// Bad input: a clear message naming the file/line/key, exit code 2, and earlier outputs kept.
TEST(CliRunTest, BadInputFailsClearlyAndKeepsOutputs) {
  const fs::path dir = TempDir("bad");
  const fs::path out = dir / "out";
  ASSERT_EQ(
      Rockbench("run " + kSrc + "/scenes/thesis_free_rocking.toml --out " + out.string()).exit_code,
      0);
  const std::string before = Slurp(out / "reference/history.csv");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  struct Case {
    std::string args, expect;
  };
  const std::string good = "[block1]\nwidth = 1.0\nheight = 3.0\ndensity = 2000.0\n";
  const Case cases[] = {
      {"run " + (dir / "missing.toml").string(), "missing.toml"},
      {"run " + write("unknown.toml", good + "colour = 3\n"), "unknown.toml:5"},
      {"run " + write("neg.toml", "[block1]\nwidth = -1.0\nheight = 3.0\ndensity = 2000.0\n"),
       "block1.width"},
      {"run " + write("nanrec.toml",
                      good + "[base.horizontal]\nfile = \"nan.txt\"\nunits = \"g\"\ndt = 0.01\n"),
       "nan.txt"},
      {"run " + write("trunc.toml", good + "[base.horizontal]\nfile = \"trunc.AT2\"\n"),
       "trunc.AT2"},
      {"run " + kSrc + "/scenes/thesis_free_rocking.toml --set run.output_interval=-1",
       "output_interval"},
      {"run " + kSrc + "/scenes/thesis_free_rocking.toml --set nosuch.key=1", "nosuch"},
      {"run " + kSrc + "/scenes/thesis_free_rocking.toml --engine nosuchengine", "nosuchengine"},
  };
  std::ofstream(dir / "nan.txt") << "0.0\n0.1\nnan\n0.2\n";
  std::ofstream(dir / "trunc.AT2")
      << "PEER NGA STRONG MOTION DATABASE RECORD\nx\nACCELERATION TIME "
         "SERIES IN UNITS OF G\nNPTS=   10, DT=   .0100 SEC,\n0.1 0.2 0.3\n";
  for (const Case& c : cases) {
    const Outcome r = Rockbench(c.args + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_EQ(Slurp(out / "reference/history.csv"), before);
  fs::remove_all(dir);
}

}  // namespace
