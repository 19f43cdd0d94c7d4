// Frame layout (no GL): where the views, text and chart go, and the bad configurations.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "renders/renderer.h"
#include "tests/common/sample.h"
#include "tests/common/stack_scene.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;

Scene Stack() {
  return testing_util::TwoBlockScene(1.25, 1.25, 3906.0, 1.0, 2.5, 6250.0);
}

History Wobble(double amp_rad, double t_end_s = 4.0) {
  History h;
  for (int i = 0; i <= static_cast<int>(t_end_s * 100); ++i) {
    const double t = 0.01 * i;
    h.samples.push_back(MakeSample({.t_s = t,
                                    .theta1_rad = amp_rad * std::sin(3 * t),
                                    .theta2_rad = 2 * amp_rad * std::sin(4 * t)}));
  }
  return h;
}

bool Inside(const PixelRect& outer, const PixelRect& inner) {
  return inner.x_px >= outer.x_px && inner.y_px >= outer.y_px &&
         inner.x_px + inner.w_px <= outer.x_px + outer.w_px + 1e-9 &&
         inner.y_px + inner.h_px <= outer.y_px + outer.h_px + 1e-9;
}

bool Disjoint(const PixelRect& a, const PixelRect& b) {
  return a.x_px + a.w_px <= b.x_px || b.x_px + b.w_px <= a.x_px || a.y_px + a.h_px <= b.y_px ||
         b.y_px + b.h_px <= a.y_px;
}

PixelRect ViewRect(const Camera& c) {
  return {c.vp_x_px, c.vp_y_px, c.vp_w_px, c.vp_h_px};
}

TEST(ComputeLayout, OverlayHasOneViewBetweenTextAndChart) {
  RenderConfig cfg;
  const FrameLayout lay =
      ComputeLayout(Stack(), {{"reference", Wobble(0.05)}, {"bullet", Wobble(0.06)}}, {}, cfg);
  ASSERT_EQ(lay.views.size(), 1u);
  const PixelRect image{0, 0, 1280, 720};
  const PixelRect view = ViewRect(lay.views[0]);
  EXPECT_TRUE(Inside(image, view));
  EXPECT_TRUE(Inside(image, lay.chart));
  EXPECT_TRUE(Disjoint(view, lay.chart));
  EXPECT_TRUE(Disjoint(view, lay.header));
  // Header: the time stamp and one line per engine.
  EXPECT_EQ(lay.header.h_px, 3 * lay.line_px);
  // The window defaults to the whole history.
  EXPECT_EQ(lay.t_from_s, 0.0);
  EXPECT_DOUBLE_EQ(lay.t_to_s, 4.0);
  // Chart range: a round number just above the peak |theta2| = 0.12 rad.
  EXPECT_GE(lay.chart_theta_max_rad, 0.12);
  EXPECT_LE(lay.chart_theta_max_rad, 0.2);
}

TEST(ComputeLayout, SideBySideGivesOneViewPerEngineWithTheSameScale) {
  RenderConfig cfg;
  cfg.layout = Layout::kSide;
  const FrameLayout lay = ComputeLayout(
      Stack(), {{"reference", Wobble(0.05)}, {"a", Wobble(0.06)}, {"b", Wobble(0.02)}}, {}, cfg);
  ASSERT_EQ(lay.views.size(), 3u);
  ASSERT_EQ(lay.view_labels.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(lay.views[i].px_per_m(), lay.views[0].px_per_m(), 1e-9);
    EXPECT_TRUE(Disjoint(ViewRect(lay.views[i]), lay.view_labels[i]));
    if (i > 0) {
      EXPECT_GE(lay.views[i].vp_x_px, lay.views[i - 1].vp_x_px + lay.views[i - 1].vp_w_px);
    }
  }
}

TEST(ComputeLayout, TheWindowLimitsTheChartRange) {
  // The motion grows with time; a window over the quiet start gets a smaller range.
  History h;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.01 * i;
    h.samples.push_back(MakeSample({.t_s = t, .theta1_rad = 0.01 * t * t, .theta2_rad = 0.0}));
  }
  RenderConfig cfg;
  cfg.t_from_s = 0.0;
  cfg.t_to_s = 1.0;
  const FrameLayout early = ComputeLayout(Stack(), {{"reference", h}}, {}, cfg);
  cfg.t_to_s = 4.0;
  const FrameLayout all = ComputeLayout(Stack(), {{"reference", h}}, {}, cfg);
  EXPECT_LT(early.chart_theta_max_rad, all.chart_theta_max_rad);
  EXPECT_GE(all.chart_theta_max_rad, 0.16);
}

TEST(ComputeLayout, BaseDisplacementWidensTheView) {
  RenderConfig cfg;
  const History h = Wobble(0.01);
  const FrameLayout still = ComputeLayout(Stack(), {{"reference", h}}, {}, cfg);
  // A swing of +-10 m is wider than the 16:9 view of the still stack (about 13 m).
  const auto moving = BaseDisplacement::FromFunction([](double t) {
    return Vec2{10.0 * std::sin(t), 0.0};
  });
  const FrameLayout shaken = ComputeLayout(Stack(), {{"reference", h}}, moving, cfg);
  EXPECT_GT(shaken.views[0].world.width_m(), 20.0);
  EXPECT_GT(shaken.views[0].world.width_m(), still.views[0].world.width_m());
  // Switched off, the base motion does not count.
  cfg.show_base_motion = false;
  const FrameLayout off = ComputeLayout(Stack(), {{"reference", h}}, moving, cfg);
  EXPECT_NEAR(off.views[0].world.width_m(), still.views[0].world.width_m(), 1e-12);
}

// A column of `n` equal drums, 0.9 m wide and 0.85 m high, and a history of it rocking.
Scene Drums(int n) {
  Scene s;
  for (int k = 0; k < n; ++k) {
    s.blocks.push_back(BlockDef{.width_m = 0.9, .height_m = 0.85, .mass_kg = 1500.0});
  }
  return s;
}

History DrumsRocking(int n, double amp_rad) {
  History h;
  h.blocks = n;
  for (int i = 0; i <= 300; ++i) {
    Sample smp(n);
    smp.t_s = 0.01 * i;
    for (int k = 0; k < n; ++k) smp.theta_rad[k] = amp_rad * (k + 1) * std::sin(3.0 * smp.t_s);
    h.samples.push_back(smp);
  }
  return h;
}

TEST(ComputeLayout, ThreeAndMoreBlocksGetOneAxisPerBlockRightOfTheView) {
  for (int n : {3, 8}) {
    SCOPED_TRACE(n);
    RenderConfig cfg;
    const FrameLayout lay = ComputeLayout(
        Drums(n), {{"reference", DrumsRocking(n, 0.01)}, {"bullet", DrumsRocking(n, 0.012)}}, {},
        cfg);
    ASSERT_EQ(lay.views.size(), 1u);
    ASSERT_EQ(lay.chart_panels.size(), static_cast<size_t>(n));
    const PixelRect image{0, 0, 1280, 720};
    const PixelRect view = ViewRect(lay.views[0]);
    EXPECT_TRUE(Inside(image, view));
    EXPECT_TRUE(Disjoint(view, lay.header));
    // The chart is a column right of the view, below the header and a line for the engines'
    // legend, down to a line for the times.
    EXPECT_GE(lay.chart.x_px, view.x_px + view.w_px);
    EXPECT_TRUE(Disjoint(lay.chart, lay.header));
    EXPECT_NEAR(lay.chart.y_px, view.y_px + lay.line_px, 1e-9);
    EXPECT_NEAR(lay.chart.y_px + lay.chart.h_px, view.y_px + view.h_px - lay.line_px, 1e-9);
    // One axis per block inside it, block 1 at the bottom, block n at the top, apart, of one
    // height, sharing the time axis (the same left and right edges).
    for (int k = 0; k < n; ++k) {
      const PixelRect& p = lay.chart_panels[k];
      EXPECT_TRUE(Inside(image, p));
      EXPECT_TRUE(Inside(lay.chart, p));
      EXPECT_EQ(p.x_px, lay.chart.x_px);
      EXPECT_EQ(p.w_px, lay.chart.w_px);
      EXPECT_NEAR(p.h_px, lay.chart_panels[0].h_px, 1e-9);
      if (k > 0) {
        EXPECT_LT(p.y_px + p.h_px, lay.chart_panels[k - 1].y_px);
      }
    }
    EXPECT_NEAR(lay.chart_panels[0].y_px + lay.chart_panels[0].h_px,
                lay.chart.y_px + lay.chart.h_px, 1e-9);
    EXPECT_NEAR(lay.chart_panels[n - 1].y_px, lay.chart.y_px, 1e-9);
    // Readable at 1280x720: an axis is at least a line of text high.
    EXPECT_GE(lay.chart_panels[0].h_px, lay.line_px);
    // The shared range: just above the top block's peak, n x 0.012 rad.
    EXPECT_GE(lay.chart_theta_max_rad, 0.012 * n);
    EXPECT_LE(lay.chart_theta_max_rad, 0.012 * n * 1.6);
  }
}

TEST(ComputeLayout, TheViewFitsTheWholeColumn) {
  // The column's height grows with the number of blocks; the camera shows all of it.
  RenderConfig cfg;
  double previous_px_per_m = 1e9;
  for (int n : {1, 2, 3, 8}) {
    SCOPED_TRACE(n);
    const FrameLayout lay =
        ComputeLayout(Drums(n), {{"reference", DrumsRocking(n, 0.01)}}, {}, cfg);
    const Camera& cam = lay.views.at(0);
    const double column_m = 0.85 * n;
    EXPECT_GE(cam.world.y_max_m, column_m);
    EXPECT_LE(cam.ToPixel({0.0, column_m}).y, cam.vp_y_px + cam.vp_h_px);
    EXPECT_GE(cam.ToPixel({0.0, column_m}).y, cam.vp_y_px);
    // And no more than needed: the column (with its ground strip and margins) fills the
    // view's height.
    EXPECT_LT(cam.world.height_m(), 1.6 * column_m);
    EXPECT_LT(cam.px_per_m(), previous_px_per_m);
    previous_px_per_m = cam.px_per_m();
  }
}

TEST(ComputeLayout, SideBySideViewsOfAStackLeaveTheChartItsColumn) {
  RenderConfig cfg;
  cfg.layout = Layout::kSide;
  const FrameLayout lay = ComputeLayout(
      Drums(6), {{"reference", DrumsRocking(6, 0.01)}, {"bullet", DrumsRocking(6, 0.01)}}, {}, cfg);
  ASSERT_EQ(lay.views.size(), 2u);
  ASSERT_EQ(lay.chart_panels.size(), 6u);
  EXPECT_NEAR(lay.views[1].px_per_m(), lay.views[0].px_per_m(), 1e-9);
  EXPECT_GE(lay.views[1].vp_x_px, lay.views[0].vp_x_px + lay.views[0].vp_w_px);
  EXPECT_LE(lay.views[1].vp_x_px + lay.views[1].vp_w_px, lay.chart.x_px);
}

TEST(ComputeLayout, TooManyAxesForTheImageIsAClearError) {
  RenderConfig cfg;
  cfg.width_px = 64;
  cfg.height_px = 48;
  try {
    ComputeLayout(Drums(64), {{"reference", DrumsRocking(64, 0.001)}}, {}, cfg);
    FAIL() << "64 axes in 48 pixels must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("give a larger size"), std::string::npos) << e.what();
  }
}

TEST(ComputeLayout, OneAndTwoBlocksKeepTheChartBelowTheView) {
  const FrameLayout lay = ComputeLayout(Stack(), {{"reference", Wobble(0.05)}}, {}, RenderConfig{});
  EXPECT_TRUE(lay.chart_panels.empty());
  EXPECT_GE(lay.chart.y_px, lay.views[0].vp_y_px + lay.views[0].vp_h_px);
}

TEST(ComputeLayout, RejectsBadConfigurations) {
  const std::vector<Track> tracks = {{"reference", Wobble(0.05)}};
  RenderConfig cfg;
  cfg.supersample = 5;
  EXPECT_THROW(ComputeLayout(Stack(), tracks, {}, cfg), std::invalid_argument);
  cfg = {};
  cfg.width_px = 20;
  EXPECT_THROW(ComputeLayout(Stack(), tracks, {}, cfg), std::invalid_argument);
  cfg = {};
  cfg.t_from_s = 3.0;
  cfg.t_to_s = 1.0;
  EXPECT_THROW(ComputeLayout(Stack(), tracks, {}, cfg), std::invalid_argument);
  EXPECT_THROW(ComputeLayout(Stack(), {}, {}, RenderConfig{}), std::invalid_argument);
  EXPECT_THROW(ComputeLayout(Stack(), {{"empty", History{}}}, {}, RenderConfig{}),
               std::invalid_argument);
}

TEST(ParseLayout, KnowsOverlayAndSide) {
  EXPECT_EQ(ParseLayout("overlay"), Layout::kOverlay);
  EXPECT_EQ(ParseLayout("side"), Layout::kSide);
  EXPECT_FALSE(ParseLayout("stacked").has_value());
}

}  // namespace
}  // namespace rockbench::renders
