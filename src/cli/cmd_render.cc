// `rockbench render SCENE_OR_RUN_DIR --out DIR [--frames] [--mp4] [--gif] ...`: pictures of a
// motion. A run folder (written by `run`/`compare`) is drawn from its history.csv files without
// simulating again; a scene file is simulated first (reference model, or --engines).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "renders/animation.h"
#include "renders/drawn_motion.h"
#include "renders/gl_context.h"
#include "renders/limits.h"
#include "renders/renderer.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/resource_estimate.h"
#include "scene/history.h"
#include "scene/limits.h"
#include "scene/scene.h"
#include "util/wall_limit.h"

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
  LimitOptions limits;  ///< --memory-budget, --wall-limit
  bool from_given = false, to_given = false;
};

// Longest --name: a base name, not a path.
constexpr size_t kMaxNameChars = 100;

[[noreturn]] void Fail(int code, const std::string& message) {
  std::fprintf(stderr, "rockbench render: %s\n", message.c_str());
  throw CLI::RuntimeError(code);
}

// A number for messages ("%g").
std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A decimal of --size as a number of pixels (a huge one saturates: it is refused anyway).
long long PixelCount(const std::string& digits) {
  long long v = 0;
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  return r.ec == std::errc() ? v : std::numeric_limits<long long>::max();
}

// The frame count of the window [from, to] checked against renders::kMaxFrames; `end` says
// where `to` came from ("--to 5" or "the run's end, 12 s").
void CheckFrameCount(const RenderOptions& opt, double t_from_s, double t_to_s,
                     const std::string& end) {
  const double frames = renders::FrameCount(t_from_s, t_to_s, opt.fps, opt.speed);
  if (frames <= static_cast<double>(renders::kMaxFrames)) return;
  Fail(kExitBadInput, end + ": the animation would have " + Num(frames) + " frames ((" +
                          Num(t_to_s) + " - " + Num(t_from_s) + ") s x --fps " + Num(opt.fps) +
                          " / --speed " + Num(opt.speed) + "), more than the limit of " +
                          std::to_string(renders::kMaxFrames) +
                          " frames: shorten the window (--from, --to), lower --fps or raise "
                          "--speed");
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

// Engines with a history in a run folder: reference first, then by name. A folder whose
// summary.json lists what its command wrote ("engines_written", `compare`) gives those only: an
// engine folder an earlier command left there is not drawn as if it were current (it is named
// on stderr).
std::vector<std::string> RunFolderEngines(const fs::path& dir) {
  std::vector<std::string> names;
  std::optional<std::vector<std::string>> written;
  try {
    std::ifstream in(dir / "summary.json");
    if (in) {
      const nlohmann::json summary = nlohmann::json::parse(in);
      if (summary.contains("engines_written")) {
        written = summary.at("engines_written").get<std::vector<std::string>>();
      }
    }
  } catch (const std::exception& e) {
    Fail(kExitBadInput, (dir / "summary.json").string() + ": not valid: " + e.what());
  }
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_directory() && fs::exists(entry.path() / "history.csv")) {
      const std::string name = entry.path().filename().string();
      if (written && std::find(written->begin(), written->end(), name) == written->end()) {
        std::fprintf(stderr,
                     "rockbench render: note: %s/ is not drawn: summary.json does not list it "
                     "among what its command wrote (an earlier command's output)\n",
                     Excerpt(name, 60).c_str());
        continue;
      }
      names.push_back(name);
    }
  }
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    if (IsReference(a) != IsReference(b)) return IsReference(a);
    return a < b;
  });
  return names;
}

// The drawing settings of the options, checked before anything is loaded (a bad value exits
// with kExitBadInput naming the option, its value and the limit).
renders::RenderConfig ConfigFromOptions(const RenderOptions& opt) {
  if (!opt.frames && !opt.mp4 && !opt.gif) {
    Fail(kExitBadInput, "nothing to make: give --frames, --mp4 and/or --gif");
  }
  // The output folder: a path the system can make (at most 4095 bytes, each name at most 255),
  // printable.
  {
    bool ok = !opt.out.empty() && opt.out.size() <= 4095;
    size_t start = 0;
    while (ok && start <= opt.out.size()) {
      const size_t end = std::min(opt.out.find('/', start), opt.out.size());
      ok = end - start <= 255;
      start = end + 1;
    }
    ok = ok && std::none_of(opt.out.begin(), opt.out.end(), [](char c) {
           return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
         });
    if (!ok) {
      Fail(kExitBadInput, "--out " + Excerpt(opt.out) + " (" + std::to_string(opt.out.size()) +
                              " bytes): expected a printable folder path of at most 4095 "
                              "bytes, each name at most 255");
    }
  }
  const std::string size = "--size " + Excerpt(opt.size);
  std::smatch m;
  static const std::regex kSize(R"(^\s*(\d+)\s*[xX]\s*(\d+)\s*$)");
  if (opt.size.size() > 64 || !std::regex_match(opt.size, m, kSize)) {
    Fail(kExitBadInput, size + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  }
  const long long w = PixelCount(m[1]), h = PixelCount(m[2]);
  if (w < renders::kMinWidth_px || h < renders::kMinHeight_px) {
    Fail(kExitBadInput, size + ": at least " + std::to_string(renders::kMinWidth_px) + "x" +
                            std::to_string(renders::kMinHeight_px) +
                            " pixels (room for the text and the chart)");
  }
  if (w > renders::kMaxSide_px || h > renders::kMaxSide_px) {
    Fail(kExitBadInput, size + ": more than the limit of " + std::to_string(renders::kMaxSide_px) +
                            " pixels per side (8K UHD is 7680x4320)");
  }
  if (opt.supersample < 1 || opt.supersample > renders::kMaxSupersample) {
    Fail(kExitBadInput, "--supersample " + std::to_string(opt.supersample) + ": expected 1.." +
                            std::to_string(renders::kMaxSupersample));
  }
  if (std::max(w, h) * opt.supersample > renders::kMaxDrawnSide_px) {
    Fail(kExitBadInput, size + " --supersample " + std::to_string(opt.supersample) + ": drawn at " +
                            std::to_string(w * opt.supersample) + "x" +
                            std::to_string(h * opt.supersample) + " pixels, more than OSMesa's " +
                            std::to_string(renders::kMaxDrawnSide_px) +
                            " per side: lower --supersample");
  }
  renders::RenderConfig config;
  config.width_px = static_cast<int>(w);
  config.height_px = static_cast<int>(h);
  config.supersample = opt.supersample;
  config.t_from_s = opt.from_s;
  config.t_to_s = opt.to_s;
  config.show_base_motion = !opt.no_base;
  if (opt.mp4 && (config.width_px % 2 != 0 || config.height_px % 2 != 0)) {
    Fail(kExitBadInput, size + ": an MP4 (H.264, yuv420p) needs an even width " + "and height");
  }
  const auto layout = renders::ParseLayout(opt.layout);
  if (!layout) {
    Fail(kExitBadInput, "--layout " + Excerpt(opt.layout) + ": expected overlay or side");
  }
  config.layout = *layout;
  if (!(opt.fps > 0.0) || !(opt.fps <= renders::kMaxFps)) {
    Fail(kExitBadInput, "--fps " + Num(opt.fps) + ": expected more than 0 and at most " +
                            Num(renders::kMaxFps) +
                            " frames per second (for slow motion, lower --speed)");
  }
  if (!(opt.speed > 0.0) || !std::isfinite(opt.speed)) {
    Fail(kExitBadInput,
         "--speed " + Num(opt.speed) + ": expected a number > 0 (0.25 is 4x slow motion)");
  }
  const double max_t = limits::kMaxDuration_s;
  if (opt.from_given && !(opt.from_s >= 0.0 && opt.from_s <= max_t)) {
    Fail(kExitBadInput, "--from " + Num(opt.from_s) + ": expected 0 to " + Num(max_t) +
                            " s (the longest run a scene may ask for)");
  }
  if (opt.to_given && !(opt.to_s >= 0.0 && opt.to_s <= max_t)) {
    Fail(kExitBadInput, "--to " + Num(opt.to_s) + ": expected 0 to " + Num(max_t) +
                            " s (the longest run a scene may ask for)");
  }
  if (opt.from_given && opt.to_given && !(opt.to_s > opt.from_s)) {
    Fail(kExitBadInput, "--to " + Num(opt.to_s) + ": must be later than --from " + Num(opt.from_s));
  }
  const bool name_ok =
      !opt.name.empty() && opt.name.size() <= kMaxNameChars && opt.name[0] != '.' &&
      std::all_of(opt.name.begin(), opt.name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!name_ok) {
    Fail(kExitBadInput, "--name " + Excerpt(opt.name) + ": expected a base name of 1 to " +
                            std::to_string(kMaxNameChars) +
                            " letters, digits, '_', '-' or '.' (not starting with '.')");
  }
  // The window is known now when --to is given: its frames are counted before any work.
  if (opt.to_given) {
    CheckFrameCount(opt, opt.from_given ? opt.from_s : 0.0, opt.to_s, "--to " + Num(opt.to_s));
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
Motion MotionOfScene(const RenderOptions& opt, const fs::path& input,
                     const ResourceBudget& budget) {
  Motion m;
  m.scene = LoadScene(input, opt.overrides);
  const std::vector<std::string> names =
      opt.engines.empty() ? std::vector<std::string>{"reference"} : opt.engines;
  // The runs' memory and time, estimated from the scene before anything is simulated.
  CheckRunEstimate(EstimateRun(m.scene, names, 0, 0, 1), budget, Excerpt(opt.input, 80));
  m.ground_motion = GroundMotion::FromScene(m.scene);
  for (const std::string& name : names) {
    EngineRun run = RunEngine(name, m.scene, m.ground_motion);
    std::printf("%s\n", run.one_line.c_str());
    m.tracks.push_back({name, std::move(run.history)});
  }
  return m;
}

// The nearest existing folder at or above `path` (where --out will be made).
fs::path ExistingAncestor(fs::path path) {
  std::error_code ec;
  path = fs::absolute(path, ec);
  while (!path.empty() && !fs::exists(path, ec) && path != path.root_path()) {
    path = path.parent_path();
  }
  return path;
}

// The window, the frame count, the memory and the disk of the export, checked before the base
// displacement is integrated and the GL context is made. Returns the estimate.
renders::ExportEstimate CheckResources(const RenderOptions& opt,
                                       const renders::RenderConfig& config, const Motion& motion,
                                       double base_t_end_s, const ResourceBudget& budget) {
  double history_end_s = 0.0;
  for (const auto& t : motion.tracks) {
    history_end_s = std::max(history_end_s, t.history.samples.back().t_s);
  }
  const double t_from_s = opt.from_given ? opt.from_s : 0.0;
  const double t_to_s = opt.to_given ? opt.to_s : history_end_s;
  if (!opt.to_given) {
    if (t_from_s > t_to_s) {
      Fail(kExitBadInput,
           "--from " + Num(t_from_s) + ": later than the run's end (" + Num(history_end_s) + " s)");
    }
    CheckFrameCount(opt, t_from_s, t_to_s,
                    "the run's end (" + Num(history_end_s) + " s, no --to given)");
  }
  renders::ExportRequest request;
  request.width_px = config.width_px;
  request.height_px = config.height_px;
  request.supersample = config.supersample;
  request.frames = renders::FrameCount(t_from_s, t_to_s, opt.fps, opt.speed);
  request.png_frames = opt.frames;
  request.mp4 = opt.mp4;
  request.gif = opt.gif;
  if (motion.have_ground_motion && !opt.no_base) {
    request.base_samples = renders::BaseDisplacementSamples(
        motion.ground_motion, base_t_end_s, renders::BaseIntegrationFor(motion.scene));
  }
  for (const auto& t : motion.tracks) {
    request.history_bytes += static_cast<double>(t.history.samples.capacity()) *
                             sizeof(decltype(t.history.samples)::value_type);
  }
  const renders::ExportEstimate e = renders::EstimateExport(request);
  const std::string size = "--size " + std::to_string(config.width_px) + "x" +
                           std::to_string(config.height_px) + " --supersample " +
                           std::to_string(config.supersample);
  const double pictures = e.gl_bytes + e.frame_bytes + e.video_bytes;
  const std::string key =
      e.base_bytes > pictures
          ? (opt.to_given ? "--to " + Num(opt.to_s) : "the run's end (" + Num(base_t_end_s) + " s)")
          : size;
  std::string what = Num(request.frames) + " frames of " + std::to_string(config.width_px) + "x" +
                     std::to_string(config.height_px) + " px: drawing buffers " +
                     ByteText(e.gl_bytes) + ", frame " + ByteText(e.frame_bytes);
  if (e.video_bytes > 0.0) what += ", ffmpeg " + ByteText(e.video_bytes);
  if (e.base_bytes > 0.0) {
    what += ", base displacement " + ByteText(e.base_bytes) + " (" + Num(request.base_samples) +
            " samples to " + Num(base_t_end_s) + " s; --no-base-motion skips it)";
  }
  if (e.history_bytes > 1024.0 * 1024.0) what += ", histories " + ByteText(e.history_bytes);
  what += ", program " + ByteText(e.program_bytes);
  try {
    CheckMemoryEstimate(e.memory_bytes(), budget, Excerpt(opt.input, 80), key, what);
  } catch (const SceneError& err) {
    Fail(kExitBadInput, err.what());
  }
  // Disk: the frames and videos against the free space where --out is (or will be).
  std::error_code ec;
  const fs::path where = ExistingAncestor(opt.out);
  const fs::space_info space = fs::space(where, ec);
  if (!ec && e.disk_bytes > static_cast<double>(space.available)) {
    Fail(kExitCannotRender, "--out " + Excerpt(opt.out, 80) + ": the export needs an estimated " +
                                ByteText(e.disk_bytes) + " on disk (" + Num(request.frames) +
                                " frames of " + std::to_string(config.width_px) + "x" +
                                std::to_string(config.height_px) + " px), more than the " +
                                ByteText(static_cast<double>(space.available)) + " free in " +
                                Excerpt(where.string(), 80));
  }
  return e;
}

// Draws the frames and videos; a failure to draw exits with kExitCannotRender.
void Draw(const RenderOptions& opt, const renders::RenderConfig& config, Motion motion,
          renders::BaseDisplacement base, const renders::ExportEstimate& estimate,
          std::optional<std::chrono::steady_clock::time_point> deadline) {
  renders::AnimationConfig anim;
  anim.out_dir = opt.out;
  anim.fps = opt.fps;
  anim.speed = opt.speed;
  anim.frames = opt.frames;
  anim.mp4 = opt.mp4;
  anim.gif = opt.gif;
  anim.name = opt.name;
  anim.deadline = deadline;
  try {
    // The GL context is created here, and only here.
    renders::FrameRenderer renderer(motion.scene, std::move(motion.tracks), std::move(base),
                                    config);
    const auto& lay = renderer.layout();
    const auto times = renders::FrameTimes(lay.t_from_s, lay.t_to_s, opt.fps, opt.speed);
    std::printf(
        "rendering %zu frames (%dx%d, %g fps, t = %g..%g s, speed %g) into %s (estimated memory "
        "%s, disk %s)\n",
        times.size(), config.width_px, config.height_px, opt.fps, lay.t_from_s, lay.t_to_s,
        opt.speed, opt.out.c_str(), ByteText(estimate.memory_bytes()).c_str(),
        ByteText(estimate.disk_bytes).c_str());
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
  } catch (const renders::DeadlineReached&) {
    // The export stopped itself just before the wall-clock limit and removed its temporary
    // files; the same message and exit code as the watchdog's (util/wall_limit.h).
    Fail(kExitWallLimit, "error: wall-clock limit of " + Num(opt.limits.wall_limit_s) +
                             " s reached (--wall-limit); no output written for what was "
                             "unfinished");
  } catch (const renders::RenderError& e) {
    Fail(kExitCannotRender, e.what());
  } catch (const std::bad_alloc&) {
    Fail(kExitCannotRender, "out of memory while drawing (std::bad_alloc), though the estimate (" +
                                ByteText(estimate.memory_bytes()) +
                                ") was within --memory-budget: lower --size or --supersample");
  } catch (const std::invalid_argument& e) {
    Fail(kExitBadInput, e.what());
  } catch (const CLI::RuntimeError&) {
    throw;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    Fail(kExitCannotRender, what.size() > 1000 ? Excerpt(what, 1000) : what);
  }
}

void Execute(const RenderOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  renders::RenderConfig config = ConfigFromOptions(opt);
  // The whole command, simulation included, obeys --wall-limit: on expiry the watchdog removes
  // this process's temporary files under --out and exits with kExitWallLimit. The export stops
  // itself a little earlier (a quarter of the limit, at most 2 s), between two frames, and
  // removes them itself, so that it is not writing a frame while the watchdog removes them.
  const ResourceBudget budget = StartLimits(opt.limits, opt.out, "render");
  std::optional<std::chrono::steady_clock::time_point> deadline;
  if (opt.limits.wall_limit_s > 0.0) {
    const double margin_s = std::min(2.0, 0.25 * opt.limits.wall_limit_s);
    deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(opt.limits.wall_limit_s - margin_s));
  }
  // The motion: read from a run folder, or simulated now from a scene file.
  const fs::path input(opt.input);
  std::error_code ec;
  if (!fs::exists(input, ec)) {
    Fail(kExitBadInput, Excerpt(opt.input, 80) + ": no such scene file or run folder" +
                            (ec ? " (" + ec.message() + ")" : std::string()));
  }
  // Before any work: can this build draw at all?
  if (!renders::GlAvailable()) Fail(kExitCannotRender, renders::GlUnavailableReason());
  Motion motion =
      fs::is_directory(input) ? MotionOfRunFolder(opt, input) : MotionOfScene(opt, input, budget);
  for (const auto& t : motion.tracks) {
    if (t.history.samples.empty()) Fail(kExitBadInput, "the " + t.engine + " history is empty");
  }

  // Base displacement by double integration of the ground acceleration, up to the end of the
  // window or of the longest history.
  double t_end_s = opt.to_given ? opt.to_s : 0.0;
  for (const auto& t : motion.tracks) t_end_s = std::max(t_end_s, t.history.samples.back().t_s);
  const renders::ExportEstimate estimate = CheckResources(opt, config, motion, t_end_s, budget);
  renders::BaseDisplacement base;
  if (motion.have_ground_motion && !opt.no_base) {
    base = renders::IntegrateBaseDisplacement(motion.ground_motion, t_end_s,
                                              renders::BaseIntegrationFor(motion.scene));
  }
  config.title = motion.scene.title;
  Draw(opt, config, std::move(motion), std::move(base), estimate, deadline);
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
  auto* from = cmd->add_option("--from", opt->from_s, "Start of the time window, s (default 0)");
  auto* to =
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
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt, from, to] {
    opt->from_given = from->count() > 0;
    opt->to_given = to->count() > 0;
    Execute(*opt);
  });
}

}  // namespace rockbench::cli
