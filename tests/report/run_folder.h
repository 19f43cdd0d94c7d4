#pragma once
// Run folders for the report tests, made by the real `rockbench` program (run/compare), so the
// reports are tested on exactly what users feed them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "util/subprocess.h"

namespace rockbench::testing_util {

inline std::filesystem::path RockbenchExe() {
  return std::filesystem::path(ROCKBENCH_BINARY_DIR) / "src" / "cli" / "rockbench";
}

/// Runs `rockbench ARGS...` (2 minutes at most). Fails the test when the program is not built.
inline ProcessResult Rockbench(const std::vector<std::string>& args) {
  const std::filesystem::path exe = RockbenchExe();
  EXPECT_TRUE(std::filesystem::exists(exe))
      << exe << " is not built: build the rockbench target before the report tests";
  std::vector<std::string> argv = {exe.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  ProcessOptions options;
  options.timeout_s = 120.0;
  return RunProcess(argv, options);
}

/// `rockbench ARGS...` that must succeed.
inline void RockbenchOk(const std::vector<std::string>& args) {
  const ProcessResult r = Rockbench(args);
  std::string line;
  for (const std::string& a : args) line += a + " ";
  ASSERT_TRUE(r.ok()) << "rockbench " << line << "failed (" << r.exit_code << "):\n"
                      << r.out << r.err;
}

inline std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Expects every file under `a` to exist under `b` with the same bytes; returns how many files
/// were compared.
inline int ExpectSameFiles(const std::filesystem::path& a, const std::filesystem::path& b) {
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const std::filesystem::path rel = std::filesystem::relative(e.path(), a);
    EXPECT_TRUE(std::filesystem::exists(b / rel)) << rel;
    EXPECT_EQ(Slurp(e.path()), Slurp(b / rel)) << rel << " differs between two reports";
    ++files;
  }
  return files;
}

inline std::filesystem::path SceneFile(const std::string& name) {
  return std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "scenes" / name;
}

}  // namespace rockbench::testing_util
