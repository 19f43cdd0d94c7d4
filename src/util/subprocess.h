#pragma once
/// Runs another program and collects what it printed, with a wall-clock limit: for gnuplot,
/// the stress catalogue's isolated cases and the report's browser check.
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench {

struct ProcessOptions {
  std::filesystem::path working_dir;  ///< empty: the caller's
  double timeout_s = 0.0;             ///< > 0: killed (SIGKILL) after this wall time, s
  std::string stdin_text;             ///< written to the child's standard input, then closed
};

struct ProcessResult {
  bool started = false;  ///< false: the program could not be started (start_error says why)
  std::string start_error;
  int exit_code = -1;      ///< the exit status when it exited normally, else -1
  int signal = 0;          ///< the signal that ended it (SIGKILL after a timeout), else 0
  bool timed_out = false;  ///< killed at the wall-clock limit
  double wall_s = 0.0;     ///< wall time from start to end, s
  std::string out, err;    ///< its standard output and standard error
  bool ok() const { return started && exit_code == 0; }
};

/// Runs argv[0] (searched on PATH when it has no '/') with argv. Never throws for the child's
/// failures; they are in the result.
ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options = {});

/// The path of the running executable (/proc/self/exe).
std::filesystem::path SelfExecutable();

}  // namespace rockbench
