#pragma once
/// Rocking modes of two stacked blocks (Roussis 1999, section 4.2) and of one block.
#include <optional>
#include <string>
#include <string_view>

namespace rockbench {

/// Mode of response. Sign convention of the thesis: theta > 0 tilts right about the right corner.
/// - kRest: both blocks still.
/// - k1a/k1b: both rock, block 2 pivots on the same side as block 1 (1a: theta2 > theta1 > 0).
/// - k2a/k2b: both rock, block 2 pivots on the opposite side (2a: theta1 > 0, theta2 < theta1).
/// - k3a/k3b: locked together, theta2 = theta1 (3a: theta1 > 0).
/// - k4a/k4b: block 1 still, block 2 rocks on it (4a: theta2 > 0).
/// A single block (no block 2) uses kRest, k3a and k3b (the stack is the one block).
enum class Mode { kRest, k1a, k1b, k2a, k2b, k3a, k3b, k4a, k4b };

/// "rest", "1a", ..., "4b".
std::string_view ModeName(Mode mode);
/// Inverse of ModeName; nullopt for an unknown name.
std::optional<Mode> ParseMode(std::string_view name);

}  // namespace rockbench
