#pragma once
/// The page's Scene section: the blocks, the initial state and run settings, the base motion
/// (PGA, PGV, PGD and a plot of the record) and every engine's settings.
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "report/run/run_figures.h"

namespace rockbench::report {

void SceneSection(const RunData& run, const GroundMotion& motion, Figures& fig);

/// What the Scene section shares with a cylinder's (cylinder_sections.h): the heading "Scene"
/// and the line naming the scene file with its --set overrides.
void SceneFileHeading(const RunData& run, Page& page);
/// The scene table's row "run": the duration, the output interval and gravity.
std::vector<std::string> RunSettingsRow(const Scene& scene);
/// The heading "Engine settings" and its table: the reference model's settings in words
/// (`reference`), then each engine's as its summary.json states them.
void EngineSettingsTable(const RunData& run, const std::string& reference, Page& page);
/// The figure "base_motion" over [0, T] (s) with its data file `dat`: the time axis and the
/// base acceleration's (g); the caller appends the plot command.
GnuplotFigure BaseMotionFigure(const std::string& dat, double T);
/// Adds to `times` the times a plot of the base motion over [0, T] (s) passes through: the
/// record samples of each of `components` and both sides of every breakpoint (kinks and jumps).
void AddMotionPlotTimes(const GroundMotion& motion, double T,
                        std::initializer_list<const std::optional<MotionComponent>*> components,
                        std::set<double>& times);

}  // namespace rockbench::report
