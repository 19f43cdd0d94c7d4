#pragma once
/// The Bullet branch of the engine registry (engines.cc calls it for "bullet" when the build
/// has Bullet, ROCKBENCH_HAVE_BULLET).
#include <limits>

#include "harness/engines.h"

namespace rockbench {

/// Runs the Bullet engine on a scene: double precision in this process, single precision
/// ([bullet] precision = "float") in the helper program rockbench-bullet-float. The summary is
/// the engine's part of summary.json (settings, wall_s, peaks, impacts, violations: slip,
/// uplift, penetration, energy growth, blow-up; status). Physics outcomes never throw; throws
/// SceneError for impossible [bullet] settings or a missing/failed helper program.
/// `stop_at_rest_after_s`: see RunEngineOptions.
EngineRun RunBulletEngine(const Scene& scene, const GroundMotion& motion,
                          double stop_at_rest_after_s = std::numeric_limits<double>::infinity());

}  // namespace rockbench
