#pragma once
/// The Bullet engine's entry point, free of Bullet headers. Compiled into rockbench_bullet
/// (double precision, used in process by the harness) and rockbench_bullet_float (single
/// precision, used only by the helper program rockbench-bullet-float).
#include "engine/engine.h"
#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {

/// "double" or "float": the btScalar this library was compiled with.
const char* CompiledPrecision();

/// Runs the engine in this process: builds the world, steps it input.steps times (stopping
/// early at overturn or blow-up) and returns the history, events and summary. Physics
/// outcomes never throw; throws std::invalid_argument when input.config.precision is not the
/// precision this library was compiled with.
EngineResult Simulate(const BulletInput& input);

}  // namespace rockbench::bullet
