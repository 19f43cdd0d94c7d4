#pragma once
/// summary.json of a run: the base motion as read and the reference model's figures.
#include <nlohmann/json.hpp>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace rockbench {

/// The reference's typed outcome (status, overturn, peaks, impacts) of a result.
RunOutcome ReferenceOutcome(const reference::Result& result);

/// The reference's part of summary.json (status, peaks, impacts, overturn, friction...).
nlohmann::json ReferenceSummaryJson(const Scene& scene, const reference::Result& result,
                                    double wall_s);

/// The model options used, as written in summary.json's "model" object.
nlohmann::json ModelOptionsJson(const ModelConfig& model);

}  // namespace rockbench
