#pragma once
/// An engine outside rockbench's process, in any language, behind the engine interface
/// (src/scene/engine.h) through the external-engine protocol (docs/external-engines.md): each run
/// writes an input file into a folder of its own, runs the engine's command on it under a
/// wall-clock and memory limit, reads the poses back and lets the engine-neutral monitor turn
/// them into modes, impacts, energy and validity flags, as for a built-in engine.
#include <memory>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engines/external/manifest.h"

namespace rockbench::external {

class ExternalEngine final : public Engine {
 public:
  explicit ExternalEngine(ExternalManifest manifest) : m_(std::move(manifest)) {}

  std::string name() const override { return m_.name; }
  std::string version() const override { return m_.version; }
  const EngineSettingsSchema& settings_schema() const override { return m_.schema; }
  std::vector<SweepSetting> SweepGrid(bool quick) const override;
  std::vector<SweepSetting> StressGrid() const override;
  /// Throws SceneError for a scene it cannot run (more blocks than its manifest's max_blocks, a
  /// setting out of range) and ExternalEngineError (protocol.h) for a run that failed: the
  /// command could not start, crashed, hung, ran out of memory or wrote poses the protocol
  /// refuses; the message names the engine, the file and the line.
  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override;

  const ExternalManifest& manifest() const { return m_; }

 private:
  ExternalManifest m_;
};

}  // namespace rockbench::external
