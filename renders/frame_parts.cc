#include "renders/frame_parts.h"

#include <algorithm>
#include <cmath>

namespace rockbench::renders {

double NiceCeil(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0}) {
    if (m * p >= x * (1.0 - 1e-12)) return m * p;
  }
  return 10.0 * p;
}

double NiceStep(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= x) return m * p;
  }
  return 10.0 * p;
}

void SetTextSizes(int height_px, FrameLayout& lay) {
  lay.font_px = std::clamp(static_cast<int>(std::lround(height_px / 34.0)), 9, 40);
  lay.line_px = static_cast<int>(std::lround(lay.font_px * 1.3));
  lay.margin_px = std::max(3, static_cast<int>(std::lround(height_px * 0.015)));
}

double PlaceHeader(const RenderConfig& config, int n, bool side, FrameLayout& lay) {
  const double m = lay.margin_px;
  const int header_lines = config.show_text ? (side ? 1 : 1 + n) : 0;
  lay.header = {m, m, config.width_px - 2 * m, static_cast<double>(header_lines * lay.line_px)};
  return header_lines > 0 ? lay.header.y_px + lay.header.h_px + m : m;
}

std::vector<PixelRect> PlaceViews(const RenderConfig& config, int n, bool side, double top,
                                  double bottom, double right, FrameLayout& lay) {
  const double m = lay.margin_px;
  if (!side) return {{m, top, right - m, bottom - top}};
  std::vector<PixelRect> views;
  const double panel_w = (right - m * n) / n;
  const int label_lines = config.show_text ? 2 : 0;
  for (int i = 0; i < n; ++i) {
    const double x = m + i * (panel_w + m);
    lay.view_labels.push_back({x, top, panel_w, static_cast<double>(label_lines * lay.line_px)});
    const double view_top = top + label_lines * lay.line_px;
    views.push_back({x, view_top, panel_w, bottom - view_top});
  }
  return views;
}

}  // namespace rockbench::renders
