#pragma once
/// The page's Friction section: the friction coefficient the rigid-block model needs along the
/// reference's samples (reference/observables.h ContactReactions), against the engines'
/// friction, and the warnings it gives (sliding would occur, tension).
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reference/geometry.h"
#include "report/run/run_figures.h"
#include "report/run/run_report.h"
#include "scene/ground_motion.h"

namespace rockbench::report {

/// |T|/N and the normal forces along the reference's samples.
struct FrictionFacts {
  double max_ground = 0.0, max_interface = 0.0;                      ///< over the plotted samples
  double min_N_ground = std::numeric_limits<double>::infinity();     ///< N
  double min_N_interface = std::numeric_limits<double>::infinity();  ///< N
  double min_N_ground_t = 0.0, min_N_interface_t = 0.0;              ///< s
  int left_out = 0;  ///< samples left out (normal force below the option's share of the weight)
  std::vector<std::array<double, 3>> rows;  ///< t, mu ground, mu interface (NaN: left out)
  Span span;                                ///< of the values kept
};

/// |T|/N along the reference's samples, left out where the normal force nearly vanishes.
FrictionFacts ComputeFriction(const RunData& run, const reference::Geometry& geo,
                              const GroundMotion& motion, const RunReportOptions& options);

/// The smallest friction coefficient between the blocks (and the ground) among the run's
/// engines, as each states it in summary.json settings.friction_combined, and that engine's
/// name; nullopt when no engine of the run states one.
std::optional<std::pair<double, std::string>> EngineFriction(const RunData& run);

/// Appends the warnings of the friction facts: sliding would occur at a contact (the model
/// needs more friction than an engine has), tension (a negative normal force).
void FrictionWarnings(const RunData& run, const reference::Geometry& geo,
                      const FrictionFacts& facts, std::vector<std::string>& warnings);

void FrictionSection(const RunData& run, const FrictionFacts& facts,
                     const RunReportOptions& options, Figures& fig);

}  // namespace rockbench::report
