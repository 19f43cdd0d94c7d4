#pragma once
/// The engines of this build: every engine listed in engines/CMakeLists.txt, built or left out
/// (with the reason). The harness reaches engines only through this list.
#include <string>
#include <vector>

#include "engines/common/engine.h"

namespace rockbench {

/// One registered engine.
struct RegisteredEngine {
  std::string name;            ///< "bullet"
  const Engine* engine;        ///< null when the build left it out
  std::string missing_reason;  ///< why it was left out ("libmujoco-dev not found")
};

/// Every registered engine, in registration order (built or not).
const std::vector<RegisteredEngine>& EngineRegistry();

/// The built engine `name`, or nullptr (not registered, or left out of this build).
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
