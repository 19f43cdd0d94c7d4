#pragma once
/// FrameRenderer's drawing of a cylinder scene (docs/renders.md "The cylinder"): the base plane
/// moving in x, y and z, each track's cylinder as a shaded prism with a stripe along one
/// generator and a radius on its top face (its spin), its axis above the top face and an arrow
/// on the base toward its lean; the top view of the axis's path; the text. Legacy GL into the
/// current context (pixel coordinates set by the caller), text on the final pixels.
#include <vector>

#include "renders/cylinder/cylinder_scene.h"
#include "renders/renderer.h"
#include "renders/text.h"

namespace rockbench::renders {

class CylinderPainter {
 public:
  /// Keeps references: every argument outlives the painter (FrameRenderer's members).
  CylinderPainter(const Scene& scene, const std::vector<Track>& tracks,
                  const BaseDisplacement& base, const RenderConfig& config,
                  const FrameLayout& layout, const Palette& palette);
  /// Draws the frame at t_s into the current GL context (cleared first).
  void DrawGl(double t_s) const;
  /// Draws the text of the frame at t_s on the final pixels.
  void DrawText(double t_s, Font* font, Image* img) const;

  /// Track i's colour: its arrow, its axis, its outline and its trace in the top view (the
  /// first track's is the block fill's dark blue, the others the planar overlay's outlines).
  static Rgb TrackColour(const Palette& palette, size_t i);

 private:
  const Scene& scene_;
  const std::vector<Track>& tracks_;
  const BaseDisplacement& base_;
  const RenderConfig& config_;
  const FrameLayout& layout_;
  const Palette& palette_;
  CylinderSize size_;

  double line_w() const;
  Vec3d BaseAt(double t_s) const;
  void DrawGround(const PerspectiveCamera& cam, double t_s) const;
  void DrawArrow(const PerspectiveCamera& cam, const CylinderAt& at, const Vec3d& base,
                 Rgb colour) const;
  void DrawCylinder(const PerspectiveCamera& cam, const CylinderPose& pose, bool solid,
                    Rgb edge) const;
  void DrawAxis(const PerspectiveCamera& cam, const CylinderPose& pose, Rgb colour) const;
  void DrawTopView(double t_s) const;
};

}  // namespace rockbench::renders
