#include "report/run/pictures_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renders/animation.h"
#include "renders/drawn_motion.h"
#include "renders/gl_context.h"
#include "renders/renderer.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;

// Keyframe times: peaks of every angle, overturning, then the reference's first impacts.
struct Keyframe {
  double t_s = 0.0;
  std::vector<std::string> why;
  std::vector<int> impacts;  // numbers of the reference's impacts at this time
  std::string Caption() const {
    std::string out;
    for (const std::string& w : why) out += (out.empty() ? "" : "; ") + w;
    if (!impacts.empty()) {
      out += out.empty() ? "" : "; ";
      out += impacts.size() == 1 ? "impact " + std::to_string(impacts.front())
                                 : "impacts " + std::to_string(impacts.front()) + " to " +
                                       std::to_string(impacts.back());
      out += " of the reference";
    }
    return out;
  }
};

std::vector<Keyframe> KeyframeTimes(const RunData& run, int max_frames) {
  std::vector<Keyframe> chosen;
  // Times within 5 ms share a frame; `impact` > 0 is the reference's impact number.
  const auto add = [&](double t, const std::string& why, int impact = 0) {
    if (std::isnan(t)) return;
    Keyframe* k = nullptr;
    for (Keyframe& c : chosen) {
      if (std::abs(c.t_s - t) < 5e-3) k = &c;
    }
    if (k == nullptr) {
      if (static_cast<int>(chosen.size()) >= max_frames) return;
      chosen.push_back({t, {}, {}});
      k = &chosen.back();
    }
    if (impact > 0) {
      k->impacts.push_back(impact);
    } else {
      k->why.push_back(why);
    }
  };
  const EngineData& ref = run.engines.front();
  for (int b = 1; b <= run.scene.block_count(); ++b) {
    const std::string key = "peaks.theta" + std::to_string(b) + ".t_s";
    add(OptNumber(ref.summary, key, run.summary_path),
        "peak |theta" + std::to_string(b) + "| of the reference");
  }
  for (const EngineData& e : run.engines) {
    add(OptNumber(e.summary, "overturn.t_s", run.summary_path), "overturn (" + e.name + ")");
  }
  int impact = 0;
  for (const Event& ev : ref.events) {
    // "interface_impact" (two blocks), "interface2_impact" ... (N >= 3 blocks).
    const bool interface_impact = ev.kind.rfind("interface", 0) == 0 && ev.kind.size() >= 16 &&
                                  ev.kind.compare(ev.kind.size() - 7, 7, "_impact") == 0;
    if (ev.kind != "ground_impact" && !interface_impact) continue;
    ++impact;
    add(ev.t_s, "", impact);
  }
  std::sort(chosen.begin(), chosen.end(),
            [](const Keyframe& a, const Keyframe& b) { return a.t_s < b.t_s; });
  return chosen;
}

}  // namespace

void PicturesSection(const RunData& run, const GroundMotion& motion,
                     const RunReportOptions& options, Figures& fig, RunReportResult& result) {
  Page& page = *fig.page;
  if (!options.keyframes && !options.animation) {
    result.left_out.push_back(
        "keyframes and animation: left out on request (--no-keyframes, "
        "--no-animation)");
    return;
  }
  if (!renders::GlAvailable()) {
    result.left_out.push_back("keyframes and animation: " + renders::GlUnavailableReason());
    return;
  }
  std::vector<renders::Track> tracks;
  for (const EngineData& e : run.engines) tracks.push_back({e.name, e.history});
  renders::RenderConfig config;
  config.width_px = options.animation_width_px;
  config.height_px = options.animation_height_px;
  config.title = run.scene.title;
  const renders::BaseDisplacement base = renders::IntegrateBaseDisplacement(
      motion, run.t_end_s, renders::BaseIntegrationFor(run.scene));
  try {
    if (options.keyframes) {
      renders::RenderConfig kc = config;
      kc.width_px = options.keyframe_width_px;
      kc.height_px = options.keyframe_height_px;
      renders::FrameRenderer renderer(run.scene, tracks, base, kc);
      page.Heading("Keyframes");
      page.Paragraph(
          "Frames drawn from the histories (renders/): the reference solid, the "
          "engines outlined on top; the strip chart shows the angles up to that time.");
      int index = 0;
      for (const Keyframe& k : KeyframeTimes(run, options.max_keyframes)) {
        char name[64];
        std::snprintf(name, sizeof name, "keyframe_%02d.png", ++index);
        renders::WritePng(renderer.Render(k.t_s), fig.page_dir / "keyframes" / name);
        page.Figure(fs::path("keyframes") / name,
                    "t = " + Fixed(k.t_s, 4) + " s: " + k.Caption() + ".");
        ++fig.count;
      }
    } else {
      result.left_out.push_back("keyframes: left out on request (--no-keyframes)");
    }
    if (options.animation) {
      renders::FrameRenderer renderer(run.scene, tracks, base, config);
      renders::AnimationConfig anim;
      anim.out_dir = fig.page_dir;
      anim.fps = options.animation_fps;
      anim.mp4 = true;
      anim.name = "animation";
      const renders::AnimationResult r = renders::ExportAnimation(renderer, anim);
      if (!r.problems.empty()) {
        std::string all;
        for (const std::string& p : r.problems) all += (all.empty() ? "" : "; ") + p;
        result.left_out.push_back("animation: " + all);
        // Without ffmpeg the exporter falls back to PNG frames; they are not part of the page.
        std::error_code ec;
        fs::remove_all(fig.page_dir / "frames", ec);
      } else {
        page.Heading("Animation");
        page.Video("animation.mp4", "The whole run at real speed, " + Num(options.animation_fps) +
                                        " frames/s, " + std::to_string(config.width_px) + "x" +
                                        std::to_string(config.height_px) + " (H.264)");
      }
    } else {
      result.left_out.push_back("animation: left out on request (--no-animation)");
    }
  } catch (const renders::RenderError& e) {
    result.left_out.push_back(std::string("keyframes and animation: ") + e.what());
  }
}

}  // namespace rockbench::report
