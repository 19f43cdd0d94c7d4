// Rendered frames checked from their pixels: colours where the geometry puts things, the tilt of
// block 2 recovered from the image, determinism, greyscale separation and a golden image.
#include "renders/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <vector>

#include "tests/common/sample.h"
#include "tests/common/stack_scene.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;

Scene Stack() {
  return testing_util::TwoBlockScene(1.25, 1.25, 3906.0, 0.5, 1.5, 1875.0);
}

// Block 2 tilted by 0.2 rad on block 1 at rest (mode 4a), held for one second.
History Tilted() {
  History h;
  h.samples = {MakeSample({.t_s = 0.0, .theta1_rad = 0.0, .theta2_rad = 0.2, .mode = Mode::k4a}),
               MakeSample({.t_s = 1.0, .theta1_rad = 0.0, .theta2_rad = 0.2, .mode = Mode::k4a})};
  return h;
}

#if ROCKBENCH_HAVE_OSMESA

int Diff(Rgb a, Rgb b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// Rec. 709 luma of an sRGB colour, 0..255.
double Luma(Rgb c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

Rgb At(const Image& img, Vec2 px) {
  return img.at(static_cast<int>(std::floor(px.x)), static_cast<int>(std::floor(px.y)));
}

class TiltedFrame : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    RenderConfig cfg;
    cfg.width_px = 640;
    cfg.height_px = 480;
    renderer_ = new FrameRenderer(Stack(), {{"reference", Tilted()}}, {}, cfg);
    image_ = new Image(renderer_->Render(0.5));
  }
  static void TearDownTestSuite() {
    delete image_;
    delete renderer_;
  }
  static FrameRenderer* renderer_;
  static Image* image_;
};
FrameRenderer* TiltedFrame::renderer_ = nullptr;
Image* TiltedFrame::image_ = nullptr;

TEST_F(TiltedFrame, CornersAreBackground) {
  const Image& img = *image_;
  const Rgb bg = renderer_->palette().background;
  EXPECT_EQ(img.at(0, 0), bg);
  EXPECT_EQ(img.at(img.width_px - 1, 0), bg);
  EXPECT_EQ(img.at(0, img.height_px - 1), bg);
  EXPECT_EQ(img.at(img.width_px - 1, img.height_px - 1), bg);
}

TEST_F(TiltedFrame, BlocksGroundAndSkyHaveTheirColoursWhereTheGeometryPutsThem) {
  const Image& img = *image_;
  const Palette& pal = renderer_->palette();
  const Camera& cam = renderer_->layout().views.at(0);
  const DrawnStack pose = PoseFor(Stack(), 0.0, 0.2);
  auto centre = [](const BlockCorners& q) {
    return Vec2{0.25 * (q[0].x + q[1].x + q[2].x + q[3].x),
                0.25 * (q[0].y + q[1].y + q[2].y + q[3].y)};
  };
  // Interior points are flat colour (edges are 1-2 px away from them).
  EXPECT_EQ(At(img, cam.ToPixel(centre(pose[0]))), pal.block(0));
  EXPECT_EQ(At(img, cam.ToPixel(centre(pose[1]))), pal.block(1));
  // Block 2's top-left corner region, 5 cm inside both edges.
  const BlockCorners& b2 = pose[1];
  const Vec2 inside{b2[3].x + 0.05 * (b2[2].x - b2[3].x) / 0.5 + 0.05 * (b2[0].x - b2[3].x) / 1.5,
                    b2[3].y + 0.05 * (b2[2].y - b2[3].y) / 0.5 + 0.05 * (b2[0].y - b2[3].y) / 1.5};
  EXPECT_EQ(At(img, cam.ToPixel(inside)), pal.block(1));
  // Just outside block 2's left edge, above block 1: sky.
  const Vec2 left_of_b2{b2[0].x - 0.1, b2[0].y + 0.3};
  EXPECT_EQ(At(img, cam.ToPixel(left_of_b2)), pal.background);
  // Ground: a quarter of the way across, three quarters of the way down the visible ground
  // (below the tick marks, which reach at most half way).
  const Box& w = cam.world;
  EXPECT_EQ(At(img, cam.ToPixel({w.x_min_m + 0.25 * w.width_m(), 0.75 * w.y_min_m})), pal.ground);
  // Sky in the view's top-left corner.
  EXPECT_EQ(At(img, cam.ToPixel({w.x_min_m + 0.05 * w.width_m(), w.y_max_m - 0.05 * w.height_m()})),
            pal.background);
}

TEST_F(TiltedFrame, Block2TiltRecoveredFromItsPixels) {
  // Principal axes of the pixels of block 2's colour inside the view: the long axis of a
  // 0.5 x 1.5 m rectangle. With ~70 px per metre, the interior has ~3000 pixels; the orientation
  // of a digitised rectangle is then good to ~0.1 degree, well inside the 0.5 degree asked for.
  const Image& img = *image_;
  const Camera& cam = renderer_->layout().views.at(0);
  const Rgb want = renderer_->palette().block(1);
  double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int y = static_cast<int>(cam.vp_y_px); y < static_cast<int>(cam.vp_y_px + cam.vp_h_px);
       ++y) {
    for (int x = static_cast<int>(cam.vp_x_px); x < static_cast<int>(cam.vp_x_px + cam.vp_w_px);
         ++x) {
      if (Diff(img.at(x, y), want) > 6) continue;
      const double cx = x + 0.5, cy = y + 0.5;
      n += 1;
      sx += cx;
      sy += cy;
      sxx += cx * cx;
      syy += cy * cy;
      sxy += cx * cy;
    }
  }
  ASSERT_GT(n, 1000);
  const double mx = sx / n, my = sy / n;
  const double mu20 = sxx / n - mx * mx, mu02 = syy / n - my * my, mu11 = sxy / n - mx * my;
  // Long-axis angle from +x in image coordinates (y down); upright is -90 degrees, and a
  // clockwise (rightward) tilt theta makes it theta - 90 degrees.
  const double phi = 0.5 * std::atan2(2 * mu11, mu20 - mu02);
  double tilt_deg = (phi + 0.5 * std::numbers::pi) * 180.0 / std::numbers::pi;
  if (tilt_deg > 90) tilt_deg -= 180;
  EXPECT_NEAR(tilt_deg, 0.2 * 180.0 / std::numbers::pi, 0.5);
  // And the pixels sit where the geometry says: pivoting about the right corner (not the left,
  // which would move the centroid ~0.1 m = ~7 px) and centred on block 1 at rest.
  const DrawnStack pose = PoseFor(Stack(), 0.0, 0.2);
  Vec2 c{};
  for (const Vec2& p : pose[1]) c = {c.x + 0.25 * p.x, c.y + 0.25 * p.y};
  const Vec2 cpx = cam.ToPixel(c);
  EXPECT_NEAR(mx, cpx.x, 1.5);
  EXPECT_NEAR(my, cpx.y, 1.5);
}

TEST_F(TiltedFrame, ColoursStayApartInGreyscale) {
  // Luma of what is drawn, sampled from the image: every pair differs by at least 25 of 255 (a
  // tenth of the range), so a greyscale print keeps background, block 2, ground and block 1
  // apart.
  const Image& img = *image_;
  const Camera& cam = renderer_->layout().views.at(0);
  const DrawnStack pose = PoseFor(Stack(), 0.0, 0.2);
  const Box& w = cam.world;
  const double l_bg = Luma(img.at(0, 0));
  const double l_b1 = Luma(At(img, cam.ToPixel({0.0, 0.6})));
  const double l_b2 = Luma(At(img, cam.ToPixel({0.5 * (pose[1][0].x + pose[1][2].x),
                                                0.5 * (pose[1][0].y + pose[1][2].y)})));
  const double l_ground =
      Luma(At(img, cam.ToPixel({w.x_min_m + 0.25 * w.width_m(), 0.75 * w.y_min_m})));
  const double l[] = {l_bg, l_b2, l_ground, l_b1};
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) EXPECT_GE(std::abs(l[i] - l[j]), 25.0) << i << " " << j;
  }
}

TEST(FrameRenderer, SameInputSameBytes) {
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  History h = Tilted();
  h.samples[1].theta_rad[0] = 0.05;
  FrameRenderer a(Stack(), {{"reference", h}}, {}, cfg);
  FrameRenderer b(Stack(), {{"reference", h}}, {}, cfg);
  const Image a1 = a.Render(0.37);
  const Image a2 = a.Render(0.37);
  const Image b1 = b.Render(0.37);
  EXPECT_EQ(a1.rgb, a2.rgb);
  EXPECT_EQ(a1.rgb, b1.rgb);
  EXPECT_EQ(EncodePng(a1), EncodePng(b1));
  // And a different time is a different picture.
  EXPECT_NE(a.Render(0.9).rgb, a1.rgb);
}

TEST(FrameRenderer, EdgesAreAntiAliased) {
  // Supersampled 2x2 and box-filtered: pixels on block 1's tilted edge take intermediate shades
  // between the block colour and the background; drawn at 1x there are none.
  History h;
  h.samples = {MakeSample({.t_s = 0.0, .theta1_rad = 0.1, .theta2_rad = 0.1, .mode = Mode::k3a})};
  auto shades = [&](int supersample) {
    RenderConfig cfg;
    cfg.width_px = 320;
    cfg.height_px = 240;
    cfg.supersample = supersample;
    cfg.show_text = false;
    cfg.show_chart = false;
    FrameRenderer r(Stack(), {{"reference", h}}, {}, cfg);
    const Image img = r.Render(0.0);
    const Palette& pal = r.palette();
    int mixed = 0;
    for (int y = 0; y < img.height_px; ++y) {
      for (int x = 0; x < img.width_px; ++x) {
        const Rgb c = img.at(x, y);
        bool known = false;
        for (Rgb k : {pal.background, pal.block(0), pal.block(1), pal.ground, pal.ground_line,
                      pal.outline}) {
          known = known || c == k;
        }
        mixed += known ? 0 : 1;
      }
    }
    return mixed;
  };
  EXPECT_EQ(shades(1), 0);
  EXPECT_GT(shades(2), 200);
}

TEST(FrameRenderer, SingleBlockScene) {
  Scene s = Stack();
  s.blocks.resize(1);
  History h;
  h.blocks = 1;
  h.samples = {MakeSample({.t_s = 0.0, .theta1_rad = -0.15, .mode = Mode::k3b, .blocks = 1})};
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  FrameRenderer r(s, {{"reference", h}}, {}, cfg);
  const Image img = r.Render(0.0);
  const Camera& cam = r.layout().views.at(0);
  const DrawnStack pose = PoseFor(s, -0.15, 0.0);
  EXPECT_EQ(At(img, cam.ToPixel({0.5 * (pose[0][0].x + pose[0][2].x),
                                 0.5 * (pose[0][0].y + pose[0][2].y)})),
            r.palette().block(0));
  // Nothing of block 2's colour anywhere in the view.
  for (int y = static_cast<int>(cam.vp_y_px); y < static_cast<int>(cam.vp_y_px + cam.vp_h_px);
       ++y) {
    for (int x = static_cast<int>(cam.vp_x_px); x < static_cast<int>(cam.vp_x_px + cam.vp_w_px);
         ++x) {
      ASSERT_GT(Diff(img.at(x, y), r.palette().block(1)), 20) << x << "," << y;
    }
  }
}

TEST(FrameRenderer, BaseDisplacementMovesTheBlocks) {
  History h = Tilted();
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  cfg.show_text = false;
  const auto base = BaseDisplacement::FromFunction([](double t) { return Vec2{0.4 * t, 0.0}; });
  FrameRenderer r(Stack(), {{"reference", h}}, base, cfg);
  const Camera& cam = r.layout().views.at(0);
  const Image img = r.Render(1.0);
  // Block 1's centre is 0.4 m to the right of where it starts.
  EXPECT_EQ(At(img, cam.ToPixel({0.4, 0.6})), r.palette().block(0));
  EXPECT_NE(At(img, cam.ToPixel({-0.55, 0.6})), r.palette().block(0));
}

TEST(FrameRenderer, MissingFontIsAClearError) {
  RenderConfig cfg;
  cfg.font_path = "/nonexistent/font.ttf";
  try {
    FrameRenderer r(Stack(), {{"reference", Tilted()}}, {}, cfg);
    FAIL() << "a missing font must throw";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/font.ttf"), std::string::npos) << e.what();
  }
}

// The look, guarded by a golden image: an overlay of two engines with text and chart.
// ROCKBENCH_UPDATE_GOLDEN=1 rewrites it. Tolerance: identical on the machine that made it; 16
// levels per channel and 0.5% of pixels beyond that allow other Mesa/FreeType versions to
// rasterise edges and hint glyphs a little differently, while any change of colour, layout or
// geometry alters thousands of pixels.
TEST(FrameRenderer, GoldenImage) {
  Scene s = Stack();
  History ref, other;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.01 * i;
    ref.samples.push_back(
        MakeSample({.t_s = t,
                    .theta1_rad = 0.08 * std::sin(2.0 * t),
                    .theta2_rad = 0.08 * std::sin(2.0 * t) + 0.12 * std::sin(3.0 * t),
                    .mode = Mode::k1a}));
    other.samples.push_back(
        MakeSample({.t_s = t,
                    .theta1_rad = 0.06 * std::sin(2.1 * t),
                    .theta2_rad = 0.06 * std::sin(2.1 * t) + 0.15 * std::sin(3.1 * t),
                    .mode = Mode::k2a}));
  }
  RenderConfig cfg;
  cfg.width_px = 320;
  cfg.height_px = 240;
  cfg.title = "golden";
  const auto base = BaseDisplacement::FromFunction([](double t) {
    return Vec2{0.1 * std::sin(t), 0.0};
  });
  FrameRenderer r(s, {{"reference", ref}, {"engine", other}}, base, cfg);
  const Image img = r.Render(1.7);
  const auto golden =
      std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "tests/renders/golden/overlay_320x240.png";
  const char* update = std::getenv("ROCKBENCH_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    WritePng(img, golden, PngConfig{.compression_level = 9});
    GTEST_SKIP() << "golden image rewritten: " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden))
      << golden << " is missing; run with ROCKBENCH_UPDATE_GOLDEN=1 to make it";
  const Image want = ReadPng(golden);
  ASSERT_EQ(want.width_px, img.width_px);
  ASSERT_EQ(want.height_px, img.height_px);
  int beyond = 0, worst = 0;
  for (int y = 0; y < img.height_px; ++y) {
    for (int x = 0; x < img.width_px; ++x) {
      const int d = Diff(img.at(x, y), want.at(x, y));
      worst = std::max(worst, d);
      beyond += d > 16 ? 1 : 0;
    }
  }
  EXPECT_LE(beyond, img.width_px * img.height_px / 200)
      << "worst channel difference " << worst << "; if the change is intended, run with "
      << "ROCKBENCH_UPDATE_GOLDEN=1 and look at " << golden;
}

// A column of n drums, 0.9 m wide and 0.85 m high.
Scene Drums(int n) {
  Scene s;
  for (int k = 0; k < n; ++k) {
    s.blocks.push_back(BlockDef{.width_m = 0.9, .height_m = 0.85, .mass_kg = 1721.25});
  }
  return s;
}

// The column tilted right by theta as one rigid body (every block at theta, locked: mode
// "rff...f"), held for a second.
History TiltedColumn(int n, double theta_rad) {
  History h;
  h.blocks = n;
  for (double t : {0.0, 1.0}) {
    Sample s(n);
    s.t_s = t;
    for (int k = 0; k < n; ++k) s.theta_rad[k] = theta_rad;
    s.mode.set(0, Contact::kRight);
    h.samples.push_back(s);
  }
  return h;
}

// A tilted column of 3 and of 8 blocks at 640x480, text and chart on: the pixels show every
// block in its colour where the chain puts it, the whole column in view, and one chart axis per
// block.
class ColumnFrame : public ::testing::TestWithParam<int> {
 protected:
  static constexpr double kTheta = 0.08;
  void SetUp() override {
    n_ = GetParam();
    RenderConfig cfg;
    cfg.width_px = 640;
    cfg.height_px = 480;
    renderer_ = std::make_unique<FrameRenderer>(
        Drums(n_), std::vector<Track>{{"reference", TiltedColumn(n_, kTheta)}}, BaseDisplacement{},
        cfg);
    image_ = renderer_->Render(0.5);
  }
  // A corner of the column tilted rigidly about block 1's right base corner (0.45, 0): its
  // position at rest turned clockwise by kTheta (an independent form of the chain for a locked
  // column).
  static Vec2 Tilted(Vec2 rest) {
    const double dx = rest.x - 0.45, dy = rest.y;
    return {0.45 + std::cos(kTheta) * dx + std::sin(kTheta) * dy,
            -std::sin(kTheta) * dx + std::cos(kTheta) * dy};
  }
  int n_ = 0;
  std::unique_ptr<FrameRenderer> renderer_;
  Image image_;
};

TEST_P(ColumnFrame, TheWholeColumnIsInViewAndAsTallAsProjected) {
  const Camera& cam = renderer_->layout().views.at(0);
  const Rgb bg = renderer_->palette().background;
  // The topmost row of the view with anything drawn on it (the outlines are near-black).
  int top_row = -1;
  for (int y = static_cast<int>(cam.vp_y_px); y < cam.vp_y_px + cam.vp_h_px && top_row < 0; ++y) {
    for (int x = static_cast<int>(cam.vp_x_px); x < cam.vp_x_px + cam.vp_w_px; ++x) {
      if (Diff(image_.at(x, y), bg) > 24) {
        top_row = y;
        break;
      }
    }
  }
  ASSERT_GE(top_row, 0);
  // The column's highest point is its top-left corner, turned about (0.45, 0).
  const Vec2 top = Tilted({-0.45, 0.85 * n_});
  const double ground_px = cam.ToPixel({0.0, 0.0}).y;
  const double want_px = ground_px - cam.ToPixel(top).y;
  EXPECT_NEAR(ground_px - top_row, want_px, 1.5);
  // In view with room to spare, and framed tightly: the column fills most of the view's height.
  EXPECT_GT(top_row, cam.vp_y_px);
  EXPECT_GT(want_px, 0.6 * cam.vp_h_px);
}

TEST_P(ColumnFrame, EveryBlockHasItsOwnColourWhereTheChainPutsIt) {
  const Camera& cam = renderer_->layout().views.at(0);
  const Palette& pal = renderer_->palette();
  for (int k = 0; k < n_; ++k) {
    SCOPED_TRACE(k + 1);
    // Its middle, at rest (0, 0.85 (k + 1/2)), tilted with the column.
    EXPECT_EQ(At(image_, cam.ToPixel(Tilted({0.0, 0.85 * (k + 0.5)}))), pal.block(k));
    for (int j = 0; j < k; ++j) EXPECT_GE(Diff(pal.block(j), pal.block(k)), 40) << j + 1;
    // Most of its area (0.9 x 0.85 m, less the outline) is of its colour.
    int count = 0;
    for (int y = static_cast<int>(cam.vp_y_px); y < cam.vp_y_px + cam.vp_h_px; ++y) {
      for (int x = static_cast<int>(cam.vp_x_px); x < cam.vp_x_px + cam.vp_w_px; ++x) {
        count += image_.at(x, y) == pal.block(k) ? 1 : 0;
      }
    }
    const double area_px = 0.9 * 0.85 * cam.px_per_m() * cam.px_per_m();
    EXPECT_GT(count, 0.6 * area_px);
    EXPECT_LT(count, 1.05 * area_px);
  }
}

TEST_P(ColumnFrame, TheTopBlocksCornerIsWhereTheChainPutsIt) {
  const Camera& cam = renderer_->layout().views.at(0);
  const Palette& pal = renderer_->palette();
  // Block n's top-right corner, and its middle, from the rigid turn; and the same from the
  // renders' chain.
  const Vec2 corner = Tilted({0.45, 0.85 * n_});
  const Vec2 middle = Tilted({0.0, 0.85 * (n_ - 0.5)});
  const DrawnStack pose = PoseFor(Drums(n_), StackState(TiltedColumn(n_, kTheta).samples[0]));
  ASSERT_EQ(pose.size(), static_cast<size_t>(n_));
  EXPECT_NEAR(pose.back()[2].x, corner.x, 1e-12);
  EXPECT_NEAR(pose.back()[2].y, corner.y, 1e-12);
  // In the image: 4 px inside the corner along the diagonal, block n's colour; 3 px outside
  // it, the background.
  const Vec2 c = cam.ToPixel(corner), m = cam.ToPixel(middle);
  const double len = std::hypot(m.x - c.x, m.y - c.y);
  const Vec2 in{c.x + 4.0 * (m.x - c.x) / len, c.y + 4.0 * (m.y - c.y) / len};
  const Vec2 out{c.x - 3.0 * (m.x - c.x) / len, c.y - 3.0 * (m.y - c.y) / len};
  EXPECT_EQ(At(image_, in), pal.block(n_ - 1));
  EXPECT_EQ(At(image_, out), pal.background);
}

TEST_P(ColumnFrame, TheChartHasOneAxisPerBlockWithItsTrace) {
  const FrameLayout& lay = renderer_->layout();
  const Palette& pal = renderer_->palette();
  ASSERT_EQ(lay.chart_panels.size(), static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) {
    SCOPED_TRACE(k + 1);
    const PixelRect& r = lay.chart_panels[k];
    // The trace: a flat line at +kTheta from 0 s to the cursor at 0.5 s (half the axis), in
    // block k's trace colour.
    int in_colour = 0, other = 0;
    for (int y = static_cast<int>(r.y_px) + 1; y < r.y_px + r.h_px - 1; ++y) {
      for (int x = static_cast<int>(r.x_px) + 1; x < r.x_px + r.w_px - 1; ++x) {
        const Rgb p = image_.at(x, y);
        if (Diff(p, pal.chart_theta(k)) <= 8) ++in_colour;
        for (int j = 0; j < n_; ++j) {
          if (j != k && Diff(pal.chart_theta(j), pal.chart_theta(k)) > 40 &&
              Diff(p, pal.chart_theta(j)) <= 8) {
            ++other;
          }
        }
      }
    }
    EXPECT_GT(in_colour, 0.45 * r.w_px);
    EXPECT_EQ(other, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(ThreeAndEightBlocks, ColumnFrame, ::testing::Values(3, 8));

#else

TEST(FrameRenderer, SaysThisBuildHasNoOsmesa) {
  try {
    FrameRenderer r(Stack(), {{"reference", Tilted()}}, {}, RenderConfig{});
    FAIL() << "rendering without OSMesa must throw";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("no OSMesa"), std::string::npos) << e.what();
  }
}

#endif

}  // namespace
}  // namespace rockbench::renders
