#include "scene/mode.h"

#include <array>

namespace rockbench {
namespace {
constexpr std::array<std::string_view, 9> kNames = {"rest", "1a", "1b", "2a", "2b",
                                                    "3a",   "3b", "4a", "4b"};
}  // namespace

std::string_view ModeName(Mode mode) {
  return kNames[static_cast<int>(mode)];
}

std::optional<Mode> ParseMode(std::string_view name) {
  for (size_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) return static_cast<Mode>(i);
  }
  return std::nullopt;
}

}  // namespace rockbench
