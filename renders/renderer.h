#pragma once
/// Frames of a scene's motion: the ground and the blocks (any number of them) at a time of one or
/// more engines' histories, with the base displacement, text (time, mode, angles) and a strip
/// chart of the angles; a cylinder in perspective with the top view of its axis's path
/// (renders/cylinder/cylinder_scene.h). Draws with legacy GL into an off-screen context
/// (gl_context.h), supersampled and box-filtered down for anti-aliased edges; text is drawn with
/// FreeType on the final pixels.
#include <array>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "renders/drawn_motion.h"
#include "renders/image.h"
#include "renders/perspective.h"
#include "renders/text.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::renders {

/// How several engines share a frame.
enum class Layout {
  kOverlay,  ///< one view: the first engine solid, the others outlined and translucent on top
  kSide,     ///< one view per engine, side by side, all solid
};

/// "overlay" / "side"; nullopt for anything else.
std::optional<Layout> ParseLayout(std::string_view name);

/// One engine's motion to draw.
struct Track {
  std::string engine;  ///< "reference", "bullet", ... (shown in the text)
  History history;
};

struct RenderConfig {
  int width_px = 1280;  ///< final image width, px
  int height_px = 720;  ///< final image height, px
  int supersample = 2;  ///< drawn at this factor per axis and box-filtered down (1..4)
  Layout layout = Layout::kOverlay;
  /// Time window, s: the camera frames the motion in it and the strip chart spans it. NaN:
  /// from 0 / to the end of the longest history.
  double t_from_s = std::numeric_limits<double>::quiet_NaN();
  double t_to_s = std::numeric_limits<double>::quiet_NaN();
  bool show_text = true;         ///< time stamp, mode and angles of each engine
  bool show_chart = true;        ///< strip chart of every block's angle up to the current time
  bool show_base_motion = true;  ///< shift ground and blocks by the base displacement
  std::string title;             ///< optional text at the top right (e.g. the scene title)
  std::filesystem::path font_path = kDefaultFontPath;
};

/// An axis-aligned rectangle of the final image, px (x right, y down from the top-left).
struct PixelRect {
  double x_px = 0.0, y_px = 0.0, w_px = 0.0, h_px = 0.0;
};

/// Where everything goes in a frame (final-image pixels). Computed without GL.
struct FrameLayout {
  double t_from_s = 0.0, t_to_s = 0.0;  ///< the resolved time window, s
  int font_px = 0;                      ///< text size, px
  int line_px = 0;                      ///< text line spacing, px
  int margin_px = 0;
  PixelRect header;                    ///< text lines at the top
  std::vector<Camera> views;           ///< overlay: one; side: one per track, left to right
  std::vector<PixelRect> view_labels;  ///< side: each view's text lines (above the view)
  bool has_chart = false;
  /// The strip chart's plot area (labels outside): below the views for one or two blocks; for
  /// three and more a column right of the views holding chart_panels.
  PixelRect chart;
  /// Three and more blocks: one small axis per block (block k + 1's at index k, block 1's at the
  /// bottom, as the stack), stacked in `chart` with a gap between them and sharing its time
  /// axis. Empty for one or two blocks (one axis, `chart`, with a trace per block).
  std::vector<PixelRect> chart_panels;
  double chart_theta_max_rad = 0.0;  ///< the chart's y range is +-this, rad (every panel's)
  /// A cylinder scene (docs/renders.md "The cylinder"; `views` is then empty): the perspective
  /// views (overlay: one; side: one per track, left to right, each below its view_labels).
  std::vector<PerspectiveCamera> perspective_views;
  /// A cylinder scene with a chart: the square top view of the axis's path (tilt_y up against
  /// tilt_x to the right, the same scale on both), its plot area; has_top_view says it is drawn.
  bool has_top_view = false;
  PixelRect top_view;
  double top_view_range_rad = 0.0;  ///< the top view's axes span +-this, rad
  double ground_half_side_m = 0.0;  ///< a cylinder scene's base plane: half its side, m
};

/// The layout of frames for these inputs (throws std::invalid_argument for a bad config or no
/// track with samples).
FrameLayout ComputeLayout(const Scene& scene, const std::vector<Track>& tracks,
                          const BaseDisplacement& base, const RenderConfig& config);

/// Colours (sRGB). Their luminances differ (Rec. 709: background 0.97, block 2 0.66, ground
/// 0.47, block 1 0.28, outlines and text 0.08), so a greyscale print keeps them apart.
struct Palette {
  Rgb background{248, 248, 246};
  Rgb ground{120, 120, 120};
  Rgb ground_line{50, 50, 50};
  /// Block k + 1's fill at index k (block(k) cycles beyond 8). Blocks 1 and 2 keep their dark
  /// blue and orange; then wine, lilac, dark green, light green, olive, light aqua. Dark and
  /// light alternate up the stack (luma 0.27, 0.66, 0.25, 0.64, 0.34, 0.75, 0.37, 0.77), so
  /// neighbours differ by at least 0.3 in greyscale; any two of the eight differ by CIE76
  /// Delta E >= 35 (>= 17 under simulated deuteranopia, protanopia and tritanopia, >= 37 between
  /// neighbours), and each differs from the background and the ground by >= 37.
  std::array<Rgb, 8> blocks{{{40, 72, 130},
                             {240, 160, 50},
                             {130, 40, 90},
                             {190, 150, 210},
                             {20, 110, 60},
                             {150, 210, 120},
                             {100, 100, 20},
                             {120, 220, 200}}};
  Rgb outline{20, 20, 20};
  Rgb text{20, 20, 20};
  Rgb chart_background{255, 255, 255};
  Rgb chart_frame{150, 150, 150};
  /// Block k + 1's angle trace and label at index k (chart_theta(k) cycles beyond 8): its fill,
  /// darkened where the fill is too light for a thin line on white.
  std::array<Rgb, 8> chart_thetas{{{40, 72, 130},
                                   {205, 110, 0},
                                   {130, 40, 90},
                                   {120, 80, 170},
                                   {20, 110, 60},
                                   {60, 150, 40},
                                   {100, 100, 20},
                                   {0, 140, 130}}};

  /// Block k + 1's fill (k = 0: block 1).
  Rgb block(int k) const { return blocks[static_cast<size_t>(k) % blocks.size()]; }
  /// Block k + 1's trace colour.
  Rgb chart_theta(int k) const {
    return chart_thetas[static_cast<size_t>(k) % chart_thetas.size()];
  }
};

/// Draws frames. Owns a GL context (created in the constructor) and the font.
class FrameRenderer {
 public:
  /// Throws RenderError when this build has no OSMesa, the font is missing or the context
  /// cannot be created; std::invalid_argument for a bad config.
  FrameRenderer(const Scene& scene, std::vector<Track> tracks, BaseDisplacement base,
                RenderConfig config);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  /// The frame at simulated time t_s into `out` (resized to the config's size).
  void Render(double t_s, Image* out);
  Image Render(double t_s);

  const FrameLayout& layout() const;
  const RenderConfig& config() const;
  const Palette& palette() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::renders
