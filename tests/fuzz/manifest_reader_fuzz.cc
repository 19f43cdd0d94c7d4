// Fuzz target manifest_reader: an external engine's manifest (rockbench::external::LoadManifest,
// engines/external/manifest.h), then its settings table resolved with the defaults, as a scene
// naming the engine without a table of its own gets it. Input: the manifest's text. The contract
// (issue 38): a manifest, or a SceneError whose message shows no control byte of the file; a
// manifest read has a command, at least one family, unique setting keys, family settings that
// are keys of the table (not the step), positive finite sweep steps, and every count within the
// manifest's caps. Anything else is a finding.
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <set>

#include "engines/external/manifest.h"
#include "scene/engine_settings.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

using rockbench::fuzz::Finding;

void CheckSteps(const std::vector<double>& steps, const char* which) {
  if (steps.empty() ||
      static_cast<std::int64_t>(steps.size()) > rockbench::external::kMaxManifestArray) {
    Finding(std::string("manifest_reader: ") + which + " has " + std::to_string(steps.size()) +
            " steps");
  }
  for (const double s : steps) {
    if (!(std::isfinite(s) && s > 0.0)) {
      Finding(std::string("manifest_reader: ") + which + " holds a step that is not positive");
    }
  }
}

void CheckManifest(const rockbench::external::ExternalManifest& m) {
  if (m.command.empty()) Finding("manifest_reader: a manifest without a command");
  if (m.families.empty()) Finding("manifest_reader: a manifest without a family");
  if (static_cast<std::int64_t>(m.families.size()) > rockbench::external::kMaxManifestFamilies) {
    Finding("manifest_reader: more families than the cap");
  }
  if (m.max_blocks < 1 || m.max_blocks > rockbench::kMaxBlocks) {
    Finding("manifest_reader: max_blocks " + std::to_string(m.max_blocks));
  }
  std::set<std::string> keys;
  for (const rockbench::SettingDef& d : m.schema.settings) {
    if (!keys.insert(d.key).second) Finding("manifest_reader: setting '" + d.key + "' twice");
  }
  // The standard keys (at most 7) and the manifest's own.
  if (static_cast<std::int64_t>(keys.size()) > rockbench::external::kMaxManifestSettings + 7) {
    Finding("manifest_reader: more settings than the cap");
  }
  for (const rockbench::external::ExternalFamily& f : m.families) {
    for (const auto& [key, value] : f.settings) {
      if (key == "time_step" || keys.count(key) == 0) {
        Finding("manifest_reader: family '" + f.name + "' sets '" + key + "'");
      }
    }
  }
  CheckSteps(m.sweep_steps_s, "sweep.steps_s");
  CheckSteps(m.quick_steps_s, "sweep.quick_steps_s");
  CheckSteps(m.stress_steps_s, "sweep.stress_steps_s");
}

void CheckMessage(const std::string& what) {
  for (const char c : what) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      Finding("manifest_reader: a message with the byte " + std::to_string(u) +
              " unquoted: " + what.substr(0, 200));
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() /
                   ("rockbench_fuzz_manifest_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  static const rockbench::Scene scene = rockbench::ParseScene(
      "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n", dir / "scene.toml");
  rockbench::ExternalEngineRef ref;
  ref.name = "fuzz";
  ref.where = "scene.toml:1";
  ref.manifest = dir / "manifest.toml";
  ref.base_dir = dir;
  std::ofstream(ref.manifest, std::ios::binary | std::ios::trunc)
      << rockbench::fuzz::Text(data, size);
  try {
    const rockbench::external::ExternalManifest m = rockbench::external::LoadManifest(ref);
    CheckManifest(m);
    // A default outside its own range is a SceneError here, as for a scene without a table.
    rockbench::fuzz::ExpectOnlySceneErrors("manifest_reader (ResolveEngineSettings)", [&] {
      (void)rockbench::ResolveEngineSettings(scene, m.schema);
    });
  } catch (const rockbench::SceneError& e) {
    CheckMessage(e.what());
  } catch (const std::exception& e) {
    Finding(std::string("manifest_reader: an exception other than SceneError escaped: ") +
            std::string(e.what()).substr(0, 2000));
  }
  return 0;
}
