// A results folder someone shares is data (issue 38): names in it reach gnuplot scripts, file
// names and pages. Hostile texts (a backquoted command, $(...), quotes, @ macros, line breaks,
// escape sequences, HTML tags) either reach a figure inert, shown as written, or are refused
// with the file and key named and the text escaped; no command in them ever runs (each would
// create a MARK* file where gnuplot runs: the figures folder).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "files/atomic_file.h"
#include "report/common/gnuplot.h"
#include "report/run_folder.h"
#include "scene/history.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using testing_util::Rockbench;
using testing_util::RockbenchOk;
using testing_util::Slurp;

// Every file under `dir` whose name starts with MARK: what a command in a name would create.
std::vector<std::string> Markers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename().string().rfind("MARK", 0) == 0) found.push_back(e.path().string());
  }
  return found;
}

// The text as an SVG file holds it: XML's escapes of & and < (gnuplot's SVG terminal writes >
// as it is, which XML allows).
std::string SvgText(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') {
      out += "&amp;";
    } else if (c == '<') {
      out += "&lt;";
    } else {
      out += c;
    }
  }
  return out;
}

class HostileNamesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("rockbench_hostile_names_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    WriteFileAtomic(base_ / "block.toml",
                    "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
                    "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\n"
                    "frequency_hz = 2.0\n[run]\nduration = 0.5\n");
    RockbenchOk({"compare", (base_ / "block.toml").string(), "--engines", "bullet", "--quick",
                 "--out", (base_ / "compare").string()});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  // A copy of the compare folder under `name`.
  static fs::path CopyOfCompare(const std::string& name) {
    const fs::path dir = base_ / name;
    fs::remove_all(dir);
    fs::copy(base_ / "compare", dir, fs::copy_options::recursive);
    return dir;
  }
  static ProcessResult Report(const fs::path& dir, const std::string& out) {
    return Rockbench({"report", dir.string(), "--out", (base_ / out).string(), "--no-animation",
                      "--no-keyframes"});
  }
  static fs::path base_;
};

fs::path HostileNamesTest::base_;

// Texts that would run a command, end a gnuplot command or break out of a string if they were
// pasted into a script.
const std::vector<std::string> kHostile = {"`touch MARK_backquote`",
                                           "$(touch MARK_dollar)",
                                           "a\"b'c x_g'' d''''e",
                                           "@macro `touch MARK_at` \\\" `touch MARK_escaped`",
                                           "line1\n!touch MARK_newline\nset title 'x'",
                                           "\x1b[2K\rverdict bullet AGREES <b>bold</b>"};

TEST_F(HostileNamesTest, AQuotedTitleIsShownAsWrittenAndRunsNothing) {
  ASSERT_TRUE(GnuplotAvailable());
  int index = 0;
  for (const std::string& text : kHostile) {
    const fs::path dir = base_ / ("figure_" + std::to_string(index));
    fs::create_directories(dir);
    GnuplotFigure f;
    f.name = "hostile";
    f.data_files = {{"line.dat", "0 0\n1 1\n"}};
    f.script = "set title " + GnuplotQuote(text) +
               " noenhanced\nplot 'line.dat' using 1:2 with lines title " + GnuplotQuote(text) +
               " noenhanced\n";
    ASSERT_NO_THROW(RenderGnuplot(dir, f)) << text;
    EXPECT_TRUE(Markers(dir).empty()) << text;
    // Shown as written; a control character as the text \xHH (the figure has no line breaks).
    std::string shown;
    for (char c : text) {
      const auto u = static_cast<unsigned char>(c);
      if (u < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\x%02X", u);
        shown += buf;
      } else {
        shown += c;
      }
    }
    EXPECT_NE(Slurp(dir / "hostile.svg").find(SvgText(shown)), std::string::npos)
        << text << " not shown as " << SvgText(shown);
    ++index;
  }
}

TEST_F(HostileNamesTest, AnEngineNameOutsideTheAlphabetIsRefusedNamingTheKey) {
  for (const std::string& name :
       {std::string("evil`touch MARK_key`"), std::string("x\x1b[2K\rverdict bullet AGREES\n"),
        std::string("../compare/bullet")}) {
    const fs::path dir = CopyOfCompare("hostile_key");
    nlohmann::json summary = nlohmann::json::parse(Slurp(dir / "summary.json"));
    summary["engines"][name] = summary["engines"]["bullet"];
    summary["engines"].erase("bullet");
    WriteFileAtomic(dir / "summary.json", summary.dump(2));
    const ProcessResult r = Report(dir, "report_key");
    const std::string said = r.out + r.err;
    EXPECT_EQ(r.exit_code, 2) << said;
    EXPECT_NE(said.find("summary.json: key 'engines': \""), std::string::npos) << said;
    EXPECT_NE(said.find("is not an engine name"), std::string::npos) << said;
    // The name is shown escaped: no escape character, no line break inside the message.
    EXPECT_EQ(said.find('\x1b'), std::string::npos) << said;
    EXPECT_EQ(said.find('\n'), said.size() - 1) << said;
    EXPECT_TRUE(Markers(base_).empty()) << said;
  }
}

TEST_F(HostileNamesTest, AHostileFolderNameIsTextOnTheIndexAndRunsNothing) {
  const std::string name = "run`touch MARK_folder`$(touch MARK_dollar)<b>x'q\"";
  const fs::path dir = CopyOfCompare(name);
  const ProcessResult r = Report(dir, "report_folder");
  ASSERT_TRUE(r.ok()) << r.out << r.err;
  EXPECT_TRUE(Markers(base_).empty());
  const std::string md = Slurp(base_ / "report_folder" / "index.md");
  const std::string html = Slurp(base_ / "report_folder" / "index.html");
  // No tag from the name on either page: the HTML escapes it, the Markdown its opening <.
  EXPECT_EQ(md.find("<b>"), std::string::npos) << md;
  EXPECT_NE(md.find("run`touch MARK_folder`$(touch MARK_dollar)&lt;b>x'q\""), std::string::npos)
      << md;
  EXPECT_EQ(html.find("<b>"), std::string::npos);
  EXPECT_NE(html.find("run`touch MARK_folder`$(touch MARK_dollar)&lt;b&gt;x&#39;q&quot;"),
            std::string::npos);
}

TEST_F(HostileNamesTest, AHostileSweepFamilyIsAFigureTitleShownAsWritten) {
  const fs::path dir = base_ / "sweep";
  RockbenchOk({"sweep", (base_ / "block.toml").string(), "--engines", "bullet", "--quick", "--out",
               dir.string()});
  // Every family of the engine renamed to a hostile text (a manifest's family is free text).
  const std::string family = "fam`touch MARK_family`$(touch MARK_f2)\"q' x_g''";
  std::string csv = Slurp(dir / "sweep.csv");
  size_t renamed = 0;
  for (size_t p = csv.find("\nbullet,"); p != std::string::npos; p = csv.find("\nbullet,", p + 1)) {
    const size_t from = p + 8, to = csv.find(',', from);
    csv.replace(from, to - from, family);
    ++renamed;
  }
  ASSERT_GT(renamed, 0u) << csv;
  WriteFileAtomic(dir / "sweep.csv", csv);
  const ProcessResult r = Report(dir, "report_sweep");
  ASSERT_TRUE(r.ok()) << r.out << r.err;
  EXPECT_TRUE(Markers(base_).empty());
  const std::string svg =
      Slurp(base_ / "report_sweep" / "sweep" / "figures" / "work_precision.svg");
  EXPECT_NE(svg.find(SvgText(family)), std::string::npos);
  // An engine column outside the alphabet is refused, naming the file, line and column.
  std::string bad = Slurp(dir / "sweep.csv");
  bad.replace(bad.find("\nbullet,") + 1, 6, "x`touch MARK_engine`");
  WriteFileAtomic(dir / "sweep.csv", bad);
  const ProcessResult refused = Report(dir, "report_sweep_bad");
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find("sweep.csv:2: column 'engine': expected an engine name"),
            std::string::npos)
      << refused.err;
  EXPECT_TRUE(Markers(base_).empty());
}

TEST_F(HostileNamesTest, AStudysEngineNamesAreCheckedBeforeAnyFigure) {
  WriteFileAtomic(base_ / "study.toml",
                  "scene = \"block.toml\"\nengines = [\"reference\"]\n"
                  "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [0.5, 3]\n");
  const fs::path dir = base_ / "study";
  RockbenchOk({"ensemble", (base_ / "study.toml").string(), "--out", dir.string(), "--jobs", "1"});
  ASSERT_EQ(Report(dir, "report_study").exit_code, 0);
  // study.json's engines and members.csv's engine column: the engine-name alphabet only.
  nlohmann::json study = nlohmann::json::parse(Slurp(dir / "study.json"));
  study["engines"] = {"reference", "../x`touch MARK_study`"};
  WriteFileAtomic(dir / "study.json", study.dump(2));
  const ProcessResult r = Report(dir, "report_study_bad");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("study.json: key 'engines': \"../x`touch MARK_study`\" is not an engine "
                       "name"),
            std::string::npos)
      << r.err;
  study["engines"] = {"reference"};
  WriteFileAtomic(dir / "study.json", study.dump(2));
  std::string members = Slurp(dir / "members.csv");
  members.replace(members.find(",reference,"), 11, ",<b>`touch MARK_row`,");
  WriteFileAtomic(dir / "members.csv", members);
  const ProcessResult row = Report(dir, "report_study_row");
  EXPECT_EQ(row.exit_code, 2) << row.out << row.err;
  EXPECT_NE(row.err.find("members.csv:2: column engine: \"<b>`touch MARK_row`\" is not an engine "
                         "name"),
            std::string::npos)
      << row.err;
  EXPECT_TRUE(Markers(base_).empty());
}

}  // namespace
}  // namespace rockbench::report
