#pragma once
/// summary.json of a run: the base motion as read and the reference model's figures.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_run.h"
#include "scene/scene.h"

namespace rockbench {

/// The reference's typed outcome (status, overturn, peaks, impacts) of a result.
RunOutcome ReferenceOutcome(const reference::Result& result);

/// The reference's part of summary.json (status, peaks, impacts, overturn, friction...).
nlohmann::json ReferenceSummaryJson(const Scene& scene, const reference::Result& result,
                                    double wall_s);

/// The model options used, as written in summary.json's "model" object.
nlohmann::json ModelOptionsJson(const ModelConfig& model);

/// summary.json of `rockbench run` (and of the Python module's run): the scene (its absolute
/// path, "" for a scene given as text, and the overrides), the base motion as read, and each
/// run's part where its engine says (AddRunSummary), in the order given.
nlohmann::json RunSummaryJson(const std::filesystem::path& scene_path,
                              const std::vector<std::string>& overrides, const Scene& scene,
                              const GroundMotion& motion,
                              const std::vector<const EngineRun*>& runs);

/// What `run` says of the base motion as read, one line each: "base.vertical padded with 60
/// zero samples to match the other component's length" for each padded component.
std::vector<std::string> PaddingNotes(const GroundMotion& motion);

}  // namespace rockbench
