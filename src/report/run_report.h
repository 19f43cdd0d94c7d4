#pragma once
/// The report of a run folder (`rockbench compare` or `rockbench run` output): one page per
/// scene, written as a self-contained report.html and its Markdown twin report.md, with the
/// gnuplot figures (SVG plus the kept .gp script and .dat data of each) in figures/, keyframes
/// from renders/ in keyframes/ and the animation beside the page. docs/report.md lists what a
/// page contains and how to restyle a figure.
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/geometry.h"
#include "scene/history.h"
#include "scene/mode.h"
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

// ---- The physics behind the figures (public for the tests). ----

/// The mode the angles and rates of a sample imply (contacts: a block tilted or turning to a
/// side pivots on that side's corner; flat and still, it sits on its face). Engines' mode
/// columns come from their own monitors; this rule gives the energy one definition for all.
Mode ModeFromAngles(const Sample& sample, bool two_blocks);

/// Kinetic energy in the base frame plus gravitational potential energy (reference::Energy: the
/// value events.csv holds), J, of a sample, from its angles and rates in the mode of
/// ModeFromAngles.
double StateEnergy_j(const reference::Geometry& geo, const Sample& sample);

/// Kinetic energy in the base frame plus potential energy above the rest position, J, of a
/// sample, from its angles and rates with the rigid-block model (reference/kinematics.h) in the
/// mode of ModeFromAngles.
double EnergyAboveRest_j(const reference::Geometry& geo, const Sample& sample);

/// Friction the rigid-block model needs at a state: contact reactions (reference/kinematics.h
/// ComputeReactions) with the accelerations of `mode` (reference/modes.h) under base
/// acceleration (xg'', yg'').
struct FrictionDemand {
  double N_ground_n = 0.0, T_ground_n = 0.0;        ///< normal (compression > 0), tangential, N
  double N_interface_n = 0.0, T_interface_n = 0.0;  ///< block 1 on block 2, N
  double mu_ground = 0.0;                           ///< |T|/N at the ground (0 when N <= 0)
  double mu_interface = 0.0;                        ///< |T|/N at the interface (0 when N <= 0)
};
FrictionDemand RequiredFriction(const reference::Geometry& geo, Mode mode, const Sample& sample,
                                double xg_mps2, double yg_mps2, Equations equations);

/// Angles of a reference history at any time: cubic Hermite between samples, using the rates
/// before each event (events.csv omega*_before) at the end of the interval it closes, so that
/// impacts do not smear. Clamped to the history's time span.
class HistoryInterpolator {
 public:
  HistoryInterpolator(const History& history, const std::vector<Event>& events);
  /// (theta1, theta2) at t, rad.
  std::array<double, 2> Angles(double t_s) const;
  double end_s() const;

 private:
  struct Node {
    double t = 0.0;
    double theta[2] = {0, 0};
    double rate_right[2] = {0, 0};  ///< rates just after t
    double rate_left[2] = {0, 0};   ///< rates just before t (differ at an impact)
  };
  std::vector<Node> nodes_;
};

}  // namespace rockbench::report
