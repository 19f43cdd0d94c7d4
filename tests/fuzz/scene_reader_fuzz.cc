// Fuzz target scene_reader: the scene file reader, rockbench::ParseScene (src/scene/scene.h).
// Input: a scene file's text. Any answer but a Scene or a SceneError is a finding.
#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  // In scenes/, so that "../records/..." resolves as it does for the shipped scenes.
  static const std::filesystem::path path = rockbench::fuzz::SourceDir() / "scenes" / "fuzz.toml";
  rockbench::fuzz::ExpectOnlySceneErrors("scene_reader", [&] {
    const rockbench::Scene scene = rockbench::ParseScene(text, path);
    // A scene that was read must pass the same checks again when built in code.
    rockbench::ValidateScene(scene);
  });
  return 0;
}
