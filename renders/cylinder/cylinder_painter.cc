// A cylinder scene's frames: the points are projected by the layout's PerspectiveCamera and
// drawn in final-image pixel coordinates (the planar renderer's projection); the cylinder is
// convex, so drawing the faces that face the camera, in any order, hides what it should.
#include "renders/cylinder/cylinder_painter.h"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "renders/frame_parts.h"
#include "renders/gl_draw.h"
#include "util/format.h"

namespace rockbench::renders {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The base plane, its grid and the light (world, unit: from the upper front left).
constexpr Rgb kPlane{214, 214, 208};
constexpr Rgb kPlaneGrid{172, 172, 166};
const Vec3d kLight{-0.42, -0.50, 0.757};

// `c` lit by a surface of unit normal n: half ambient, half diffuse.
Rgb Shaded(Rgb c, const Vec3d& n) {
  const double d = std::max(0.0, n[0] * kLight[0] + n[1] * kLight[1] + n[2] * kLight[2]);
  const double f = 0.5 + 0.5 * d;
  auto ch = [&](uint8_t v) { return static_cast<uint8_t>(std::lround(std::min(255.0, v * f))); };
  return {ch(c.r), ch(c.g), ch(c.b)};
}

// `c` moved toward white by `frac`.
Rgb Lighter(Rgb c, double frac) {
  auto ch = [&](uint8_t v) { return static_cast<uint8_t>(std::lround(v + frac * (255.0 - v))); };
  return {ch(c.r), ch(c.g), ch(c.b)};
}

void Vertex(const PerspectiveCamera& cam, const Vec3d& p) {
  const Vec2 q = cam.ToPixel(p);
  glVertex2d(q.x, q.y);
}

Vec3d Plus(const Vec3d& a, const Vec3d& b, double s = 1.0) {
  return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}

std::string TiltText(const CylinderAt& at) {
  return "tilt " + Format("%.4f", at.state.tilt_rad) + " rad   azimuth " +
         Format("%+.3f", WrappedAzimuth_rad(at.state.azimuth_rad)) + " rad";
}

}  // namespace

CylinderPainter::CylinderPainter(const Scene& scene, const std::vector<Track>& tracks,
                                 const BaseDisplacement& base, const RenderConfig& config,
                                 const FrameLayout& layout, const Palette& palette)
    : scene_(scene),
      tracks_(tracks),
      base_(base),
      config_(config),
      layout_(layout),
      palette_(palette),
      size_(CylinderSizeOf(scene)) {}

Rgb CylinderPainter::TrackColour(const Palette& palette, size_t i) {
  return i == 0 ? palette.chart_theta(0) : OverlayOutline(i);
}

double CylinderPainter::line_w() const {
  return LineWidth_px(config_);
}

Vec3d CylinderPainter::BaseAt(double t_s) const {
  return config_.show_base_motion ? BaseShift(base_, t_s) : Vec3d{0.0, 0.0, 0.0};
}

void CylinderPainter::DrawGround(const PerspectiveCamera& cam, double t_s) const {
  const Vec3d b = BaseAt(t_s);
  const double g = layout_.ground_half_side_m;
  const int s = config_.supersample;
  auto at = [&](double x, double y) { return Vec3d{b[0] + x, b[1] + y, b[2]}; };
  // The plane's square, filled (GL_QUADS) or its edge (GL_LINE_LOOP).
  auto square = [&](GLenum mode) {
    glBegin(mode);
    Vertex(cam, at(-g, -g));
    Vertex(cam, at(g, -g));
    Vertex(cam, at(g, g));
    Vertex(cam, at(-g, g));
    glEnd();
  };
  Colour(kPlane);
  square(GL_QUADS);
  // A grid fixed to the plane (it moves with the base), its middle lines darker.
  const double step = NiceStep(2.0 * g / 8.0);
  const long k_max = static_cast<long>(std::floor(g / step + 1e-9));
  glLineWidth(static_cast<float>(line_w() * s));
  glBegin(GL_LINES);
  for (long k = -k_max; k <= k_max; ++k) {
    Colour(k == 0 ? palette_.ground : kPlaneGrid);
    const double u = static_cast<double>(k) * step;
    Vertex(cam, at(u, -g));
    Vertex(cam, at(u, g));
    Vertex(cam, at(-g, u));
    Vertex(cam, at(g, u));
  }
  glEnd();
  glLineWidth(static_cast<float>(1.5 * line_w() * s));
  Colour(palette_.ground_line);
  square(GL_LINE_LOOP);
  // A fixed mark in front of the plane's near edge at rest: the plane moves past it.
  glBegin(GL_TRIANGLES);
  glVertex2d(cam.ToPixel({0.0, -1.04 * g, 0.0}).x, cam.ToPixel({0.0, -1.04 * g, 0.0}).y);
  Vertex(cam, {-0.05 * g, -1.14 * g, 0.0});
  Vertex(cam, {0.05 * g, -1.14 * g, 0.0});
  glEnd();
}

void CylinderPainter::DrawArrow(const PerspectiveCamera& cam, const CylinderAt& at,
                                const Vec3d& base, Rgb colour) const {
  if (!(at.state.tilt_rad > 0.0)) return;
  const double r = size_.radius_m;
  const CylinderPose pose = PoseOfCylinder(at.state, size_, base);
  const Vec3d foot = pose.Point(0.0, -1.0, 0.0);
  const double ux = std::cos(at.state.azimuth_rad), uy = std::sin(at.state.azimuth_rad);
  // On the base plane, from under the bottom face's centre to 1.6 radii beyond its rim.
  auto p = [&](double along, double across) {
    return Vec3d{foot[0] + along * ux - across * uy, foot[1] + along * uy + across * ux, base[2]};
  };
  const double length = 2.6 * r, head = 0.5 * r;
  Colour(colour);
  glBegin(GL_QUADS);
  Vertex(cam, p(0.0, -0.06 * r));
  Vertex(cam, p(length - head, -0.06 * r));
  Vertex(cam, p(length - head, 0.06 * r));
  Vertex(cam, p(0.0, 0.06 * r));
  glEnd();
  glBegin(GL_TRIANGLES);
  Vertex(cam, p(length, 0.0));
  Vertex(cam, p(length - head, -0.22 * r));
  Vertex(cam, p(length - head, 0.22 * r));
  glEnd();
}

void CylinderPainter::DrawCylinder(const PerspectiveCamera& cam, const CylinderPose& pose,
                                   bool solid, Rgb edge) const {
  const int n = kCylinderSides;
  const int s = config_.supersample;
  const Rgb fill = palette_.block(0);
  const Rgb stripe = palette_.block(1);
  const double alpha = solid ? 1.0 : 0.3;
  auto angle = [&](int k) { return 2.0 * kPi * k / n; };
  auto radial = [&](double a) { return pose.Direction({std::cos(a), std::sin(a), 0.0}); };
  std::vector<bool> front(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double mid = 0.5 * (angle(k) + angle(k + 1));
    front[k] = cam.Faces(pose.Point(mid, 0.0), radial(mid));
  }
  const Vec3d axis = pose.Axis();
  const bool top = cam.Faces(pose.Point(0.0, 1.0, 0.0), axis);
  const bool bottom = cam.Faces(pose.Point(0.0, -1.0, 0.0), {-axis[0], -axis[1], -axis[2]});
  if (!solid) glEnable(GL_BLEND);
  // The side, lit per vertex (smooth between the prism's edges).
  glBegin(GL_QUADS);
  for (int k = 0; k < n; ++k) {
    if (!front[k]) continue;
    // Bottom and top at angle k, then top and bottom at angle k + 1.
    const double a0 = angle(k), a1 = angle(k + 1);
    Colour(Shaded(fill, radial(a0)), alpha);
    Vertex(cam, pose.Point(a0, -1.0));
    Vertex(cam, pose.Point(a0, 1.0));
    Colour(Shaded(fill, radial(a1)), alpha);
    Vertex(cam, pose.Point(a1, 1.0));
    Vertex(cam, pose.Point(a1, -1.0));
  }
  glEnd();
  // The faces, lighter than the side.
  for (const double z : {1.0, -1.0}) {
    if (!(z > 0 ? top : bottom)) continue;
    const Vec3d normal = z > 0 ? axis : Vec3d{-axis[0], -axis[1], -axis[2]};
    Colour(Shaded(Lighter(fill, 0.25), normal), alpha);
    glBegin(GL_POLYGON);
    for (int k = 0; k < n; ++k) Vertex(cam, pose.Point(angle(k), z));
    glEnd();
  }
  if (!solid) glDisable(GL_BLEND);
  // The generator at body angle 0 as a stripe, and the radius to it on the top face: they turn
  // with the spin.
  const double half = 0.09;  // rad
  const Rgb mark = solid ? stripe : edge;
  if (cam.Faces(pose.Point(0.0, 0.0), radial(0.0))) {
    glBegin(GL_QUADS);
    Colour(solid ? Shaded(stripe, radial(0.0)) : edge);
    Vertex(cam, pose.Point(-half, -1.0, 1.002));
    Vertex(cam, pose.Point(-half, 1.0, 1.002));
    Vertex(cam, pose.Point(half, 1.0, 1.002));
    Vertex(cam, pose.Point(half, -1.0, 1.002));
    glEnd();
  }
  if (top) {
    const Vec3d across = pose.Direction({0.0, 0.06 * pose.size.radius_m, 0.0});
    const Vec3d c = pose.Point(0.0, 1.0, 0.0);
    const Vec3d rim = pose.Point(0.0, 1.0, 1.0);
    Colour(solid ? Shaded(mark, axis) : edge);
    glBegin(GL_QUADS);
    Vertex(cam, Plus(c, across, -1.0));
    Vertex(cam, Plus(rim, across, -1.0));
    Vertex(cam, Plus(rim, across));
    Vertex(cam, Plus(c, across));
    glEnd();
  }
  // Edges: the outline (the sides' silhouette and the rims where they bound a visible face).
  Colour(edge);
  glLineWidth(static_cast<float>((solid ? 1.0 : 1.6) * line_w() * s));
  glBegin(GL_LINES);
  for (int k = 0; k < n; ++k) {
    const int prev = (k + n - 1) % n;
    if (front[k] != front[prev]) {
      Vertex(cam, pose.Point(angle(k), -1.0));
      Vertex(cam, pose.Point(angle(k), 1.0));
    }
    for (const double z : {1.0, -1.0}) {
      if (front[k] || (z > 0 ? top : bottom)) {
        Vertex(cam, pose.Point(angle(k), z));
        Vertex(cam, pose.Point(angle(k + 1), z));
      }
    }
  }
  glEnd();
}

void CylinderPainter::DrawAxis(const PerspectiveCamera& cam, const CylinderPose& pose,
                               Rgb colour) const {
  glLineWidth(static_cast<float>(2.0 * line_w() * config_.supersample));
  Colour(colour);
  glBegin(GL_LINES);
  Vertex(cam, pose.Point(0.0, 1.0, 0.0));
  Vertex(cam, pose.Point(0.0, 1.6, 0.0));
  glEnd();
}

void CylinderPainter::DrawTopView(double t_s) const {
  const PixelRect& r = layout_.top_view;
  const double lw = line_w();
  const int s = config_.supersample;
  const double range = layout_.top_view_range_rad;
  auto px = [&](double tx, double ty) {
    return Vec2{r.x_px + 0.5 * (tx / range + 1.0) * r.w_px,
                r.y_px + 0.5 * (1.0 - ty / range) * r.h_px};
  };
  PlotArea(r, lw, palette_);
  Colour(palette_.chart_frame);
  FillRect({r.x_px, r.y_px + 0.5 * r.h_px - 0.5 * lw, r.w_px, lw});
  FillRect({r.x_px + 0.5 * r.w_px - 0.5 * lw, r.y_px, lw, r.h_px});
  glEnable(GL_SCISSOR_TEST);
  ScissorTo(r, config_);
  // The critical angle atan(D / H): beyond it a cylinder at rest on its rim falls.
  const double critical = std::atan2(size_.radius_m, size_.half_height_m);
  if (critical < range) {
    glEnable(GL_LINE_STIPPLE);
    glLineStipple(2 * s, 0xCCCC);
    glLineWidth(static_cast<float>(lw * s));
    glBegin(GL_LINE_LOOP);
    for (int k = 0; k < 96; ++k) {
      const double a = 2.0 * kPi * k / 96;
      const Vec2 p = px(critical * std::cos(a), critical * std::sin(a));
      glVertex2d(p.x, p.y);
    }
    glEnd();
    glDisable(GL_LINE_STIPPLE);
  }
  // Each track's path up to t (the others first, dashed; the first on top, solid).
  const double t_clamped = std::clamp(t_s, layout_.t_from_s, layout_.t_to_s);
  for (size_t j = tracks_.size(); j-- > 0;) {
    const History& h = tracks_[j].history;
    const StateQuantityReader tx(h, "tilt_x"), ty(h, "tilt_y");
    TrackLine(j, lw, s);
    Colour(TrackColour(palette_, j));
    HistoryStrip(
        h, layout_.t_from_s, t_clamped,
        [&](double t) {
          const CylinderState st = CylinderStateAt(h, t).state;
          return px(st.tilt_x_rad(), st.tilt_y_rad());
        },
        [&](const Sample& smp) { return px(tx(smp, 1), ty(smp, 1)); });
    glDisable(GL_LINE_STIPPLE);
  }
  // The current points, the first track's on top.
  for (size_t j = tracks_.size(); j-- > 0;) {
    const CylinderState now = CylinderStateAt(tracks_[j].history, t_clamped).state;
    const Vec2 c = px(now.tilt_x_rad(), now.tilt_y_rad());
    const double radius = (j == 0 ? 3.0 : 2.5) * lw;
    Colour(TrackColour(palette_, j));
    glBegin(GL_POLYGON);
    for (int k = 0; k < 24; ++k) {
      const double a = 2.0 * kPi * k / 24;
      glVertex2d(c.x + radius * std::cos(a), c.y + radius * std::sin(a));
    }
    glEnd();
  }
  glDisable(GL_SCISSOR_TEST);
}

void CylinderPainter::DrawGl(double t_s) const {
  const int s = config_.supersample;
  BeginFrame(config_, palette_);
  // The side is lit per vertex: colours interpolated across each face.
  glShadeModel(GL_SMOOTH);

  const Vec3d base = BaseAt(t_s);
  std::vector<CylinderAt> states;
  std::vector<CylinderPose> poses;
  for (const Track& tr : tracks_) {
    states.push_back(CylinderStateAt(tr.history, t_s));
    poses.push_back(PoseOfCylinder(states.back().state, size_, base));
  }
  const bool side = layout_.perspective_views.size() > 1;
  for (size_t v = 0; v < layout_.perspective_views.size(); ++v) {
    const PerspectiveCamera& cam = layout_.perspective_views[v];
    glEnable(GL_SCISSOR_TEST);
    glScissor(static_cast<int>(std::lround(cam.vp_x_px * s)),
              static_cast<int>(std::lround((config_.height_px - cam.vp_y_px - cam.vp_h_px) * s)),
              static_cast<int>(std::lround(cam.vp_w_px * s)),
              static_cast<int>(std::lround(cam.vp_h_px * s)));
    DrawGround(cam, t_s);
    if (side) {
      DrawArrow(cam, states[v], base, TrackColour(palette_, v));
      DrawCylinder(cam, poses[v], true, palette_.outline);
      DrawAxis(cam, poses[v], TrackColour(palette_, v));
    } else {
      for (size_t i = 0; i < tracks_.size(); ++i) {
        DrawArrow(cam, states[i], base, TrackColour(palette_, i));
      }
      DrawCylinder(cam, poses[0], true, palette_.outline);
      DrawAxis(cam, poses[0], TrackColour(palette_, 0));
      for (size_t i = 1; i < tracks_.size(); ++i) {
        DrawCylinder(cam, poses[i], false, TrackColour(palette_, i));
        DrawAxis(cam, poses[i], TrackColour(palette_, i));
      }
    }
    glDisable(GL_SCISSOR_TEST);
  }
  if (layout_.has_top_view) DrawTopView(t_s);
}

void CylinderPainter::DrawText(double t_s, Font* font, Image* img) const {
  const int asc = font->ascender_px();
  auto baseline = [&](const PixelRect& r, int line) {
    return static_cast<int>(std::lround(r.y_px)) + line * layout_.line_px + asc;
  };
  const int x0 = static_cast<int>(std::lround(layout_.header.x_px));
  if (config_.show_text) {
    std::string stamp = "t = " + Format("%.3f", t_s) + " s";
    if (config_.show_base_motion && !base_.empty()) {
      const Vec3d b = BaseShift(base_, t_s);
      stamp += "    base x = " + Format("%+.3f", b[0]) + " m, y = " + Format("%+.3f", b[1]) + " m";
      if (b[2] != 0.0) stamp += ", z = " + Format("%+.3f", b[2]) + " m";
    }
    const int stamp_w = font->Draw(img, x0, baseline(layout_.header, 0), stamp, palette_.text);
    if (!config_.title.empty()) {
      const int room = static_cast<int>(layout_.header.w_px) - stamp_w - 2 * layout_.font_px;
      const std::string title = room > 0 ? Fitted(font, config_.title, room) : std::string();
      const int right = static_cast<int>(std::lround(layout_.header.x_px + layout_.header.w_px));
      font->Draw(img, right - font->Measure(title), baseline(layout_.header, 0), title,
                 palette_.text);
    }
    if (layout_.perspective_views.size() > 1) {
      for (size_t i = 0; i < tracks_.size(); ++i) {
        const PixelRect& r = layout_.view_labels[i];
        const int x = static_cast<int>(std::lround(r.x_px));
        const CylinderAt at = CylinderStateAt(tracks_[i].history, t_s);
        const int room = static_cast<int>(r.w_px);
        font->Draw(img, x, baseline(r, 0),
                   Fitted(font, tracks_[i].engine + "   mode " + at.mode, room), palette_.text);
        font->Draw(img, x, baseline(r, 1), Fitted(font, TiltText(at), room), palette_.text);
      }
    } else {
      for (size_t i = 0; i < tracks_.size(); ++i) {
        const CylinderAt at = CylinderStateAt(tracks_[i].history, t_s);
        const std::string style =
            tracks_.size() > 1 ? (i == 0 ? " (solid)" : " (outline)") : std::string();
        const std::string line =
            tracks_[i].engine + style + "   mode " + at.mode + "   " + TiltText(at);
        font->Draw(img, x0, baseline(layout_.header, static_cast<int>(i) + 1),
                   Fitted(font, line, static_cast<int>(layout_.header.w_px)), palette_.text);
      }
    }
  }
  if (layout_.has_top_view) {
    const PixelRect& r = layout_.top_view;
    const int gap = std::max(2, layout_.font_px / 3);
    const int left = static_cast<int>(std::lround(r.x_px));
    const int right = static_cast<int>(std::lround(r.x_px + r.w_px));
    const int room = right - left;
    const std::string title = Fitted(font, "axis path, seen from above", room);
    font->Draw(img, (left + right - font->Measure(title)) / 2,
               static_cast<int>(std::lround(r.y_px)) - gap - font->descender_px(), title,
               palette_.text);
    const int below = static_cast<int>(std::lround(r.y_px + r.h_px)) + gap + asc;
    const std::string range = Format("%g", layout_.top_view_range_rad);
    const std::string lo = "-" + range, hi = "+" + range + " rad";
    font->Draw(img, left, below, lo, palette_.text);
    font->Draw(img, right - font->Measure(hi), below, hi, palette_.text);
    const std::string x_label = "tilt_x →";
    font->Draw(img, (left + right - font->Measure(x_label)) / 2, below, x_label, palette_.text);
    // The second line: tilt_y's direction, then each track in its colour (solid or dashed).
    std::string legend = "tilt_y ↑";
    int x = left;
    const int y2 = below + layout_.line_px;
    x += font->Draw(img, x, y2, legend, palette_.text);
    for (size_t i = 0; i < tracks_.size(); ++i) {
      const std::string item = "  " + tracks_[i].engine + (i == 0 ? "" : " (dashed)");
      if (x + font->Measure(item) > right) break;
      x += font->Draw(img, x, y2, item, TrackColour(palette_, i));
    }
  }
}

}  // namespace rockbench::renders
