#pragma once
/// A cylinder (shape "cylinder", docs/three-d.md) as drawn, without GL: its state at a time of
/// a history, the points of its surface, the base it stands on, and the layout of its frames (a
/// perspective view and the top view of the axis's path). The pose is scene/cylinder_state.h's
/// (CylinderRotation, CylinderCentre): the one convention of the reference and the engines.
/// The drawing itself is FrameRenderer's (renders/cylinder/cylinder_painter.cc).
#include <string>
#include <vector>

#include "renders/drawn_motion.h"
#include "renders/perspective.h"
#include "renders/renderer.h"
#include "scene/cylinder_state.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::renders {

/// The side the camera looks from: the direction from the scene to the eye seen from above, from
/// +x toward +y (-70 degrees: in front of the x-z plane, a little to the right, so that +x runs
/// to the right of the image and +y into it), and its height above the horizon.
inline constexpr double kCylinderCameraAzimuth_rad = -70.0 * 3.14159265358979323846 / 180.0;
inline constexpr double kCylinderCameraElevation_rad = 25.0 * 3.14159265358979323846 / 180.0;
/// Sides of the prism drawn for the cylinder: enough that its outline looks round.
inline constexpr int kCylinderSides = 48;

/// A cylinder history's state at t_s, and whether it stands on its rim.
struct CylinderAt {
  CylinderState state;  ///< tilt, azimuth and spin (the rates are left at 0)
  bool on_rim = false;  ///< mode "rim" (else "rest", on its face)
  std::string mode;     ///< the mode's name, as history.csv writes it
};

/// The state of body 1 of a cylinder history at t_s: between the two samples around t_s the
/// tilt vector (tilt_x, tilt_y) is interpolated linearly (the tilt is its length, the azimuth
/// its direction, kept continuous with the earlier sample's; at a zero vector that sample's),
/// and so is the heading azimuth + spin (by its change within half a turn), the spin being the
/// heading less the azimuth; the mode is the sample's at or before t_s. Held constant before
/// the first and after the last sample (a pair of samples at an event's time: the later one
/// from that time on). Throws std::invalid_argument for an empty history or one of another
/// kind.
CylinderAt CylinderStateAt(const History& history, double t_s);

/// A cylinder's size: radius and half-height, m (Scene::blocks[0]).
struct CylinderSize {
  double radius_m = 0.0;
  double half_height_m = 0.0;
};
CylinderSize CylinderSizeOf(const Scene& scene);

/// The base's displacement at t_s in world axes, m: (x_g, the transverse displacement, the
/// vertical y_g).
Vec3d BaseShift(const BaseDisplacement& base, double t_s);

/// A cylinder posed for drawing: its centre, rotation (body -> world) and size.
struct CylinderPose {
  Vec3d centre_m{};  ///< world, m (the base shift included)
  Mat3d rotation{};  ///< CylinderRotation
  CylinderSize size;
  /// The world point at body angle `angle_rad` (from the body's x axis toward its y axis), at
  /// `radius_frac` of the radius from the axis and `z_frac` of the half-height along it (+1:
  /// the top face, -1: the bottom face).
  Vec3d Point(double angle_rad, double z_frac, double radius_frac = 1.0) const;
  /// The world direction of a body vector.
  Vec3d Direction(const Vec3d& body) const;
  /// The axis (body z), world, unit.
  Vec3d Axis() const { return {rotation[2], rotation[5], rotation[8]}; }
};

/// The pose of a state on a base shifted by `base_m` (CylinderCentre plus the shift).
CylinderPose PoseOfCylinder(const CylinderState& state, const CylinderSize& size,
                            const Vec3d& base_m);

/// Lays out a cylinder scene's frames into `lay`, whose time window is set: the header (the time
/// stamp, and in the overlay layout a line per track), the perspective views (overlay: one;
/// side: one per track, each with two lines of text above it), every one framing the whole
/// motion of every track in the window with the base plane, and with config.show_chart the
/// square top view of the axis's path right of them (tilt_x to the right, tilt_y up, +-
/// top_view_range_rad on both). Throws std::invalid_argument when the image is too small.
void PlaceCylinderLayout(const Scene& scene, const std::vector<Track>& tracks,
                         const BaseDisplacement& base, const RenderConfig& config,
                         FrameLayout& lay);

}  // namespace rockbench::renders
