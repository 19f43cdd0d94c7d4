#pragma once
/// The Bullet engine's cylinder run (shape "cylinder", issue 41), free of Bullet headers. Built
/// in double precision only (rockbench_bullet, in process): the single-precision helper program
/// does not build the cylinder, and the adapter refuses a float cylinder scene (SceneError).
#include "engine/engine.h"
#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {

/// Runs the cylinder of `input` (one body, shape "cylinder") in this process with RunCylinderWorld
/// (engines/common/cylinder_world.h). Physics outcomes never throw; throws std::invalid_argument
/// when the input asks for single precision.
EngineResult SimulateCylinder(const BulletInput& input);

}  // namespace rockbench::bullet
