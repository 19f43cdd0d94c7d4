#pragma once
// Runs a shell command for the tests of rockbench as a program: its exit code and what it
// printed (standard output and error together), the rockbench program itself, and a file's
// bytes.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rockbench::testing_util {

struct ShellRun {
  int exit_code = -1;  ///< -1: it did not exit normally
  std::string output;  ///< stdout and stderr
};

inline ShellRun Shell(const std::string& command) {
  ShellRun r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

#ifdef ROCKBENCH_EXE
/// Runs the rockbench program under test (ROCKBENCH_EXE, which the test programs that run it
/// define: rockbench_test's PROGRAM) with `args`, as a shell would split them.
inline ShellRun Rockbench(const std::string& args) {
  return Shell(std::string(ROCKBENCH_EXE) + " " + args);
}
#endif

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace rockbench::testing_util
