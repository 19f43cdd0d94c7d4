// Fuzz target scene_overrides: the CLI's `--set key=value` overrides on a shipped scene,
// rockbench::ParseScene(text, path, overrides) (src/scene/scene.h).
// Input: the first line names a shipped scene (a file name in scenes/, e.g. "harmonic.toml"; an
// unknown name picks one by the sum of its bytes), every further line is one override string as
// the CLI passes it (empty lines included). Any answer but a Scene or a SceneError is a finding.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "tests/fuzz/fuzz_target.h"

namespace {

struct ShippedScene {
  std::string name;
  std::filesystem::path path;
  std::string text;
};

// scenes/*.toml, sorted by name, read once.
const std::vector<ShippedScene>& ShippedScenes() {
  static const std::vector<ShippedScene> scenes = [] {
    std::vector<ShippedScene> v;
    const std::filesystem::path dir = rockbench::fuzz::SourceDir() / "scenes";
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".toml") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      v.push_back({entry.path().filename().string(), entry.path(), text.str()});
    }
    std::sort(v.begin(), v.end(),
              [](const ShippedScene& a, const ShippedScene& b) { return a.name < b.name; });
    if (v.empty()) rockbench::fuzz::Finding("scene_overrides: no scenes/*.toml to start from");
    return v;
  }();
  return scenes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  std::vector<std::string> lines;
  size_t start = 0;
  while (true) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  const std::vector<ShippedScene>& scenes = ShippedScenes();
  const std::string& name = lines.front();
  auto it = std::find_if(scenes.begin(), scenes.end(),
                         [&](const ShippedScene& s) { return s.name == name; });
  if (it == scenes.end()) {
    size_t sum = 0;
    for (unsigned char c : name) sum += c;
    it = scenes.begin() + static_cast<std::ptrdiff_t>(sum % scenes.size());
  }
  const std::vector<std::string> overrides(lines.begin() + 1, lines.end());
  rockbench::fuzz::ExpectOnlySceneErrors("scene_overrides", [&] {
    const rockbench::Scene scene = rockbench::ParseScene(it->text, it->path, overrides);
    rockbench::ValidateScene(scene);
  });
  return 0;
}
