#pragma once
/// The parts of a run page that a cylinder (shape "cylinder", docs/three-d.md) has in place of a
/// planar stack's: its outcome in words (the overturn's time and azimuth), its scene and base
/// motion in three components, the tilt against time, the axis's path seen from above (tilt_y
/// against tilt_x, equal axes) and its events. The planar sections (theta angles, agreement,
/// impacts of the thesis's model, energy and friction of the planar model) have no meaning for
/// it and are left out (docs/report.md "The cylinder").
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "report/run/run_figures.h"
#include "report/run/run_readers.h"

namespace rockbench::report {

/// The reference's outcome and every engine's, in words; the warnings (the reference's
/// assumptions violated, an engine's significant monitor flags) into `warnings`.
std::string CylinderOutcome(const RunData& run, std::vector<std::string>& warnings);

/// The scene: the cylinder, its initial state, the landing clearance, the run; the base motion
/// (its components' peaks and a figure of the three accelerations); the engines' settings.
void CylinderSceneSection(const RunData& run, const GroundMotion& motion, Figures& fig);

/// The figure "tilt": every run's tilt against time, the overturns marked.
void CylinderTiltFigure(const RunData& run, Figures& fig);

/// The figure "axis_path": every run's tilt vector, tilt_y against tilt_x (rad, equal axes, the
/// critical angle atan(D / H) as a dashed circle when in range), the end of each path and each
/// run's overturn marked, the reference's labelled with its time and azimuth. Its data files
/// axis_path.<run>.dat carry t_s, tilt_x1_rad and tilt_y1_rad of each run's history.
void CylinderAxisPathFigure(const RunData& run, Figures& fig);

/// The events of every run: landings, rests, onsets, overturns and the rest, counted.
void CylinderEventsSection(const RunData& run, Figures& fig);

}  // namespace rockbench::report
