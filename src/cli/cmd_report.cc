// `rockbench report RUN_DIR... --out DIR`: a page per run folder (report.html, its Markdown twin
// report.md, figures, keyframes, animation) and DIR/index.html + index.md linking them. A folder
// holding sweep.csv gets the work-precision report instead.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "report/run/run_report.h"
#include "report/study/study_csv.h"
#include "report/study/study_report.h"
#include "report/sweep/work_precision.h"
#include "scene/scene.h"

namespace rockbench::cli {
namespace {
namespace fs = std::filesystem;

struct ReportOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool no_animation = false;
  bool no_keyframes = false;
  std::string animation_size = "640x360";
  double fps = 25.0;
};

// Exit code when the report cannot be made on this machine (gnuplot missing or failing,
// files not writable); bad input exits with kExitBadInput.
constexpr int kExitCannotReport = 1;

[[noreturn]] void Fail(int code, const std::string& message) {
  std::fprintf(stderr, "rockbench report: %s\n", message.c_str());
  throw CLI::RuntimeError(code);
}

// The page folder's name: the run folder's own name.
std::string RunName(const fs::path& dir) {
  const fs::path p = fs::absolute(dir).lexically_normal();
  return p.filename().empty() ? p.parent_path().filename().string() : p.filename().string();
}

void Execute(const ReportOptions& opt) {
  report::RunReportOptions ro;
  ro.animation = !opt.no_animation;
  ro.keyframes = !opt.no_keyframes;
  ro.animation_fps = opt.fps;
  std::smatch m;
  static const std::regex kSize(R"(^\s*(\d+)\s*[xX]\s*(\d+)\s*$)");
  if (!std::regex_match(opt.animation_size, m, kSize)) {
    Fail(kExitBadInput, "--animation-size " + opt.animation_size +
                            ": expected WIDTHxHEIGHT in pixels, e.g. 640x360");
  }
  ro.animation_width_px = ro.keyframe_width_px = std::stoi(m[1]);
  ro.animation_height_px = ro.keyframe_height_px = std::stoi(m[2]);
  if (ro.animation_width_px < 64 || ro.animation_height_px < 64 || ro.animation_width_px % 2 ||
      ro.animation_height_px % 2) {
    Fail(kExitBadInput, "--animation-size " + opt.animation_size +
                            ": width and height must be even and at least 64 px (H.264)");
  }
  if (!(opt.fps > 0.0 && opt.fps <= 120.0)) Fail(kExitBadInput, "--fps must be in (0, 120]");

  // Check every input and every name before any work: two runs of one name would overwrite
  // each other's page.
  std::map<std::string, std::string> seen;
  for (const std::string& in : opt.inputs) {
    const fs::path dir(in);
    if (!fs::is_directory(dir)) {
      Fail(kExitBadInput, in + ": not a run folder (expected a folder written by `rockbench run`, "
                               "`compare` or `sweep`)");
    }
    if (!fs::exists(dir / "sweep.csv") && !fs::exists(dir / "summary.json") &&
        !report::IsEnsembleFolder(dir)) {
      Fail(kExitBadInput, in + ": has neither summary.json (run or compare), sweep.csv (sweep) "
                               "nor study.json and members.csv (ensemble)");
    }
    const std::string name = RunName(dir);
    const auto [it, fresh] = seen.emplace(name, in);
    if (!fresh) {
      Fail(kExitBadInput, in + " and " + it->second + " have the same name '" + name +
                              "': their reports would share " + opt.out + "/" + name +
                              " (rename or copy one of them)");
    }
  }
  const fs::path out(opt.out);
  std::vector<report::IndexEntry> index;
  for (const std::string& in : opt.inputs) {
    const fs::path dir(in);
    try {
      if (report::IsEnsembleFolder(dir)) {
        const fs::path page = report::WriteEnsembleReport(dir, out);
        index.push_back(
            {page.filename().string(), "ensemble report: " + RunName(dir), "ensemble", 0});
        std::printf("%s: %s\n", in.c_str(), (page / "report.html").string().c_str());
        continue;
      }
      if (fs::exists(dir / "sweep.csv")) {
        const fs::path page = report::WriteSweepReport(dir, out);
        index.push_back(
            {page.filename().string(), "work-precision report: " + RunName(dir), "sweep", 0});
        std::printf("%s: %s\n", in.c_str(), (page / "report.html").string().c_str());
        continue;
      }
      const report::RunReportResult r = report::WriteRunReport(dir, out, ro);
      index.push_back({r.name, r.scene, r.outcome, static_cast<int>(r.warnings.size())});
      std::printf("%s: %s (%d figures, %zu validity warnings)\n", in.c_str(),
                  (r.page_dir / "report.html").string().c_str(), r.figure_count, r.warnings.size());
      for (const std::string& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
      for (const std::string& l : r.left_out) std::printf("  left out: %s\n", l.c_str());
    } catch (const SceneError& e) {
      Fail(kExitBadInput, e.what());
    } catch (const report::ReportInputError& e) {
      Fail(kExitBadInput, e.what());
    } catch (const std::invalid_argument& e) {
      Fail(kExitBadInput, e.what());
    } catch (const CLI::RuntimeError&) {
      throw;
    } catch (const std::runtime_error& e) {
      // A sweep report's errors are its sweep.csv's (file and line); a run report's other
      // failures are the machine's (gnuplot, rendering, files).
      Fail(fs::exists(dir / "sweep.csv") ? kExitBadInput : kExitCannotReport, e.what());
    }
  }
  report::WriteReportIndex(out, index);
  std::printf("index: %s\n", (out / "index.html").string().c_str());
}

}  // namespace

void RegisterReport(CLI::App& app) {
  auto opt = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand(
      "report", "HTML + Markdown report of run folders (from run/compare) or sweep folders");
  cmd->add_option("runs", opt->inputs, "Run folders (or sweep folders)")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder: OUT/<run name>/report.html, OUT/index.html")
      ->required();
  cmd->add_flag("--no-animation", opt->no_animation, "Leave the animation out");
  cmd->add_flag("--no-keyframes", opt->no_keyframes, "Leave the keyframes out");
  cmd->add_option("--animation-size", opt->animation_size,
                  "Keyframe and animation size WIDTHxHEIGHT, px (even)")
      ->capture_default_str();
  cmd->add_option("--fps", opt->fps, "Animation frames per second (real time)")
      ->capture_default_str();
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
