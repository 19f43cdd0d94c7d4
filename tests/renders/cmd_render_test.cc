// `rockbench render` run as a program: from a scene file (simulated first), from a run folder
// (drawn from its histories, not simulated again), and its errors.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "renders/limits.h"
#include "renders/renderer.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "tests/common/sample.h"
#include "tests/common/shell_test.h"
#include "tests/common/spawn_quiet.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;
namespace fs = std::filesystem;

const fs::path kSource = ROCKBENCH_SOURCE_DIR;

using Result = testing_util::ShellRun;

// `rockbench render ARGS`: its exit status and what it printed.
Result RunCli(const std::string& args) {
  return testing_util::Shell(std::string(ROCKBENCH_CLI) + " render " + args);
}

fs::path Folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rockbench_cmd_render_test_" + name);
  fs::remove_all(dir);
  return dir;
}

#if ROCKBENCH_HAVE_OSMESA

// Files in `dir`, the hidden ones (an export's list of its frames) left out.
int CountFiles(const fs::path& dir) {
  int n = 0;
  if (!fs::exists(dir)) return 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    n += e.is_regular_file() && e.path().filename().string()[0] != '.' ? 1 : 0;
  }
  return n;
}

// What `rockbench render DIR --size 320x240` draws of run folder DIR, drawn in process: its
// scene.toml and the histories of the runs named, at the same size, layout and title.
std::unique_ptr<FrameRenderer> DirectRenderer(const fs::path& dir,
                                              const std::vector<std::string>& runs, Layout layout) {
  const Scene scene = LoadScene(dir / "scene.toml");
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  cfg.layout = layout;
  cfg.title = scene.title;
  std::vector<Track> tracks;
  for (const std::string& run : runs) {
    tracks.push_back({run, ReadHistoryCsv(dir / run / "history.csv")});
  }
  return std::make_unique<FrameRenderer>(scene, std::move(tracks), BaseDisplacement{}, cfg);
}

TEST(CmdRender, SceneFileIsSimulatedThenDrawn) {
  const fs::path out = Folder("scene");
  const Result r = RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " +
                          out.string() + " --frames --size 160x120 --to 0.5 --fps 10");
  ASSERT_EQ(r.exit_code, 0) << r.output;
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
        MakeSample({.t_s = 0.1 * i, .theta1_rad = 0.3, .theta2_rad = 0.3, .mode = Mode::k3a}));
    other.samples.push_back(
        MakeSample({.t_s = 0.1 * i, .theta1_rad = -0.2, .theta2_rad = 0.1, .mode = Mode::k2b}));
  }
  WriteFileAtomic(dir / "reference" / "history.csv", HistoryToCsv(ref));
  WriteFileAtomic(dir / "other" / "history.csv", HistoryToCsv(other));
  const fs::path out = dir / "pictures";
  const Result r = RunCli(dir.string() + " --out " + out.string() +
                          " --frames --size 320x240 --fps 10 --layout side");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("reference:"), std::string::npos) << "simulated again:\n" << r.output;
  ASSERT_EQ(CountFiles(out / "frames"), 10);
  // The same frame drawn directly from the same files.
  const auto direct = DirectRenderer(dir, {"reference", "other"}, Layout::kSide);
  EXPECT_EQ(ReadPng(out / "frames" / "frame_00004.png").rgb, direct->Render(0.4).rgb);
  fs::remove_all(dir);
}

TEST(CmdRender, ACylinderRunFolderIsDrawnWithItsBaseMovingInXAndY) {
  // `rockbench run` of the rotating harmonic (both horizontal components), then drawn from its
  // folder: every frame is the direct render of its history with the base displacement of the
  // scene's three components (the transverse one included).
  const fs::path dir = Folder("cylinder");
  const fs::path scene_path = kSource / "scenes/three_d/cylinder_rotating_harmonic.toml";
  const Result run = testing_util::Shell(std::string(ROCKBENCH_CLI) + " run " +
                                         scene_path.string() + " --out " + dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const fs::path out = dir / "pictures";
  const Result r =
      RunCli(dir.string() + " --out " + out.string() + " --frames --size 320x240 --fps 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(CountFiles(out / "frames"), 12);  // 6 s at 2 frames a second
  const Scene scene = LoadScene(scene_path);
  const History h = ReadHistoryCsv(dir / "reference" / "history.csv");
  const BaseDisplacement base = IntegrateBaseDisplacement(
      GroundMotion::FromScene(scene), h.samples.back().t_s, BaseIntegrationFor(scene));
  ASSERT_TRUE(base.has_transverse());
  EXPECT_NE(base.TransverseAt(1.5), 0.0);
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  cfg.title = scene.title;
  FrameRenderer direct(scene, {{"reference", h}}, base, cfg);
  EXPECT_EQ(ReadPng(out / "frames" / "frame_00003.png").rgb, direct.Render(1.5).rgb);
  // Without the transverse displacement the frame differs: the CLI drew it.
  BaseDisplacement no_y = IntegrateBaseDisplacement(
      GroundMotion::FromScene(scene), h.samples.back().t_s, BaseIntegrationFor(scene));
  no_y.SetTransverse(std::vector<double>{});
  FrameRenderer without(scene, {{"reference", h}}, no_y, cfg);
  EXPECT_NE(ReadPng(out / "frames" / "frame_00003.png").rgb, without.Render(1.5).rgb);
  fs::remove_all(dir);
}

TEST(CmdRender, AStackOfThreeBlocksIsDrawnFromItsRunFolder) {
  // A run folder of a three-block scene ([[block]] tables) with a three-block history: drawn
  // as it is, one frame per tenth of a second, each the direct render of the same files.
  const fs::path dir = Folder("three_blocks");
  fs::create_directories(dir / "reference");
  std::ofstream(dir / "scene.toml") << "title = \"three drums\"\n"
                                    << "[[block]]\nwidth = 0.9\nheight = 0.85\ndensity = 2700.0\n"
                                    << "[[block]]\nwidth = 0.9\nheight = 0.85\ndensity = 2700.0\n"
                                    << "[[block]]\nwidth = 0.8\nheight = 0.85\ndensity = 2700.0\n"
                                    << "[initial]\ntheta = [0.05, 0.05, 0.05]\n"
                                    << "[run]\nduration = 0.5\n";
  History h;
  h.blocks = 3;
  for (int i = 0; i <= 5; ++i) {
    Sample s(3);
    s.t_s = 0.1 * i;
    for (int k = 0; k < 3; ++k) s.theta_rad[k] = 0.05 + 0.01 * i * k;
    h.samples.push_back(s);
  }
  WriteFileAtomic(dir / "reference" / "history.csv", HistoryToCsv(h));
  const fs::path out = dir / "pictures";
  const Result r =
      RunCli(dir.string() + " --out " + out.string() + " --frames --size 320x240 --fps 10");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(CountFiles(out / "frames"), 5);
  ASSERT_EQ(LoadScene(dir / "scene.toml").block_count(), 3);
  const auto direct = DirectRenderer(dir, {"reference"}, Layout::kOverlay);
  EXPECT_EQ(direct->layout().chart_panels.size(), 3u);
  EXPECT_EQ(ReadPng(out / "frames" / "frame_00003.png").rgb, direct->Render(0.3).rgb);
  fs::remove_all(dir);
}

#else

TEST(CmdRender, SaysThisBuildHasNoOsmesa) {
  const fs::path out = Folder("no_osmesa");
  const Result r = RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " +
                          out.string() + " --frames --size 160x120 --to 0.5");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("no OSMesa"), std::string::npos) << r.output;
  // Said before any work: the reference model did not run.
  EXPECT_EQ(r.output.find("reference:"), std::string::npos) << r.output;
  fs::remove_all(out);
}

#endif

#if ROCKBENCH_HAVE_OSMESA

// Every entry of `dir` (recursively) whose name holds ".tmp": temporary files left behind.
std::vector<std::string> Temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().find(".tmp") != std::string::npos) {
      found.push_back(it->path().string());
    }
  }
  return found;
}

// Runs `rockbench render ARGS` as a child; its exit status and peak resident memory (kB).
struct Measured {
  int status = -1;
  long max_rss_kb = 0;
};

// Starts `rockbench render ARGS` as a child with its stdout on /dev/null; its pid, -1 when it
// could not start.
pid_t SpawnRender(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {ROCKBENCH_CLI, "render"};
  argv.insert(argv.end(), args.begin(), args.end());
  return testing_util::SpawnQuiet(std::move(argv));
}

// A test's output folder: no temporary left in it, then removed.
void ExpectNoTemporariesAndRemove(const fs::path& out) {
  EXPECT_EQ(Temporaries(out), std::vector<std::string>{});
  fs::remove_all(out);
}

// A test's output folder with frames/NAME holding `text` (an earlier export's or the user's).
fs::path FolderWithFrame(const std::string& folder, const std::string& name,
                         const std::string& text) {
  const fs::path out = Folder(folder);
  fs::create_directories(out / "frames");
  std::ofstream(out / "frames" / name) << text;
  return out;
}

Measured RunMeasured(const std::vector<std::string>& args) {
  Measured m;
  const pid_t pid = SpawnRender(args);
  if (pid < 0) return m;
  int st = 0;
  rusage usage{};
  ::wait4(pid, &st, 0, &usage);
  m.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  m.max_rss_kb = usage.ru_maxrss;
  return m;
}

// The whole drawing is estimated before it starts: a 2048x2048 frame at supersample 2 peaks
// below its estimate, and the estimate is not far above it (the estimate is what the memory
// budget is checked against).
TEST(CmdRender, TheMemoryEstimateBoundsTheRun) {
  const fs::path out = Folder("measured");
  const Measured m =
      RunMeasured({(kSource / "scenes/thesis_free_rocking.toml").string(), "--out", out.string(),
                   "--frames", "--size", "2048x2048", "--to", "0.1", "--fps", "10"});
  ASSERT_EQ(m.status, 0);
  ExportRequest request;
  request.width_px = request.height_px = 2048;
  request.supersample = 2;
  request.frames = 1;
  request.png_frames = true;
  const double estimate = EstimateExport(request).memory_bytes();
  double peak = 1024.0 * static_cast<double>(m.max_rss_kb);
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's shadow memory, redzones and quarantine add to every allocation: 449 MiB
  // against 298 MiB measured. The estimate is of the release build; under ASan only the order
  // of magnitude is checked.
  peak /= 2.0;
#endif
  EXPECT_LE(peak, estimate) << "peak " << peak << " B, estimate " << estimate << " B";
#if !defined(__SANITIZE_ADDRESS__)
  EXPECT_LE(estimate, 1.6 * peak) << "peak " << peak << " B, estimate " << estimate << " B";
#endif
  fs::remove_all(out);
}

// --wall-limit stops a long export between two frames: exit 3, the watchdog's message, and no
// frames/, no video and no temporary file in the output folder (a video's ffmpeg ends too).
TEST(CmdRender, WallLimitStopsTheExportWithoutPartialOutput) {
  const fs::path out = Folder("wall");
  const auto start = std::chrono::steady_clock::now();
  const Result r =
      RunCli((kSource / "scenes/thesis_rinaldi228.toml").string() + " --out " + out.string() +
             " --frames --mp4 --gif --size 640x480 --fps 60 --speed 0.05 "
             "--wall-limit 2");
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("rockbench render: error: wall-clock limit of 2 s reached "
                          "(--wall-limit); no output written for what was unfinished"),
            std::string::npos)
      << r.output;
  EXPECT_LT(took_s, 10.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a straggling ffmpeg
  EXPECT_FALSE(fs::exists(out / "frames"));
  EXPECT_FALSE(fs::exists(out / "animation.mp4"));
  EXPECT_FALSE(fs::exists(out / "animation.gif"));
  ExpectNoTemporariesAndRemove(out);
}

// A render killed with SIGKILL (no chance to tidy up) leaves no frames/ (the frames are made in
// a hidden .frames.tmp<pid> folder renamed whole); the next render into the folder removes that
// folder (it holds the killed export's list of frames) and writes the whole sequence, replacing
// an earlier longer one (the frames its list names).
TEST(CmdRender, AKilledRenderLeavesNoPartialOutput) {
  const fs::path out = FolderWithFrame("killed", "frame_99999.png", "an older, longer export");
  std::ofstream(out / "frames" / ".rockbench-frames")
      << "# rockbench render: the frames it wrote in this folder (a file not listed is not its "
         "own)\nframe_99999.png\n";
  const pid_t pid =
      SpawnRender({(kSource / "scenes/thesis_rinaldi228.toml").string(), "--out", out.string(),
                   "--frames", "--size", "320x240", "--fps", "60", "--speed", "0.02"});
  ASSERT_GE(pid, 0);
  const fs::path tmp = out / (".frames.tmp" + std::to_string(pid));
  const auto start = std::chrono::steady_clock::now();
  auto frames_in = [](const fs::path& d) {
    std::error_code ec;
    int n = 0;
    for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec)) ++n;
    return n;
  };
  while (frames_in(tmp) < 10 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFSIGNALED(st)) << "the render ended before it was killed";
  EXPECT_GE(frames_in(tmp), 10);
  // The older export is untouched, and none of the killed one's frames is in frames/.
  EXPECT_EQ(CountFiles(out / "frames"), 1);
  // The next render removes the dead process's folder and replaces the older frames.
  const Result r = RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " +
                          out.string() + " --frames --size 160x120 --to 0.5 --fps 10");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_EQ(CountFiles(out / "frames"), 5);
  EXPECT_FALSE(fs::exists(out / "frames" / "frame_99999.png"));
  ExpectNoTemporariesAndRemove(out);
}

// A frames folder holding the user's own frame_*.png (no export's list names them) is refused
// before anything is drawn, and left as it was; a hidden folder named like a dead export's
// temporary frames but without its list is left alone. Files of the user's beside an earlier
// export's frames stay when a new export replaces those.
TEST(CmdRender, TheUsersFramesAreNeverDeleted) {
  const fs::path out = FolderWithFrame("users", "frame_00000.png", "the user's");
  fs::create_directories(out / ".frames.tmp999999999");
  std::ofstream(out / ".frames.tmp999999999" / "frame_00000.png") << "the user's";
  const std::string scene = (kSource / "scenes/thesis_free_rocking.toml").string();
  const Result r =
      RunCli(scene + " --out " + out.string() + " --frames --size 160x120 --to 0.5 --fps 10");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find((out / "frames").string() +
                          ": holds files this command did not write (frame_00000.png): nothing "
                          "was drawn or deleted"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(testing_util::ReadFile(out / "frames" / "frame_00000.png"), "the user's");
  // Into a fresh folder beside them; then again over its own frames, the user's note kept.
  fs::remove_all(out / "frames");
  const Result a =
      RunCli(scene + " --out " + out.string() + " --frames --size 160x120 --to 0.5 --fps 10");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  std::ofstream(out / "frames" / "notes.txt") << "the user's";
  const Result b =
      RunCli(scene + " --out " + out.string() + " --frames --size 160x120 --to 0.3 --fps 10");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_EQ(CountFiles(out / "frames"), 4);  // 3 frames and the note
  EXPECT_EQ(testing_util::ReadFile(out / "frames" / "notes.txt"), "the user's");
  EXPECT_EQ(testing_util::ReadFile(out / ".frames.tmp999999999" / "frame_00000.png"), "the user's");
  fs::remove_all(out);
}

#endif

// Sizes, frame rates and frame counts are checked before anything is simulated, loaded or
// made: each error names the option, its value and the limit, and exits 2 (issue 21:
// `--fps 1e9` wrote 2e8 PNGs until killed; `--to 1e9` and `--size 100000x100000` exhausted the
// memory).
TEST(CmdRender, LimitsAreCheckedBeforeAnyWork) {
  const std::string scene = (kSource / "scenes/thesis_free_rocking.toml").string();
  const fs::path out = Folder("limits");
  struct Case {
    std::string args, expected;
  };
  const Case cases[] = {
      {"--fps 1e9", "--fps 1e+09: expected more than 0 and at most 240 frames per second"},
      {"--fps nan", "--fps nan: expected more than 0 and at most 240"},
      {"--to 1e9", "--to 1e+09: expected 0 to 86400 s"},
      {"--from -1", "--from -1: expected 0 to 86400 s"},
      {"--from 2 --to 1", "--to 1: must be later than --from 2"},
      {"--size 100000x100000", "--size 100000x100000: more than the limit of 8192 pixels per side"},
      {"--size 99999999999999999999999x720",
       "--size 99999999999999999999999x720: more than the limit of 8192 pixels per side"},
      {"--size 32x32", "--size 32x32: at least 64x48 pixels"},
      {"--size 8192x4096 --supersample 4",
       "--size 8192x4096 --supersample 4: drawn at 32768x16384 pixels, more than OSMesa's 16384 "
       "per side"},
      {"--supersample 9", "--supersample 9: expected 1..4"},
      {"--to 5000",
       "--to 5000: the animation would have 150000 frames ((5000 - 0) s x --fps 30 / "
       "--speed 1), more than the limit of 100000 frames"},
      {"--to 1 --speed 1e-300", "the animation would have 3e+301 frames"},
      {"--speed 0", "--speed 0: expected a number > 0"},
      {"--name ../elsewhere", "--name ../elsewhere: expected a base name"},
      {"--size " + std::string(100000, '1') + "x720", "--size 1111111111"},
      {"--wall-limit -1", "--wall-limit"},
      {"--memory-budget 0", "--memory-budget"},
      {"--size 640x480 --name a --wall-limit 0.5 --fps 300", "--fps 300"},
  };
  for (const Case& c : cases) {
    const Result r = RunCli(scene + " --out " + out.string() + " --frames " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("reference:"), std::string::npos) << "simulated: " << c.args;
    EXPECT_LT(r.output.size(), 1000u) << c.args;
  }
  EXPECT_FALSE(fs::exists(out));
  const Result long_out =
      RunCli(scene + " --out " + out.string() + "/" + std::string(300, 'o') + " --frames");
  EXPECT_EQ(long_out.exit_code, 2) << long_out.output;
  EXPECT_NE(long_out.output.find("expected a printable folder path of at most 4095 bytes, each "
                                 "name at most 255"),
            std::string::npos)
      << long_out.output;
  EXPECT_LT(long_out.output.size(), 400u);
}

#if ROCKBENCH_HAVE_OSMESA

// What is known only from the motion is checked once it is, before any frame is drawn: the
// window's frame count up to the run's end, and the memory estimate against --memory-budget.
TEST(CmdRender, TheRunsWindowAndTheMemoryAreCheckedBeforeDrawing) {
  const std::string scene = (kSource / "scenes/thesis_free_rocking.toml").string();
  const fs::path out = Folder("budget");
  Result r = RunCli(scene + " --out " + out.string() + " --frames --fps 240 --speed 0.001");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("the run's end (6 s, no --to given): the animation would have 1.44e+06 "
                          "frames"),
            std::string::npos)
      << r.output;
  r = RunCli(scene + " --out " + out.string() + " --frames --size 8192x8192");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("thesis_free_rocking.toml: --size 8192x8192 --supersample 2: needs an "
                          "estimated"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("more than the memory budget of 2 GiB"), std::string::npos) << r.output;
  r = RunCli(scene + " --out " + out.string() + " --frames --memory-budget 0.05");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("more than the memory budget of 51.2 MiB"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

#endif

TEST(CmdRender, AskingForNoPicturesIsAnErrorBeforeAnyWork) {
  const fs::path out = Folder("nothing");
  const Result r =
      RunCli((kSource / "scenes/thesis_free_rocking.toml").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing to make"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CmdRender, BadOptionsNameTheOption) {
  const std::string scene = (kSource / "scenes/thesis_free_rocking.toml").string();
  const fs::path out = Folder("bad");
  Result r = RunCli(scene + " --out " + out.string() + " --frames --size 640by480");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  r = RunCli(scene + " --out " + out.string() + " --mp4 --size 641x480");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("even"), std::string::npos) << r.output;
  r = RunCli(scene + " --out " + out.string() + " --frames --layout stacked");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--layout"), std::string::npos) << r.output;
  r = RunCli(out.string() + "/missing --out " + out.string() + " --frames");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no such scene file or run folder"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace rockbench::renders
