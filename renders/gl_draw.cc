#include "renders/gl_draw.h"

#include <algorithm>

namespace rockbench::renders {

Rgb OverlayOutline(size_t i) {
  constexpr Rgb kOutlines[] = {{15, 15, 15}, {180, 20, 20}, {20, 130, 60}};
  return kOutlines[(i - 1) % 3];
}

double LineWidth_px(const RenderConfig& config) {
  return std::max(1.0, config.height_px / 480.0);
}

void Colour(Rgb c, double alpha) {
  glColor4d(c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

void FillRect(const PixelRect& r) {
  glBegin(GL_QUADS);
  glVertex2d(r.x_px, r.y_px);
  glVertex2d(r.x_px + r.w_px, r.y_px);
  glVertex2d(r.x_px + r.w_px, r.y_px + r.h_px);
  glVertex2d(r.x_px, r.y_px + r.h_px);
  glEnd();
}

void BeginFrame(const RenderConfig& config, const Palette& palette) {
  const int s = config.supersample;
  glViewport(0, 0, config.width_px * s, config.height_px * s);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  // Final-image pixel coordinates, y down.
  glOrtho(0, config.width_px, config.height_px, 0, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  // Opaque drawing without blending (cheaper per pixel); translucent fills turn it on.
  glDisable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(palette.background.r / 255.f, palette.background.g / 255.f,
               palette.background.b / 255.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void ScissorTo(const PixelRect& r, const RenderConfig& config) {
  const int s = config.supersample;
  glScissor(static_cast<int>(r.x_px * s),
            static_cast<int>((config.height_px - r.y_px - r.h_px) * s),
            static_cast<int>(r.w_px * s), static_cast<int>(r.h_px * s));
}

void PlotArea(const PixelRect& r, double lw_px, const Palette& palette) {
  Colour(palette.chart_frame);
  FillRect({r.x_px - lw_px, r.y_px - lw_px, r.w_px + 2 * lw_px, r.h_px + 2 * lw_px});
  Colour(palette.chart_background);
  FillRect(r);
}

void TrackLine(size_t i, double lw_px, int supersample) {
  if (i > 0) {
    glEnable(GL_LINE_STIPPLE);
    glLineStipple(3 * supersample, 0xF0F0);
  }
  glLineWidth(static_cast<float>((i == 0 ? 1.5 : 1.2) * lw_px * supersample));
}

}  // namespace rockbench::renders
