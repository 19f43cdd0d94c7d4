#pragma once
/// The engines of this build: every engine listed in engines/CMakeLists.txt, built or left out
/// (with the reason). The harness reaches engines only through this list.
#include <string>
#include <string_view>
#include <vector>

#include "engine/engine.h"

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
  /// Where a scene brought it: "FILE:LINE" of the scene's [external.<name>] table; empty for a
  /// built-in engine and for one of a registry file the user owns. Such an engine is data of
  /// the scene, not the user's word: it runs only once the user names it (ParseEngineList).
  std::string brought_by;
  /// A scene-brought engine the user has not named: left out of "all" and of BuiltEngineNames,
  /// and refused in a study's engine list (CheckEngineName).
  bool awaits_user = false;
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

/// Names of the built engines the user may run without naming them, in registration order: the
/// built-in engines and those of the registry files (and any scene-brought engine the user named
/// on the command line): never one a scene brought on its own.
std::vector<std::string> BuiltEngineNames();

/// Engine names from a --engines value the user typed: a comma-separated list of built engine
/// names, or "all" (BuiltEngineNames: the built-in and registered engines, not those a scene
/// brings). Naming a scene-brought engine ([external.<name>] in the scene) is the user's word
/// to run it. Throws SceneError naming an unknown or left-out engine (and why).
std::vector<std::string> ParseEngineList(const std::string& text);

/// The engines of a --engines value besides the reference, which every comparison and sweep runs
/// anyway: ParseEngineList of the list without the name "reference" (naming it adds nothing);
/// empty when the list names the reference alone. Throws as ParseEngineList.
std::vector<std::string> ParseEnginesBesideReference(const std::string& text);

/// The engines of `selected` that build the bodies of `scene` (engine/engine.h's
/// CheckBuildsBodies), in order; one line per engine left out, "rockbench: compare: not run:
/// SCENE: block1.shape: the engine 'box2d' builds bodies of shape ...", in *not_run. For "all" on
/// a scene whose bodies some engines do not build (a cylinder in a planar engine).
std::vector<std::string> EnginesThatBuild(const Scene& scene,
                                          const std::vector<std::string>& selected,
                                          std::string* not_run);

/// Checks one engine name that a file (not the user) lists, as a study's `engines` does: the
/// reference, or a built engine of the build or of a registry file the user owns. Throws SceneError
/// (without a place: the caller adds the file and key) for a text that is no single engine name
/// ("all", "bullet,ode", " bullet"), an unknown or left-out engine, and a scene-brought engine the
/// user has not named, saying how to opt in.
void CheckEngineName(const std::string& name);

/// How to opt in to the scene-brought engine `name` ("name it on the command line: --engines
/// NAME, or add its [external.NAME] table to a registry file you own: ...").
std::string OptInText(const std::string& name);

/// One line per scene-brought engine the user has not named and `selected` leaves out:
/// "rockbench: not run: external engine X, which FILE:LINE brings ([external.X]): ...how to opt
/// in"; empty when there is none. `compare` and `sweep` print it when the engines were "all".
std::string NotRunNote(const std::vector<std::string>& selected);

/// Checks every engine table of a scene: a built engine's against its schema (SceneError naming
/// FILE:LINE and the key), a left-out engine's is kept unchecked, any other table is an error
/// naming the scene's tables and the engines.
void CheckEngineTables(const Scene& scene);

/// "bullet (Bullet 3.24 ...)\nmujoco: left out (libmujoco-dev not found)\n...", one line each.
std::string EngineListText();

}  // namespace rockbench
