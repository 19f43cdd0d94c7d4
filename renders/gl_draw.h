#pragma once
/// What FrameRenderer's drawing of planar blocks (renderer.cc) and of a cylinder
/// (cylinder_painter.cc) share: legacy GL in final-image pixel coordinates (y down; the
/// projection scales them to the supersampled buffer). Built with OSMesa only.
#include <GL/gl.h>

#include <cstddef>

#include "renders/renderer.h"
#include "scene/history.h"

namespace rockbench::renders {

/// The outline colour of track i >= 1 (the second, third, ...) in the overlay layout, cycling
/// through three (luminances 0.06, 0.21, 0.40).
Rgb OverlayOutline(size_t i);

/// The frame's line width, final-image px: 1 up to 480 px high, in proportion above.
double LineWidth_px(const RenderConfig& config);

/// The current colour (sRGB, opacity `alpha`).
void Colour(Rgb c, double alpha = 1.0);

/// An axis-aligned rectangle, filled.
void FillRect(const PixelRect& r);

/// The state every frame starts from: the viewport, the projection to final-image px, no depth
/// test, culling or blending (the blend function set for translucent fills), the background
/// cleared.
void BeginFrame(const RenderConfig& config, const Palette& palette);

/// The scissor box of rectangle `r` (whole pixels of the supersampled buffer, truncated); the
/// caller enables the test.
void ScissorTo(const PixelRect& r, const RenderConfig& config);

/// A chart's plot area: `r` filled with the chart background inside a frame `lw_px` wide.
void PlotArea(const PixelRect& r, double lw_px, const Palette& palette);

/// The line of track i's curve in a chart: the first solid, 1.5 line widths (`lw_px`) wide; the
/// others dashed (the stipple enabled: the caller disables it), 1.2 wide.
void TrackLine(size_t i, double lw_px, int supersample);

/// A line strip through a history from t_from_s to t_to_s (s): its point at t_from_s, every
/// sample after it up to t_to_s, its point at t_to_s; at_time(t) and at_sample(sample) give the
/// pixel (Vec2).
template <typename AtTime, typename AtSample>
void HistoryStrip(const History& h, double t_from_s, double t_to_s, const AtTime& at_time,
                  const AtSample& at_sample) {
  glBegin(GL_LINE_STRIP);
  const Vec2 p0 = at_time(t_from_s);
  glVertex2d(p0.x, p0.y);
  for (const Sample& smp : h.samples) {
    if (smp.t_s <= t_from_s) continue;
    if (smp.t_s > t_to_s) break;
    const Vec2 p = at_sample(smp);
    glVertex2d(p.x, p.y);
  }
  const Vec2 p1 = at_time(t_to_s);
  glVertex2d(p1.x, p1.y);
  glEnd();
}

}  // namespace rockbench::renders
