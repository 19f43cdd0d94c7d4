#pragma once
// Checks of JSON documents the program writes, for tests.
#include <cmath>

#include <nlohmann/json.hpp>

namespace rockbench::testing_util {

/// Every number in a JSON document is finite (nlohmann keeps a NaN as a number in memory and
/// writes it as null: either way it would be a result that is not one).
inline bool AllFinite(const nlohmann::json& j) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_structured()) {
    for (const auto& v : j) {
      if (!AllFinite(v)) return false;
    }
  }
  return true;
}

}  // namespace rockbench::testing_util
