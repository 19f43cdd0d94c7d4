// Frame layout and camera: pure arithmetic, built with or without OSMesa.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "renders/cylinder/cylinder_scene.h"
#include "renders/frame_parts.h"
#include "renders/limits.h"
#include "renders/renderer.h"

namespace rockbench::renders {
namespace {

// Throws std::invalid_argument for an image size or supersampling out of the limits.
void CheckImageSize(const RenderConfig& config) {
  const std::string size = std::to_string(config.width_px) + "x" + std::to_string(config.height_px);
  if (config.width_px < kMinWidth_px || config.height_px < kMinHeight_px) {
    throw std::invalid_argument("image size " + size + ": must be at least " +
                                std::to_string(kMinWidth_px) + "x" + std::to_string(kMinHeight_px) +
                                " pixels");
  }
  if (config.width_px > kMaxSide_px || config.height_px > kMaxSide_px) {
    throw std::invalid_argument("image size " + size + ": more than the limit of " +
                                std::to_string(kMaxSide_px) + " pixels per side");
  }
  if (config.supersample < 1 || config.supersample > kMaxSupersample) {
    throw std::invalid_argument("supersampling factor " + std::to_string(config.supersample) +
                                ": must be 1.." + std::to_string(kMaxSupersample));
  }
  if (std::max(config.width_px, config.height_px) * config.supersample > kMaxDrawnSide_px) {
    throw std::invalid_argument(
        "image size " + size + " at supersample " + std::to_string(config.supersample) +
        ": drawn at more than OSMesa's " + std::to_string(kMaxDrawnSide_px) + " pixels per side");
  }
}

// The time window (config's, else the whole of the longest history) into `lay`; the tracks'
// histories. Throws for no track, an empty history or a window that ends before it starts.
std::vector<const History*> TimeWindow(const std::vector<Track>& tracks, const RenderConfig& config,
                                       FrameLayout& lay) {
  if (tracks.empty()) throw std::invalid_argument("nothing to draw: no history given");
  std::vector<const History*> histories;
  double t_end_s = 0.0;
  for (const Track& t : tracks) {
    if (t.history.samples.empty()) {
      throw std::invalid_argument("the history of '" + t.engine + "' has no samples");
    }
    histories.push_back(&t.history);
    t_end_s = std::max(t_end_s, t.history.samples.back().t_s);
  }
  lay.t_from_s = std::isnan(config.t_from_s) ? 0.0 : config.t_from_s;
  lay.t_to_s = std::isnan(config.t_to_s) ? t_end_s : config.t_to_s;
  if (!(lay.t_to_s >= lay.t_from_s)) {
    throw std::invalid_argument("the time window ends before it starts");
  }
  return histories;
}

// What is left for the views once the header and the chart have their places: [m, right] by
// [top, bottom], px.
struct ViewArea {
  double top = 0.0, bottom = 0.0, right = 0.0;
};

// The header (the time stamp line, and in the overlay layout one line per engine of `n`) and
// the chart: below the views, or for a stack of three and more blocks (`stacked`) a column
// right of them. Throws when no room is left for the views.
ViewArea PlaceHeaderAndChart(const RenderConfig& config, int n, bool side, bool stacked,
                             FrameLayout& lay) {
  const int w = config.width_px, h = config.height_px;
  const double m = lay.margin_px;
  ViewArea area;
  area.top = PlaceHeader(config, n, side, lay);
  area.bottom = h - m;
  // The views' right edge: the image's margin, or the stacked chart's column.
  area.right = w - m;
  if (config.show_chart && !stacked) {
    lay.has_chart = true;
    // The plot area, with a gutter on the left for the angle labels and a line below for the
    // time labels and the legend.
    const double chart_h = std::max(24.0, std::round(0.2 * h));
    lay.chart = {m, h - m - chart_h, w - 2 * m, chart_h - lay.line_px};
    area.bottom = lay.chart.y_px - m;
  } else if (config.show_chart) {
    lay.has_chart = true;
    // A column of 40% of the width right of the views, from below the header to a line for the
    // time labels and the range: a tall stack is narrow, and its views keep the height. With
    // several engines a line above it says which is solid and which dashed. The gutter for the
    // labels comes off its left side below.
    const double column_w = std::round(0.4 * (w - 2 * m));
    const double legend_h = n > 1 ? lay.line_px : 0.0;
    lay.chart = {w - m - column_w, area.top + legend_h, column_w,
                 h - m - lay.line_px - area.top - legend_h};
    area.right = lay.chart.x_px - m;
  }
  if (area.bottom - area.top < 16.0 || area.right - m < 16.0) {
    throw std::invalid_argument("image too small for the text and chart: give a larger size");
  }
  return area;
}

// The chart's range: the largest |theta| of the tracks in the window, rounded up to a round
// number, rad.
double ChartRange_rad(const std::vector<Track>& tracks, const FrameLayout& lay) {
  double peak = 0.0;
  auto add_peak = [&](const History& hist, const Sample& s) {
    for (int k = 0; k < std::min(hist.blocks, s.blocks()); ++k) {
      peak = std::max(peak, std::abs(s.theta_rad[k]));
    }
  };
  for (const Track& t : tracks) {
    add_peak(t.history, StateAt(t.history, lay.t_from_s));
    add_peak(t.history, StateAt(t.history, lay.t_to_s));
    for (const Sample& s : t.history.samples) {
      if (s.t_s >= lay.t_from_s && s.t_s <= lay.t_to_s) add_peak(t.history, s);
    }
  }
  return NiceCeil(std::max(peak, 1e-4) * 1.05);
}

// The stacked chart's gutter for the labels "θ<k>" and one axis per block of `blocks`, block 1
// at the bottom. Throws when an axis would be too small.
void PlaceStackedChart(int blocks, FrameLayout& lay) {
  // Theta and a subscript digit are about 0.6 and 0.4 em wide; the range goes on the line below.
  const double digits = std::floor(std::log10(static_cast<double>(blocks))) + 1.0;
  const double gutter_px = std::round((0.6 + 0.4 * digits + 0.6) * lay.font_px);
  lay.chart.x_px += gutter_px;
  lay.chart.w_px -= gutter_px;
  // A gap between two neighbours (a quarter of the font, at most a fifth of an axis's share
  // when there are many).
  const double gap_px = std::max(1.0, std::min(std::max(2.0, std::round(0.25 * lay.font_px)),
                                               std::floor(0.2 * lay.chart.h_px / blocks)));
  const double panel_h = (lay.chart.h_px - (blocks - 1) * gap_px) / blocks;
  if (panel_h < 4.0 || lay.chart.w_px < 16.0) {
    throw std::invalid_argument("image too small for the chart of " + std::to_string(blocks) +
                                " blocks' angles: give a larger size");
  }
  for (int k = 0; k < blocks; ++k) {
    lay.chart_panels.push_back({lay.chart.x_px,
                                lay.chart.y_px + (blocks - 1 - k) * (panel_h + gap_px),
                                lay.chart.w_px, panel_h});
  }
}

}  // namespace

std::optional<Layout> ParseLayout(std::string_view name) {
  if (name == "overlay") return Layout::kOverlay;
  if (name == "side") return Layout::kSide;
  return std::nullopt;
}

FrameLayout ComputeLayout(const Scene& scene, const std::vector<Track>& tracks,
                          const BaseDisplacement& base, const RenderConfig& config) {
  CheckImageSize(config);
  FrameLayout lay;
  const std::vector<const History*> histories = TimeWindow(tracks, config, lay);
  if (scene.three_dimensional()) {
    PlaceCylinderLayout(scene, tracks, base, config, lay);
    return lay;
  }

  const int n = static_cast<int>(tracks.size());
  const bool side = config.layout == Layout::kSide && n > 1;
  // Three and more blocks: one small axis per block, in a column right of the views.
  const int blocks = scene.block_count();
  const bool stacked = blocks >= 3;
  SetTextSizes(config.height_px, lay);
  const ViewArea area = PlaceHeaderAndChart(config, n, side, stacked, lay);
  const double top = area.top, bottom = area.bottom, views_right = area.right;

  const Box box = MotionBox(scene, histories, config.show_base_motion ? base : BaseDisplacement{},
                            lay.t_from_s, lay.t_to_s);
  // The views share [m, views_right] (whole numbers of pixels: the same widths as w - 2 m and
  // w - m (n + 1) when there is no stacked chart).
  for (const PixelRect& r : PlaceViews(config, n, side, top, bottom, views_right, lay)) {
    lay.views.push_back(FitCamera(box, r.x_px, r.y_px, r.w_px, r.h_px));
  }

  lay.chart_theta_max_rad = ChartRange_rad(tracks, lay);
  if (lay.has_chart && !stacked) {
    // A gutter on the left for the range label "+<max>" (DejaVu Sans digits are 0.64 em wide).
    char label[32];
    std::snprintf(label, sizeof label, "+%g", lay.chart_theta_max_rad);
    const double gutter_px =
        std::round((0.64 * std::max<double>(std::strlen(label), 3.0) + 0.6) * lay.font_px);
    lay.chart.x_px += gutter_px;
    lay.chart.w_px -= gutter_px;
  } else if (lay.has_chart) {
    PlaceStackedChart(blocks, lay);
  }
  return lay;
}

}  // namespace rockbench::renders
