#include "renders/animation.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "renders/limits.h"

extern char** environ;

namespace rockbench::renders {
namespace fs = std::filesystem;

std::optional<fs::path> FindExecutable(const std::string& name) {
  auto executable = [](const fs::path& p) {
    struct stat st;
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) {
    if (executable(name)) return fs::path(name);
    return std::nullopt;
  }
  const char* path_env = std::getenv("PATH");
  std::string path = path_env ? path_env : "/usr/local/bin:/usr/bin:/bin";
  size_t start = 0;
  while (start <= path.size()) {
    const size_t end = std::min(path.find(':', start), path.size());
    const std::string dir = path.substr(start, end - start);
    if (!dir.empty() && executable(fs::path(dir) / name)) return fs::path(dir) / name;
    start = end + 1;
  }
  return std::nullopt;
}

struct FfmpegPipe::Impl {
  pid_t pid = -1;
  int stdin_fd = -1;
  int stderr_fd = -1;
  std::thread drain;
  std::string messages;  // ffmpeg's standard error (the last 16 kB)
  bool closed = false;

  void StartDrain() {
    drain = std::thread([this] {
      char buf[4096];
      for (;;) {
        const ssize_t n = ::read(stderr_fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        messages.append(buf, static_cast<size_t>(n));
        if (messages.size() > 16384) messages.erase(0, messages.size() - 16384);
      }
    });
  }

  // Waits for ffmpeg; an error message when it did not exit with status 0.
  std::string Wait() {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (drain.joinable()) drain.join();
    ::close(stderr_fd);
    stderr_fd = -1;
    pid = -1;
    std::string why;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return why;
    why = WIFEXITED(status) ? "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status))
                            : "ffmpeg was stopped by signal " + std::to_string(WTERMSIG(status));
    while (!messages.empty() && (messages.back() == '\n' || messages.back() == '\r')) {
      messages.pop_back();
    }
    if (!messages.empty()) why += ": " + messages;
    return why;
  }
};

FfmpegPipe::FfmpegPipe(const fs::path& ffmpeg, std::vector<std::string> args)
    : impl_(std::make_unique<Impl>()) {
  // stdin: frames; stderr: messages; exec_pipe: the child's errno when it cannot start ffmpeg
  // (closed by a successful exec).
  int in_pipe[2], err_pipe[2], exec_pipe[2];
  if (::pipe2(in_pipe, O_CLOEXEC) != 0)
    throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(in_pipe[0]);
    ::close(in_pipe[1]);
    throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
  }
  if (::pipe2(exec_pipe, O_CLOEXEC) != 0) {
    for (int fd : {in_pipe[0], in_pipe[1], err_pipe[0], err_pipe[1]}) ::close(fd);
    throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
  }
  std::vector<std::string> argv_s;
  argv_s.push_back(ffmpeg.string());
  for (auto& a : args) argv_s.push_back(std::move(a));
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: only async-signal-safe calls until exec. ffmpeg dies with this process (a
    // wall-clock limit or a kill must not leave it writing a temporary file).
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (::dup2(in_pipe[0], 0) < 0 || devnull < 0 || ::dup2(devnull, 1) < 0 ||
        ::dup2(err_pipe[1], 2) < 0) {
      const int err = errno;
      (void)!::write(exec_pipe[1], &err, sizeof err);
      ::_exit(127);
    }
    ::execve(argv[0], argv.data(), environ);
    const int err = errno;
    (void)!::write(exec_pipe[1], &err, sizeof err);
    ::_exit(127);
  }
  const int fork_errno = errno;
  ::close(in_pipe[0]);
  ::close(err_pipe[1]);
  ::close(exec_pipe[1]);
  int exec_errno = 0;
  if (pid > 0) {
    ssize_t n;
    while ((n = ::read(exec_pipe[0], &exec_errno, sizeof exec_errno)) < 0 && errno == EINTR) {
    }
    if (n != static_cast<ssize_t>(sizeof exec_errno)) exec_errno = 0;
  }
  ::close(exec_pipe[0]);
  if (pid < 0 || exec_errno != 0) {
    ::close(in_pipe[1]);
    ::close(err_pipe[0]);
    if (pid > 0) {
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
    }
    throw std::runtime_error("cannot start " + ffmpeg.string() + ": " +
                             std::strerror(pid < 0 ? fork_errno : exec_errno));
  }
  impl_->pid = pid;
  impl_->stdin_fd = in_pipe[1];
  impl_->stderr_fd = err_pipe[0];
  impl_->StartDrain();
}

FfmpegPipe::~FfmpegPipe() {
  if (impl_->closed || impl_->pid < 0) return;
  if (impl_->stdin_fd >= 0) ::close(impl_->stdin_fd);
  ::kill(impl_->pid, SIGKILL);
  impl_->Wait();
}

void FfmpegPipe::Write(const Image& frame) {
  if (impl_->closed) throw std::runtime_error("ffmpeg: writing a frame after the input was closed");
  // SIGPIPE blocked while writing: a dead ffmpeg gives EPIPE here instead of ending us.
  sigset_t pipe_set, old_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old_set);
  const uint8_t* p = frame.rgb.data();
  size_t left = frame.rgb.size();
  int err = 0;
  while (left > 0) {
    const ssize_t n = ::write(impl_->stdin_fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  if (err == EPIPE) {
    // Consume the pending SIGPIPE before unblocking it.
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_set, nullptr);
  if (err != 0) {
    ::close(impl_->stdin_fd);
    impl_->stdin_fd = -1;
    impl_->closed = true;
    std::string why = impl_->Wait();
    if (why.empty()) why = "ffmpeg stopped reading frames";
    throw std::runtime_error(why + " (writing a frame: " + std::strerror(err) + ")");
  }
}

void FfmpegPipe::Close() {
  if (impl_->closed) return;
  impl_->closed = true;
  ::close(impl_->stdin_fd);
  impl_->stdin_fd = -1;
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
struct TempFiles {
  std::vector<fs::path> paths;
  ~TempFiles() {
    std::error_code ec;
    for (const auto& p : paths) fs::remove(p, ec);
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
  }
};

// The temporary files of an earlier export into `dir` whose process is gone (a kill leaves
// them): the hidden names this file makes, ".<name>.tmp<pid>...", are removed when no process
// <pid> exists.
void RemoveStaleTemps(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    // Only the names ExportAnimation makes: .frames.tmp<pid>, .<name>.mp4.tmp<pid>,
    // .<name>.gif.tmp<pid>, .<name>.palette.tmp<pid>.png.
    size_t at = std::string::npos;
    for (const char* kind : {".frames.tmp", ".mp4.tmp", ".gif.tmp", ".palette.tmp"}) {
      const size_t k = f.find(kind);
      if (k != std::string::npos) at = k + std::strlen(kind) - 4;
    }
    if (f.empty() || f[0] != '.' || at == std::string::npos) continue;
    size_t digits = at + 4;
    while (digits < f.size() && std::isdigit(static_cast<unsigned char>(f[digits]))) ++digits;
    if (digits == at + 4 || digits - at - 4 > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(f.substr(at + 4, digits - at - 4)));
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) stale.push_back(it->path());
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
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

// Puts the complete frames of `tmp_dir` in place as frames_dir. The frame_*.png files of an
// earlier export are removed first (a shorter export would otherwise be mistaken for a longer
// one); other files in frames_dir stay.
void InstallFrames(const fs::path& tmp_dir, const fs::path& frames_dir) {
  if (fs::is_directory(frames_dir)) {
    for (const auto& entry : fs::directory_iterator(frames_dir)) {
      const std::string f = entry.path().filename().string();
      if (f.starts_with("frame_") && f.ends_with(".png")) fs::remove(entry.path());
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
  RemoveStaleTemps(config.out_dir);
  const fs::path frames_dir = config.out_dir / "frames";
  int digits = 5;
  for (size_t n = times.size(); n >= 100000; n /= 10) ++digits;
  // Every file is made under a temporary name holding ".tmp<pid>" (util/wall_limit.h removes
  // them when the command's wall-clock limit ends it) and renamed when complete: the frames in
  // a hidden folder that becomes frames/ once the last one is written, so that a killed export
  // never leaves part of a sequence.
  const std::string tmp_suffix = ".tmp" + std::to_string(::getpid());
  const fs::path mp4_path = config.out_dir / (config.name + ".mp4");
  const fs::path gif_path = config.out_dir / (config.name + ".gif");
  const fs::path mp4_tmp = config.out_dir / ("." + config.name + ".mp4" + tmp_suffix);
  const fs::path gif_tmp = config.out_dir / ("." + config.name + ".gif" + tmp_suffix);
  const fs::path palette_tmp =
      config.out_dir / ("." + config.name + ".palette" + tmp_suffix + ".png");
  TempFiles temps;
  temps.paths = {mp4_tmp, gif_tmp, palette_tmp};
  TempDir frames_tmp;
  if (out.frames) {
    frames_tmp.path = config.out_dir / (".frames" + tmp_suffix);
    fs::remove_all(frames_tmp.path);
    fs::create_directories(frames_tmp.path);
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
    frames_tmp.path.clear();
    result.written.push_back(frames_dir);
  }
  if (out.mp4) {
    fs::rename(mp4_tmp, mp4_path);
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
    result.written.push_back(gif_path);
  }
  result.render_wall_s = render_s;
  result.png_wall_s = png_s;
  result.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace rockbench::renders
