#pragma once
// What every test suite run over the built engines shares: its parameters (the engines' names)
// and how a parameter names a test.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "run/engine_registry.h"

namespace rockbench::testing_util {

/// The built engines' names (BuiltEngineNames); "no engine built" when there are none, so
/// that a suite never passes by having nothing to run (Bullet is a required dependency).
inline std::vector<std::string> SuiteEngines() {
  std::vector<std::string> names = BuiltEngineNames();
  if (names.empty()) names.push_back("no engine built");
  return names;
}

/// A test's name from its engine's name (gtest allows no space in a name).
inline std::string EngineTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = info.param;
  std::replace(n.begin(), n.end(), ' ', '_');
  return n;
}

}  // namespace rockbench::testing_util
