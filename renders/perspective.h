#pragma once
/// A pinhole camera for the 3-D scenes (a cylinder, docs/renders.md "The cylinder"): world
/// points (m; +x along [base.horizontal], +y along [base.transverse], +z up) to pixels of the
/// final image (x right, y down from the top-left corner). No GL: the frame's points are
/// projected here and drawn in pixel coordinates, as the planar views are.
#include <vector>

#include "scene/cylinder_state.h"
#include "scene/vec2.h"

namespace rockbench::renders {

struct PerspectiveCamera {
  Vec3d eye_m{};                    ///< the camera's position, world, m
  Vec3d right{};                    ///< unit, world: the image's +x
  Vec3d up{};                       ///< unit, world: the image's -y
  Vec3d forward{};                  ///< unit, world: the viewing direction
  double focal_px = 1.0;            ///< pixels per unit of (lateral offset / depth)
  double cx_px = 0.0, cy_px = 0.0;  ///< where the viewing axis meets the image, px
  /// The viewport, final-image px.
  double vp_x_px = 0.0, vp_y_px = 0.0, vp_w_px = 0.0, vp_h_px = 0.0;

  /// Depth of a world point along `forward` from the eye, m (> 0: in front of the camera).
  double Depth_m(const Vec3d& p) const;
  /// Pixel coordinates (continuous, px) of a world point in front of the camera.
  Vec2 ToPixel(const Vec3d& p) const;
  /// Whether a surface through `point` with outward `normal` faces the camera.
  bool Faces(const Vec3d& point, const Vec3d& normal) const;
};

/// The camera looking from `azimuth_rad` (from +x toward +y, the direction from the scene to
/// the eye seen from above) and `elevation_rad` above the horizon, placed and zoomed so that
/// every point of `points` lies within the viewport with `margin_frac` of its size to spare on
/// each side: the eye at a distance where the points' bounding sphere is in front of it, then
/// the focal length and the image centre chosen so that the projected points' bounding box fills
/// the viewport (exact for a fixed eye). Throws std::invalid_argument for no points or an empty
/// viewport.
PerspectiveCamera FramePerspective(const std::vector<Vec3d>& points, double azimuth_rad,
                                   double elevation_rad, double vp_x_px, double vp_y_px,
                                   double vp_w_px, double vp_h_px, double margin_frac = 0.05);

}  // namespace rockbench::renders
