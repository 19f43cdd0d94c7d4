// A cylinder as drawn, without GL: its state at a time, its pose, the perspective camera and the
// layout of its frames.
#include "renders/cylinder/cylinder_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "renders/frame_parts.h"

namespace rockbench::renders {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d Sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double Dot3(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3d Cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d Unit(const Vec3d& a) {
  const double n = std::sqrt(Dot3(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// The box of `points`: its lowest and highest x, y and z.
void BoundingBox(const std::vector<Vec3d>& points, Vec3d& lo, Vec3d& hi) {
  const double inf = std::numeric_limits<double>::infinity();
  lo = {inf, inf, inf};
  hi = {-inf, -inf, -inf};
  for (const Vec3d& p : points) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
}

// The quantities of a cylinder history, looked up once.
struct CylinderReaders {
  explicit CylinderReaders(const History& h)
      : tilt_x(h, "tilt_x"), tilt_y(h, "tilt_y"), azimuth(h, "azimuth"), spin(h, "spin") {}
  StateQuantityReader tilt_x, tilt_y, azimuth, spin;
};

std::string ModeName(const Configuration& mode) {
  const std::vector<std::string>& names = CylinderKind().contact_names;
  const auto c = static_cast<size_t>(mode.size() > 0 ? mode[0] : Contact::kFace);
  return c < names.size() ? names[c] : std::string("?");
}

}  // namespace

double PerspectiveCamera::Depth_m(const Vec3d& p) const {
  return Dot3(Sub(p, eye_m), forward);
}

Vec2 PerspectiveCamera::ToPixel(const Vec3d& p) const {
  const Vec3d d = Sub(p, eye_m);
  const double z = Dot3(d, forward);
  return {cx_px + focal_px * Dot3(d, right) / z, cy_px - focal_px * Dot3(d, up) / z};
}

bool PerspectiveCamera::Faces(const Vec3d& point, const Vec3d& normal) const {
  return Dot3(Sub(eye_m, point), normal) > 0.0;
}

PerspectiveCamera FramePerspective(const std::vector<Vec3d>& points, double azimuth_rad,
                                   double elevation_rad, double vp_x_px, double vp_y_px,
                                   double vp_w_px, double vp_h_px, double margin_frac) {
  if (points.empty()) throw std::invalid_argument("FramePerspective: no points to frame");
  if (!(vp_w_px > 0.0 && vp_h_px > 0.0)) {
    throw std::invalid_argument("FramePerspective: an empty viewport");
  }
  PerspectiveCamera cam;
  cam.vp_x_px = vp_x_px;
  cam.vp_y_px = vp_y_px;
  cam.vp_w_px = vp_w_px;
  cam.vp_h_px = vp_h_px;
  // The points' bounding box: its centre is looked at, its half-diagonal bounds them.
  Vec3d lo, hi;
  BoundingBox(points, lo, hi);
  const Vec3d centre{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const double radius = std::max(0.5 * std::sqrt(Dot3(Sub(hi, lo), Sub(hi, lo))), 1e-6);
  const Vec3d to_eye{std::cos(elevation_rad) * std::cos(azimuth_rad),
                     std::cos(elevation_rad) * std::sin(azimuth_rad), std::sin(elevation_rad)};
  // Far enough that the sphere is seen within a cone of half-angle 17 degrees: a mild
  // perspective, every point well in front of the eye.
  const double distance = radius / std::sin(17.0 * kPi / 180.0);
  for (int i = 0; i < 3; ++i) cam.eye_m[i] = centre[i] + distance * to_eye[i];
  cam.forward = {-to_eye[0], -to_eye[1], -to_eye[2]};
  cam.right = Unit(Cross(cam.forward, {0.0, 0.0, 1.0}));
  cam.up = Cross(cam.right, cam.forward);
  // The projected points' box at unit focal length, then the focal length and centre that fit it.
  const double inf = std::numeric_limits<double>::infinity();
  double a0 = inf, a1 = -inf, b0 = inf, b1 = -inf;
  for (const Vec3d& p : points) {
    const Vec3d d = Sub(p, cam.eye_m);
    const double z = Dot3(d, cam.forward);
    const double a = Dot3(d, cam.right) / z, b = Dot3(d, cam.up) / z;
    a0 = std::min(a0, a);
    a1 = std::max(a1, a);
    b0 = std::min(b0, b);
    b1 = std::max(b1, b);
  }
  const double room = 1.0 - 2.0 * margin_frac;
  cam.focal_px = std::min(room * vp_w_px / std::max(a1 - a0, 1e-12),
                          room * vp_h_px / std::max(b1 - b0, 1e-12));
  cam.cx_px = vp_x_px + 0.5 * vp_w_px - cam.focal_px * 0.5 * (a0 + a1);
  cam.cy_px = vp_y_px + 0.5 * vp_h_px + cam.focal_px * 0.5 * (b0 + b1);
  return cam;
}

CylinderAt CylinderStateAt(const History& history, double t_s) {
  const auto& s = history.samples;
  if (s.empty()) throw std::invalid_argument("CylinderStateAt: the history has no samples");
  if (history.shape != CylinderKind().shape) {
    throw std::invalid_argument("CylinderStateAt: a history of " + history.shape +
                                " bodies, not of a cylinder");
  }
  const CylinderReaders q(history);
  // First sample strictly after t (after a pair at an event time: the later one).
  auto it = std::upper_bound(s.begin(), s.end(), t_s,
                             [](double t, const Sample& x) { return t < x.t_s; });
  const Sample& a = it == s.begin() ? s.front() : *(it - 1);
  const Sample& b = (it == s.begin() || it == s.end()) ? a : *it;
  const double span = b.t_s - a.t_s;
  const double w = span > 0.0 ? std::clamp((t_s - a.t_s) / span, 0.0, 1.0) : 0.0;
  CylinderAt out;
  const double tx = q.tilt_x(a, 1) + w * (q.tilt_x(b, 1) - q.tilt_x(a, 1));
  const double ty = q.tilt_y(a, 1) + w * (q.tilt_y(b, 1) - q.tilt_y(a, 1));
  const double az_a = q.azimuth(a, 1);
  out.state.tilt_rad = std::hypot(tx, ty);
  out.state.azimuth_rad =
      out.state.tilt_rad > 0.0
          ? az_a + std::remainder(std::atan2(ty, tx) - az_a, 2.0 * kPi)  // continuous with a
          : az_a;
  const double heading_a = az_a + q.spin(a, 1);
  const double heading_b = q.azimuth(b, 1) + q.spin(b, 1);
  const double heading = heading_a + w * std::remainder(heading_b - heading_a, 2.0 * kPi);
  out.state.spin_rad = heading - out.state.azimuth_rad;
  out.on_rim = a.mode.size() > 0 && a.mode[0] != Contact::kFace;
  out.mode = ModeName(a.mode);
  return out;
}

CylinderSize CylinderSizeOf(const Scene& scene) {
  if (scene.blocks.empty()) throw std::invalid_argument("CylinderSizeOf: the scene has no body");
  const BlockDef& b = scene.blocks.front();
  return {0.5 * b.diameter_m, 0.5 * b.height_m};
}

Vec3d BaseShift(const BaseDisplacement& base, double t_s) {
  const Vec2 xz = base.At(t_s);
  return {xz.x, base.TransverseAt(t_s), xz.y};
}

Vec3d CylinderPose::Direction(const Vec3d& v) const {
  const Mat3d& q = rotation;
  return {q[0] * v[0] + q[1] * v[1] + q[2] * v[2], q[3] * v[0] + q[4] * v[1] + q[5] * v[2],
          q[6] * v[0] + q[7] * v[1] + q[8] * v[2]};
}

Vec3d CylinderPose::Point(double angle_rad, double z_frac, double radius_frac) const {
  const double r = radius_frac * size.radius_m;
  const Vec3d d =
      Direction({r * std::cos(angle_rad), r * std::sin(angle_rad), z_frac * size.half_height_m});
  return {centre_m[0] + d[0], centre_m[1] + d[1], centre_m[2] + d[2]};
}

CylinderPose PoseOfCylinder(const CylinderState& state, const CylinderSize& size,
                            const Vec3d& base_m) {
  CylinderPose pose;
  pose.size = size;
  pose.rotation = CylinderRotation(state);
  const Vec3d c = CylinderCentre(state, size.radius_m, size.half_height_m);
  pose.centre_m = {c[0] + base_m[0], c[1] + base_m[1], c[2] + base_m[2]};
  return pose;
}

void PlaceCylinderLayout(const Scene& scene, const std::vector<Track>& tracks,
                         const BaseDisplacement& base, const RenderConfig& config,
                         FrameLayout& lay) {
  const int w = config.width_px, h = config.height_px;
  const int n = static_cast<int>(tracks.size());
  const bool side = config.layout == Layout::kSide && n > 1;
  // Text sizes and header as the planar frames'.
  SetTextSizes(h, lay);
  const double m = lay.margin_px;
  const double top = PlaceHeader(config, n, side, lay);
  const double bottom = h - m;
  double views_right = w - m;
  const CylinderSize size = CylinderSizeOf(scene);
  const BaseDisplacement still;
  const BaseDisplacement& shown = config.show_base_motion ? base : still;

  // Every pose of every track in the window (relative to its base), and the peak tilt.
  std::vector<Vec3d> body_points;
  double peak_tilt_rad = 0.0;
  const int ring = 16;
  auto add_state = [&](const CylinderState& st) {
    peak_tilt_rad = std::max(peak_tilt_rad, st.tilt_rad);
    const CylinderPose pose = PoseOfCylinder(st, size, {0.0, 0.0, 0.0});
    for (int k = 0; k < ring; ++k) {
      const double a = 2.0 * kPi * k / ring;
      body_points.push_back(pose.Point(a, 1.0));
      body_points.push_back(pose.Point(a, -1.0));
    }
    // The axis drawn above the top face.
    body_points.push_back(pose.Point(0.0, 1.6, 0.0));
  };
  add_state({});
  for (const Track& t : tracks) {
    add_state(CylinderStateAt(t.history, lay.t_from_s).state);
    add_state(CylinderStateAt(t.history, lay.t_to_s).state);
    for (const Sample& s : t.history.samples) {
      if (s.t_s < lay.t_from_s || s.t_s > lay.t_to_s) continue;
      add_state(CylinderStateAt(t.history, s.t_s).state);
    }
  }
  // The base plane: a square about the base's position that holds every pose's footprint with
  // room for the lean's arrow (a diameter beyond the rim).
  double reach_m = 0.0;
  for (const Vec3d& p : body_points) {
    reach_m = std::max({reach_m, std::abs(p[0]), std::abs(p[1])});
  }
  lay.ground_half_side_m = 1.15 * std::max(reach_m, 3.0 * size.radius_m) + 0.5 * size.radius_m;
  const double g = lay.ground_half_side_m;
  // The poses' box (relative to the base) and the plane, at the base's positions over the window.
  Vec3d lo, hi;
  BoundingBox(body_points, lo, hi);
  std::vector<Vec3d> points;
  const int base_steps = shown.empty() ? 0 : 400;
  for (int i = 0; i <= base_steps; ++i) {
    const double t = lay.t_from_s + (lay.t_to_s - lay.t_from_s) * i / std::max(base_steps, 1);
    const Vec3d b = BaseShift(shown, t);
    for (int c = 0; c < 8; ++c) {
      points.push_back({b[0] + (c & 1 ? hi[0] : lo[0]), b[1] + (c & 2 ? hi[1] : lo[1]),
                        b[2] + (c & 4 ? hi[2] : lo[2])});
    }
    for (double sx : {-1.0, 1.0}) {
      for (double sy : {-1.0, 1.0}) points.push_back({b[0] + sx * g, b[1] + sy * g, b[2]});
    }
  }
  // The fixed mark of the base's rest position, in front of the plane's near edge.
  points.push_back({0.0, -1.12 * g, 0.0});

  if (config.show_chart) {
    // A square right of the views: a line of text above it and two below it.
    const double room_h = bottom - top - 3.0 * lay.line_px;
    const double side_px = std::floor(std::min(room_h, std::round(0.36 * (w - 2 * m))));
    if (side_px < 24.0) {
      throw std::invalid_argument(
          "image too small for the text and the top view: give a larger "
          "size");
    }
    lay.has_top_view = true;
    lay.top_view = {w - m - side_px, top + lay.line_px, side_px, side_px};
    views_right = lay.top_view.x_px - 2.0 * m;
    lay.top_view_range_rad = NiceCeil(std::max(peak_tilt_rad, 1e-4) * 1.05);
  }
  if (bottom - top < 16.0 || views_right - m < 16.0) {
    throw std::invalid_argument("image too small for the text and chart: give a larger size");
  }
  for (const PixelRect& r : PlaceViews(config, n, side, top, bottom, views_right, lay)) {
    lay.perspective_views.push_back(FramePerspective(points, kCylinderCameraAzimuth_rad,
                                                     kCylinderCameraElevation_rad, r.x_px, r.y_px,
                                                     r.w_px, r.h_px));
  }
}

}  // namespace rockbench::renders
