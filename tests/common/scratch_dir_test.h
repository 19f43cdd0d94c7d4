#pragma once
// A test fixture with a fresh scratch folder per test (removed afterwards) and a helper that
// writes a file into it. Shared by the test suites that need files on disk.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace rockbench::testing_util {

class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string leaf = "rockbench_test_" + std::to_string(::getpid()) + "_" +
                       info->test_suite_name() + "_" + info->name();
    // Parameterised tests have "/" in their names: one folder level, not several.
    std::replace(leaf.begin(), leaf.end(), '/', '_');
    dir_ = std::filesystem::temp_directory_path() / leaf;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  /// Writes `text` (bytes as given) to dir_/name and returns the path.
  std::filesystem::path Write(const std::string& name, const std::string& text) {
    const std::filesystem::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::filesystem::path dir_;
};

}  // namespace rockbench::testing_util
