// `rockbench render SCENE_OR_RUN_DIR --out DIR [--frames] [--mp4] [--gif] ...`: pictures of a
// motion. A run folder (written by `run`/`compare`) is drawn from its history.csv files without
// simulating again; a scene file is simulated first (reference model, or --engines).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/engines.h"
#include "renders/animation.h"
#include "renders/geometry.h"
#include "renders/gl_context.h"
#include "renders/renderer.h"
#include "scene/ground_motion.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::cli {
namespace {
namespace fs = std::filesystem;

// Exit code when this build or machine cannot make the pictures (no OSMesa, no font, ffmpeg
// missing or failing); bad input exits with kExitBadInput.
constexpr int kExitCannotRender = 1;

struct RenderOptions {
  std::string input;
  std::string out;
  bool frames = false, mp4 = false, gif = false;
  double fps = 30.0;
  std::string size = "1280x720";
  double from_s = std::numeric_limits<double>::quiet_NaN();
  double to_s = std::numeric_limits<double>::quiet_NaN();
  double speed = 1.0;
  std::string layout = "overlay";
  int supersample = 2;
  std::vector<std::string> engines;
  std::vector<std::string> overrides;
  bool no_base = false;
  std::string name = "animation";
};

[[noreturn]] void Fail(int code, const std::string& message) {
  std::fprintf(stderr, "rockbench render: %s\n", message.c_str());
  throw CLI::RuntimeError(code);
}

// The scene of a run folder: DIR/scene.toml, else the path and overrides in DIR/summary.json.
Scene RunFolderScene(const fs::path& dir) {
  if (fs::exists(dir / "scene.toml")) return LoadScene(dir / "scene.toml");
  const fs::path summary_path = dir / "summary.json";
  if (!fs::exists(summary_path)) {
    Fail(kExitBadInput, dir.string() + " is neither a scene file nor a run folder (no scene.toml " +
                            "and no summary.json in it)");
  }
  nlohmann::json summary;
  try {
    std::ifstream in(summary_path);
    summary = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    Fail(kExitBadInput, summary_path.string() + ": not valid JSON: " + e.what());
  }
  const auto scene_json = summary.find("scene");
  if (scene_json == summary.end() || !scene_json->contains("path")) {
    Fail(kExitBadInput, summary_path.string() + ": no scene.path, and " + dir.string() +
                            " has no scene.toml: cannot tell the scene's geometry");
  }
  std::vector<std::string> overrides;
  if (scene_json->contains("overrides")) {
    overrides = (*scene_json)["overrides"].get<std::vector<std::string>>();
  }
  return LoadScene((*scene_json)["path"].get<std::string>(), overrides);
}

// Engines with a history in a run folder: reference first, then by name.
std::vector<std::string> RunFolderEngines(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_directory() && fs::exists(entry.path() / "history.csv")) {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    if ((a == "reference") != (b == "reference")) return a == "reference";
    return a < b;
  });
  return names;
}

// The drawing settings of the options, checked (a bad value exits with kExitBadInput).
renders::RenderConfig ConfigFromOptions(const RenderOptions& opt) {
  if (!opt.frames && !opt.mp4 && !opt.gif) {
    Fail(kExitBadInput, "nothing to make: give --frames, --mp4 and/or --gif");
  }
  std::smatch m;
  static const std::regex kSize(R"(^\s*(\d+)\s*[xX]\s*(\d+)\s*$)");
  if (!std::regex_match(opt.size, m, kSize)) {
    Fail(kExitBadInput, "--size " + opt.size + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  }
  renders::RenderConfig config;
  config.width_px = std::stoi(m[1]);
  config.height_px = std::stoi(m[2]);
  config.supersample = opt.supersample;
  config.t_from_s = opt.from_s;
  config.t_to_s = opt.to_s;
  config.show_base_motion = !opt.no_base;
  if (opt.mp4 && (config.width_px % 2 != 0 || config.height_px % 2 != 0)) {
    Fail(kExitBadInput,
         "--size " + opt.size + ": an MP4 (H.264, yuv420p) needs an even width " + "and height");
  }
  const auto layout = renders::ParseLayout(opt.layout);
  if (!layout) Fail(kExitBadInput, "--layout " + opt.layout + ": expected overlay or side");
  config.layout = *layout;
  if (!(opt.fps > 0.0)) Fail(kExitBadInput, "--fps must be > 0");
  if (!(opt.speed > 0.0)) Fail(kExitBadInput, "--speed must be > 0 (0.25 is 4x slow motion)");
  if (!std::isnan(opt.from_s) && opt.from_s < 0.0) Fail(kExitBadInput, "--from must be >= 0");
  if (!std::isnan(opt.from_s) && !std::isnan(opt.to_s) && !(opt.to_s > opt.from_s)) {
    Fail(kExitBadInput, "--to must be later than --from");
  }
  return config;
}

// What is drawn: the scene, one track per engine, and the base motion when it can be built.
struct Motion {
  Scene scene;
  std::vector<renders::Track> tracks;
  GroundMotion ground_motion;
  bool have_ground_motion = true;
};

// The motion of a run folder, drawn as it was run.
Motion MotionOfRunFolder(const RenderOptions& opt, const fs::path& input) {
  if (!opt.overrides.empty()) {
    Fail(kExitBadInput, "--set applies to a scene file; a run folder is drawn as it was run");
  }
  Motion m;
  m.scene = RunFolderScene(input);
  std::vector<std::string> names = opt.engines.empty() ? RunFolderEngines(input) : opt.engines;
  if (names.empty()) Fail(kExitBadInput, opt.input + ": no <engine>/history.csv in this folder");
  for (const std::string& name : names) {
    const fs::path path = input / name / "history.csv";
    if (!fs::exists(path)) Fail(kExitBadInput, path.string() + ": not found");
    m.tracks.push_back({name, ReadHistoryCsv(path)});
  }
  try {
    m.ground_motion = GroundMotion::FromScene(m.scene);
  } catch (const SceneError& e) {
    m.have_ground_motion = false;
    std::fprintf(stderr, "rockbench render: warning: base motion not drawn (%s)\n", e.what());
  }
  return m;
}

// The motion of a scene file, simulated now (the reference unless --engines says otherwise).
Motion MotionOfScene(const RenderOptions& opt, const fs::path& input) {
  Motion m;
  m.scene = LoadScene(input, opt.overrides);
  m.ground_motion = GroundMotion::FromScene(m.scene);
  const std::vector<std::string> names =
      opt.engines.empty() ? std::vector<std::string>{"reference"} : opt.engines;
  for (const std::string& name : names) {
    EngineRun run = RunEngine(name, m.scene, m.ground_motion);
    std::printf("%s\n", run.one_line.c_str());
    m.tracks.push_back({name, std::move(run.history)});
  }
  return m;
}

// Draws the frames and videos; a failure to draw exits with kExitCannotRender.
void Draw(const RenderOptions& opt, const renders::RenderConfig& config, Motion motion,
          renders::BaseDisplacement base) {
  renders::AnimationConfig anim;
  anim.out_dir = opt.out;
  anim.fps = opt.fps;
  anim.speed = opt.speed;
  anim.frames = opt.frames;
  anim.mp4 = opt.mp4;
  anim.gif = opt.gif;
  anim.name = opt.name;
  try {
    // The GL context is created here, and only here.
    renders::FrameRenderer renderer(motion.scene, std::move(motion.tracks), std::move(base),
                                    config);
    const auto& lay = renderer.layout();
    const auto times = renders::FrameTimes(lay.t_from_s, lay.t_to_s, opt.fps, opt.speed);
    std::printf("rendering %zu frames (%dx%d, %g fps, t = %g..%g s, speed %g) into %s\n",
                times.size(), config.width_px, config.height_px, opt.fps, lay.t_from_s, lay.t_to_s,
                opt.speed, opt.out.c_str());
    std::fflush(stdout);
    const renders::AnimationResult result = renders::ExportAnimation(renderer, anim);
    for (const auto& path : result.written) std::printf("wrote %s\n", path.string().c_str());
    std::printf("%d frames; drawing %.2f s, PNG %.2f s, total %.2f s\n", result.frame_count,
                result.render_wall_s, result.png_wall_s, result.wall_s);
    if (!result.problems.empty()) {
      std::string all;
      for (const auto& p : result.problems) all += (all.empty() ? "" : "; ") + p;
      Fail(kExitCannotRender, all);
    }
  } catch (const renders::RenderError& e) {
    Fail(kExitCannotRender, e.what());
  } catch (const std::invalid_argument& e) {
    Fail(kExitBadInput, e.what());
  } catch (const CLI::RuntimeError&) {
    throw;
  } catch (const std::runtime_error& e) {
    Fail(kExitCannotRender, e.what());
  }
}

void Execute(const RenderOptions& opt) {
  renders::RenderConfig config = ConfigFromOptions(opt);
  // The motion: read from a run folder, or simulated now from a scene file.
  const fs::path input(opt.input);
  if (!fs::exists(input)) Fail(kExitBadInput, opt.input + ": no such scene file or run folder");
  // Before any work: can this build draw at all?
  if (!renders::GlAvailable()) Fail(kExitCannotRender, renders::GlUnavailableReason());
  Motion motion =
      fs::is_directory(input) ? MotionOfRunFolder(opt, input) : MotionOfScene(opt, input);
  for (const auto& t : motion.tracks) {
    if (t.history.samples.empty()) Fail(kExitBadInput, "the " + t.engine + " history is empty");
  }

  // Base displacement by double integration of the ground acceleration.
  double t_end_s = std::isnan(opt.to_s) ? 0.0 : opt.to_s;
  for (const auto& t : motion.tracks) t_end_s = std::max(t_end_s, t.history.samples.back().t_s);
  renders::BaseDisplacement base;
  if (motion.have_ground_motion && !opt.no_base) {
    base = renders::IntegrateBaseDisplacement(motion.ground_motion, t_end_s);
  }
  config.title = motion.scene.title;
  Draw(opt, config, std::move(motion), std::move(base));
}

}  // namespace

void RegisterRender(CLI::App& app) {
  auto opt = std::make_shared<RenderOptions>();
  auto* cmd = app.add_subcommand(
      "render", "Draw a motion: PNG frames, MP4 and/or GIF (from a run folder or a scene file)");
  cmd->add_option("input", opt->input,
                  "Run folder (from run/compare: drawn as is) or scene file (simulated first)")
      ->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->required();
  cmd->add_flag("--frames", opt->frames, "PNG frames in OUT/frames/");
  cmd->add_flag("--mp4", opt->mp4, "OUT/animation.mp4 (H.264 via ffmpeg)");
  cmd->add_flag("--gif", opt->gif, "OUT/animation.gif (via ffmpeg)");
  cmd->add_option("--fps", opt->fps, "Frames per second of video")->capture_default_str();
  cmd->add_option("--size", opt->size, "Frame size WIDTHxHEIGHT, px")->capture_default_str();
  cmd->add_option("--from", opt->from_s, "Start of the time window, s (default 0)");
  cmd->add_option("--to", opt->to_s, "End of the time window, s (default: end of the run)");
  cmd->add_option("--speed", opt->speed,
                  "Simulated seconds per video second (0.25: 4x slow motion)")
      ->capture_default_str();
  cmd->add_option("--layout", opt->layout, "overlay (one view) or side (a view per engine)")
      ->capture_default_str();
  cmd->add_option("--supersample", opt->supersample,
                  "Anti-aliasing: draw at N x N samples per pixel (1..4)")
      ->capture_default_str();
  cmd->add_option("--engines,-e", opt->engines,
                  "Engines: scene file: to run (default reference); run folder: to draw "
                  "(default all)");
  cmd->add_option("--set", opt->overrides, "Override a scene value: key=value (scene files)");
  cmd->add_flag("--no-base-motion", opt->no_base, "Keep the ground still (no base displacement)");
  cmd->add_option("--name", opt->name, "Base name of the video files")->capture_default_str();
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
