#pragma once
/// The motion as drawn (no GL; named apart from reference/geometry.h, the model's block
/// geometry): block corners from a state, state at a time of a
/// history, the base displacement and the camera that frames a whole motion. The corners come
/// from the scene's pivot chain (scene/stack_pose.h) and the base displacement from the
/// kinematic drive's ground path (scene/ground_displacement.h), the same the engines use.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "scene/stack_pose.h"
#include "scene/vec2.h"

namespace rockbench::renders {

/// The stack's state of a sample of a history: its angles and rates; the blocks of the scene
/// above the history's top block (a history of fewer blocks than the scene: a single-block
/// history drawn on a two-block scene) ride locked on it, with its angle and rate (theta2 =
/// theta1, omega2 = omega1).
InitialState StackState(const Sample& sample);

/// The corners of a stack's blocks, bottom first: one quad per block of the scene, m.
using DrawnStack = std::vector<BlockCorners>;

/// Block corners for a state, thesis convention: theta > 0 tilts right (clockwise). Block 1
/// turns by theta1 about its right base corner when theta1 > 0, its left one when theta1 < 0.
/// Block k + 1 is centred on block k at rest and turns by (theta_{k+1} - theta_k) relative to
/// it, on its top face, about its own right base corner when theta_{k+1} > theta_k and its left
/// one when theta_{k+1} < theta_k. A zero angle takes the side of its rate (PivotSide), which
/// moves no corner. The corners are scene/stack_pose.h StackCornersAt's: the one placement of
/// the engines, their initial poses and the external engines' input.
/// `base` shifts everything (ground displacement x_g, y_g, m). Angles in rad, rates in rad/s.
DrawnStack PoseFor(const Scene& scene, const InitialState& state, Vec2 base = {});
/// The same for one or two blocks at rest rates (omega1 = omega2 = 0).
DrawnStack PoseFor(const Scene& scene, double theta1_rad, double theta2_rad, Vec2 base = {});

/// The state of a history at t_s: thetas interpolated linearly between the samples around t_s,
/// the mode of the sample at or before t_s; held constant before the first and after the last
/// sample. Throws std::invalid_argument for an empty history.
Sample StateAt(const History& history, double t_s);

/// Base (ground) displacement x_g(t), y_g(t), m: none, sampled, or any callable; for a 3-D
/// scene (a cylinder) also the transverse displacement along +y ([base.transverse]).
class BaseDisplacement {
 public:
  using Function = std::function<Vec2(double t_s)>;
  using TransverseFunction = std::function<double(double t_s)>;
  /// No displacement (the ground stays put).
  BaseDisplacement() = default;
  /// Sampled at t0_s + k dt_s; linear between samples, held beyond the ends. x_m and y_m have
  /// the same length (y_m may be empty: no vertical displacement).
  static BaseDisplacement FromSamples(double t0_s, double dt_s, std::vector<double> x_m,
                                      std::vector<double> y_m);
  static BaseDisplacement FromFunction(Function f);

  /// The transverse displacement (a 3-D scene's +y), m: sampled on this displacement's grid
  /// (the same length as x_m; linear between samples, held beyond the ends), or any callable.
  /// Throws std::invalid_argument for samples of another length.
  void SetTransverse(std::vector<double> transverse_m);
  void SetTransverse(TransverseFunction f);

  /// x_g (along +x) and y_g (vertical, up), m.
  Vec2 At(double t_s) const;
  /// The transverse displacement (along +y of a 3-D scene), m; 0 without one.
  double TransverseAt(double t_s) const;
  bool empty() const { return !function_ && x_m_.empty() && !has_transverse(); }
  bool has_transverse() const { return transverse_function_ || !t_m_.empty(); }

 private:
  Function function_;
  TransverseFunction transverse_function_;
  double t0_s_ = 0.0, dt_s_ = 0.0;
  std::vector<double> x_m_, y_m_, t_m_;
};

/// The kinematic drive's settings the base displacement is integrated with
/// (scene/ground_displacement.h IntegrateGroundPath).
struct BaseIntegrationConfig {
  /// The step grid, s: the kinematic drive's time step (default 1e-4 s, every engine's default
  /// time_step).
  double dt_s = 1e-4;
  /// The baseline correction's corner, Hz: the kinematic drive's kinematic_highpass_hz (default
  /// 0, its default: no correction).
  double highpass_hz = 0.0;
  /// The run's duration, s: with a high-pass (whose zero-phase filter looks ahead) the path is
  /// integrated over at least [0, run_duration_s], as the engines integrate it, so that a
  /// shorter window shows the same path. 0: the window only.
  double run_duration_s = 0.0;
};

/// The settings of the scene's kinematic drive: of the first engine table (in name order) with
/// drive = "kinematic", its time_step and kinematic_highpass_hz where given; the defaults of
/// BaseIntegrationConfig otherwise (and for a scene with no kinematic-drive engine). The
/// scene's run duration in every case.
BaseIntegrationConfig BaseIntegrationFor(const Scene& scene);

/// Base displacement from a scene's ground motion on [0, t_end_s]: the ground path of a
/// kinematic-drive engine with these settings (IntegrateGroundPath: the acceleration sampled on
/// the grid t_n = n dt, leapfrog double integration from rest, then the zero-phase Butterworth
/// high-pass when highpass_hz > 0), x_g(0) = y_g(0) = 0, linear between the grid's points. No
/// vertical component gives no vertical displacement; empty motion an empty displacement. A
/// transverse component ([base.transverse], a 3-D scene's +y) gives the transverse displacement
/// by the same rule (the engines' ut_m, engines/common/engine_input.h).
BaseDisplacement IntegrateBaseDisplacement(const GroundMotion& motion, double t_end_s,
                                           const BaseIntegrationConfig& config = {});
/// Samples IntegrateBaseDisplacement holds per component for this motion up to t_end_s, as a
/// double for the memory estimate: the grid's points (ceil(window / dt) + 1), and with a
/// high-pass the filter's two pads (1.2 / (highpass_hz dt) each); 0 for no motion.
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
  /// Pixel coordinates (continuous, px) of a world point (m).
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
