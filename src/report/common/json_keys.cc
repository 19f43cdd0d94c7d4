#include "report/common/json_keys.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "files/atomic_file.h"
#include "scene/history.h"
#include "scene/limits.h"

namespace rockbench::report {

namespace fs = std::filesystem;
using nlohmann::json;

json ReadJson(const fs::path& path) {
  const std::string text = ReadTextFile(path);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw std::runtime_error(path.string() + ": not valid JSON: " + e.what());
  }
}

const json* Find(const json& root, const std::string& dotted) {
  const json* j = &root;
  size_t start = 0;
  while (start <= dotted.size()) {
    const size_t dot = dotted.find('.', start);
    const std::string part = dotted.substr(start, dot == std::string::npos ? dot : dot - start);
    if (!j->is_object()) return nullptr;
    const auto it = j->find(part);
    if (it == j->end()) return nullptr;
    j = &*it;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return j;
}

namespace {

// A value for a message: its JSON text (invalid UTF-8 replaced), escaped and cut to an excerpt.
std::string Shown(const json& j) {
  return Excerpt(j.dump(-1, ' ', false, json::error_handler_t::replace), 200);
}

}  // namespace

double OptNumber(const json& root, const std::string& key, const fs::path& file) {
  const json* j = Find(root, key);
  if (j == nullptr || j->is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!j->is_number()) {
    throw std::runtime_error(file.string() + ": key '" + key + "' must be a number, found " +
                             Shown(*j));
  }
  return j->get<double>();
}

double NeedNumber(const json& root, const std::string& key, const fs::path& file) {
  const double v = OptNumber(root, key, file);
  if (std::isnan(v)) {
    throw std::runtime_error(file.string() + ": key '" + key + "' is missing (expected a number)");
  }
  return v;
}

std::string OptString(const json& root, const std::string& key, const fs::path& file) {
  const json* j = Find(root, key);
  if (j == nullptr || j->is_null()) return "";
  if (!j->is_string()) {
    throw std::runtime_error(file.string() + ": key '" + key + "' must be a string, found " +
                             Shown(*j));
  }
  return j->get<std::string>();
}

bool OptBool(const json& root, const std::string& key, const fs::path& file) {
  const json* j = Find(root, key);
  if (j == nullptr || j->is_null()) return false;
  if (!j->is_boolean()) {
    throw std::runtime_error(file.string() + ": key '" + key + "' must be true or false, found " +
                             Shown(*j));
  }
  return j->get<bool>();
}

}  // namespace rockbench::report
