#pragma once
/// Animations: PNG frame sequences, and MP4 (H.264) / GIF made by piping raw RGB frames to
/// ffmpeg. Every file is written under a temporary name and renamed when complete.
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renders/image.h"
#include "renders/renderer.h"

namespace rockbench::renders {

/// The program `name` on PATH (or `name` itself when it contains a '/' and is executable):
/// FindProgram (util/subprocess.h), under the name the renders' callers know.
std::optional<std::filesystem::path> FindExecutable(const std::string& name);

/// A running ffmpeg reading raw rgb24 frames on its standard input (a Subprocess of
/// util/subprocess.h that dies with the thread that started it).
class FfmpegPipe {
 public:
  /// Starts `ffmpeg` with `args` (without the program name). Throws std::runtime_error.
  FfmpegPipe(const std::filesystem::path& ffmpeg, std::vector<std::string> args);
  ~FfmpegPipe();  ///< kills ffmpeg when Close() was not called
  FfmpegPipe(const FfmpegPipe&) = delete;
  FfmpegPipe& operator=(const FfmpegPipe&) = delete;

  /// Sends one frame's pixels. Throws std::runtime_error when ffmpeg has stopped reading.
  void Write(const Image& frame);
  /// Ends the input and waits. Throws std::runtime_error with ffmpeg's messages when it exits
  /// with a non-zero status or a signal.
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What to make from a FrameRenderer.
struct AnimationConfig {
  std::filesystem::path out_dir;   ///< created when missing
  double fps = 30.0;               ///< frames per second of video
  double speed = 1.0;              ///< simulated seconds per video second (0.25: 4x slow motion)
  bool frames = false;             ///< PNG frames in out_dir/frames/frame_NNNNN.png
  bool mp4 = false;                ///< out_dir/<name>.mp4, H.264 (libx264), yuv420p
  bool gif = false;                ///< out_dir/<name>.gif, palettegen + paletteuse
  std::string name = "animation";  ///< base name of the video files
  /// Frames: a fast zlib level and the "sub" filter (about 2x faster than the default PNG
  /// settings, files about 1.7x larger; docs/renders.md).
  PngConfig png{.compression_level = 3, .filter = PngFilter::kSub};
  int x264_crf = 20;                     ///< quality (lower is better; 18-23 is typical)
  std::string x264_preset = "veryfast";  ///< x264 speed preset
  /// ffmpeg program; empty: `ffmpeg` on PATH.
  std::filesystem::path ffmpeg;
  /// Called after each frame of the first pass with (frames done, frames in all).
  std::function<void(int, int)> progress;
  /// When set, the export stops before drawing a frame or putting an output in place after
  /// this time: it throws DeadlineReached, its temporary files removed (the command's
  /// --wall-limit).
  std::optional<std::chrono::steady_clock::time_point> deadline;
};

/// The export passed AnimationConfig::deadline; nothing unfinished was left behind.
struct DeadlineReached : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What an export made.
struct AnimationResult {
  int frame_count = 0;
  std::vector<double> frame_times_s;           ///< simulated time of each frame, s
  std::vector<std::filesystem::path> written;  ///< files made (the frames folder once)
  std::vector<std::string> problems;           ///< outputs that could not be made, and why
  double render_wall_s = 0.0;                  ///< drawing frames (GL, downsampling, text), s
  double png_wall_s = 0.0;                     ///< PNG compression and writing, s
  double wall_s = 0.0;                         ///< everything, including waiting for ffmpeg, s
};

/// Renders frames at FrameTimes(layout window, fps, speed) and writes what `config` asks for.
/// Every file is made under a temporary name holding ".tmp<pid>" and renamed when complete; the
/// PNG frames go to the hidden folder OUT/.frames.tmp<pid>, renamed to OUT/frames when the last
/// one is written (the frame_*.png files of an earlier export in OUT/frames are removed then),
/// so that an export stopped at any point leaves no part of a sequence. Temporary files of an
/// earlier export whose process is gone (killed) are removed first.
/// When ffmpeg is missing and a video was asked for, it says so in `problems` and writes the PNG
/// frames instead. Throws std::invalid_argument (odd size for MP4, bad fps/speed, nothing asked)
/// and std::runtime_error (ffmpeg failed, files).
AnimationResult ExportAnimation(FrameRenderer& renderer, const AnimationConfig& config);

}  // namespace rockbench::renders
