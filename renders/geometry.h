#pragma once
/// Pure geometry of the drawing (no GL): block corners from a state, state at a time of a
/// history, the base displacement and the camera that frames a whole motion.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "scene/ground_motion.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::renders {

/// A point or vector in the plane of motion, m (x right, y up).
struct Vec2 {
  double x_m = 0.0;
  double y_m = 0.0;
};

/// Corners of a block, counter-clockwise from the bottom-left: bottom-left, bottom-right,
/// top-right, top-left (in the block's own frame), in world coordinates, m.
using Quad = std::array<Vec2, 4>;

/// Where the blocks of a scene are for one state.
struct StackPose {
  Quad block1;
  bool has_block2 = false;
  Quad block2;  ///< valid when has_block2
};

/// Block corners for a state, thesis convention: theta > 0 tilts right (clockwise).
/// Block 1 rotates by theta1 about its right base corner when theta1 > 0, its left one when
/// theta1 < 0. Block 2 is centred on block 1 at rest and rotates by (theta2 - theta1) relative to
/// block 1, on block 1's top face, about its own right base corner when theta2 > theta1 and its
/// left one when theta2 < theta1 (a block 2 wider than block 1 pivots on block 1's corner).
/// `base` shifts everything (ground displacement x_g, y_g). Angles in rad.
StackPose PoseFor(const Scene& scene, double theta1_rad, double theta2_rad, Vec2 base = {});

/// The state of a history at t_s: thetas interpolated linearly between the samples around t_s,
/// the mode of the sample at or before t_s; held constant before the first and after the last
/// sample. Throws std::invalid_argument for an empty history.
Sample StateAt(const History& history, double t_s);

/// Base (ground) displacement x_g(t), y_g(t), m: none, sampled, or any callable.
class BaseDisplacement {
 public:
  using Function = std::function<Vec2(double t_s)>;
  /// No displacement (the ground stays put).
  BaseDisplacement() = default;
  /// Sampled at t0_s + k dt_s; linear between samples, held beyond the ends. x_m and y_m have
  /// the same length (y_m may be empty: no vertical displacement).
  static BaseDisplacement FromSamples(double t0_s, double dt_s, std::vector<double> x_m,
                                      std::vector<double> y_m);
  static BaseDisplacement FromFunction(Function f);

  Vec2 At(double t_s) const;
  bool empty() const { return !function_ && x_m_.empty(); }

 private:
  Function function_;
  double t0_s_ = 0.0, dt_s_ = 0.0;
  std::vector<double> x_m_, y_m_;
};

/// Settings of the double integration of ground acceleration into displacement.
struct BaseIntegrationConfig {
  /// Sample interval, s, when no component is a record (records use their own dt).
  double dt_s = 1e-3;
};

/// Base displacement from a scene's ground motion on [0, t_end_s]: trapezoidal integration of
/// the acceleration to velocity, a simple baseline correction (the least-squares straight line
/// through the velocity is removed, so a record that ends with a residual velocity does not
/// drift away), then trapezoidal integration to displacement (x_g(0) = y_g(0) = 0). Empty motion
/// gives an empty displacement.
BaseDisplacement IntegrateBaseDisplacement(const GroundMotion& motion, double t_end_s,
                                           const BaseIntegrationConfig& config = {});
/// Samples IntegrateBaseDisplacement takes (and holds, per component) for this motion up to
/// t_end_s: t_end_s / dt + 1 (0 for no motion), as a double for the memory estimate.
double BaseDisplacementSamples(const GroundMotion& motion, double t_end_s,
                               const BaseIntegrationConfig& config = {});

/// An axis-aligned box in world coordinates, m.
struct Box {
  double x_min_m = 0.0, x_max_m = 0.0, y_min_m = 0.0, y_max_m = 0.0;
  double width_m() const { return x_max_m - x_min_m; }
  double height_m() const { return y_max_m - y_min_m; }
};

/// Isotropic world->pixel mapping onto a viewport of the final image (pixel coordinates: x right,
/// y down, origin at the top-left corner of the image, pixel (i, j) covers [i, i+1) x [j, j+1)).
struct Camera {
  Box world;             ///< the world box shown (aspect equals the viewport's)
  double vp_x_px = 0.0;  ///< viewport left edge, px
  double vp_y_px = 0.0;  ///< viewport top edge, px
  double vp_w_px = 0.0;  ///< viewport width, px
  double vp_h_px = 0.0;  ///< viewport height, px
  /// Pixel coordinates (continuous) of a world point.
  Vec2 ToPixel(Vec2 world_m) const;
  /// Pixels per metre (the same on both axes).
  double px_per_m() const { return vp_w_px / world.width_m(); }
};

/// The box that holds every block corner of every sample of `histories` with t in
/// [t_from_s, t_to_s] (base displacement included), the ground surface and a strip of ground
/// below it (a fifth of the stack height), grown by `margin_frac` of its size on every side.
Box MotionBox(const Scene& scene, const std::vector<const History*>& histories,
              const BaseDisplacement& base, double t_from_s, double t_to_s,
              double margin_frac = 0.06);

/// A camera showing `box` centred in the viewport with true proportions (the box is widened or
/// heightened to the viewport's aspect ratio; its bottom edge is kept).
Camera FitCamera(const Box& box, double vp_x_px, double vp_y_px, double vp_w_px, double vp_h_px);

/// Times of the frames of an animation of [t_from_s, t_to_s] at `fps` frames per second of video
/// and `speed` (simulated seconds per video second; 0.5 is half-speed slow motion):
/// t_k = t_from_s + k speed / fps, k = 0 .. n-1, n = max(1, round((t_to - t_from) fps / speed)),
/// so the video lasts (t_to - t_from) / speed seconds. Throws std::invalid_argument for fps or
/// speed <= 0, t_to < t_from, or more than kMaxFrames frames (renders/limits.h).
std::vector<double> FrameTimes(double t_from_s, double t_to_s, double fps, double speed);

}  // namespace rockbench::renders
