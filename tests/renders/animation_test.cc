// Animations: MP4 and GIF read back with ffprobe (frame count, size, duration), PNG frames, the
// missing-ffmpeg fallback and ffmpeg failures.
#include "renders/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "tests/common/sample.h"
#include "tests/common/stack_scene.h"

// Everything here draws frames: built only with OSMesa (tests/renders/CMakeLists.txt).
namespace rockbench::renders {
namespace {

using testing_util::MakeSample;
namespace fs = std::filesystem;

Scene Stack() {
  return testing_util::TwoBlockScene(1.0, 1.5, 100.0, 0.6, 1.0, 30.0);
}

// The number of entries of folder `dir`, the hidden ones (an export's list of its frames) left
// out.
long FileCount(const fs::path& dir) {
  long n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string()[0] != '.';
  return n;
}

History Rocking() {
  History h;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    h.samples.push_back(MakeSample({.t_s = t,
                                    .theta1_rad = 0.1 * std::sin(6 * t),
                                    .theta2_rad = 0.1 * std::sin(6 * t) + 0.1 * std::sin(9 * t),
                                    .mode = Mode::k1a}));
  }
  return h;
}

RenderConfig Small() {
  RenderConfig cfg;
  cfg.width_px = 160;
  cfg.height_px = 120;
  return cfg;
}

// A fresh folder under the temporary directory.
fs::path Folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rockbench_animation_test_" + name);
  fs::remove_all(dir);
  return dir;
}

// ffprobe's key=value lines for the first video stream and the container.
std::map<std::string, std::string> Probe(const fs::path& file) {
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,width,height,pix_fmt,nb_read_frames -show_entries format=duration "
      "-of default=noprint_wrappers=1 '" +
      file.string() + "'";
  std::map<std::string, std::string> out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char line[512];
  while (std::fgets(line, sizeof line, p)) {
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const auto eq = s.find('=');
    if (eq != std::string::npos) out[s.substr(0, eq)] = s.substr(eq + 1);
  }
  pclose(p);
  return out;
}

bool HaveFfmpeg() {
  return FindExecutable("ffmpeg") && FindExecutable("ffprobe");
}

TEST(ExportAnimation, Mp4AndGifHaveTheFramesSizeAndDuration) {
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg/ffprobe not installed (Debian package ffmpeg)";
  // 1 s of motion at 10 fps in 2x slow motion (speed 0.5): 20 frames, a 2 s video.
  FrameRenderer renderer(Stack(), {{"reference", Rocking()}}, {}, Small());
  AnimationConfig cfg;
  cfg.out_dir = Folder("videos");
  cfg.fps = 10.0;
  cfg.speed = 0.5;
  cfg.mp4 = true;
  cfg.gif = true;
  const AnimationResult r = ExportAnimation(renderer, cfg);
  EXPECT_TRUE(r.problems.empty());
  EXPECT_EQ(r.frame_count, 20);
  for (const char* name : {"animation.mp4", "animation.gif"}) {
    const auto info = Probe(cfg.out_dir / name);
    SCOPED_TRACE(name);
    EXPECT_EQ(info.at("nb_read_frames"), "20");
    EXPECT_EQ(info.at("width"), "160");
    EXPECT_EQ(info.at("height"), "120");
    // 20 frames of 0.1 s; GIF delays are whole centiseconds (0.1 s exactly) and MP4 time bases
    // are exact for 10 fps: 1 ms covers the containers' rounding of the last frame's duration.
    EXPECT_NEAR(std::stod(info.at("duration")), 2.0, 1e-3);
  }
  EXPECT_EQ(Probe(cfg.out_dir / "animation.mp4").at("codec_name"), "h264");
  EXPECT_EQ(Probe(cfg.out_dir / "animation.mp4").at("pix_fmt"), "yuv420p");
  EXPECT_EQ(Probe(cfg.out_dir / "animation.gif").at("codec_name"), "gif");
  // Only the finished files are left (no temporary names).
  int entries = 0;
  for (const auto& e : fs::directory_iterator(cfg.out_dir)) {
    ++entries;
    EXPECT_EQ(e.path().filename().string()[0] == '.', false) << e.path();
  }
  EXPECT_EQ(entries, 2);
  fs::remove_all(cfg.out_dir);
}

TEST(ExportAnimation, FramesArePngsOfTheRenderedImages) {
  FrameRenderer renderer(Stack(), {{"reference", Rocking()}}, {}, Small());
  AnimationConfig cfg;
  cfg.out_dir = Folder("frames");
  cfg.fps = 5.0;
  cfg.frames = true;
  // An earlier, longer export left more frames (its list names them): they are removed.
  fs::create_directories(cfg.out_dir / "frames");
  WritePng(Image(4, 4), cfg.out_dir / "frames" / "frame_00099.png");
  std::ofstream(cfg.out_dir / "frames" / ".rockbench-frames")
      << "# rockbench render: the frames it wrote in this folder (a file not listed is not its "
         "own)\nframe_00099.png\n";
  const AnimationResult r = ExportAnimation(renderer, cfg);
  ASSERT_EQ(r.frame_count, 5);
  EXPECT_EQ(FileCount(cfg.out_dir / "frames"), 5);
  // Frame 3 is the picture at t = 3 / 5 s.
  const Image frame3 = ReadPng(cfg.out_dir / "frames" / "frame_00003.png");
  EXPECT_NEAR(r.frame_times_s[3], 0.6, 1e-12);
  EXPECT_EQ(frame3.rgb, renderer.Render(r.frame_times_s[3]).rgb);
  fs::remove_all(cfg.out_dir);
}

// A short run of three blocks rocking apart (a history made by hand: each block's own phase).
History ThreeRocking() {
  History h;
  h.blocks = 3;
  for (int i = 0; i <= 60; ++i) {
    Sample s(3);
    s.t_s = 0.01 * i;
    for (int k = 0; k < 3; ++k) s.theta_rad[k] = 0.04 * (k + 1) * std::sin(6 * s.t_s + 0.5 * k);
    h.samples.push_back(s);
  }
  return h;
}

TEST(ExportAnimation, AThreeBlockRunHasItsFrames) {
  // 0.6 s at 10 fps in 2x slow motion: 12 frames, a 1.2 s video, each frame the picture of
  // its time (three blocks, a chart axis each).
  Scene scene;
  for (double w : {0.9, 0.8, 0.7}) {
    scene.blocks.push_back(BlockDef{.width_m = w, .height_m = 0.85, .mass_kg = 100.0});
  }
  RenderConfig rc = Small();
  rc.width_px = 320;
  rc.height_px = 240;
  FrameRenderer renderer(scene, {{"reference", ThreeRocking()}}, {}, rc);
  ASSERT_EQ(renderer.layout().chart_panels.size(), 3u);
  AnimationConfig cfg;
  cfg.out_dir = Folder("three_blocks");
  cfg.fps = 10.0;
  cfg.speed = 0.5;
  cfg.frames = true;
  cfg.mp4 = HaveFfmpeg();
  const AnimationResult r = ExportAnimation(renderer, cfg);
  EXPECT_TRUE(r.problems.empty());
  ASSERT_EQ(r.frame_count, 12);
  EXPECT_EQ(FileCount(cfg.out_dir / "frames"), 12);
  EXPECT_NEAR(r.frame_times_s[7], 0.35, 1e-12);
  EXPECT_EQ(ReadPng(cfg.out_dir / "frames" / "frame_00007.png").rgb,
            renderer.Render(r.frame_times_s[7]).rgb);
  if (cfg.mp4) {
    const auto info = Probe(cfg.out_dir / "animation.mp4");
    EXPECT_EQ(info.at("nb_read_frames"), "12");
    EXPECT_NEAR(std::stod(info.at("duration")), 1.2, 1e-3);
  }
  fs::remove_all(cfg.out_dir);
}

TEST(ExportAnimation, WithoutFfmpegItSaysSoAndWritesTheFrames) {
  FrameRenderer renderer(Stack(), {{"reference", Rocking()}}, {}, Small());
  AnimationConfig cfg;
  cfg.out_dir = Folder("no_ffmpeg");
  cfg.fps = 4.0;
  cfg.mp4 = true;
  cfg.ffmpeg = "/nonexistent/ffmpeg";
  const AnimationResult r = ExportAnimation(renderer, cfg);
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_NE(r.problems[0].find("ffmpeg not found"), std::string::npos) << r.problems[0];
  EXPECT_FALSE(fs::exists(cfg.out_dir / "animation.mp4"));
  EXPECT_TRUE(fs::exists(cfg.out_dir / "frames" / "frame_00000.png"));
  EXPECT_TRUE(fs::exists(cfg.out_dir / "frames" / "frame_00003.png"));
  EXPECT_FALSE(fs::exists(cfg.out_dir / "frames" / "frame_00004.png"));
  fs::remove_all(cfg.out_dir);
}

TEST(ExportAnimation, RejectsAnOddSizeForMp4AndAnEmptyRequest) {
  RenderConfig odd = Small();
  odd.width_px = 161;
  FrameRenderer renderer(Stack(), {{"reference", Rocking()}}, {}, odd);
  AnimationConfig cfg;
  cfg.out_dir = Folder("odd");
  EXPECT_THROW(ExportAnimation(renderer, cfg), std::invalid_argument);
  cfg.mp4 = true;
  EXPECT_THROW(ExportAnimation(renderer, cfg), std::invalid_argument);
  EXPECT_FALSE(fs::exists(cfg.out_dir));
}

TEST(FfmpegPipe, AFailingFfmpegIsReportedWithItsMessage) {
  const auto ffmpeg = FindExecutable("ffmpeg");
  if (!ffmpeg) GTEST_SKIP() << "ffmpeg not installed (Debian package ffmpeg)";
  const fs::path out = Folder("fail");
  fs::create_directories(out);
  // An encoder that does not exist: ffmpeg exits non-zero before reading much.
  FfmpegPipe pipe(*ffmpeg, {"-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt",
                            "rgb24", "-video_size", "16x16", "-i", "pipe:0", "-c:v",
                            "no_such_encoder", "-f", "mp4", "-y", (out / "x.mp4").string()});
  Image frame(16, 16);
  std::string message;
  try {
    for (int i = 0; i < 200; ++i) pipe.Write(frame);
    pipe.Close();
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("ffmpeg exited with status"), std::string::npos) << message;
  EXPECT_NE(message.find("no_such_encoder"), std::string::npos) << message;
  fs::remove_all(out);
}

}  // namespace
}  // namespace rockbench::renders
