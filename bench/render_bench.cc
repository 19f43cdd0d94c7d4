// Rendering speed (docs/renders.md): frames from OSMesa into PNG-ready RGB buffers, PNG
// compression alone, and a whole 20 s MP4 export of the thesis-geometry earthquake scene.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "motion/ground_motion.h"
#include "renders/animation.h"
#include "renders/drawn_motion.h"
#include "renders/renderer.h"
#include "run/engine_run.h"
#include "scene/scene.h"

namespace {
using namespace rockbench;
using namespace rockbench::renders;

const std::filesystem::path kScene =
    std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "scenes" / "thesis_rinaldi228.toml";

// The thesis-geometry earthquake scene run by the reference model, once.
struct Run {
  Scene scene;
  GroundMotion motion;
  History history;
  BaseDisplacement base;
};

const Run& ThesisRun() {
  static const Run run = [] {
    Run r;
    r.scene = LoadScene(kScene);
    r.motion = GroundMotion::FromScene(r.scene);
    r.history = RunEngine("reference", r.scene, r.motion).history;
    r.base = IntegrateBaseDisplacement(r.motion, 20.0, BaseIntegrationFor(r.scene));
    return r;
  }();
  return run;
}

RenderConfig Config(int w, int h, int supersample) {
  RenderConfig c;
  c.width_px = w;
  c.height_px = h;
  c.supersample = supersample;
  c.t_from_s = 0.0;
  c.t_to_s = 20.0;
  return c;
}

// One frame: GL drawing, finish, box filter + flip, text. Times sweep the record so the state,
// text and chart change every frame.
void BM_RenderFrame(benchmark::State& state) {
  const Run& run = ThesisRun();
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  FrameRenderer renderer(run.scene, {{"reference", run.history}}, run.base,
                         Config(w, h, static_cast<int>(state.range(2))));
  Image frame;
  double t = 0.0;
  for (auto _ : state) {
    renderer.Render(t, &frame);
    benchmark::DoNotOptimize(frame.rgb.data());
    t = std::fmod(t + 1.0 / 30.0, 20.0);
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)
    ->Args({1280, 720, 1})
    ->Args({1280, 720, 2})
    ->Args({1280, 720, 3})
    ->Args({640, 360, 2})
    ->ArgNames({"w", "h", "ss"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// PNG compression of one 1280x720 frame: zlib level and row filter (0 none, 1 sub, 2 adaptive).
// Level 6 / none is the default for single images, level 3 / sub the one for animation frames.
void BM_EncodePng(benchmark::State& state) {
  const Run& run = ThesisRun();
  FrameRenderer renderer(run.scene, {{"reference", run.history}}, run.base, Config(1280, 720, 2));
  const Image frame = renderer.Render(3.0);
  PngConfig png;
  png.compression_level = static_cast<int>(state.range(0));
  png.filter = static_cast<PngFilter>(state.range(1));
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string data = EncodePng(frame, png);
    bytes = data.size();
    benchmark::DoNotOptimize(data.data());
  }
  state.counters["kB"] = static_cast<double>(bytes) / 1024.0;
}
BENCHMARK(BM_EncodePng)
    ->Args({6, 0})
    ->Args({6, 2})
    ->Args({3, 1})
    ->Args({1, 1})
    ->ArgNames({"level", "filter"})
    ->Unit(benchmark::kMillisecond);

// The whole export: 20 s at 30 fps (600 frames), 1280x720, MP4 through ffmpeg/libx264.
void BM_ExportMp4_20s(benchmark::State& state) {
  const Run& run = ThesisRun();
  const auto ffmpeg = FindExecutable("ffmpeg");
  if (!ffmpeg) {
    state.SkipWithError("ffmpeg not installed");
    return;
  }
  const auto out = std::filesystem::temp_directory_path() / "rockbench_render_bench";
  for (auto _ : state) {
    FrameRenderer renderer(run.scene, {{"reference", run.history}}, run.base, Config(1280, 720, 2));
    AnimationConfig anim;
    anim.out_dir = out;
    anim.mp4 = true;
    anim.fps = 30.0;
    const AnimationResult r = ExportAnimation(renderer, anim);
    state.counters["frames"] = r.frame_count;
    state.counters["draw_s"] = r.render_wall_s;
  }
  std::filesystem::remove_all(out);
}
BENCHMARK(BM_ExportMp4_20s)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The same 600 frames written as PNG files (no video).
void BM_ExportFrames_20s(benchmark::State& state) {
  const Run& run = ThesisRun();
  const auto out = std::filesystem::temp_directory_path() / "rockbench_render_bench_frames";
  for (auto _ : state) {
    FrameRenderer renderer(run.scene, {{"reference", run.history}}, run.base, Config(1280, 720, 2));
    AnimationConfig anim;
    anim.out_dir = out;
    anim.frames = true;
    anim.fps = 30.0;
    const AnimationResult r = ExportAnimation(renderer, anim);
    state.counters["frames"] = r.frame_count;
    state.counters["draw_s"] = r.render_wall_s;
    state.counters["png_s"] = r.png_wall_s;
  }
  std::filesystem::remove_all(out);
}
BENCHMARK(BM_ExportFrames_20s)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
