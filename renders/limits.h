#pragma once
/// Limits of a picture and of an animation, and the estimate of the memory and disk an export
/// needs, so that `rockbench render` can refuse a request before anything is allocated or drawn
/// (docs/renders.md, "Limits"). Pure arithmetic: built with or without OSMesa.
#include <cstdint>

namespace rockbench::renders {

/// Smallest image: the text lines and the strip chart need this much room (ComputeLayout).
inline constexpr int kMinWidth_px = 64;
inline constexpr int kMinHeight_px = 48;
/// Largest image side, px: 8K UHD is 7680 x 4320; larger frames are posters, not animations,
/// and an 8192 x 8192 frame drawn at supersample 2 already needs about 2 GiB.
inline constexpr int kMaxSide_px = 8192;
/// Largest side of the supersampled drawing buffer, px: OSMesa's limit (OSMESA_MAX_WIDTH and
/// OSMESA_MAX_HEIGHT of Mesa 22, llvmpipe).
inline constexpr int kMaxDrawnSide_px = 16384;
/// Anti-aliasing factor per axis: 1 (none) to 4 (16 samples per pixel).
inline constexpr int kMaxSupersample = 4;
/// Frames per second of video: films play at 24, screens at 60, fast ones at 120-240; slow
/// motion is `--speed`, not a higher frame rate.
inline constexpr double kMaxFps = 240.0;
/// Frames of one animation: 55 minutes of video at 30 fps, a 300 s record in 4x slow motion at
/// 60 fps fits with room. Frames are drawn at about 50 a second (docs/renders.md,
/// "Performance"): 100,000 take half an hour, twice that for a GIF.
inline constexpr int64_t kMaxFrames = 100000;

/// Frames of the window [t_from_s, t_to_s] at `fps` and `speed`, as FrameTimes counts them
/// (max(1, round((t_to - t_from) / (speed / fps)))), without making them. A huge, infinite or NaN
/// count is returned as it is (+inf for NaN), for the caller to refuse.
double FrameCount(double t_from_s, double t_to_s, double fps, double speed);

/// What an export asks for, for the estimate.
struct ExportRequest {
  int width_px = 0, height_px = 0;  ///< the final image
  int supersample = 1;
  double frames = 0.0;
  bool png_frames = false, mp4 = false, gif = false;
  double base_samples = 0.0;   ///< samples of the base displacement (BaseDisplacementSamples)
  double history_bytes = 0.0;  ///< the histories drawn (held during the export)
};

/// The memory (bytes, peak, this process and ffmpeg) and disk (bytes) of an export. Each part is
/// an upper estimate from the buffers the code allocates and, for Mesa, ffmpeg and the file
/// sizes, from measurements (docs/renders.md, "Limits").
struct ExportEstimate {
  double program_bytes = 0.0;  ///< the program, its libraries and Mesa (measured: 130 MiB)
  double gl_bytes = 0.0;       ///< the supersampled RGBA buffer, ours and Mesa's (2.25x)
  double frame_bytes = 0.0;    ///< the final RGB frame and its PNG encoding
  double times_bytes = 0.0;    ///< the frame times
  double history_bytes = 0.0;  ///< the histories drawn
  double base_bytes = 0.0;     ///< the base displacement's integration (5 doubles a sample)
  double video_bytes = 0.0;    ///< the ffmpeg processes (x264's look-ahead frames, the GIF's)
  double disk_bytes = 0.0;     ///< PNG frames and video files written
  double memory_bytes() const {
    return program_bytes + gl_bytes + frame_bytes + times_bytes + history_bytes + base_bytes +
           video_bytes;
  }
};

ExportEstimate EstimateExport(const ExportRequest& request);

/// Estimated bytes of one PNG frame of w x h px at the animation settings (zlib 3, sub filter):
/// 4 KiB plus 0.1 byte a pixel, about 3x the measured 32 kB of a 1280x720 frame.
double PngFrameEstimate_bytes(int width_px, int height_px);

}  // namespace rockbench::renders
