// RenderGnuplot: figures come out as SVG with the kept script and data, failures say why and
// leave no figure behind.
#include "report/common/gnuplot.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/scratch_dir_test.h"
#include "util/subprocess.h"

namespace rockbench::report {
namespace {

using GnuplotTest = testing_util::ScratchDirTest;

std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

GnuplotFigure LineFigure() {
  GnuplotFigure f;
  f.name = "line";
  f.data_files = {{"line.dat", "0 0\n1 1\n2 4\n"}};
  f.script =
      "set xlabel 'time t (s)'\nset ylabel 'angle {/Symbol q}_1 (rad)'\n"
      "plot 'line.dat' using 1:2 with lines title 'reference model'\n";
  return f;
}

TEST_F(GnuplotTest, WritesTheFigureItsScriptAndItsData) {
  ASSERT_TRUE(GnuplotAvailable()) << "gnuplot-nox is a test dependency (scripts/install-deps.sh)";
  const std::filesystem::path svg = RenderGnuplot(dir_, LineFigure());
  EXPECT_EQ(svg, dir_ / "line.svg");
  const std::string text = Slurp(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("reference model"), std::string::npos);  // the legend
  EXPECT_NE(text.find("time t (s)"), std::string::npos);       // the axis label
  EXPECT_TRUE(std::filesystem::exists(dir_ / "line.gp"));
  EXPECT_EQ(Slurp(dir_ / "line.dat"), "0 0\n1 1\n2 4\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "line.svg.tmp"));
}

TEST_F(GnuplotTest, TheKeptScriptRedrawsTheSameFigureOnItsOwn) {
  ASSERT_TRUE(GnuplotAvailable());
  const std::string first = Slurp(RenderGnuplot(dir_, LineFigure()));
  std::filesystem::remove(dir_ / "line.svg");
  ProcessOptions options;
  options.working_dir = dir_;
  const ProcessResult r = RunProcess({GnuplotProgram(), "line.gp"}, options);
  ASSERT_TRUE(r.ok()) << r.err;
  EXPECT_EQ(Slurp(dir_ / "line.svg"), first);
}

TEST_F(GnuplotTest, AFailingScriptThrowsWithGnuplotsMessageAndLeavesNoFigure) {
  ASSERT_TRUE(GnuplotAvailable());
  GnuplotFigure f = LineFigure();
  f.script = "plot 'missing.dat' using 1:2 with lines\n";
  try {
    RenderGnuplot(dir_, f);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("line.gp"), std::string::npos) << what;
    EXPECT_NE(what.find("missing.dat"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "line.svg"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "line.svg.tmp"));
}

TEST(GnuplotQuote, EscapesQuotesAndBackslashes) {
  EXPECT_EQ(GnuplotQuote("a\"b\\c"), "\"a\\\"b\\\\c\"");
}

}  // namespace
}  // namespace rockbench::report
