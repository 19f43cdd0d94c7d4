// The limits of a picture and an animation and the estimate of an export (renders/limits.h), no
// GL: the frame count agrees with the frames made, too many frames and too large an image are
// refused before anything is allocated, and the estimate adds up the buffers it names.
#include "renders/limits.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "renders/drawn_motion.h"
#include "renders/renderer.h"
#include "tests/common/sample.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;

TEST(FrameCount, IsTheCountFrameTimesMakes) {
  for (const auto& [from, to, fps, speed] : {std::array<double, 4>{0.0, 5.42015, 60.0, 0.25},
                                             {1.0, 3.0, 30.0, 0.5},
                                             {0.0, 0.0, 30.0, 1.0},
                                             {0.0, 0.1, 10.0, 1.0},
                                             {0.0, 20.0, 30.0, 1.0},
                                             {2.5, 2.6, 240.0, 0.001}}) {
    EXPECT_EQ(FrameCount(from, to, fps, speed),
              static_cast<double>(FrameTimes(from, to, fps, speed).size()))
        << from << " " << to << " " << fps << " " << speed;
  }
  // Huge, infinite and NaN counts are returned for the caller to refuse, never wrapped.
  EXPECT_EQ(FrameCount(0.0, 1e9, 30.0, 1.0), 3e10);
  EXPECT_EQ(FrameCount(0.0, 1.0, 30.0, 1e-320), std::numeric_limits<double>::infinity());
  EXPECT_EQ(FrameCount(0.0, std::nan(""), 30.0, 1.0), std::numeric_limits<double>::infinity());
}

TEST(FrameTimes, RefusesMoreThanTheFrameLimitBeforeAllocating) {
  EXPECT_EQ(FrameTimes(0.0, 1.0, 100000.0, 1.0).size(), static_cast<size_t>(kMaxFrames));
  EXPECT_THROW(FrameTimes(0.0, 1e9, 30.0, 1.0), std::invalid_argument);
  EXPECT_THROW(FrameTimes(0.0, 1.0, 30.0, 1e-300), std::invalid_argument);
  try {
    FrameTimes(0.0, 4000.0, 30.0, 1.0);
    ADD_FAILURE() << "120000 frames were made";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the animation would have 120000 frames, more than the limit of 100000");
  }
}

TEST(ComputeLayout, RefusesImagesPastTheSizeLimitsBeforeAnyBuffer) {
  Scene scene;
  scene.blocks = {{.width_m = 0.4, .height_m = 1.2, .mass_kg = 960.0}};
  History h;
  h.samples = {MakeSample({.t_s = 0.0}), MakeSample({.t_s = 1.0})};
  const std::vector<Track> tracks = {{"reference", h}};
  RenderConfig cfg;
  cfg.width_px = kMaxSide_px;
  cfg.height_px = kMaxSide_px / 2;
  cfg.supersample = 2;
  EXPECT_NO_THROW(ComputeLayout(scene, tracks, {}, cfg));
  cfg.width_px = kMaxSide_px + 2;
  EXPECT_THROW(ComputeLayout(scene, tracks, {}, cfg), std::invalid_argument);
  cfg.width_px = 100000;
  cfg.height_px = 100000;
  EXPECT_THROW(ComputeLayout(scene, tracks, {}, cfg), std::invalid_argument);
  cfg.width_px = 4200;
  cfg.height_px = 720;
  cfg.supersample = 4;  // drawn at 16800 px, past OSMesa's 16384
  try {
    ComputeLayout(scene, tracks, {}, cfg);
    ADD_FAILURE() << "a 16800 px drawing was laid out";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "image size 4200x720 at supersample 4: drawn at more than OSMesa's 16384 pixels "
                 "per side");
  }
}

TEST(EstimateExport, AddsUpTheBuffersItNames) {
  ExportRequest r;
  r.width_px = 1000;
  r.height_px = 500;
  r.supersample = 2;
  r.frames = 300;
  r.png_frames = true;
  r.base_samples = 1000;
  r.history_bytes = 4096;
  const ExportEstimate e = EstimateExport(r);
  EXPECT_EQ(e.gl_bytes, 2.25 * 4 * 2000 * 1000);
  EXPECT_EQ(e.frame_bytes, 2.0 * 3 * 500000 + 65536);
  EXPECT_EQ(e.times_bytes, 8.0 * 300);
  EXPECT_EQ(e.base_bytes, 40.0 * 1000);
  EXPECT_EQ(e.history_bytes, 4096.0);
  EXPECT_EQ(e.video_bytes, 0.0);
  EXPECT_EQ(e.memory_bytes(), e.program_bytes + e.gl_bytes + e.frame_bytes + e.times_bytes +
                                  e.history_bytes + e.base_bytes);
  EXPECT_EQ(e.disk_bytes, 300 * PngFrameEstimate_bytes(1000, 500));
  // A video adds ffmpeg's memory and its file.
  r.mp4 = true;
  const ExportEstimate v = EstimateExport(r);
  EXPECT_GT(v.video_bytes, 0.0);
  EXPECT_GT(v.disk_bytes, e.disk_bytes);
  // The largest picture the limits allow at supersample 2 (7680x4320, 8K UHD) fits the default
  // budget of 2 GiB as frames; 8192x8192 does not.
  r = {};
  r.width_px = 7680;
  r.height_px = 4320;
  r.supersample = 2;
  r.frames = 100;
  r.png_frames = true;
  EXPECT_LT(EstimateExport(r).memory_bytes(), 2.0 * 1024 * 1024 * 1024);
  r.width_px = r.height_px = 8192;
  EXPECT_GT(EstimateExport(r).memory_bytes(), 2.0 * 1024 * 1024 * 1024);
}

}  // namespace
}  // namespace rockbench::renders
