#pragma once
/// Single precision without linking two Bullets into one program: the float engine lives in the
/// helper program rockbench-bullet-float, run as a subprocess. The input goes to it in a
/// temporary file (protocol.h), its output comes back in another; see docs/bullet.md.
#include <filesystem>

#include "engine/engine.h"
#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {

/// The helper program's path: $ROCKBENCH_BULLET_FLOAT_HELPER if set, else rockbench-bullet-float
/// next to the running program, else the build tree's copy. Throws std::runtime_error naming
/// the places it looked when none exists.
std::filesystem::path FindFloatHelper();

/// Runs the single-precision engine in the helper program. Thread-safe (each call has its own
/// temporary files). Throws std::runtime_error when the helper is missing or fails.
EngineResult RunFloatHelper(const BulletInput& input);

}  // namespace rockbench::bullet
