#include "renders/animation.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "files/atomic_file.h"
#include "renders/limits.h"
#include "scene/history.h"
#include "util/subprocess.h"
#include "util/wall_limit.h"

namespace rockbench::renders {
namespace fs = std::filesystem;

std::optional<fs::path> FindExecutable(const std::string& name) {
  return FindProgram(name);
}

struct FfmpegPipe::Impl {
  Subprocess ffmpeg;
  bool closed = false;

  // Waits for ffmpeg; an error message when it did not exit with status 0.
  std::string Wait() {
    const ExitStatus status = ffmpeg.Wait();
    std::string why;
    if (status.ok()) return why;
    why = status.signal == 0 ? "ffmpeg exited with status " + std::to_string(status.exit_code)
                             : "ffmpeg was stopped by signal " + std::to_string(status.signal);
    std::string messages = ffmpeg.captured_err();
    while (!messages.empty() && (messages.back() == '\n' || messages.back() == '\r')) {
      messages.pop_back();
    }
    if (!messages.empty()) why.append(": ").append(messages);
    return why;
  }
};

FfmpegPipe::FfmpegPipe(const fs::path& ffmpeg, std::vector<std::string> args)
    : impl_(std::make_unique<Impl>()) {
  std::vector<std::string> argv;
  argv.push_back(ffmpeg.string());
  for (auto& a : args) argv.push_back(std::move(a));
  // stdin: frames; stdout: nothing we read; stderr: ffmpeg's messages (the last 16 kB). ffmpeg
  // dies with this process: a wall-clock limit or a kill must not leave it writing a temporary
  // file.
  SpawnOptions options;
  options.in = Stdio::kPipe;
  options.out = Stdio::kNull;
  options.err = Stdio::kCapture;
  options.capture_limit_bytes = 16384;
  options.die_with_parent = true;
  impl_->ffmpeg = Subprocess(argv, options);
  if (!impl_->ffmpeg.started()) {
    throw std::runtime_error(std::string("cannot start ").append(impl_->ffmpeg.start_error()));
  }
}

FfmpegPipe::~FfmpegPipe() {
  if (impl_->closed || !impl_->ffmpeg.running()) return;
  impl_->ffmpeg.Kill(SIGKILL);
  impl_->Wait();
}

void FfmpegPipe::Write(const Image& frame) {
  if (impl_->closed) throw std::runtime_error("ffmpeg: writing a frame after the input was closed");
  const int err = impl_->ffmpeg.WriteStdin(frame.rgb.data(), frame.rgb.size());
  if (err != 0) {
    impl_->closed = true;
    std::string why = impl_->Wait();
    if (why.empty()) why = "ffmpeg stopped reading frames";
    throw std::runtime_error(why + " (writing a frame: " + std::strerror(err) + ")");
  }
}

void FfmpegPipe::Close() {
  if (impl_->closed) return;
  impl_->closed = true;
  const std::string why = impl_->Wait();
  if (!why.empty()) throw std::runtime_error(why);
}

namespace {

std::string Number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The size of the raw frames ffmpeg reads.
struct FrameSize {
  int width_px = 0, height_px = 0;
};

std::vector<std::string> RawInput(const FrameSize& like, double fps) {
  return {"-hide_banner", "-loglevel",
          "error",        "-nostats",
          "-f",           "rawvideo",
          "-pix_fmt",     "rgb24",
          "-video_size",  std::to_string(like.width_px) + "x" + std::to_string(like.height_px),
          "-framerate",   Number(fps),
          "-i",           "pipe:0"};
}

// Removes files on scope exit unless released (temporary outputs of a failed export).
// Registered as this process's temporaries (util/wall_limit.h: a signal or the wall-clock limit
// removes them too).
struct TempFiles {
  std::vector<fs::path> paths;
  explicit TempFiles(std::vector<fs::path> p) : paths(std::move(p)) {
    for (const auto& path : paths) RegisterTemporary(path);
  }
  ~TempFiles() {
    std::error_code ec;
    for (const auto& p : paths) {
      fs::remove(p, ec);
      ForgetTemporary(p);
    }
  }
};

}  // namespace

namespace {

void CheckRequest(const AnimationConfig& config, const RenderConfig& rc) {
  if (!config.frames && !config.mp4 && !config.gif) {
    throw std::invalid_argument("nothing to make: ask for frames, an MP4 or a GIF");
  }
  if (!(config.fps > 0.0) || !(config.fps <= kMaxFps)) {
    throw std::invalid_argument("frame rate " + Number(config.fps) + ": must be > 0 and at most " +
                                Number(kMaxFps) + " frames per second");
  }
  if (config.mp4 && (rc.width_px % 2 != 0 || rc.height_px % 2 != 0)) {
    throw std::invalid_argument("MP4 (H.264, yuv420p) needs an even width and height; " +
                                std::to_string(rc.width_px) + "x" + std::to_string(rc.height_px) +
                                " is not");
  }
}

// What the export makes: without ffmpeg, PNG frames instead of the videos (said in problems).
struct Outputs {
  bool frames = false, mp4 = false, gif = false;
  std::optional<fs::path> ffmpeg;
};

Outputs ResolveOutputs(const AnimationConfig& config, std::vector<std::string>* problems) {
  Outputs out{config.frames, config.mp4, config.gif, std::nullopt};
  if (!out.mp4 && !out.gif) return out;
  out.ffmpeg =
      config.ffmpeg.empty() ? FindExecutable("ffmpeg") : FindExecutable(config.ffmpeg.string());
  if (!out.ffmpeg) {
    problems->push_back(
        "ffmpeg not found (" +
        (config.ffmpeg.empty() ? std::string("not on PATH") : config.ffmpeg.string()) +
        "; install the Debian package ffmpeg): no " +
        std::string(out.mp4 && out.gif ? "MP4 or GIF"
                    : out.mp4          ? "MP4"
                                       : "GIF") +
        " written; the PNG frames are written instead");
    out.frames = true;
    out.mp4 = out.gif = false;
  }
  return out;
}

// Removes a folder and everything in it on scope exit unless released (the frames of a failed
// export).
struct TempDir {
  fs::path path;
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
    Release();
  }
  // Kept (renamed into place): no longer a temporary.
  void Release() {
    if (!path.empty()) ForgetTemporary(path);
    path.clear();
  }
};

std::string FrameName(size_t k, int digits);

// The list of frames an export wrote into a frames folder (and into its temporary folder while
// it writes them): the first line says what it is, then one file name a line. Files a folder
// holds that are not listed are not the export's: never deleted or overwritten.
constexpr const char* kFramesList = ".rockbench-frames";
constexpr const char* kFramesListHeader =
    "# rockbench render: the frames it wrote in this folder (a file not listed is not its own)";

// The frames listed in `dir`'s list; nullopt when it has none.
std::optional<std::vector<std::string>> ListedFrames(const fs::path& dir) {
  std::ifstream in(dir / kFramesList);
  if (!in) return std::nullopt;
  std::string line;
  if (!std::getline(in, line) || line != kFramesListHeader) return std::nullopt;
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    if (line.starts_with("frame_") && line.ends_with(".png") && line.find('/') == line.npos) {
      names.push_back(line);
    }
  }
  return names;
}

void WriteFramesList(const fs::path& dir, const std::vector<std::string>& names) {
  std::string text = std::string(kFramesListHeader) + "\n";
  for (const std::string& n : names) text += n + "\n";
  WriteFileAtomic(dir / kFramesList, text);
}

// The frames folder of an earlier export into `dir` whose process is gone (a SIGKILL leaves
// it): a hidden ".frames.tmp<pid>" folder holding the export's list, whose process <pid> no
// longer exists, loses the frames its list names and the list (and goes when that empties
// it). Anything else named like it is left alone.
void RemoveStaleTemps(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    const std::string prefix = ".frames.tmp";
    if (!f.starts_with(prefix) || f.size() == prefix.size() || f.size() > prefix.size() + 9 ||
        f.find_first_not_of("0123456789", prefix.size()) != std::string::npos) {
      continue;
    }
    const pid_t pid = static_cast<pid_t>(std::stol(f.substr(prefix.size())));
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH && ListedFrames(it->path())) {
      stale.push_back(it->path());
    }
  }
  for (const auto& p : stale) {
    const std::optional<std::vector<std::string>> listed = ListedFrames(p);
    for (const std::string& name : listed.value_or(std::vector<std::string>{})) {
      fs::remove(p / name, ec);
    }
    fs::remove(p / kFramesList, ec);
    fs::remove(p, ec);  // only when empty
  }
}

// Refuses (std::invalid_argument) a frames folder that holds files an export of rockbench did
// not write there, or whose files would be overwritten by `count` frames of `digits` digits:
// nothing is drawn, nothing deleted.
void CheckFramesFolder(const fs::path& frames_dir, size_t count, int digits) {
  std::error_code ec;
  if (!fs::is_directory(frames_dir, ec)) {
    if (fs::exists(frames_dir, ec)) {
      throw std::invalid_argument(frames_dir.string() + ": exists and is not a folder");
    }
    return;
  }
  const std::optional<std::vector<std::string>> listed = ListedFrames(frames_dir);
  std::vector<std::string> foreign;
  for (fs::directory_iterator it(frames_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if (f == kFramesList && listed) continue;
    if (listed && std::find(listed->begin(), listed->end(), f) != listed->end()) continue;
    foreign.push_back(f);
  }
  if (foreign.empty()) return;
  std::sort(foreign.begin(), foreign.end());
  if (listed) {
    // Files of the user's beside an earlier export's: refused only where a frame would take
    // a name of theirs.
    std::vector<std::string> taken;
    for (const std::string& f : foreign) {
      for (size_t k = 0; k < count && taken.size() < 3; ++k) {
        if (f == FrameName(k, digits)) taken.push_back(f);
      }
    }
    if (taken.empty()) return;
    foreign = taken;
  }
  std::string names;
  for (size_t k = 0; k < foreign.size() && k < 3; ++k) names += (k ? ", " : "") + foreign[k];
  if (foreign.size() > 3) names += ", ... (" + std::to_string(foreign.size()) + " files)";
  throw std::invalid_argument(
      frames_dir.string() + ": holds files this command did not write (" + names +
      "): nothing was drawn or deleted; render into another --out folder, or move them away");
}

// Writes a frame into the export's temporary folder: plainly (the folder, renamed when the last
// frame is written, is what makes the sequence appear whole), without creating the folder again
// when it has been removed (by the wall-clock watchdog) and without a sync per frame.
void WriteFrame(const fs::path& path, const std::string& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot create: " + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(err));
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) {
    throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
  }
}

// Throws DeadlineReached past the config's deadline.
void CheckDeadline(const AnimationConfig& config) {
  if (config.deadline && std::chrono::steady_clock::now() >= *config.deadline) {
    throw DeadlineReached("the export's deadline passed");
  }
}

// Puts the complete frames of `tmp_dir` in place as frames_dir, with their list. The frames
// an earlier export listed there are removed first (a shorter export would otherwise be
// mistaken for a longer one); files it did not list stay (CheckFramesFolder refused the
// export if a frame would take one's name).
void InstallFrames(const fs::path& tmp_dir, const fs::path& frames_dir) {
  if (fs::is_directory(frames_dir)) {
    if (const auto listed = ListedFrames(frames_dir)) {
      for (const std::string& f : *listed) fs::remove(frames_dir / f);
      fs::remove(frames_dir / kFramesList);
    }
    if (fs::is_empty(frames_dir)) fs::remove(frames_dir);
  }
  if (!fs::exists(frames_dir)) {
    fs::rename(tmp_dir, frames_dir);
    return;
  }
  for (const auto& entry : fs::directory_iterator(tmp_dir)) {
    fs::rename(entry.path(), frames_dir / entry.path().filename());
  }
  fs::remove(tmp_dir);
}

std::vector<std::string> Mp4Args(const FrameSize& like, const AnimationConfig& config,
                                 const fs::path& out) {
  auto args = RawInput(like, config.fps);
  for (const char* a : {"-an", "-c:v", "libx264", "-preset"}) args.push_back(a);
  args.push_back(config.x264_preset);
  args.push_back("-crf");
  args.push_back(std::to_string(config.x264_crf));
  for (const char* a : {"-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", "-y"}) {
    args.push_back(a);
  }
  args.push_back(out.string());
  return args;
}

std::vector<std::string> PaletteArgs(const FrameSize& like, double fps, const fs::path& out) {
  auto args = RawInput(like, fps);
  for (const char* a : {"-vf", "palettegen=stats_mode=full", "-f", "image2", "-y"}) {
    args.push_back(a);
  }
  args.push_back(out.string());
  return args;
}

std::vector<std::string> GifArgs(const FrameSize& like, double fps, const fs::path& palette,
                                 const fs::path& out) {
  auto args = RawInput(like, fps);
  args.push_back("-i");
  args.push_back(palette.string());
  for (const char* a : {"-lavfi", "[0:v][1:v]paletteuse=dither=bayer:bayer_scale=5", "-loop", "0",
                        "-f", "gif", "-y"}) {
    args.push_back(a);
  }
  args.push_back(out.string());
  return args;
}

// "frame_00042.png": the index zero-padded to `digits`.
std::string FrameName(size_t k, int digits) {
  std::string index = std::to_string(k);
  index.insert(0, static_cast<size_t>(std::max(0, digits - static_cast<int>(index.size()))), '0');
  return "frame_" + index + ".png";
}

}  // namespace

AnimationResult ExportAnimation(FrameRenderer& renderer, const AnimationConfig& config) {
  using Clock = std::chrono::steady_clock;
  const auto t_start = Clock::now();
  const RenderConfig& rc = renderer.config();
  CheckRequest(config, rc);
  const FrameLayout& lay = renderer.layout();
  AnimationResult result;
  result.frame_times_s = FrameTimes(lay.t_from_s, lay.t_to_s, config.fps, config.speed);
  const auto& times = result.frame_times_s;
  result.frame_count = static_cast<int>(times.size());
  const Outputs out = ResolveOutputs(config, &result.problems);

  fs::create_directories(config.out_dir);
  const fs::path frames_dir = config.out_dir / "frames";
  int digits = 5;
  for (size_t n = times.size(); n >= 100000; n /= 10) ++digits;
  // Before any work: a frames folder with files not of an export's is refused.
  if (out.frames) CheckFramesFolder(frames_dir, times.size(), digits);
  RemoveStaleTemps(config.out_dir);
  // Every file is made under a temporary name holding ".tmp<pid>", registered (util/wall_limit.h
  // removes exactly those when a signal or the wall-clock limit ends the command) and renamed
  // when complete: the frames in a hidden folder that becomes frames/ once the last one is
  // written, so that a killed export never leaves part of a sequence.
  const std::string tmp_suffix = ".tmp" + std::to_string(::getpid());
  const fs::path mp4_path = config.out_dir / (config.name + ".mp4");
  const fs::path gif_path = config.out_dir / (config.name + ".gif");
  const fs::path mp4_tmp = config.out_dir / ("." + config.name + ".mp4" + tmp_suffix);
  const fs::path gif_tmp = config.out_dir / ("." + config.name + ".gif" + tmp_suffix);
  const fs::path palette_tmp =
      config.out_dir / ("." + config.name + ".palette" + tmp_suffix + ".png");
  TempFiles temps({mp4_tmp, gif_tmp, palette_tmp});
  TempDir frames_tmp;
  if (out.frames) {
    // A folder of its own (an existing one of that name is not this export's), registered,
    // and holding the list of the frames it will hold (a kill leaves it recognisable).
    const fs::path tmp_dir = config.out_dir / (".frames" + tmp_suffix);
    if (!fs::create_directory(tmp_dir)) {
      throw std::runtime_error(tmp_dir.string() +
                               ": exists, and this export did not make it: move it away");
    }
    RegisterTemporary(tmp_dir, /*folder=*/true);
    frames_tmp.path = tmp_dir;
    std::vector<std::string> names;
    for (size_t k = 0; k < times.size(); ++k) names.push_back(FrameName(k, digits));
    WriteFramesList(frames_tmp.path, names);
  }

  Image frame;
  double render_s = 0.0, png_s = 0.0;
  auto render = [&](double t) {
    const auto a = Clock::now();
    renderer.Render(t, &frame);
    render_s += std::chrono::duration<double>(Clock::now() - a).count();
  };
  // Sizes of the raw input for ffmpeg.
  const FrameSize like{rc.width_px, rc.height_px};

  // Pass 1: PNG frames, MP4, and the GIF's palette, from one rendering of each frame.
  {
    std::unique_ptr<FfmpegPipe> mp4_pipe, palette_pipe;
    if (out.mp4) {
      mp4_pipe = std::make_unique<FfmpegPipe>(*out.ffmpeg, Mp4Args(like, config, mp4_tmp));
    }
    if (out.gif) {
      palette_pipe =
          std::make_unique<FfmpegPipe>(*out.ffmpeg, PaletteArgs(like, config.fps, palette_tmp));
    }
    for (size_t k = 0; k < times.size(); ++k) {
      CheckDeadline(config);
      render(times[k]);
      if (mp4_pipe) mp4_pipe->Write(frame);
      if (palette_pipe) palette_pipe->Write(frame);
      if (out.frames) {
        const auto a = Clock::now();
        WriteFrame(frames_tmp.path / FrameName(k, digits), EncodePng(frame, config.png));
        png_s += std::chrono::duration<double>(Clock::now() - a).count();
      }
      if (config.progress) config.progress(static_cast<int>(k) + 1, result.frame_count);
    }
    if (mp4_pipe) mp4_pipe->Close();
    if (palette_pipe) palette_pipe->Close();
  }
  CheckDeadline(config);
  if (out.frames) {
    InstallFrames(frames_tmp.path, frames_dir);
    frames_tmp.Release();
    result.written.push_back(frames_dir);
  }
  if (out.mp4) {
    fs::rename(mp4_tmp, mp4_path);
    ForgetTemporary(mp4_tmp);
    result.written.push_back(mp4_path);
  }

  // Pass 2: the GIF, drawn again with the palette of all frames.
  if (out.gif) {
    FfmpegPipe gif_pipe(*out.ffmpeg, GifArgs(like, config.fps, palette_tmp, gif_tmp));
    for (double t : times) {
      CheckDeadline(config);
      render(t);
      gif_pipe.Write(frame);
    }
    gif_pipe.Close();
    CheckDeadline(config);
    fs::rename(gif_tmp, gif_path);
    ForgetTemporary(gif_tmp);
    result.written.push_back(gif_path);
  }
  result.render_wall_s = render_s;
  result.png_wall_s = png_s;
  result.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace rockbench::renders
