#include "scene/limits.h"

#include <cmath>
#include <cstdio>

#include "scene/scene.h"

namespace rockbench {

std::string ByteText(double bytes) {
  if (!std::isfinite(bytes)) return "an unbounded amount";
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g %s", bytes, units[u]);
  return buf;
}

void CheckMemoryEstimate(double estimate_bytes, const ResourceBudget& budget,
                         const std::string& where, const std::string& key,
                         const std::string& what) {
  if (estimate_bytes <= budget.memory_bytes) return;
  throw SceneError(where + ": " + key + ": needs an estimated " + ByteText(estimate_bytes) +
                   " (" + what + "), more than the memory budget of " +
                   ByteText(budget.memory_bytes) +
                   ": shorten or coarsen it, or raise the budget with --memory-budget GIB");
}

}  // namespace rockbench
