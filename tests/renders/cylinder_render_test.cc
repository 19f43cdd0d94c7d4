// A cylinder's frames (renders/cylinder/cylinder_scene.h, cylinder_painter.cc) checked from their pixels
// and from the layout: the cylinder is where its lean puts it, the base plane moves with the
// transverse displacement, the top view's point is where tilt_x and tilt_y put it, the azimuth
// and the spin each change the picture, the camera keeps every pose in view, and the same input
// gives the same bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "renders/cylinder/cylinder_scene.h"
#include "renders/renderer.h"
#include "scene/body_kind.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::renders {
namespace {

constexpr double kPi = std::numbers::pi;

// The shipped free-wobbling cylinder: D = 0.5 m, H = 1.5 m.
Scene CylinderScene() {
  return LoadScene(std::string(ROCKBENCH_SOURCE_DIR) +
                   "/scenes/three_d/cylinder_free_wobbling.toml");
}

// One row of a cylinder history: tilt, azimuth and spin (rad) at t_s, on its rim unless the tilt
// is 0; the tilt vector from the tilt and azimuth, as docs/three-d.md defines it.
struct Row {
  double t_s, tilt_rad, azimuth_rad, spin_rad = 0.0;
};
History CylinderHistory(const std::vector<Row>& rows) {
  const BodyKind& kind = CylinderKind();
  History h;
  h.blocks = 1;
  h.shape = kind.shape;
  auto index = [&](const std::string& stem) {
    for (size_t i = 0; i < kind.state.size(); ++i) {
      if (kind.state[i].stem == stem) return i;
    }
    throw std::logic_error("no quantity " + stem);
  };
  for (const Row& r : rows) {
    Sample s(1, kind);
    s.t_s = r.t_s;
    s.state[index("tilt")][0] = r.tilt_rad;
    s.state[index("azimuth")][0] = r.azimuth_rad;
    s.state[index("spin")][0] = r.spin_rad;
    s.state[index("tilt_x")][0] = r.tilt_rad * std::cos(r.azimuth_rad);
    s.state[index("tilt_y")][0] = r.tilt_rad * std::sin(r.azimuth_rad);
    s.mode.set(0, r.tilt_rad > 0.0 ? Contact::kRight : Contact::kFace);
    h.samples.push_back(s);
  }
  return h;
}

TEST(CylinderStateAt, InterpolatesTheTiltVectorAndHoldsTheEnds) {
  // From tilt 0.1 at azimuth 0 to tilt 0.1 at azimuth 0.2: halfway the tilt vector is the mean
  // of the two, of length 0.1 cos(0.1) pointing at azimuth 0.1 (a chord of the circle).
  const History h = CylinderHistory({{0.0, 0.1, 0.0, 0.0}, {1.0, 0.1, 0.2, 0.4}});
  const CylinderAt mid = CylinderStateAt(h, 0.5);
  EXPECT_NEAR(mid.state.tilt_rad, 0.1 * std::cos(0.1), 1e-15);
  EXPECT_NEAR(mid.state.azimuth_rad, 0.1, 1e-14);
  // The heading azimuth + spin goes from 0 to 0.6: 0.3 halfway, the spin 0.3 - 0.1.
  EXPECT_NEAR(mid.state.spin_rad, 0.2, 1e-14);
  EXPECT_TRUE(mid.on_rim);
  EXPECT_EQ(mid.mode, "rim");
  // Held before the first and after the last sample.
  EXPECT_DOUBLE_EQ(CylinderStateAt(h, -1.0).state.azimuth_rad, 0.0);
  EXPECT_DOUBLE_EQ(CylinderStateAt(h, 5.0).state.azimuth_rad, 0.2);
  // An azimuth unwrapped by the history (engines keep it continuous) stays continuous.
  const History turns = CylinderHistory({{0.0, 0.1, 20.0}, {1.0, 0.1, 20.2}});
  EXPECT_NEAR(CylinderStateAt(turns, 0.5).state.azimuth_rad, 20.1, 1e-12);
}

TEST(CylinderStateAt, RefusesAPlanarHistory) {
  History planar;
  planar.blocks = 1;
  planar.samples.push_back(Sample(1));
  EXPECT_THROW(CylinderStateAt(planar, 0.0), std::invalid_argument);
}

TEST(CylinderLayout, APlanarSceneHasNoPerspectiveView) {
  Scene planar;
  planar.blocks.push_back({.width_m = 0.5, .height_m = 1.5, .mass_kg = 100.0});
  History h;
  h.blocks = 1;
  h.samples = {Sample(1)};
  const FrameLayout lay = ComputeLayout(planar, {{"reference", h}}, {}, RenderConfig{});
  EXPECT_TRUE(lay.perspective_views.empty());
  EXPECT_FALSE(lay.has_top_view);
  EXPECT_EQ(lay.views.size(), 1u);
}

// The centre of a cylinder of radius R and half-height h leaning at `tilt` toward `azimuth` on
// the rim point (R cos azimuth, R sin azimuth, 0), written here from the geometry: the axis is
// (sin tilt cos azimuth, sin tilt sin azimuth, cos tilt), and from the contact point the centre
// is R back toward the axis's foot along the tilted bottom face, then h up the axis.
Vec3d IndependentCentre(double tilt, double azimuth, double R, double h) {
  const double ct = std::cos(tilt), st = std::sin(tilt), cp = std::cos(azimuth),
               sp = std::sin(azimuth);
  // Down-slope direction in the bottom face: (cos tilt cos az, cos tilt sin az, -sin tilt).
  return {R * cp - R * ct * cp + h * st * cp, R * sp - R * ct * sp + h * st * sp, R * st + h * ct};
}

TEST(CylinderLayout, TheCameraKeepsEveryPoseOfTheWindowInView) {
  // A fall from 0.4 rad toward azimuth 2 to 1.5 rad, turning a little.
  std::vector<Row> rows;
  for (int k = 0; k <= 100; ++k) rows.push_back({k * 0.01, 0.4 + 0.011 * k, 2.0 + 0.002 * k});
  const History h = CylinderHistory(rows);
  RenderConfig cfg;
  cfg.width_px = 640;
  cfg.height_px = 360;
  const Scene scene = CylinderScene();
  const FrameLayout lay = ComputeLayout(scene, {{"reference", h}}, {}, cfg);
  ASSERT_EQ(lay.perspective_views.size(), 1u);
  const PerspectiveCamera& cam = lay.perspective_views[0];
  const double R = 0.25, hh = 0.75;
  for (const Row& r : rows) {
    // The rim points from the centre and the rotation of scene/cylinder_state.h's ZYZ angles.
    const Vec3d c = IndependentCentre(r.tilt_rad, r.azimuth_rad, R, hh);
    const Mat3d q = CylinderRotation({.tilt_rad = r.tilt_rad, .azimuth_rad = r.azimuth_rad});
    for (int k = 0; k < 16; ++k) {
      for (double z : {-hh, hh}) {
        const Vec3d b{R * std::cos(k * kPi / 8), R * std::sin(k * kPi / 8), z};
        const Vec3d p{c[0] + q[0] * b[0] + q[1] * b[1] + q[2] * b[2],
                      c[1] + q[3] * b[0] + q[4] * b[1] + q[5] * b[2],
                      c[2] + q[6] * b[0] + q[7] * b[1] + q[8] * b[2]};
        ASSERT_GT(cam.Depth_m(p), 0.0);
        const Vec2 px = cam.ToPixel(p);
        EXPECT_GE(px.x, cam.vp_x_px) << r.t_s;
        EXPECT_LE(px.x, cam.vp_x_px + cam.vp_w_px) << r.t_s;
        EXPECT_GE(px.y, cam.vp_y_px) << r.t_s;
        EXPECT_LE(px.y, cam.vp_y_px + cam.vp_h_px) << r.t_s;
      }
    }
  }
  // The top view spans the peak tilt (1.5 rad) and the perspective view is left of it.
  EXPECT_TRUE(lay.has_top_view);
  EXPECT_GE(lay.top_view_range_rad, 1.5);
  EXPECT_NEAR(lay.top_view.w_px, lay.top_view.h_px, 1e-9);
  EXPECT_LT(cam.vp_x_px + cam.vp_w_px, lay.top_view.x_px);
}

#if ROCKBENCH_HAVE_OSMESA

// The reference's fill (dark blue, shaded from half to full brightness) and its arrow and axis
// (the same blue): blue clearly above red and green. The base plane, background and text are
// grey (r = g = b within 6), the stripe orange.
bool IsCylinderBlue(Rgb c) {
  return c.b > c.r + 30 && c.b > c.g + 20;
}

struct Centroid {
  double x = 0.0, y = 0.0;
  long n = 0;
};
Centroid BlueCentroid(const Image& img, const PerspectiveCamera& cam) {
  Centroid c;
  for (int y = static_cast<int>(cam.vp_y_px); y < static_cast<int>(cam.vp_y_px + cam.vp_h_px);
       ++y) {
    for (int x = static_cast<int>(cam.vp_x_px); x < static_cast<int>(cam.vp_x_px + cam.vp_w_px);
         ++x) {
      if (!IsCylinderBlue(img.at(x, y))) continue;
      c.x += x + 0.5;
      c.y += y + 0.5;
      ++c.n;
    }
  }
  if (c.n > 0) {
    c.x /= c.n;
    c.y /= c.n;
  }
  return c;
}

RenderConfig SmallConfig() {
  RenderConfig cfg;
  cfg.width_px = 640;
  cfg.height_px = 360;
  return cfg;
}

TEST(CylinderFrame, TheCylinderLeansTowardItsTiltXInTheImage) {
  // 0.3 rad toward +x for a second, then toward -x (azimuth pi).
  const History h =
      CylinderHistory({{0.0, 0.3, 0.0}, {1.0, 0.3, 0.0}, {1.0, 0.3, kPi}, {2.0, 0.3, kPi}});
  FrameRenderer r(CylinderScene(), {{"reference", h}}, {}, SmallConfig());
  const PerspectiveCamera& cam = r.layout().perspective_views.at(0);
  const Centroid plus = BlueCentroid(r.Render(0.5), cam);
  const Centroid minus = BlueCentroid(r.Render(1.5), cam);
  ASSERT_GT(plus.n, 500);
  ASSERT_GT(minus.n, 500);
  // The camera looks from the -y side (azimuth -70 degrees): +x runs to the right of the image.
  // The centres 2 (h sin 0.3 - R (1 - cos 0.3)) = 0.42 m apart; the blue's centroid (side,
  // faces, arrow) moves the same way by at least a third of the centres' projected distance.
  const double R = 0.25, hh = 0.75;
  const double projected = cam.ToPixel(IndependentCentre(0.3, 0.0, R, hh)).x -
                           cam.ToPixel(IndependentCentre(0.3, kPi, R, hh)).x;
  EXPECT_GT(projected, 20.0);
  EXPECT_GT(plus.x - minus.x, projected / 3.0) << plus.x << " " << minus.x;
}

TEST(CylinderFrame, TheBasePlaneMovesWithTheTransverseDisplacement) {
  // Upright, the base still until t = 1 and then 0.4 m along +y: +y runs away from the camera,
  // up the image.
  const History h = CylinderHistory({{0.0, 0.0, 0.0}, {2.0, 0.0, 0.0}});
  BaseDisplacement base = BaseDisplacement::FromFunction([](double) { return Vec2{}; });
  base.SetTransverse([](double t) { return t < 1.0 ? 0.0 : 0.4; });
  FrameRenderer r(CylinderScene(), {{"reference", h}}, base, SmallConfig());
  const PerspectiveCamera& cam = r.layout().perspective_views.at(0);
  const Centroid still = BlueCentroid(r.Render(0.5), cam);
  const Centroid moved = BlueCentroid(r.Render(1.5), cam);
  ASSERT_GT(still.n, 500);
  EXPECT_LT(moved.y, still.y - 5.0) << still.y << " " << moved.y;
  // The cylinder's foot is where the projection of (0, 0.4, 0) puts it: the base shift reaches
  // the pose.
  EXPECT_NEAR(moved.y - still.y, cam.ToPixel({0.0, 0.4, 0.75}).y - cam.ToPixel({0.0, 0.0, 0.75}).y,
              6.0);
}

TEST(CylinderFrame, TheTopViewPointIsWhereTiltXAndTiltYPutIt) {
  // Constant at tilt 0.2 toward azimuth 2.5: tilt_x = -0.160, tilt_y = +0.120.
  const double tilt = 0.2, az = 2.5;
  const History h = CylinderHistory({{0.0, tilt, az}, {1.0, tilt, az}});
  FrameRenderer r(CylinderScene(), {{"reference", h}}, {}, SmallConfig());
  const FrameLayout& lay = r.layout();
  ASSERT_TRUE(lay.has_top_view);
  const Image img = r.Render(0.5);
  const PixelRect& p = lay.top_view;
  const double range = lay.top_view_range_rad;
  EXPECT_GE(range, tilt);
  // tilt_x to the right, tilt_y up, the same scale on both, 0 at the middle.
  auto pixel = [&](double tx, double ty) {
    return img.at(static_cast<int>(std::floor(p.x_px + 0.5 * p.w_px + tx / range * 0.5 * p.w_px)),
                  static_cast<int>(std::floor(p.y_px + 0.5 * p.h_px - ty / range * 0.5 * p.h_px)));
  };
  const double tx = tilt * std::cos(az), ty = tilt * std::sin(az);
  const Rgb trace = r.palette().chart_theta(0);
  EXPECT_EQ(pixel(tx, ty), trace);
  // Its mirror images hold no point: the background.
  EXPECT_EQ(pixel(-tx, ty), r.palette().chart_background);
  EXPECT_EQ(pixel(tx, -ty), r.palette().chart_background);
}

// Pixels that differ between two frames inside a rectangle.
long DifferingPixels(const Image& a, const Image& b, double x0, double y0, double w, double h) {
  long n = 0;
  for (int y = static_cast<int>(y0); y < static_cast<int>(y0 + h); ++y) {
    for (int x = static_cast<int>(x0); x < static_cast<int>(x0 + w); ++x) {
      n += a.at(x, y) == b.at(x, y) ? 0 : 1;
    }
  }
  return n;
}

TEST(CylinderFrame, TheAzimuthAloneAndTheSpinAloneChangeThePicture) {
  // One camera for all three poses: a single history, each pose held for a second.
  const History h = CylinderHistory({{0.0, 0.2, 0.0, 0.0},
                                     {1.0, 0.2, 0.0, 0.0},
                                     {1.0, 0.2, 1.0, -1.0},
                                     {2.0, 0.2, 1.0, -1.0},
                                     {2.0, 0.2, 0.0, 1.5},
                                     {3.0, 0.2, 0.0, 1.5}});
  FrameRenderer r(CylinderScene(), {{"reference", h}}, {}, SmallConfig());
  const PerspectiveCamera& cam = r.layout().perspective_views.at(0);
  const Image base = r.Render(0.5), turned = r.Render(1.5), spun = r.Render(2.5);
  // The azimuth from 0 to 1 rad (the heading azimuth + spin kept): the lean turns.
  EXPECT_GT(DifferingPixels(base, turned, cam.vp_x_px, cam.vp_y_px, cam.vp_w_px, cam.vp_h_px), 300);
  // The spin alone (tilt and azimuth kept): only the stripe and the top face's radius move.
  EXPECT_GT(DifferingPixels(base, spun, cam.vp_x_px, cam.vp_y_px, cam.vp_w_px, cam.vp_h_px), 30);
  // Same lean, so the silhouette's blue centroid moves by less than a pixel or two.
  const Centroid a = BlueCentroid(base, cam), b = BlueCentroid(spun, cam);
  EXPECT_NEAR(a.x, b.x, 2.0);
}

TEST(CylinderFrame, SameInputSameBytes) {
  const History ref = CylinderHistory({{0.0, 0.05, 0.3, 0.0}, {1.0, 0.15, 1.3, 0.5}});
  const History other = CylinderHistory({{0.0, 0.06, 0.2, 0.0}, {1.0, 0.12, 1.0, 0.3}});
  BaseDisplacement base = BaseDisplacement::FromFunction([](double t) {
    return Vec2{0.1 * t, 0.0};
  });
  base.SetTransverse([](double t) { return -0.05 * t; });
  for (Layout layout : {Layout::kOverlay, Layout::kSide}) {
    RenderConfig cfg = SmallConfig();
    cfg.layout = layout;
    cfg.title = "a cylinder";
    FrameRenderer a(CylinderScene(), {{"reference", ref}, {"bullet", other}}, base, cfg);
    FrameRenderer b(CylinderScene(), {{"reference", ref}, {"bullet", other}}, base, cfg);
    const Image a1 = a.Render(0.37);
    EXPECT_EQ(a1.rgb, a.Render(0.37).rgb);
    EXPECT_EQ(a1.rgb, b.Render(0.37).rgb);
    EXPECT_NE(a1.rgb, a.Render(0.9).rgb);
  }
}

#endif

}  // namespace
}  // namespace rockbench::renders
