#pragma once
/// Wall-clock time of runs (reported beside results, never part of them).
#include <chrono>

namespace rockbench {

/// Seconds elapsed on the steady clock since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rockbench
