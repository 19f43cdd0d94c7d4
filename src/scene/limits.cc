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

namespace {
ResourceBudget& Budget() {
  static ResourceBudget budget;
  return budget;
}
}  // namespace

void SetProcessBudget(const ResourceBudget& budget) {
  Budget() = budget;
}
const ResourceBudget& ProcessBudget() {
  return Budget();
}

std::string InputFileProblem(const std::filesystem::path& path, const std::string& what,
                             double max_bytes) {
  const std::string& raw = path.native();
  const std::string shown = Excerpt(raw, 200);
  if (raw.empty()) return "expected a " + what + " path, got \"\"";
  if (raw.find('\0') != std::string::npos) {
    return shown + ": the path holds a NUL character; expected a " + what + " path";
  }
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec && st.type() != std::filesystem::file_type::not_found) {
    return shown + ": cannot open the " + what + ": " + ec.message();
  }
  switch (st.type()) {
    case std::filesystem::file_type::not_found:
      return shown + ": no such " + what;
    case std::filesystem::file_type::regular:
      break;
    case std::filesystem::file_type::directory:
      return shown + ": is a folder; expected a " + what;
    default:
      return shown + ": is not a regular file (a device, pipe or socket); expected a " + what;
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return shown + ": cannot read the " + what + ": " + ec.message();
  if (static_cast<double>(size) > max_bytes) {
    return shown + ": the " + what + " is " + ByteText(static_cast<double>(size)) +
           ", more than the " + ByteText(max_bytes) + " an input file may be (docs/limits.md)";
  }
  return "";
}

void CheckMemoryEstimate(double estimate_bytes, const ResourceBudget& budget,
                         const std::string& where, const std::string& key,
                         const std::string& what) {
  if (estimate_bytes <= budget.memory_bytes) return;
  throw SceneError(where + ": " + key + ": needs an estimated " + ByteText(estimate_bytes) + " (" +
                   what + "), more than the memory budget of " + ByteText(budget.memory_bytes) +
                   ": shorten or coarsen it, or raise the budget with --memory-budget GIB");
}

}  // namespace rockbench
