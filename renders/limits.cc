// The limits of an export and the estimate of its memory and disk (renders/limits.h).
#include "renders/limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockbench::renders {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

}  // namespace

double FrameCount(double t_from_s, double t_to_s, double fps, double speed) {
  // The same arithmetic as FrameTimes (the window over the step between frames).
  const double n = (t_to_s - t_from_s) / (speed / fps);
  if (std::isnan(n)) return std::numeric_limits<double>::infinity();
  return std::max(1.0, std::round(n));
}

double PngFrameEstimate_bytes(int width_px, int height_px) {
  return 4096.0 + 0.1 * static_cast<double>(width_px) * height_px;
}

ExportEstimate EstimateExport(const ExportRequest& r) {
  const double pixels = static_cast<double>(r.width_px) * r.height_px;
  const double drawn = pixels * r.supersample * r.supersample;
  ExportEstimate e;
  // Measured: a one-frame render at 1280x720 peaks at 134 MiB, most of it the program, Mesa's
  // llvmpipe (LLVM) and the font.
  e.program_bytes = 130.0 * kMiB;
  // Our RGBA buffer, and Mesa's own colour buffer of the same size that it copies into ours,
  // with an eighth more for Mesa's tiles and our rows (measured: 4096x2048 at supersample 4
  // peaks at 1.11 GiB, 2.1 times the 512 MiB buffer above the program and the frame).
  e.gl_bytes = 2.25 * 4.0 * drawn;
  // The RGB frame and the PNG encoding of one frame (at most the raw bytes plus headers).
  e.frame_bytes = 2.0 * 3.0 * pixels + 64.0 * 1024.0;
  e.times_bytes = 8.0 * r.frames;
  e.history_bytes = r.history_bytes;
  // IntegrateBaseDisplacement: the two acceleration series on the drive's step grid, then per
  // component the leapfrog path, the high-pass's padded copy and the corrected path (5 doubles a
  // sample at the peak; BaseDisplacementSamples counts the pads as samples).
  e.base_bytes = 5.0 * 8.0 * r.base_samples;
  // ffmpeg: x264's look-ahead and reference frames (measured: 171 MB at 1280x720, about 100
  // yuv420 frames); the GIF's palettegen and paletteuse hold a few RGB frames.
  double video = 0.0;
  if (r.mp4) video += 64.0 * kMiB + 100.0 * 1.5 * pixels;
  if (r.gif) video += 64.0 * kMiB + 8.0 * 3.0 * pixels;
  e.video_bytes = video;
  // Disk: the frames (PNG_FRAME_ESTIMATE each), an MP4 at about 0.02 byte a pixel a frame (x264
  // at CRF 20 on flat colour: measured about 0.005), a GIF the same (measured 0.004).
  double disk = 0.0;
  if (r.png_frames) disk += r.frames * PngFrameEstimate_bytes(r.width_px, r.height_px);
  if (r.mp4) disk += r.frames * 0.02 * pixels;
  if (r.gif) disk += r.frames * 0.02 * pixels;
  e.disk_bytes = disk;
  return e;
}

}  // namespace rockbench::renders
