#include "report/common/names.h"

#include <stdexcept>

#include "scene/limits.h"

namespace rockbench::report {

bool IsEngineName(std::string_view name) {
  if (name == "reference") return true;
  if (name.empty() || name.size() > kMaxEngineNameChars || name[0] < 'a' || name[0] > 'z') {
    return false;
  }
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

void RequireEngineName(const std::string& name, const std::string& where) {
  if (IsEngineName(name)) return;
  throw std::runtime_error(where + ": \"" + Excerpt(name) +
                           "\" is not an engine name (expected \"reference\" or lower-case "
                           "letters, digits and '_', starting with a letter, at most " +
                           std::to_string(kMaxEngineNameChars) +
                           " characters): a name read from a results folder is refused, not used");
}

}  // namespace rockbench::report
