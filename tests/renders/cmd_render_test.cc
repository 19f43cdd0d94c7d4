// `rockbench render` run as a program: from a scene file (simulated first), from a run folder
// (drawn from its histories, not simulated again), and its errors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "renders/renderer.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::renders {
namespace {
namespace fs = std::filesystem;

const fs::path kSource = ROCKBENCH_SOURCE_DIR;

struct Result {
  int status = -1;
  std::string output;  // standard output and error
};

Result RunCli(const std::string& args) {
  Result r;
  const std::string cmd = std::string(ROCKBENCH_CLI) + " render " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

fs::path Folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rockbench_cmd_render_test_" + name);
  fs::remove_all(dir);
  return dir;
}

#if ROCKBENCH_HAVE_OSMESA

int CountFiles(const fs::path& dir) {
  int n = 0;
  if (!fs::exists(dir)) return 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

TEST(CmdRender, SceneFileIsSimulatedThenDrawn) {
  const fs::path out = Folder("scene");
  const Result r = RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " +
                          out.string() + " --frames --size 160x120 --to 0.5 --fps 10");
  ASSERT_EQ(r.status, 0) << r.output;
  // The reference model ran (its one-line summary is printed).
  EXPECT_NE(r.output.find("reference:"), std::string::npos) << r.output;
  EXPECT_EQ(CountFiles(out / "frames"), 5);
  fs::remove_all(out);
}

TEST(CmdRender, RunFolderIsDrawnFromItsHistories) {
  // A run folder made by hand: histories that no simulation of this scene would give (block 1
  // held at 0.3 rad), so the frame proves the files were drawn as they are.
  const fs::path dir = Folder("run");
  fs::create_directories(dir / "reference");
  fs::create_directories(dir / "other");
  fs::copy_file(kSource / "scenes/thesis_free_rocking.toml", dir / "scene.toml");
  History ref, other;
  for (int i = 0; i <= 10; ++i) {
    ref.samples.push_back(
        {.t_s = 0.1 * i, .theta1_rad = 0.3, .theta2_rad = 0.3, .mode = Mode::k3a});
    other.samples.push_back(
        {.t_s = 0.1 * i, .theta1_rad = -0.2, .theta2_rad = 0.1, .mode = Mode::k2b});
  }
  WriteFileAtomic(dir / "reference" / "history.csv", HistoryToCsv(ref));
  WriteFileAtomic(dir / "other" / "history.csv", HistoryToCsv(other));
  const fs::path out = dir / "pictures";
  const Result r = RunCli(dir.string() + " --out " + out.string() +
                          " --frames --size 320x240 --fps 10 --layout side");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("reference:"), std::string::npos) << "simulated again:\n" << r.output;
  ASSERT_EQ(CountFiles(out / "frames"), 10);
  // The same frame drawn directly from the same files.
  const Scene scene = LoadScene(dir / "scene.toml");
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  cfg.layout = Layout::kSide;
  cfg.title = scene.title;
  FrameRenderer direct(scene,
                       {{"reference", ReadHistoryCsv(dir / "reference" / "history.csv")},
                        {"other", ReadHistoryCsv(dir / "other" / "history.csv")}},
                       {}, cfg);
  EXPECT_EQ(ReadPng(out / "frames" / "frame_00004.png").rgb, direct.Render(0.4).rgb);
  fs::remove_all(dir);
}

#else

TEST(CmdRender, SaysThisBuildHasNoOsmesa) {
  const fs::path out = Folder("no_osmesa");
  const Result r = RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " +
                          out.string() + " --frames --size 160x120 --to 0.5");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("no OSMesa"), std::string::npos) << r.output;
  // Said before any work: the reference model did not run.
  EXPECT_EQ(r.output.find("reference:"), std::string::npos) << r.output;
  fs::remove_all(out);
}

#endif

TEST(CmdRender, AskingForNoPicturesIsAnErrorBeforeAnyWork) {
  const fs::path out = Folder("nothing");
  const Result r =
      RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("nothing to make"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CmdRender, BadOptionsNameTheOption) {
  const std::string scene = (kSource / "scenes/thesis_free_rocking.toml").string();
  const fs::path out = Folder("bad");
  Result r = RunCli(scene + " --out " + out.string() + " --frames --size 640by480");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  r = RunCli(scene + " --out " + out.string() + " --mp4 --size 641x480");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("even"), std::string::npos) << r.output;
  r = RunCli(scene + " --out " + out.string() + " --frames --layout stacked");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--layout"), std::string::npos) << r.output;
  r = RunCli(out.string() + "/missing --out " + out.string() + " --frames");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("no such scene file or run folder"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace rockbench::renders
