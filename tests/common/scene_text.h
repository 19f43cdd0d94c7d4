#pragma once
// Scenes as TOML text, for the tests of the scene's reader and its rules.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rockbench::testing_util {

/// The thesis's two blocks in [block1] and [block2] tables; tests append or edit tables.
inline const std::string kThesisBlocksToml =
    "[block1]\nwidth = 1.25\nheight = 1.25\ndensity = 2500.0\n"
    "[block2]\nwidth = 1.0\nheight = 2.5\ndensity = 2500.0\n";

/// The message of the SceneError that parsing `text` (as the file `path`, with `overrides`)
/// throws; "" when it parses.
inline std::string SceneErrorOf(const std::string& text,
                                const std::vector<std::string>& overrides = {},
                                const std::filesystem::path& path = "scenes/x.toml") {
  try {
    ParseScene(text, path, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace rockbench::testing_util
