// FrameRenderer: legacy fixed-function GL into a supersampled off-screen buffer, box-filtered
// down, then FreeType text on the final pixels.
#include "renders/renderer.h"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "renders/cylinder/cylinder_painter.h"
#include "renders/frame_parts.h"
#include "renders/gl_context.h"
#include "renders/gl_draw.h"
#include "scene/mode.h"
#include "util/format.h"

namespace rockbench::renders {
namespace {

// A quad in pixel coordinates (final-image px; the projection scales to the supersampled buffer).
using PixelQuad = std::array<Vec2, 4>;

PixelQuad ToPixels(const Camera& cam, const BlockCorners& q) {
  PixelQuad p;
  for (int i = 0; i < 4; ++i) p[i] = cam.ToPixel(q[i]);
  return p;
}

// The rectangle shrunk by d px on every side (corners moved along both adjacent edges).
PixelQuad Inset(const PixelQuad& q, double d_px) {
  PixelQuad out;
  for (int i = 0; i < 4; ++i) {
    const Vec2& c = q[i];
    const Vec2& next = q[(i + 1) % 4];
    const Vec2& prev = q[(i + 3) % 4];
    auto unit = [](Vec2 a, Vec2 b) {
      const double dx = b.x - a.x, dy = b.y - a.y;
      const double len = std::hypot(dx, dy);
      return len > 0 ? Vec2{dx / len, dy / len} : Vec2{};
    };
    const Vec2 u = unit(c, next), v = unit(c, prev);
    out[i] = {c.x + d_px * (u.x + v.x), c.y + d_px * (u.y + v.y)};
  }
  return out;
}

void FillQuad(const PixelQuad& q) {
  glBegin(GL_QUADS);
  for (const Vec2& p : q) glVertex2d(p.x, p.y);
  glEnd();
}

// The band between a quad and its inset.
void Ring(const PixelQuad& outer, const PixelQuad& inner) {
  glBegin(GL_TRIANGLE_STRIP);
  for (int i = 0; i <= 4; ++i) {
    glVertex2d(outer[i % 4].x, outer[i % 4].y);
    glVertex2d(inner[i % 4].x, inner[i % 4].y);
  }
  glEnd();
}

// An axis-aligned line as a thin rectangle (exact width, no line-rasterisation rules).
void HLine(double x0, double x1, double y, double width) {
  FillRect({x0, y - 0.5 * width, x1 - x0, width});
}
void VLine(double x, double y0, double y1, double width) {
  FillRect({x - 0.5 * width, y0, width, y1 - y0});
}

// "θ" and block k's number as subscript digits (U+2080..U+2089): "θ₁₂" for k = 12.
std::string ThetaLabel(int k) {
  std::string out = "θ";
  for (char d : std::to_string(k)) {
    out += "\xE2\x82";
    out += static_cast<char>(0x80 + (d - '0'));
  }
  return out;
}

// The angles of a sample of three and more blocks, in mrad steps: "θ₁…θ₈ = +0.012 +0.034 ...
// rad".
std::string StackedAngles(const Sample& s) {
  std::string out = ThetaLabel(1) + "…" + ThetaLabel(s.blocks()) + " =";
  for (double theta : s.theta_rad) {
    out += ' ';
    out += Format("%+.3f", theta);
  }
  return out + " rad";
}

}  // namespace

struct FrameRenderer::Impl {
  Scene scene;
  std::vector<Track> tracks;
  BaseDisplacement base;
  RenderConfig config;
  FrameLayout layout;
  Palette palette;
  std::unique_ptr<Font> font;
  std::unique_ptr<GlContext> gl;
  /// A cylinder scene's drawing (renders/cylinder/cylinder_painter.h); null for planar blocks.
  std::unique_ptr<CylinderPainter> cylinder;

  double line_w() const { return LineWidth_px(config); }

  Vec2 BaseAt(double t) const { return config.show_base_motion ? base.At(t) : Vec2{}; }

  void Scissor(const Camera& cam) const {
    const int s = config.supersample;
    const int x0 = static_cast<int>(std::lround(cam.vp_x_px * s));
    const int x1 = static_cast<int>(std::lround((cam.vp_x_px + cam.vp_w_px) * s));
    const int y_top = static_cast<int>(std::lround(cam.vp_y_px * s));
    const int y_bot = static_cast<int>(std::lround((cam.vp_y_px + cam.vp_h_px) * s));
    glScissor(x0, config.height_px * s - y_bot, x1 - x0, y_bot - y_top);
  }

  void DrawGround(const Camera& cam, double t) const {
    const Vec2 b = BaseAt(t);
    const Box& w = cam.world;
    const double big = 2.0 * (w.width_m() + w.height_m());
    const Vec2 top_left = cam.ToPixel({w.x_min_m - big, b.y});
    const Vec2 bottom_right = cam.ToPixel({w.x_max_m + big, w.y_min_m - big});
    Colour(palette.ground);
    FillRect({top_left.x, top_left.y, bottom_right.x - top_left.x, bottom_right.y - top_left.y});
    // Ticks fixed to the ground (they move with x_g), every round number of metres.
    const double step_m = NiceStep(w.width_m() / 12.0);
    const double ground_px = cam.vp_y_px + cam.vp_h_px - top_left.y;
    const double tick_px = std::min(0.5 * ground_px, 0.03 * config.height_px);
    Colour(palette.ground_line);
    const long k0 = static_cast<long>(std::floor((w.x_min_m - b.x) / step_m));
    const long k1 = static_cast<long>(std::ceil((w.x_max_m - b.x) / step_m));
    for (long k = k0; k <= k1; ++k) {
      const Vec2 p = cam.ToPixel({b.x + k * step_m, b.y});
      VLine(p.x, p.y, p.y + tick_px, line_w());
    }
    HLine(top_left.x, bottom_right.x, top_left.y, 1.5 * line_w());
    // A fixed marker under the ground's rest position (x = 0): the ticks move past it.
    const Vec2 o = cam.ToPixel({0.0, w.y_min_m});
    const double mh = std::min(0.6 * ground_px, 0.03 * config.height_px);
    Colour(palette.background);
    glBegin(GL_TRIANGLES);
    glVertex2d(o.x, o.y - mh);
    glVertex2d(o.x - 0.6 * mh, o.y);
    glVertex2d(o.x + 0.6 * mh, o.y);
    glEnd();
  }

  DrawnStack PoseOf(const Track& track, double t) const {
    return PoseFor(scene, StackState(StateAt(track.history, t)), BaseAt(t));
  }

  // Solid blocks: an outline band and the block colour inside.
  void DrawSolid(const Camera& cam, const DrawnStack& pose) const {
    auto one = [&](const BlockCorners& q, Rgb fill) {
      const PixelQuad outer = ToPixels(cam, q);
      Colour(palette.outline);
      FillQuad(outer);
      Colour(fill);
      FillQuad(Inset(outer, line_w()));
    };
    for (size_t k = 0; k < pose.size(); ++k) one(pose[k], palette.block(static_cast<int>(k)));
  }

  // Outlined, translucent blocks (other engines in the overlay layout).
  void DrawOutlined(const Camera& cam, const DrawnStack& pose, Rgb outline) const {
    auto one = [&](const BlockCorners& q, Rgb fill) {
      const PixelQuad outer = ToPixels(cam, q);
      const PixelQuad inner = Inset(outer, 2.0 * line_w());
      glEnable(GL_BLEND);
      Colour(fill, 0.35);
      FillQuad(inner);
      glDisable(GL_BLEND);
      Colour(outline);
      Ring(outer, inner);
    };
    for (size_t k = 0; k < pose.size(); ++k) one(pose[k], palette.block(static_cast<int>(k)));
  }

  // Block `which`'s angle in `h` from the window's start to t_clamped, as a line strip through
  // the samples (px maps a time and an angle to pixels).
  template <typename ToPixel>
  void Trace(const History& h, size_t which, double t_clamped, const ToPixel& px) const {
    HistoryStrip(
        h, layout.t_from_s, t_clamped,
        [&](double t) { return px(t, StateAt(h, t).theta_rad[which]); },
        [&](const Sample& smp) { return px(smp.t_s, smp.theta_rad[which]); });
  }

  void DrawChart(double t) const {
    const PixelRect& r = layout.chart;
    PlotArea(r, line_w(), palette);
    const double span = std::max(layout.t_to_s - layout.t_from_s, 1e-9);
    auto px = [&](double ts, double theta) {
      const double half = 0.5 * r.h_px - 2.0 * line_w();
      return Vec2{r.x_px + (ts - layout.t_from_s) / span * r.w_px,
                  r.y_px + 0.5 * r.h_px - theta / layout.chart_theta_max_rad * half};
    };
    // Zero line and the current time.
    Colour(palette.chart_frame);
    HLine(r.x_px, r.x_px + r.w_px, r.y_px + 0.5 * r.h_px, line_w());
    const double t_clamped = std::clamp(t, layout.t_from_s, layout.t_to_s);
    VLine(px(t_clamped, 0).x, r.y_px, r.y_px + r.h_px, line_w());
    // Curves up to t: the first engine solid, the others dashed.
    const int s = config.supersample;
    glEnable(GL_SCISSOR_TEST);
    ScissorTo(r, config);
    for (size_t i = 0; i < tracks.size(); ++i) {
      const History& h = tracks[i].history;
      TrackLine(i, line_w(), s);
      for (int which = h.blocks == 2 ? 1 : 0; which >= 0; --which) {
        Colour(palette.chart_theta(which));
        Trace(h, which, t_clamped, px);
      }
      glDisable(GL_LINE_STIPPLE);
    }
    glDisable(GL_SCISSOR_TEST);
  }

  // Three and more blocks: one small axis per block, each with its block's trace of every engine
  // (the first solid, the others dashed), a zero line and the time cursor.
  void DrawStackedChart(double t) const {
    const double span = std::max(layout.t_to_s - layout.t_from_s, 1e-9);
    const double t_clamped = std::clamp(t, layout.t_from_s, layout.t_to_s);
    const int s = config.supersample;
    for (size_t k = 0; k < layout.chart_panels.size(); ++k) {
      const PixelRect& r = layout.chart_panels[k];
      auto px = [&](double ts, double theta) {
        const double half = std::max(0.5 * r.h_px - 2.0 * line_w(), 0.35 * r.h_px);
        return Vec2{r.x_px + (ts - layout.t_from_s) / span * r.w_px,
                    r.y_px + 0.5 * r.h_px - theta / layout.chart_theta_max_rad * half};
      };
      PlotArea(r, line_w(), palette);
      Colour(palette.chart_frame);
      HLine(r.x_px, r.x_px + r.w_px, r.y_px + 0.5 * r.h_px, line_w());
      VLine(px(t_clamped, 0).x, r.y_px, r.y_px + r.h_px, line_w());
      glEnable(GL_SCISSOR_TEST);
      ScissorTo(r, config);
      Colour(palette.chart_theta(static_cast<int>(k)));
      for (size_t i = 0; i < tracks.size(); ++i) {
        const History& h = tracks[i].history;
        // A history of fewer blocks: the blocks above its top one ride locked on it.
        const size_t which = std::min(k, static_cast<size_t>(std::max(h.blocks, 1) - 1));
        TrackLine(i, line_w(), s);
        Trace(h, which, t_clamped, px);
        glDisable(GL_LINE_STIPPLE);
      }
      glDisable(GL_SCISSOR_TEST);
    }
  }

  void DrawGl(double t) {
    BeginFrame(config, palette);
    const bool side = layout.views.size() > 1;
    for (size_t v = 0; v < layout.views.size(); ++v) {
      const Camera& cam = layout.views[v];
      glEnable(GL_SCISSOR_TEST);
      Scissor(cam);
      DrawGround(cam, t);
      if (side) {
        DrawSolid(cam, PoseOf(tracks[v], t));
      } else {
        DrawSolid(cam, PoseOf(tracks[0], t));
        for (size_t i = 1; i < tracks.size(); ++i) {
          DrawOutlined(cam, PoseOf(tracks[i], t), OverlayOutline(i));
        }
      }
      glDisable(GL_SCISSOR_TEST);
    }
    if (layout.has_chart) {
      if (layout.chart_panels.empty()) {
        DrawChart(t);
      } else {
        DrawStackedChart(t);
      }
    }
  }

  std::string StateText(const Track& track, double t, bool with_name) const {
    const Sample s = StateAt(track.history, t);
    std::string line;
    if (with_name) line = track.engine + "   ";
    if (track.history.blocks >= 3) {
      return line + "mode " + ConfigurationName(s.mode) + "   " + StackedAngles(s);
    }
    line +=
        "mode " + ConfigurationName(s.mode) + "   θ₁ = " + Format("%+.4f", s.theta_rad[0]) + " rad";
    if (track.history.blocks == 2) line += "   θ₂ = " + Format("%+.4f", s.theta_rad[1]) + " rad";
    return line;
  }

  // The stacked chart's labels: each axis's θk left of it in its trace's colour (every
  // step-th axis when they are lower than a line of text), on the line below the times and the
  // range every axis shares, and on the line above which engine is solid and which dashed.
  void DrawStackedChartText(Image* img) {
    const int asc = font->ascender_px();
    const std::vector<PixelRect>& panels = layout.chart_panels;
    const int gap = std::max(2, layout.font_px / 3);
    const int left = static_cast<int>(std::lround(layout.chart.x_px));
    const int right = static_cast<int>(std::lround(layout.chart.x_px + layout.chart.w_px));
    const double pitch_px = panels.size() > 1 ? panels[0].y_px - panels[1].y_px : 1e9;
    const size_t step = static_cast<size_t>(std::ceil(0.9 * layout.line_px / pitch_px));
    for (size_t k = 0; k < panels.size(); k += std::max<size_t>(step, 1)) {
      const std::string label = ThetaLabel(static_cast<int>(k) + 1);
      const PixelRect& r = panels[k];
      font->Draw(img, left - gap - font->Measure(label),
                 static_cast<int>(std::lround(r.y_px + 0.5 * r.h_px)) + asc / 2, label,
                 palette.chart_theta(static_cast<int>(k)));
    }
    const int below =
        static_cast<int>(std::lround(layout.chart.y_px + layout.chart.h_px)) + gap + asc;
    const std::string t_from = Format("%.4g", layout.t_from_s) + " s";
    const std::string t_end = Format("%.4g", layout.t_to_s) + " s";
    font->Draw(img, left, below, t_from, palette.text);
    font->Draw(img, right - font->Measure(t_end), below, t_end, palette.text);
    // The range every axis shares, between the two times.
    const std::string range = "±" + Format("%g", layout.chart_theta_max_rad) + " rad";
    font->Draw(img, (left + right - font->Measure(range)) / 2, below, range, palette.text);
    if (tracks.size() > 1) {
      // Above the column: which engine is solid, which dashed (shortened when it does not fit).
      std::string legend = tracks[0].engine + " solid, ";
      for (size_t i = 1; i < tracks.size(); ++i) {
        legend += tracks[i].engine + (i + 1 < tracks.size() ? ", " : " dashed");
      }
      legend = Fitted(font.get(), legend, right - left);
      font->Draw(img, (left + right - font->Measure(legend)) / 2,
                 static_cast<int>(std::lround(layout.chart.y_px)) - gap, legend, palette.text);
    }
  }

  void DrawText(double t, Image* img) {
    const int asc = font->ascender_px();
    auto baseline = [&](const PixelRect& r, int line) {
      return static_cast<int>(std::lround(r.y_px)) + line * layout.line_px + asc;
    };
    const int x0 = static_cast<int>(std::lround(layout.header.x_px));
    if (config.show_text) {
      std::string stamp = "t = " + Format("%.3f", t) + " s";
      if (config.show_base_motion && !base.empty()) {
        const Vec2 b = base.At(t);
        stamp += "    base x = " + Format("%+.3f", b.x) + " m";
        if (b.y != 0.0) stamp += ", y = " + Format("%+.3f", b.y) + " m";
      }
      const int stamp_w = font->Draw(img, x0, baseline(layout.header, 0), stamp, palette.text);
      if (!config.title.empty()) {
        // Right-aligned, shortened with an ellipsis where it would run into the time stamp.
        const int room = static_cast<int>(layout.header.w_px) - stamp_w - 2 * layout.font_px;
        std::string kept = config.title, title = config.title;
        while (!kept.empty() && font->Measure(title) > room) {
          // Drop the last code point (its continuation bytes, then its lead byte).
          while (!kept.empty()) {
            const auto c = static_cast<unsigned char>(kept.back());
            kept.pop_back();
            if ((c & 0xC0) != 0x80) break;
          }
          title.assign(kept).append("…");
        }
        if (kept.empty()) title.clear();
        const int right = static_cast<int>(std::lround(layout.header.x_px + layout.header.w_px));
        font->Draw(img, right - font->Measure(title), baseline(layout.header, 0), title,
                   palette.text);
      }
      if (layout.views.size() > 1) {
        for (size_t i = 0; i < tracks.size(); ++i) {
          const PixelRect& r = layout.view_labels[i];
          const int x = static_cast<int>(std::lround(r.x_px));
          const Sample s = StateAt(tracks[i].history, t);
          font->Draw(img, x, baseline(r, 0),
                     tracks[i].engine + "   mode " + ConfigurationName(s.mode), palette.text);
          if (tracks[i].history.blocks >= 3) {
            font->Draw(img, x, baseline(r, 1),
                       Fitted(font.get(), StackedAngles(s), static_cast<int>(r.w_px)),
                       palette.text);
            continue;
          }
          std::string angles = "θ₁ = " + Format("%+.4f", s.theta_rad[0]);
          if (tracks[i].history.blocks == 2) {
            angles += "   θ₂ = " + Format("%+.4f", s.theta_rad[1]);
          }
          font->Draw(img, x, baseline(r, 1), angles + " rad", palette.text);
        }
      } else {
        for (size_t i = 0; i < tracks.size(); ++i) {
          const std::string style =
              tracks.size() > 1 ? (i == 0 ? " (solid)" : " (outline)") : std::string();
          std::string line = tracks[i].engine + style + "   " + StateText(tracks[i], t, false);
          // Eight angles may not fit a narrow frame: shortened, they end in an ellipsis.
          if (tracks[i].history.blocks >= 3) {
            line = Fitted(font.get(), line, static_cast<int>(layout.header.w_px));
          }
          font->Draw(img, x0, baseline(layout.header, static_cast<int>(i) + 1), line, palette.text);
        }
      }
    }
    if (layout.has_chart && !layout.chart_panels.empty()) {
      DrawStackedChartText(img);
    } else if (layout.has_chart) {
      // Angle range left of the plot, times and legend on the line below it.
      const PixelRect& r = layout.chart;
      const int gap = std::max(2, layout.font_px / 3);
      const int left = static_cast<int>(std::lround(r.x_px));
      const int right = static_cast<int>(std::lround(r.x_px + r.w_px));
      const int top = static_cast<int>(std::lround(r.y_px)) + asc;
      const int bottom = static_cast<int>(std::lround(r.y_px + r.h_px));
      const std::string up = Format("+%g", layout.chart_theta_max_rad);
      const std::string down = Format("-%g", layout.chart_theta_max_rad);
      font->Draw(img, left - gap - font->Measure(up), top, up, palette.text);
      const std::string rad = "rad";
      font->Draw(img, left - gap - font->Measure(rad),
                 static_cast<int>(std::lround(r.y_px + 0.5 * r.h_px)) + asc / 2, rad, palette.text);
      font->Draw(img, left - gap - font->Measure(down), bottom, down, palette.text);
      const int below = bottom + gap + asc;
      const std::string t_from = Format("%.4g", layout.t_from_s) + " s";
      const std::string t_end = Format("%.4g", layout.t_to_s) + " s";
      font->Draw(img, left, below, t_from, palette.text);
      font->Draw(img, right - font->Measure(t_end), below, t_end, palette.text);
      // Legend: theta1 and theta2 in their line colours; solid/dashed per engine.
      std::string engines;
      if (tracks.size() > 1) {
        engines = "   " + tracks[0].engine + " solid, ";
        for (size_t i = 1; i < tracks.size(); ++i) {
          engines += tracks[i].engine + (i + 1 < tracks.size() ? ", " : " dashed");
        }
      }
      const bool two = std::any_of(tracks.begin(), tracks.end(),
                                   [](const Track& tr) { return tr.history.blocks == 2; });
      const int space = font->Measure("  ");
      const int w1 = font->Measure("θ₁");
      const int w2 = two ? space + font->Measure("θ₂") : 0;
      int x = static_cast<int>(std::lround(r.x_px + 0.5 * r.w_px)) -
              (w1 + w2 + font->Measure(engines)) / 2;
      x += font->Draw(img, x, below, "θ₁", palette.chart_theta(0));
      if (two) x += space + font->Draw(img, x + space, below, "θ₂", palette.chart_theta(1));
      font->Draw(img, x, below, engines, palette.text);
    }
  }
};

FrameRenderer::FrameRenderer(const Scene& scene, std::vector<Track> tracks, BaseDisplacement base,
                             RenderConfig config)
    : impl_(std::make_unique<Impl>()) {
  impl_->layout = ComputeLayout(scene, tracks, base, config);
  impl_->scene = scene;
  impl_->tracks = std::move(tracks);
  impl_->base = std::move(base);
  impl_->config = std::move(config);
  if (impl_->config.show_text || impl_->config.show_chart) {
    impl_->font = std::make_unique<Font>(impl_->config.font_path, impl_->layout.font_px);
  }
  impl_->gl = CreateGlContext(impl_->config.width_px * impl_->config.supersample,
                              impl_->config.height_px * impl_->config.supersample);
  if (impl_->scene.three_dimensional()) {
    impl_->cylinder = std::make_unique<CylinderPainter>(
        impl_->scene, impl_->tracks, impl_->base, impl_->config, impl_->layout, impl_->palette);
  }
}

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::Render(double t_s, Image* out) {
  impl_->gl->MakeCurrent();
  if (impl_->cylinder) {
    impl_->cylinder->DrawGl(t_s);
  } else {
    impl_->DrawGl(t_s);
  }
  const uint8_t* pixels = impl_->gl->Finish();
  out->width_px = impl_->config.width_px;
  out->height_px = impl_->config.height_px;
  DownsampleFlip(pixels, impl_->config.supersample, out);
  if (impl_->font && impl_->cylinder) {
    impl_->cylinder->DrawText(t_s, impl_->font.get(), out);
  } else if (impl_->font) {
    impl_->DrawText(t_s, out);
  }
}

Image FrameRenderer::Render(double t_s) {
  Image img;
  Render(t_s, &img);
  return img;
}

const FrameLayout& FrameRenderer::layout() const {
  return impl_->layout;
}
const RenderConfig& FrameRenderer::config() const {
  return impl_->config;
}
const Palette& FrameRenderer::palette() const {
  return impl_->palette;
}

}  // namespace rockbench::renders
