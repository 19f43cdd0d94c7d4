// The tolerance-file reader: every malformed entry fails with a message naming the file, the
// entry and what was expected; grouping; and bound checks (pass, fail, margins, abs, nulls).
#include "tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "run/engine_run.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench::agreement {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "scenes";
const std::string kFile = "tol.toml";

// One valid entry on a two-block scene, with `extra` lines appended to it.
std::string Entry(const std::string& extra = "",
                  const std::string& metric = "theta2.max_abs_error_rad",
                  const std::string& bound = "max = 1.2e-3") {
  return "[[bound]]\nscene = \"thesis_free_rocking.toml\"\nengine = \"bullet\"\nmetric = \"" +
         metric + "\"\n" + bound + "\nwhy = \"measured 6.0e-4 rad; 2x margin\"\n" + extra;
}

// The message of the ToleranceError that parsing `text` throws ("" if none), its scenes in
// `scenes` (the shipped ones by default).
std::string Error(const std::string& text, const std::filesystem::path& scenes = kScenes) {
  try {
    ParseTolerances(text, kFile, scenes);
  } catch (const ToleranceError& e) {
    return e.what();
  }
  return "";
}

TEST(TolerancesTest, ReadsAValidFile) {
  const std::string text = Entry() + "\n" +
                           Entry("settings = [\"bullet.time_step=1e-3\"]\n",
                                 "abs(theta1.peak_rel_error)", "max = 0.01") +
                           "\n" + Entry("", "impacts_matched", "min = 35") + "\n" +
                           Entry("", "final.agree", "equals = true");
  const std::vector<Bound> b = ParseTolerances(text, kFile, kScenes);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].scene, "thesis_free_rocking.toml");
  EXPECT_EQ(b[0].engine, "bullet");
  EXPECT_EQ(b[0].line, 1);
  EXPECT_EQ(b[0].index, 1);
  EXPECT_EQ(b[0].metric_path, "theta2.max_abs_error_rad");
  EXPECT_FALSE(b[0].metric_abs);
  ASSERT_TRUE(b[0].max.has_value());
  EXPECT_EQ(*b[0].max, 1.2e-3);
  EXPECT_FALSE(b[0].min || b[0].equals);
  EXPECT_TRUE(b[0].settings.empty());
  EXPECT_EQ(b[1].settings, std::vector<std::string>{"bullet.time_step=1e-3"});
  EXPECT_TRUE(b[1].metric_abs);
  EXPECT_EQ(b[1].metric_path, "theta1.peak_rel_error");
  EXPECT_EQ(*b[2].min, 35.0);
  EXPECT_EQ(*b[3].equals, nlohmann::json(true));
  EXPECT_EQ(b[3].index, 4);
  EXPECT_TRUE(std::filesystem::is_regular_file(b[3].scene_path));
}

TEST(TolerancesTest, EveryMistakeNamesTheFileTheEntryAndTheKey) {
  struct Case {
    std::string text, expect1, expect2;
  };
  const std::vector<Case> cases = {
      {Entry("bond = 3\n"), "bond: unknown key", ""},
      {Entry("why = \"x\"\n"), "", ""},  // duplicate key: a TOML error with file:line
      {"[[bound]]\nscene = \"thesis_free_rocking.toml\"\nengine = \"bullet\"\n"
       "metric = \"impacts_matched\"\nmin = 3\n",
       "why: missing", ""},
      {Entry("", "impacts_matched", "min = 3\nmax = 40"), "exactly one of max, min, equals", ""},
      {Entry("", "impacts_matched", ""), "expected exactly one of max, min", ""},
      {Entry("", "theta2.max_abs_eror_rad"), "unknown metric 'theta2.max_abs_eror_rad'",
       "theta2.max_abs_error_rad"},
      {Entry("", "theta2", "max = 1"), "unknown metric 'theta2'", ""},
      {Entry("", "final.agree", "max = 1"), "is a boolean: bound it with equals", ""},
      {Entry("", "impacts_matched", "equals = true"), "is a number: bound it with max or min", ""},
      {Entry("", "abs(final.agree)", "equals = true"), "abs() applies to numbers only", ""},
      {Entry("", "theta1.max_abs_error_rad", "max = \"1e-3\""), "max: expected a number", ""},
      {Entry("", "theta1.max_abs_error_rad", "max = nan"), "max: expected a finite number", ""},
      {Entry("settings = [\"bullet.time_stp=1e-3\"]\n"), "settings do not load", "bullet.time_stp"},
      {Entry("settings = [\"bullet.time_step\"]\n"), "expected key=value", ""},
      {Entry("settings = \"bullet.time_step=1e-3\"\n"), "settings: expected an array", ""},
      {Entry("", "impacts_matched", "min = 3") + Entry("", "impacts_matched", "min = 4"),
       "bound #2", "repeats an earlier entry"},
      {"title = \"x\"\n" + Entry(), "title: unknown key", ""},
      {Entry("", "wall_s", "max = 10"), "wall_s is a timing", ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string msg = Error(c.text);
    EXPECT_NE(msg.find(kFile + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect1), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect2), std::string::npos) << msg;
  }
}

TEST(TolerancesTest, EntryMessagesSayWhichEntryAndWhere) {
  const std::string msg = Error(Entry() + "\n" + Entry("", "theta9.max_abs_error_rad"));
  // The second entry starts at line 8 (its [[bound]] header); it is #2.
  EXPECT_NE(msg.find("tol.toml:8: bound #2 (thesis_free_rocking.toml, bullet, [], "
                     "theta9.max_abs_error_rad)"),
            std::string::npos)
      << msg;
}

TEST(TolerancesTest, SceneMustExistAndTheta2NeedsTwoBlocks) {
  std::string text = Entry();
  text.replace(text.find("thesis_free_rocking"), 19, "thesis_free_rockin");
  EXPECT_NE(Error(text).find("scene: no such scene file"), std::string::npos) << Error(text);
  // Housner's scene is one block: theta2 does not exist there, theta1 does.
  text = Entry();
  text.replace(text.find("thesis_free_rocking"), 19, "housner_free_rocking");
  EXPECT_NE(Error(text).find("unknown metric 'theta2.max_abs_error_rad' for this scene (one "
                             "block)"),
            std::string::npos)
      << Error(text);
  text.replace(text.find("theta2"), 6, "theta1");
  EXPECT_EQ(Error(text), "");
}

TEST(TolerancesTest, EngineMustBeKnownAndTheReferenceNeedsOtherSettings) {
  std::string text = Entry();
  text.replace(text.find("\"bullet\""), 8, "\"bulet\"");
  EXPECT_NE(Error(text).find("engine: unknown engine 'bulet'"), std::string::npos);
  text = Entry();
  text.replace(text.find("\"bullet\""), 8, "\"reference\"");
  EXPECT_NE(Error(text).find("reference_settings: required"), std::string::npos) << Error(text);
  EXPECT_EQ(Error(text + "reference_settings = [\"model.rtol=1e-12\"]\n"), "");
  EXPECT_NE(Error(text + "reference_settings = [\"model.rtol=-1\"]\n")
                .find("reference_settings do not load"),
            std::string::npos);
  // On an engine's row the comparison would ignore them: an error, not a silent no-op.
  EXPECT_NE(Error(Entry() + "reference_settings = [\"model.rtol=1e-12\"]\n")
                .find("reference_settings: only with engine = \"reference\""),
            std::string::npos)
      << Error(Entry() + "reference_settings = [\"model.rtol=1e-12\"]\n");
}

TEST(TolerancesTest, RunTimeKeysAreAcceptedWhereTheShapeIsOnlyKnownAfterARun) {
  // "violations" is null in an empty agreement; the engine fills it with an object.
  EXPECT_EQ(Error(Entry("", "violations.sliding", "equals = false")), "");
  EXPECT_EQ(Error(Entry("", "abs(overturn.time_error_s)", "max = 0.01")), "");
}

TEST(TolerancesTest, GroupsByComparisonInFileOrder) {
  const std::string rs = "reference_settings = [\"model.rtol=1e-12\"]\n";
  std::string ref = Entry(rs, "theta1.max_abs_error_rad");
  ref.replace(ref.find("\"bullet\""), 8, "\"reference\"");
  const std::string text = Entry() + "\n" + ref + "\n" +
                           Entry("settings = [\"bullet.time_step=1e-3\"]\n") + "\n" +
                           Entry("", "impacts_matched", "min = 30");
  const std::vector<BoundGroup> g = GroupBounds(ParseTolerances(text, kFile, kScenes));
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0].TestName(), "thesis_free_rocking_bullet");
  ASSERT_EQ(g[0].bounds.size(), 2u);
  EXPECT_EQ(g[0].bounds[1].metric, "impacts_matched");
  EXPECT_EQ(g[1].TestName(), "thesis_free_rocking_reference_vs_model_rtol_1e_12");
  EXPECT_EQ(g[2].TestName(), "thesis_free_rocking_bullet_bullet_time_step_1e_3");
}

TEST(TolerancesTest, NamesThatWouldCollideAreAnError) {
  const std::string text = Entry("settings = [\"bullet.time_step=1e-3\"]\n") + "\n" +
                           Entry("settings = [\"bullet.time_step = 1e-3\"]\n");
  const std::vector<Bound> b = ParseTolerances(text, kFile, kScenes);
  EXPECT_THROW(GroupBounds(b), ToleranceError);
}

// A bound from text, for the checks below.
Bound One(const std::string& metric, const std::string& bound) {
  return ParseTolerances(Entry("", metric, bound), kFile, kScenes).at(0);
}

TEST(TolerancesTest, CheckBoundPassesFailsAndSaysWhy) {
  nlohmann::json a;
  a["theta2"]["max_abs_error_rad"] = 6.0e-4;
  a["theta2"]["peak_rel_error"] = -2.0e-3;
  a["impacts_matched"] = 35;
  a["final"]["agree"] = true;
  a["overturn"]["time_error_s"] = nullptr;

  Verdict v = CheckBound(One("theta2.max_abs_error_rad", "max = 1.2e-3"), a);
  EXPECT_TRUE(v.pass);
  EXPECT_NE(v.message.find("margin 2.00x"), std::string::npos) << v.message;

  // Over the bound: the message has the metric, the measured value, the bound and the why.
  v = CheckBound(One("theta2.max_abs_error_rad", "max = 5e-4"), a);
  EXPECT_FALSE(v.pass);
  EXPECT_EQ(v.measured, "0.0006");
  for (const char* part : {"theta2.max_abs_error_rad", "max 0.0005", "measured 0.0006", "FAILED",
                           "why: measured 6.0e-4 rad; 2x margin", "tol.toml:1"}) {
    EXPECT_NE(v.message.find(part), std::string::npos) << part << "\n" << v.message;
  }
  // A bound equal to the measurement passes (bounds are inclusive).
  EXPECT_TRUE(CheckBound(One("theta2.max_abs_error_rad", "max = 6e-4"), a).pass);

  // abs(): -2e-3 is within 1e-3 only without it.
  EXPECT_FALSE(CheckBound(One("abs(theta2.peak_rel_error)", "max = 1e-3"), a).pass);
  EXPECT_TRUE(CheckBound(One("abs(theta2.peak_rel_error)", "max = 2.5e-3"), a).pass);

  // min.
  EXPECT_TRUE(CheckBound(One("impacts_matched", "min = 35"), a).pass);
  EXPECT_FALSE(CheckBound(One("impacts_matched", "min = 36"), a).pass);

  // equals.
  EXPECT_TRUE(CheckBound(One("final.agree", "equals = true"), a).pass);
  EXPECT_FALSE(CheckBound(One("final.agree", "equals = false"), a).pass);

  // A null (no overturn) or a missing key fails a numeric bound, saying so.
  v = CheckBound(One("abs(overturn.time_error_s)", "max = 0.01"), a);
  EXPECT_FALSE(v.pass);
  EXPECT_NE(v.message.find("null"), std::string::npos) << v.message;
  v = CheckBound(One("theta1.max_abs_error_rad", "max = 0.01"), a);
  EXPECT_FALSE(v.pass);
  EXPECT_NE(v.message.find("no such key"), std::string::npos) << v.message;
}

// A scratch folder holding a stack of three blocks (`stack3.toml`: a statue on a plinth on a
// pedestal, 1 s of free rocking of the statue).
class ThreeBlocksTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    Write("stack3.toml",
          "title = \"three blocks\"\n"
          "[[block]]\nwidth = 1.0\nheight = 1.1\ndensity = 2300.0\n"
          "[[block]]\nwidth = 0.7\nheight = 0.2\ndensity = 2700.0\n"
          "[[block]]\nwidth = 0.4\nheight = 1.5\ndensity = 2700.0\n"
          "[initial]\ntheta = [0.0, 0.0, 0.05]\nomega = [0.0, 0.0, 0.0]\n"
          "[run]\nduration = 1.0\noutput_interval = 0.01\n");
  }
  // The message of the ToleranceError that one bound on stack3.toml throws ("" if none).
  std::string ErrorOn(const std::string& metric, const std::string& bound) {
    std::string text = Entry("", metric, bound);
    text.replace(text.find("thesis_free_rocking"), 19, "stack3");
    return Error(text, dir_);
  }
};

TEST_F(ThreeBlocksTest, AStackOfNBlocksHasTheMetricsOfEachBlock) {
  // Three blocks: theta3 and its final error exist, theta4 does not.
  EXPECT_EQ(ErrorOn("theta3.max_abs_error_predictable_rad", "max = 1e-3"), "");
  EXPECT_EQ(ErrorOn("theta3.predictability_horizon_s", "min = 1"), "");
  EXPECT_EQ(ErrorOn("final.theta3_error_rad", "max = 1e-3"), "");
  EXPECT_EQ(ErrorOn("theta2.samples_beyond", "max = 0"), "");
  const std::string msg = ErrorOn("theta4.max_abs_error_rad", "max = 1e-3");
  EXPECT_NE(msg.find("unknown metric 'theta4.max_abs_error_rad' for this scene (3 blocks)"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("theta3.max_abs_error_rad"), std::string::npos) << msg;
}

class UnguardedScenesTest : public testing_util::ScratchDirTest {};

TEST_F(UnguardedScenesTest, ASceneWithoutAnEngineBoundIsReported) {
  // Two scenes (copies of shipped ones) and a stray non-scene file.
  std::filesystem::copy_file(kScenes / "housner_free_rocking.toml", dir_ / "a.toml");
  std::filesystem::copy_file(kScenes / "housner_free_rocking.toml", dir_ / "b.toml");
  Write("notes.txt", "not a scene");
  EXPECT_EQ(SceneFiles(dir_), (std::vector<std::string>{"a.toml", "b.toml"}));
  const std::string a =
      "[[bound]]\nscene = \"a.toml\"\nengine = \"bullet\"\nmetric = "
      "\"impacts_matched\"\nmin = 4\nwhy = \"w\"\n";
  std::string b_ref = a;
  b_ref.replace(b_ref.find("a.toml"), 6, "b.toml");
  b_ref.replace(b_ref.find("\"bullet\""), 8, "\"reference\"");
  b_ref += "reference_settings = [\"model.rtol=1e-12\"]\n";
  // b.toml has only a reference-against-itself bound: not guarded, for any engine; a.toml is
  // guarded for Bullet only.
  std::vector<Bound> bounds = ParseTolerances(a + b_ref, kFile, dir_);
  std::vector<std::string> expected;
  for (const char* scene : {"a.toml", "b.toml"}) {
    for (const std::string& engine : KnownEngines()) {
      if (engine == "reference" || (std::string(scene) == "a.toml" && engine == "bullet")) continue;
      expected.push_back(std::string(scene) + ": " + engine);
    }
  }
  EXPECT_EQ(UnguardedScenes(bounds, dir_), expected);
  // A bound per scene and engine guards them all.
  std::string all;
  for (const char* scene : {"a.toml", "b.toml"}) {
    for (const std::string& engine : KnownEngines()) {
      if (engine == "reference") continue;
      std::string x = a;
      x.replace(x.find("a.toml"), 6, scene);
      x.replace(x.find("\"bullet\""), 8, "\"" + engine + "\"");
      all += x;
    }
  }
  bounds = ParseTolerances(all + b_ref, kFile, dir_);
  EXPECT_TRUE(UnguardedScenes(bounds, dir_).empty());
}

}  // namespace
}  // namespace rockbench::agreement
