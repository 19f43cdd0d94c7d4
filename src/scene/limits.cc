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

std::string Excerpt(std::string_view text, size_t max_chars) {
  std::string out;
  size_t i = 0;
  for (; i < text.size() && out.size() < max_chars; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\r') {
      out += "\\r";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == 0) {
      out += "\\0";
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
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
