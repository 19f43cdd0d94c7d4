#pragma once
/// The engines of this build: every engine listed in engines/CMakeLists.txt, built or left out
/// (with the reason). The harness reaches engines only through this list.
#include <string>
#include <string_view>
#include <vector>

#include "scene/engine.h"

namespace rockbench {

/// The reference's name: the engine every other is compared with (run/reference_engine.h).
inline constexpr std::string_view kReferenceEngine = "reference";

/// Whether `engine` is the reference: the one place the harness tells the reference's role (the
/// baseline of every comparison) from the engines'; both run through the same interface.
inline bool IsReference(std::string_view engine) {
  return engine == kReferenceEngine;
}

/// One registered engine.
struct RegisteredEngine {
  std::string name;            ///< "bullet"
  const Engine* engine;        ///< null when the build left it out
  std::string missing_reason;  ///< why it was left out ("libmujoco-dev not found")
};

/// Every registered engine, in registration order (built or not): the built-in engines, then
/// the external ones (docs/external-engines.md) of the repository's registry
/// (engines/external_engines.toml), of the registry files ROCKBENCH_EXTERNAL_ENGINES names
/// (separated by ':') and of the scenes loaded so far. An external engine that cannot run here
/// (its program or packages missing) is listed as left out, with the reason.
std::vector<RegisteredEngine> EngineRegistry();

/// Registers the external engines a scene names ([external.<name>]). A name taken by a
/// built-in engine or by another external engine named differently is a SceneError naming both
/// places; the same engine named again is registered once. CheckEngineTables calls it.
void RegisterExternalEngines(const Scene& scene);

/// The engine `name`: "reference" (run/reference_engine.h) or a built physics engine; nullptr
/// when it is not registered or was left out of this build.
const Engine* FindEngine(const std::string& name);

/// Names of the built engines, in registration order.
std::vector<std::string> BuiltEngineNames();

/// Engine names from a --engines value: a comma-separated list of built engine names, or "all"
/// (every built engine). Throws SceneError naming an unknown or left-out engine (and why).
std::vector<std::string> ParseEngineList(const std::string& text);

/// Checks every engine table of a scene: a built engine's against its schema (SceneError naming
/// FILE:LINE and the key), a left-out engine's is kept unchecked, any other table is an error
/// naming the scene's tables and the engines.
void CheckEngineTables(const Scene& scene);

/// "bullet (Bullet 3.24 ...)\nmujoco: left out (libmujoco-dev not found)\n...", one line each.
std::string EngineListText();

}  // namespace rockbench
