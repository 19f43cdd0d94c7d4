#pragma once
// Starting a program in the background for tests that signal or measure it (its standard output
// to /dev/null, its standard error to a file or inherited), and whether a process still runs.
#include <fcntl.h>
#include <spawn.h>
#include <sys/types.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern char** environ;

namespace rockbench::testing_util {

/// Spawns argv[0] with `argv`; stdout goes to /dev/null, stderr to `stderr_file` when given.
/// Returns the child's pid, or -1 when it could not be started.
inline pid_t SpawnQuiet(std::vector<std::string> argv,
                        const std::filesystem::path& stderr_file = {}) {
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  if (!stderr_file.empty()) {
    posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
  }
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, cargs[0], &actions, nullptr, cargs.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

/// Whether process `pid` runs (a zombie does not), from /proc/<pid>/stat.
inline bool ProcessRuns(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat)) return false;
  const size_t close = stat.rfind(')');
  return close != std::string::npos && stat[close + 2] != 'Z';
}

}  // namespace rockbench::testing_util
