#include "report/run/pictures_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "engine/outcome.h"
#include "renders/animation.h"
#include "renders/drawn_motion.h"
#include "renders/gl_context.h"
#include "renders/renderer.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"

namespace rockbench::report {

namespace fs = std::filesystem;

std::string Keyframe::Caption() const {
  std::string out;
  for (const std::string& w : why) out += (out.empty() ? "" : "; ") + w;
  if (!impacts.empty()) {
    out += out.empty() ? "" : "; ";
    out += impacts.size() == 1 ? std::string("impact ") + std::to_string(impacts.front())
                               : std::string("impacts ") + std::to_string(impacts.front()) +
                                     " to " + std::to_string(impacts.back());
    out += " of the reference";
  }
  return out;
}

namespace {

// "ground_impact", "interface_impact" (two blocks), "interface2_impact" ... (N >= 3 blocks).
bool IsImpact(const Event& ev) {
  return ImpactInterface(ev.kind) >= 0;
}

// The blocks 1..n in the order their peaks claim frames: in order when the frames suffice;
// else `frames` blocks spread evenly from the bottom to the top first (1 and n among them), then
// the rest, so that a tall stack's frames do not all go to its lower blocks.
std::vector<int> PeakOrder(int n, int frames) {
  std::vector<int> order;
  std::vector<bool> taken(static_cast<size_t>(n) + 1, false);
  if (n > frames && frames >= 2) {
    for (int i = 0; i < frames; ++i) {
      const int b =
          1 + static_cast<int>(std::lround(static_cast<double>(i) * (n - 1) / (frames - 1)));
      if (!taken[b]) order.push_back(b);
      taken[b] = true;
    }
  }
  for (int b = 1; b <= n; ++b) {
    if (!taken[b]) order.push_back(b);
  }
  return order;
}

}  // namespace

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
  const int blocks = run.scene.block_count();
  // A cylinder's peak is its tilt's (summary.json peaks.tilt1).
  const bool cylinder = run.scene.three_dimensional();
  const auto add_peak = [&](int b) {
    const std::string key = (cylinder ? "peaks.tilt" : "peaks.theta") + std::to_string(b) + ".t_s";
    add(OptNumber(ref.summary, key, run.summary_path),
        cylinder ? "peak tilt of the reference"
                 : "peak |theta" + std::to_string(b) + "| of the reference");
  };
  const auto add_overturns = [&] {
    for (const EngineData& e : run.engines) {
      add(OptNumber(e.summary, "overturn.t_s", run.summary_path), "overturn (" + e.name + ")");
    }
  };
  if (blocks <= 2) {
    // One and two blocks: the peaks, the overturns, then the reference's impacts in time order.
    for (int b = 1; b <= blocks; ++b) add_peak(b);
    add_overturns();
    int impact = 0;
    for (const Event& ev : ref.events) {
      if (IsImpact(ev)) add(ev.t_s, "", ++impact);
    }
  } else {
    // N >= 3 blocks: fair across the blocks. The overturns first (more peaks than frames would
    // crowd them out), the peaks spread over the stack, then the impacts in rounds: every
    // interface's first impact (in time order), then every interface's second, ..., so that
    // the chatter of one interface cannot take every frame left.
    add_overturns();
    for (const int b : PeakOrder(blocks, max_frames - static_cast<int>(chosen.size()))) {
      add_peak(b);
    }
    std::vector<std::pair<int, int>> rounds;  // (rank within its interface, impact number)
    std::map<std::string, int> seen;          // impacts so far per interface (event kind)
    std::vector<double> times;
    for (const Event& ev : ref.events) {
      if (!IsImpact(ev)) continue;
      times.push_back(ev.t_s);
      rounds.push_back({seen[ev.kind]++, static_cast<int>(times.size())});
    }
    std::sort(rounds.begin(), rounds.end());
    for (const auto& r : rounds) add(times[r.second - 1], "", r.second);
    // Each frame's text as in time order: its peaks by block, then the overturns.
    const auto rank = [](const std::string& why) {
      const std::string peak = "peak |theta";
      return why.rfind(peak, 0) == 0 ? std::stoi(why.substr(peak.size())) : kMaxBlocks + 1;
    };
    for (Keyframe& k : chosen) {
      std::sort(k.impacts.begin(), k.impacts.end());
      std::stable_sort(k.why.begin(), k.why.end(), [&](const std::string& a, const std::string& b) {
        return rank(a) < rank(b);
      });
    }
  }
  std::sort(chosen.begin(), chosen.end(),
            [](const Keyframe& a, const Keyframe& b) { return a.t_s < b.t_s; });
  return chosen;
}

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
          run.scene.three_dimensional()
              ? "Frames drawn from the histories (renders/): the cylinder in perspective, the "
                "reference solid, the engines outlined on top, an arrow on the base toward "
                "each one's lean; the square on the right is the axis's path seen from above "
                "up to that time."
              : "Frames drawn from the histories (renders/): the reference solid, the "
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
