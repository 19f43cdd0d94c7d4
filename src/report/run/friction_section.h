#pragma once
/// The page's Friction section: the friction coefficient the rigid-block model needs along the
/// reference's samples (reference/observables.h ContactReactions), against the engines'
/// friction, and the warnings it gives (sliding would occur, tension).
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/stack_model.h"
#include "report/run/run_figures.h"
#include "report/run/run_report.h"

namespace rockbench::report {

/// |T|/N and the normal forces along the reference's samples, per interface (0: block 1 on the
/// ground; k: block k + 1 on block k).
struct FrictionFacts {
  std::vector<double> max_mu;   ///< over the plotted samples
  std::vector<double> min_N;    ///< N
  std::vector<double> min_N_t;  ///< s
  int left_out = 0;  ///< samples left out (normal force below the option's share of the weight)
  std::vector<std::vector<double>> rows;  ///< t, mu of each interface (NaN: left out)
  Span span;                              ///< of the values kept
};

/// |T|/N along the reference's samples, left out where the normal force nearly vanishes.
FrictionFacts ComputeFriction(const RunData& run, const reference::StackModel& model,
                              const GroundMotion& motion, const RunReportOptions& options);

/// The smallest friction coefficient between the blocks (and the ground) among the run's
/// engines, as each states it in summary.json settings.friction_combined, and that engine's
/// name; nullopt when no engine of the run states one.
std::optional<std::pair<double, std::string>> EngineFriction(const RunData& run);

/// Appends the warnings of the friction facts: sliding would occur at a contact (the model
/// needs more friction than an engine has), tension (a negative normal force).
void FrictionWarnings(const RunData& run, const reference::StackModel& model,
                      const FrictionFacts& facts, std::vector<std::string>& warnings);

void FrictionSection(const RunData& run, const FrictionFacts& facts,
                     const RunReportOptions& options, Figures& fig);

}  // namespace rockbench::report
