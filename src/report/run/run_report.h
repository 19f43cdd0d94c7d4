#pragma once
/// The report of a run folder (`rockbench compare` or `rockbench run` output): one page per
/// scene, written as a self-contained report.html and its Markdown twin report.md, with the
/// gnuplot figures (SVG plus the kept .gp script and .dat data of each) in figures/, keyframes
/// from renders/ in keyframes/ and the animation beside the page. docs/report.md lists what a
/// page contains and how to restyle a figure. The page's parts are one file each: run_readers.h
/// (reading the folder), run_figures.h (what the figures share), interpolation.h, and the
/// sections (outcome, scene, angles, agreement, impacts, energy, friction, pictures); this file
/// assembles them.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::report {

/// The run folder is not usable: a file missing or malformed, a key missing or of the wrong
/// type, the scene file gone. The message names the file (and key or line). Other failures
/// (gnuplot, rendering, writing files) are plain std::runtime_error.
struct ReportInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a run report contains beyond its figures.
struct RunReportOptions {
  bool keyframes = true;          ///< PNG frames at the peaks and first impacts
  int max_keyframes = 8;          ///< at most this many keyframes
  int keyframe_width_px = 640;    ///< keyframe size, px
  int keyframe_height_px = 360;   ///<
  bool animation = true;          ///< animation.mp4 (H.264 through ffmpeg) beside the page
  int animation_width_px = 640;   ///< animation size, px (even: H.264 yuv420p)
  int animation_height_px = 360;  ///<
  double animation_fps = 25.0;    ///< frames per second, real time
  /// Required-friction samples where a contact's normal force is below this fraction of the
  /// stack's weight are left out of the friction figure (|T|/N has no meaning as N -> 0).
  double friction_min_normal_fraction = 0.01;
  /// Figure errors below this are drawn at it (log axis; the first sample's error is 0), rad.
  double error_floor_rad = 1e-10;
};

/// What WriteRunReport made, for the CLI and the index page.
struct RunReportResult {
  std::string name;                   ///< the run folder's name (the page folder's name)
  std::filesystem::path page_dir;     ///< OUT_DIR/<name>
  std::string title;                  ///< the page title
  std::string scene;                  ///< the scene's title (or its file name)
  std::string outcome;                ///< one line: the reference's status and the engines
  std::vector<std::string> warnings;  ///< validity warnings, as on the page
  std::vector<std::string> left_out;  ///< parts left out and why (options, no ffmpeg, ...)
  int figure_count = 0;               ///< figures on the page (plots and keyframes)
};

/// Writes the report of RUN_DIR into OUT_DIR/<run folder name>/: report.html, report.md,
/// figures/*.svg|.gp|.dat, keyframes/*.png and animation.mp4. Reads RUN_DIR/summary.json (the
/// scene path and overrides: the scene is reloaded for its geometry, base motion and friction),
/// comparison.json when present and <engine>/history.csv and events.csv. Throws
/// ReportInputError naming the file (and key or line) that is missing or malformed, or the
/// scene file that is gone; SceneError for a scene that no longer loads.
RunReportResult WriteRunReport(const std::filesystem::path& run_dir,
                               const std::filesystem::path& out_dir,
                               const RunReportOptions& options = {});

/// One line of the index page.
struct IndexEntry {
  std::string name;     ///< page folder name, relative to the index
  std::string title;    ///< page title
  std::string outcome;  ///< one line
  int warning_count = 0;
};

/// Writes OUT_DIR/index.html and index.md linking OUT_DIR/<name>/report.html (.md).
void WriteReportIndex(const std::filesystem::path& out_dir, const std::vector<IndexEntry>& pages);

}  // namespace rockbench::report
