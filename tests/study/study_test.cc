// Study files (src/study/study.h), member rows and members.csv (study_member.h) and the
// journal (study_runner.h), in process: members in product and zip order, derived axes against
// their definitions, error messages naming the file, line and key, rows that survive JSON, and
// a journal that resumes after a line cut short.
#include "study/study.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/sine_pulse_block.h"
#include "common/stack_scene.h"
#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "scene/limits.h"
#include "study/study_member.h"
#include "study/study_runner.h"

namespace rockbench {
namespace {

class StudyTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    Write("block.toml", testing_util::SinePulseBlockToml("2.0"));
  }
  std::string Error(const std::string& study_text) {
    try {
      LoadStudy(Write("study.toml", study_text));
    } catch (const SceneError& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(StudyTest, ProductMembersVaryTheLastAxisFastest) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\n"
                                     "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\n"
                                     "values = [0.1, 0.2, 0.3]\n"
                                     "[[axis]]\nkey = \"base.horizontal.frequency_hz\"\n"
                                     "values = [1, 2.5]\n"));
  ASSERT_EQ(s.member_count(), 6);
  EXPECT_EQ(s.ValueIndices(0), (std::vector<int>{0, 0}));
  EXPECT_EQ(s.ValueIndices(1), (std::vector<int>{0, 1}));
  EXPECT_EQ(s.ValueIndices(5), (std::vector<int>{2, 1}));
  EXPECT_EQ(s.engines, std::vector<std::string>{"reference"});
  EXPECT_EQ(s.axes[1].values[0].text, "1");
  const Scene m3 = MemberScene(s, 3);
  EXPECT_EQ(m3.horizontal->amplitude_g, 0.2);
  EXPECT_EQ(m3.horizontal->frequency_hz, 2.5);
}

TEST_F(StudyTest, ZipTakesValueIOfEveryAxis) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\ncombine = \"zip\"\n"
                                     "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\n"
                                     "values = [0.1, 0.2]\n"
                                     "[[axis]]\nkey = \"run.duration\"\nvalues = [1.5, 3]\n"));
  ASSERT_EQ(s.member_count(), 2);
  const Scene m1 = MemberScene(s, 1);
  EXPECT_EQ(m1.horizontal->amplitude_g, 0.2);
  EXPECT_EQ(m1.run.duration_s, 3.0);
  EXPECT_NE(Error("scene = \"block.toml\"\ncombine = \"zip\"\n"
                  "[[axis]]\nkey = \"run.duration\"\nvalues = [1, 2]\n"
                  "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\nvalues = [0.1]\n")
                .find("has 1 values"),
            std::string::npos);
}

// Derived axes against their definitions: p = sqrt(3 g / 4 R), the uplift acceleration
// g tan(alpha), a PGA target met exactly (the scale is the ratio of peaks) and lengths scaled.
TEST_F(StudyTest, DerivedAxesFollowTheirDefinitions) {
  const StudyDef s =
      LoadStudy(Write("study.toml",
                      "scene = \"block.toml\"\n"
                      "[[axis]]\nkey = \"size_factor\"\nvalues = [2]\n"
                      "[[axis]]\nkey = \"pulse.frequency_ratio\"\nvalues = [3]\n"
                      "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [1.5]\n"));
  const Scene m = MemberScene(s, 0);
  EXPECT_EQ(m.blocks[0].width_m, 0.8);
  EXPECT_EQ(m.blocks[0].height_m, 2.4);
  const double R = std::hypot(0.4, 1.2);
  const double p = std::sqrt(3.0 * 9.81 / (4.0 * R));
  EXPECT_NEAR(m.horizontal->frequency_hz, 3.0 * p / (2.0 * M_PI), 1e-15);
  EXPECT_NEAR(m.horizontal->amplitude_g * kStandardGravity_mps2, 1.5 * 9.81 / 3.0, 1e-14);

  const StudyDef t = LoadStudy(Write("study2.toml",
                                     "scene = \"block.toml\"\n"
                                     "[[axis]]\nkey = \"base.horizontal.pga_g\"\n"
                                     "values = [0.45]\n"
                                     "[[axis]]\nkey = \"base.horizontal.pgv_mps\"\n"
                                     "values = [0.2]\n"));
  const Scene n = MemberScene(t, 0);
  // pga_g first, then pgv_mps rescales: the last one applied holds.
  const IntensityMeasures im = MeasureIntensity(MotionComponent::FromDef(*n.horizontal), 2.0);
  EXPECT_NEAR(im.pgv_mps, 0.2, 1e-15);
}

TEST_F(StudyTest, PgaTargetIsMetToRounding) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\n"
                                     "[[axis]]\nkey = \"base.horizontal.pga_g\"\n"
                                     "values = [0.45, 1.2]\n"));
  for (int64_t i = 0; i < 2; ++i) {
    const Scene m = MemberScene(s, i);
    const IntensityMeasures im = MeasureIntensity(MotionComponent::FromDef(*m.horizontal), 2.0);
    EXPECT_NEAR(im.pga_mps2 / kStandardGravity_mps2, s.axes[0].values[i].number, 1e-15);
  }
}

TEST_F(StudyTest, ErrorsNameTheFileLineAndKey) {
  EXPECT_NE(Error("scene = \"block.toml\"\nbogus = 1\n").find("study.toml:2: bogus: unknown key"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\nengines = [\"reference\", \"nosuch\"]\n")
                .find("study.toml:2: engines: "),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\n[[axis]]\nkey = \"run.duration\"\nvalues = []\n")
                .find("values is empty"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\n[[axis]]\nkey = \"block1.colour\"\nvalues = [1]\n")
                .find("unknown key block1.colour"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\n[[axis]]\nkey = \"block1.width\"\nvalues = [-1]\n")
                .find("block1.width"),
            std::string::npos);
  EXPECT_NE(Error("[[axis]]\nkey = \"run.duration\"\nvalues = [1]\n").find("scene: required"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\n[[axis]]\nkey = \"base.horizontal.file\"\n"
                  "glob = \"records/*.AT2\"\n")
                .find("matches no file"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\n[[axis]]\nkey = \"size_factor\"\nvalues = [0]\n")
                .find("expected positive numbers"),
            std::string::npos);
}

// A value the scene refuses is blamed on the study: its file and line, the axis and value (or
// the `set` entry) that gave it, and the member's values, then the scene's own message; every
// value of every axis is checked when the study is read (issue 21: the base scene was blamed).
TEST_F(StudyTest, AValueOutOfRangeBlamesTheStudysAxisAndValue) {
  const std::string axis =
      Error("scene = \"block.toml\"\n[[axis]]\nkey = \"block1.width\"\nvalues = [0.2, -1]\n");
  EXPECT_EQ(axis.find(dir_.string() + "/study.toml:2: axis block1.width = -1 (member 1: "
                                      "block1.width = -1): "),
            0u)
      << axis;
  EXPECT_NE(axis.find("block1.width: expected a positive number"), std::string::npos) << axis;
  EXPECT_NE(axis.find("got -1"), std::string::npos) << axis;

  const std::string set = Error(
      "scene = \"block.toml\"\nset = [\"run.duration=2\", "
      "\"block1.height=-3\"]\n");
  EXPECT_EQ(set.find(dir_.string() + "/study.toml:2: set \"block1.height=-3\": "), 0u) << set;
  EXPECT_NE(set.find("got -3"), std::string::npos) << set;

  // A derived axis: size_factor 1e-300 makes a width of 4e-301 m.
  const std::string derived = Error(
      "scene = \"block.toml\"\n[[axis]]\nkey = \"run.duration\"\nvalues = [1, 2]\n"
      "[[axis]]\nkey = \"size_factor\"\nvalues = [1, 1e-300]\n");
  EXPECT_EQ(derived.find(dir_.string() + "/study.toml:5: axis size_factor = 1e-300 (member 1: "
                                         "run.duration = 1, size_factor = 1e-300): "),
            0u)
      << derived;
  EXPECT_NE(derived.find("block1.width"), std::string::npos) << derived;

  // A base scene whose record every member replaces may name a file that does not exist: the
  // member's missing record is the axis's, not the base scene's.
  Write("placeholder.toml",
        "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
        "[base.horizontal]\nfile = \"placeholder.AT2\"\n[run]\nduration = 2.0\n");
  const std::string record = Error(
      "scene = \"placeholder.toml\"\n[[axis]]\n"
      "key = \"base.horizontal.file\"\nvalues = [\"nosuch.AT2\"]\n");
  EXPECT_EQ(record.find(dir_.string() + "/study.toml:2: axis base.horizontal.file = nosuch.AT2 "
                                        "(member 0: base.horizontal.file = nosuch.AT2): "),
            0u)
      << record;
  EXPECT_NE(record.find("nosuch.AT2: no such record file"), std::string::npos) << record;

  // A broken base scene is the `scene` key's.
  Write("bad_base.toml", "[block1]\nwidth = -0.4\nheight = 1.2\ndensity = 2000.0\n");
  const std::string base = Error("scene = \"bad_base.toml\"\n");
  EXPECT_EQ(base.find(dir_.string() + "/study.toml:1: scene \""), 0u) << base;
  EXPECT_NE(base.find("block1.width"), std::string::npos) << base;
}

// A combination the scene refuses that no single value shows (block 2 wider than block 1 only
// for the second value of both axes) is found when that member runs: its row is an error that
// names the axis whose value made it fail and every value of the member.
TEST_F(StudyTest, AMembersErrorRowNamesTheAxisValueAndTheMember) {
  Write("stack.toml",
        "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
        "[block2]\nwidth = 0.3\nheight = 0.9\ndensity = 2000.0\n"
        "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\nfrequency_hz = 2.0\n"
        "[run]\nduration = 1.0\n");
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"stack.toml\"\n"
                                     "[[axis]]\nkey = \"block1.width\"\nvalues = [0.4, 0.35]\n"
                                     "[[axis]]\nkey = \"block2.width\"\nvalues = [0.3, 0.38]\n"));
  ASSERT_EQ(s.member_count(), 4);
  EXPECT_TRUE(RunMemberHere(s, 2, "reference").has_result);
  const MemberRow r = RunMemberHere(s, 3, "reference");
  EXPECT_EQ(r.status, "error");
  EXPECT_EQ(r.detail.find(dir_.string() + "/study.toml:5: axis block2.width = 0.38 (member 3: "
                                          "block1.width = 0.35, block2.width = 0.38): "),
            0u)
      << r.detail;
  EXPECT_NE(r.detail.find("block2.width: expected at most block1.width"), std::string::npos)
      << r.detail;
  EXPECT_EQ(MemberText(s, 3), "member 3: block1.width = 0.35, block2.width = 0.38");
}

// A NUL in a file name printed "rockbench ensemble: " and nothing more; an over-long path a bare
// file system error of the whole path. Both now name the file, line and key, and show an
// excerpt.
TEST_F(StudyTest, ControlCharactersAndImpossiblePathsAreNamedInShort) {
  const std::string nul = Error("scene = \"blo\\u0000ck.toml\"\n");
  EXPECT_EQ(nul, dir_.string() +
                     "/study.toml:1: scene: \"blo\\0ck.toml\" holds a control "
                     "character (byte 3); expected printable text");
  const std::string long_path = Error("scene = \"" + std::string(5000, 'a') + ".toml\"\n");
  EXPECT_NE(long_path.find("study.toml:1: scene: \"aaaa"), std::string::npos) << long_path;
  EXPECT_NE(long_path.find("... (5005 bytes)\" is a path of 5005 bytes, more than the 4095"),
            std::string::npos)
      << long_path;
  EXPECT_LT(long_path.size(), 400u);
  const std::string long_name = Error("scene = \"d/" + std::string(300, 'b') + ".toml\"\n");
  EXPECT_NE(long_name.find("holds a name of 305 bytes, more than the 255"), std::string::npos)
      << long_name;
  const std::string record =
      Error("scene = \"block.toml\"\n[[axis]]\nkey = \"base.horizontal.file\"\nvalues = [\"" +
            std::string(3000, 'r') + "/" + std::string(3000, 'r') + ".AT2\"]\n");
  EXPECT_NE(record.find("study.toml:4: axis base.horizontal.file: \"rrrr"), std::string::npos)
      << record;
  EXPECT_LT(record.size(), 400u);
  const std::string glob = Error(
      "scene = \"block.toml\"\n[[axis]]\nkey = \"base.horizontal.file\"\n"
      "glob = \"" +
      std::string(5000, 'g') + "*.AT2\"\n");
  EXPECT_NE(glob.find("axis base.horizontal.file: glob: \"gggg"), std::string::npos) << glob;
  EXPECT_LT(glob.size(), 400u);
  const std::string key = Error(
      "scene = \"block.toml\"\n[[axis]]\nkey = \"run.\\u0000duration\"\n"
      "values = [1]\n");
  EXPECT_NE(key.find("study.toml:2: [[axis]] key: \"run.\\0duration\" holds a control"),
            std::string::npos)
      << key;
  const std::string set = Error("scene = \"block.toml\"\nset = [\"run.duration=\\u00012\"]\n");
  EXPECT_NE(set.find("study.toml:2: set: \"run.duration=\\x012\" holds a control"),
            std::string::npos)
      << set;
  const std::string value = Error(
      "scene = \"block.toml\"\n[[axis]]\n"
      "key = \"base.horizontal.kind\"\nvalues = [\"ricker\\n\"]\n");
  EXPECT_NE(value.find("axis base.horizontal.kind: \"ricker\\n\" holds a control"),
            std::string::npos)
      << value;
  // An unknown key of a megabyte is cut to an excerpt.
  const std::string unknown =
      Error("scene = \"block.toml\"\n" + std::string(1 << 20, 'k') + " = 1\n");
  EXPECT_NE(unknown.find("study.toml:2: kkkk"), std::string::npos);
  EXPECT_LT(unknown.size(), 400u);
}

// At most kMaxStudyRuns runs (members x engines), checked before any member is built and
// without overflow (ten axes of 100 values are 1e20 members).
TEST_F(StudyTest, TheStudysSizeIsLimited) {
  const auto values = [](int n) {
    std::string v = "[";
    for (int i = 0; i < n; ++i) v += (i ? ", " : "") + std::to_string(1.0 + 0.001 * i);
    return v + "]";
  };
  const std::string big = Error(
      "scene = \"block.toml\"\nengines = [\"reference\", \"bullet\"]\n"
      "[[axis]]\nkey = \"run.duration\"\nvalues = " +
      values(1000) + "\n[[axis]]\nkey = \"block1.height\"\nvalues = " + values(501) + "\n");
  EXPECT_NE(big.find("study.toml: 501000 members x 2 runs = 1002000 runs (axes: run.duration "
                     "(1000) x block1.height (501)), more than the limit of 1000000 runs"),
            std::string::npos)
      << big;
  std::string huge = "scene = \"block.toml\"\n";
  const char* keys[] = {"run.duration",
                        "block1.height",
                        "block1.width",
                        "block1.density",
                        "run.gravity",
                        "base.horizontal.amplitude_g",
                        "base.horizontal.frequency_hz",
                        "initial.theta1",
                        "model.rtol",
                        "run.output_interval"};
  for (const char* k : keys) {
    huge += "[[axis]]\nkey = \"" + std::string(k) + "\"\nvalues = " + values(100) + "\n";
  }
  const std::string e = Error(huge);
  EXPECT_NE(e.find("1e+20 members x 1 runs = 1e+20 runs"), std::string::npos) << e;
  // Exactly at the limit is fine as far as the size goes (the axis's 1000 values are checked).
  EXPECT_EQ(
      Error("scene = \"block.toml\"\n[[axis]]\nkey = \"run.duration\"\nvalues = " + values(1000) +
            "\n[[axis]]\nkey = \"block1.height\"\nvalues = " + values(1000) + "\n"),
      "no error");
}

// A member whose run would need more than the memory budget is refused when the study is read,
// naming the axis and value and the scene key of the estimate; a larger budget lets it load.
TEST_F(StudyTest, AMemberPastTheMemoryBudgetIsRefusedNamingItsAxis) {
  const std::string text =
      "scene = \"block.toml\"\n[[axis]]\nkey = \"run.output_interval\"\n"
      "values = [0.01, 1e-9]\n";
  const std::string e = Error(text);
  EXPECT_EQ(e.find(dir_.string() + "/study.toml:2: axis run.output_interval = 1e-09 (member 1: "
                                   "run.output_interval = 1e-09): "),
            0u)
      << e;
  EXPECT_NE(e.find("run.output_interval: needs an estimated"), std::string::npos) << e;
  EXPECT_NE(e.find("more than the memory budget of 2 GiB"), std::string::npos) << e;
  const ResourceBudget before = ProcessBudget();
  ResourceBudget large;
  large.memory_bytes = 1e13;
  SetProcessBudget(large);
  EXPECT_EQ(Error(text), "no error");
  SetProcessBudget(before);
}

// A run that runs out of memory all the same (here: an address-space limit far below the
// memory budget its estimate was checked against) is a row that says so and names the engine
// and the member's values, not a bare "std::bad_alloc". Run in a child process: the limit is
// its own.
TEST_F(StudyTest, ARunOutOfMemoryIsARowThatSaysSo) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "an address-space limit and AddressSanitizer's shadow memory do not mix";
#endif
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\n"
                                     "[[axis]]\nkey = \"run.duration\"\nvalues = [2, 100]\n"
                                     "[[axis]]\nkey = \"run.output_interval\"\n"
                                     "values = [0.01]\n"));
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(fds[0]);
    ResourceBudget large;
    large.memory_bytes = 1e13;
    SetProcessBudget(large);
    // Member 1: 100 s at an output interval of 1 us would hold 1e8 history rows (GBs); the
    // address space is capped 256 MiB above what the process holds now.
    StudyDef t = s;
    t.axes[1].values[0].toml = t.axes[1].values[0].text = "1e-06";
    const std::string status = testing_util::ReadFile("/proc/self/status");
    const size_t at = status.find("VmSize:");
    const long vm_kb = at == std::string::npos ? 0 : std::stol(status.substr(at + 7));
    const rlimit cap{static_cast<rlim_t>(vm_kb + 256 * 1024) * 1024,
                     static_cast<rlim_t>(vm_kb + 256 * 1024) * 1024};
    ::setrlimit(RLIMIT_AS, &cap);
    const MemberRow r = RunMemberHere(t, 1, "reference");
    const std::string out = r.status + "\n" + r.detail;
    (void)!::write(fds[1], out.data(), out.size());
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) out.append(buf, n);
  ::close(fds[0]);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st)) << out;
  EXPECT_EQ(out.find("error\nout of memory (std::bad_alloc) in the reference run of member 1: "
                     "run.duration = 100, run.output_interval = 1e-06: "),
            0u)
      << out;
}

TEST_F(StudyTest, WallLimitIsInTheRangeOfWallLimit) {
  EXPECT_NE(Error("scene = \"block.toml\"\nwall_limit_s = 1e300\n")
                .find("study.toml:2: wall_limit_s: expected 0.001 to 1e+07 s, got 1e+300"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"block.toml\"\nwall_limit_s = 5e-324\n").find("wall_limit_s"),
            std::string::npos);
}

TEST_F(StudyTest, RowsSurviveJsonAndTheirCsvLineNamesTheirRun) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\n"
                                     "set = [\"base.horizontal.frequency_hz=0.5\"]\n"
                                     "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\n"
                                     "values = [0.1, 0.5]\n"));
  const MemberRow r = RunMemberHere(s, 1, "reference");
  ASSERT_TRUE(r.has_result) << r.detail;
  // A 0.5 g sine pulse of 2 s (omega_p / p = 0.92) on a block of tan(alpha) = 1/3: 1.5 times
  // the uplift acceleration for longer than the block's own time scale overturns it (0.9 g
  // would throw it off its pivot: the model stops, assumption_violated); 0.1 g, below the
  // uplift acceleration g / 3, does not lift it.
  EXPECT_EQ(r.overturned_block, 1);
  EXPECT_EQ(r.status, "overturned");
  const MemberRow q = MemberRowFromJson(MemberRowToJson(r));
  EXPECT_EQ(MembersCsvLine(s, q), MembersCsvLine(s, r));
  const std::optional<RowKey> key = MembersCsvKey(s, MembersCsvLine(s, r));
  ASSERT_TRUE(key);
  EXPECT_EQ(key->member, 1);
  EXPECT_EQ(key->engine, "reference");
  const std::string line = MembersCsvLine(s, r);
  EXPECT_FALSE(MembersCsvKey(s, line.substr(0, line.size() - 5)));
  const MemberRow still = RunMemberHere(s, 0, "reference");
  EXPECT_EQ(still.overturned_block, 0);
  EXPECT_EQ(still.peak_theta_rad.at(0), 0.0);
  EXPECT_EQ(*still.pga_g, 0.1);
  EXPECT_TRUE(*still.converged);
}

TEST_F(StudyTest, JournalResumesAfterALineCutShort) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"block.toml\"\n"
                                     "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\n"
                                     "values = [0.1, 0.2, 0.3]\n"));
  const std::filesystem::path out = dir_ / "out";
  {
    MembersJournal j(s, out, /*resume=*/false);
    j.Append(FailedRow(2, "reference", "error", "x"));
  }
  EXPECT_THROW(MembersJournal(s, out, false), SceneError);
  // A kill in the middle of a write leaves part of a line.
  std::ofstream(out / "members.csv", std::ios::app) << "0,0.1,1.2";
  MembersJournal j(s, out, /*resume=*/true);
  EXPECT_EQ(j.rows_at_open(), 1);
  const std::vector<StudyTask> pending = PendingTasks(s, j);
  ASSERT_EQ(pending.size(), 2u);
  EXPECT_EQ(pending[0].member, 0);
  EXPECT_EQ(pending[1].member, 1);
  EXPECT_THROW(j.Finish(), SceneError);  // two runs have no row yet
}

// Every study shipped in scenes/studies/ (the files with a `scene =` key; the others are their
// base scenes) loads, and every member's scene is valid and its motion loads: the README's
// commands cannot fail on a member's input. (scale_10000.toml's 10,000 members take about 1 s.)
TEST(ShippedStudies, EveryMembersSceneAndMotionLoad) {
  const std::filesystem::path dir = std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "scenes/studies";
  int studies = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\nscene = ") == std::string::npos) continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++studies;
    const StudyDef study = LoadStudy(entry.path());
    ASSERT_GT(study.member_count(), 0);
    for (int64_t m = 0; m < study.member_count(); ++m) {
      const Scene scene = MemberScene(study, m);
      const GroundMotion motion = GroundMotion::FromScene(scene);
      ASSERT_TRUE(motion.has_horizontal()) << "member " << m;
    }
  }
  EXPECT_GE(studies, 6);
}

// N >= 3 blocks (issue 23): a study over block3.width of a 3-block stack runs. Every member
// has the study's three blocks, its row has the per-block columns of the header (p3, alpha3,
// peak_theta3, theta3's error and horizon), survives JSON, and the journal's key reader finds
// its engine column.
TEST_F(StudyTest, AStudyOverBlock3WidthRuns) {
  Write("stack.toml", testing_util::StackSceneToml(3, 0.5));
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"stack.toml\"\n"
                                     "[[axis]]\nkey = \"block3.width\"\nvalues = [0.5, 0.7]\n"));
  ASSERT_EQ(s.blocks, 3);
  ASSERT_EQ(s.member_count(), 2);
  EXPECT_DOUBLE_EQ(MemberScene(s, 1).blocks[2].width_m, 0.7);
  const std::string header = MembersCsvHeader(s);
  for (const char* column : {",p3_radps,alpha3_rad,", ",peak_theta2_rad,peak_theta3_rad,impacts,",
                             ",theta2_max_abs_error_rad,theta3_max_abs_error_rad,theta1_horizon_s,",
                             ",theta2_horizon_s,theta3_horizon_s,impacts_matched,"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column << " in " << header;
  }
  const auto cells = [](const std::string& line) {
    return std::count(line.begin(), line.end(), ',') + 1;
  };
  for (int64_t m = 0; m < 2; ++m) {
    const MemberRow row = RunMemberHere(s, m, "reference");
    ASSERT_TRUE(row.has_result) << row.status << ": " << row.detail;
    ASSERT_EQ(row.p_radps.size(), 3u);
    ASSERT_EQ(row.peak_theta_rad.size(), 3u);
    // Block 3's alpha is its own: atan(B3 / H3) with the member's width.
    EXPECT_DOUBLE_EQ(row.alpha_rad[2], std::atan2(m == 0 ? 0.5 : 0.7, 1.8));
    EXPECT_GT(row.peak_theta_rad[2], 0.0);
    const std::string line = MembersCsvLine(s, row);
    EXPECT_EQ(cells(line), cells(header)) << line;
    const std::optional<RowKey> key = MembersCsvKey(s, line);
    ASSERT_TRUE(key.has_value()) << line;
    EXPECT_EQ(key->member, m);
    EXPECT_EQ(key->engine, "reference");
    const MemberRow back = MemberRowFromJson(MemberRowToJson(row));
    EXPECT_EQ(MembersCsvLine(s, back), line);
  }
  // A row without a result keeps the row's shape.
  const std::string failed = MembersCsvLine(s, FailedRow(1, "reference", "error", "x"));
  EXPECT_EQ(cells(failed), cells(header));
  ASSERT_TRUE(MembersCsvKey(s, failed).has_value());
}

}  // namespace
}  // namespace rockbench
