#pragma once
/// The page's Keyframes and Animation: frames drawn from the histories (renders/) at the peaks,
/// overturning and the reference's first impacts, and the animation of the whole run.
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "report/run/run_figures.h"
#include "report/run/run_report.h"

namespace rockbench::report {

/// A keyframe: its time and why it was chosen.
struct Keyframe {
  double t_s = 0.0;
  std::vector<std::string> why;  ///< peaks and overturns at this time ("peak |theta2| of ...")
  std::vector<int> impacts;      ///< numbers of the reference's impacts at this time, ascending
  /// "peak |theta1| of the reference; impacts 3 to 4 of the reference".
  std::string Caption() const;
};

/// The keyframes of a run, in time order, at most `max_frames` (times within 5 ms share one):
/// the reference's peak of every block, each run's overturn, then the reference's impacts.
/// One and two blocks: in that order, the impacts in time order. N >= 3 blocks, fair across the
/// blocks: the overturns first; the peaks, spread evenly from block 1 to block N when there
/// are more blocks than frames; the impacts in rounds over the interfaces (each one's first
/// impact, then each one's second, ...), so that no block's events take every frame left.
std::vector<Keyframe> KeyframeTimes(const RunData& run, int max_frames);

void PicturesSection(const RunData& run, const GroundMotion& motion,
                     const RunReportOptions& options, Figures& fig, RunReportResult& result);

}  // namespace rockbench::report
