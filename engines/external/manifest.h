#pragma once
/// An external engine's manifest (docs/external-engines.md): the command that runs it, what it
/// says of itself, the keys of its settings table and the grids of the work-precision sweep and
/// the stress catalogue. A TOML file; a scene or registry that gives only a command gets the
/// protocol's standard settings and grids.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "engine/engine.h"
#include "scene/engine_settings.h"
#include "scene/scene.h"

namespace rockbench::external {

/// The protocol version this build speaks (the input's "protocol_version", the manifest's
/// `protocol`).
inline constexpr int kProtocolVersion = 1;

/// One settings family of the sweep: a curve of the work-precision figure.
/// The largest manifest file, bytes: a manifest is a few kB (the repository's are under 2 kB);
/// 1 MiB holds thousands of settings tables. A larger file is refused before it is parsed.
inline constexpr std::int64_t kMaxManifestBytes = std::int64_t{1} << 20;
/// The most [settings.<key>] tables, [[sweep.family]] tables and entries of one array (command,
/// drives, requires, choices, sweep steps) a manifest may have: the built-in engines have at
/// most 20 settings and 4 families; the caps keep every look-up of a run small.
inline constexpr std::int64_t kMaxManifestSettings = 1000;
inline constexpr std::int64_t kMaxManifestFamilies = 100;
inline constexpr std::int64_t kMaxManifestArray = 1000;

struct ExternalFamily {
  std::string name;  ///< "Rapier (ours)": the settings that stay fixed along it
  std::string id;    ///< the stress cases' prefix: "ours"
  std::vector<std::pair<std::string, SettingValue>> settings;  ///< what it sets besides the step
};

struct ExternalManifest {
  std::string name;            ///< the engine's name and table: "rapier"
  std::string where;           ///< where it was named: "FILE:LINE"
  std::filesystem::path file;  ///< the manifest (empty: a bare command)
  /// The command with relative program and file arguments made absolute; the input file's path
  /// is appended when it runs.
  std::vector<std::string> command;
  std::string version;          ///< "Rapier 0.20.0 (...)"; a bare command: "external: COMMAND"
  int max_blocks = kMaxBlocks;  ///< the most blocks it simulates
  /// The drives it takes: "inertial" and/or "kinematic" (the input's drive.kind).
  std::vector<std::string> drives = {"inertial"};
  /// Files (relative to the manifest) that must exist for it to run: its installed packages.
  std::vector<std::filesystem::path> requires_files;
  /// The hint when one is missing ("run scripts/install-deps.sh").
  std::string install_hint;
  /// The settings table's keys: the protocol's standard ones, then the manifest's.
  EngineSettingsSchema schema;
  /// Sweep steps (s): the full grid and the CI's; the stress catalogue's, the CI subset being
  /// each family's coarsest.
  std::vector<double> sweep_steps_s = {1.0 / 60.0, 1e-3, 1e-4, 1e-5};
  std::vector<double> quick_steps_s = {1e-3, 1e-4};
  std::vector<double> stress_steps_s = {1.0 / 60.0, 1e-3, 1e-4, 1e-5};
  std::vector<ExternalFamily> families;  ///< at least one (a bare command: "NAME")
  /// Why it cannot run on this machine (its program or a required file is missing); empty:
  /// it can.
  std::string missing_reason;
};

/// The manifest of an engine a scene or registry names: reads `ref.manifest`, or makes the
/// standard one of `ref.command`. Throws SceneError naming the file, line and key of a bad
/// manifest, and a manifest that is not a regular file or is past the caps above (naming the
/// file and the cap). A program or required file that is missing is not an error:
/// missing_reason says it. Reading takes time linear in the file's size.
ExternalManifest LoadManifest(const ExternalEngineRef& ref);

/// The standard keys every external engine's table has (docs/external-engines.md): time_step,
/// drive (of `drives`), kinematic_highpass_hz, output_every_steps, wall_limit_s and
/// memory_limit_mib (with the given defaults).
void AddProtocolSettings(EngineSettingsSchema& schema, const std::vector<std::string>& drives,
                         double wall_limit_s, double memory_limit_mib);

/// The values of the standard keys that rockbench itself reads (the time step and the drive go
/// to MakeEngineInput), from a table resolved against a schema with AddProtocolSettings.
struct ProtocolSettings {
  std::int64_t output_every_steps = 1;  ///< poses written every this many steps
  double wall_limit_s = 0.0;            ///< the run is killed past this wall-clock time, s
  double memory_limit_mib = 0.0;        ///< ... or past this resident memory, MiB
};
ProtocolSettings ReadProtocolSettings(const EngineSettings& settings);

}  // namespace rockbench::external
