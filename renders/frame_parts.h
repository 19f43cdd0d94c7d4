#pragma once
/// What the planar frames' layout (frame_layout.cc) and a cylinder's (cylinder_scene.cc) share,
/// without GL: round numbers for axes, the text sizes, the header and the views' places.
#include <vector>

#include "renders/renderer.h"

namespace rockbench::renders {

/// The smallest of 1, 1.5, 2, 3, 4, 5, 6, 8 times a power of ten that is >= x (x > 0): a chart's
/// range.
double NiceCeil(double x);
/// The smallest of 1, 2, 5 times a power of ten that is >= x (x > 0): a grid's or ticks' step.
double NiceStep(double x);

/// The text sizes of a frame `height_px` high into `lay`: font_px, line_px and margin_px.
void SetTextSizes(int height_px, FrameLayout& lay);

/// The header into lay.header, a margin in from the top: with show_text the time stamp's line,
/// and unless `side` one line for each of the `n` tracks. Returns where what is below it starts,
/// px from the top (a margin below it).
double PlaceHeader(const RenderConfig& config, int n, bool side, FrameLayout& lay);

/// The views' rectangles in [margin, right] x [top, bottom] (px): one, or with `side` one per
/// track of `n` side by side, a margin apart, each below its lines of text (two with show_text,
/// pushed to lay.view_labels).
std::vector<PixelRect> PlaceViews(const RenderConfig& config, int n, bool side, double top,
                                  double bottom, double right, FrameLayout& lay);

}  // namespace rockbench::renders
