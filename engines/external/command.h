#pragma once
/// Runs an external engine's command (util/subprocess.h: the project's one way to start a
/// process) in a folder of its own and a process group of its own, under a wall-clock and a
/// memory limit, and says how it ended.
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench::external {

/// What to run and within which limits.
struct CommandSpec {
  /// The program (a path, or a name looked up in PATH) and its arguments.
  std::vector<std::string> argv;
  std::filesystem::path working_dir;  ///< the child's current folder
  std::filesystem::path stderr_file;  ///< its standard error (its standard output is dropped)
  double wall_limit_s = 600.0;        ///< killed (with its process group) past this wall time, s
  /// Killed once the resident memory of its process group (VmRSS, read from /proc every 50 ms)
  /// exceeds this, MiB. Resident, not virtual: a WebAssembly or JIT runtime reserves far more
  /// address space than it touches, so an address-space limit would kill it at its start.
  double memory_limit_mib = 4096.0;
};

/// How it ended.
struct CommandResult {
  bool started = false;       ///< false: the program could not be run (see start_error)
  std::string start_error;    ///< "python4: No such file or directory"
  int exit_code = -1;         ///< the exit status when it exited normally, else -1
  int signal = 0;             ///< the signal that ended it (0: none)
  bool timed_out = false;     ///< killed at the wall-clock limit
  bool over_memory = false;   ///< killed at the memory limit
  double wall_s = 0.0;        ///< from start to end, s
  double peak_rss_mib = 0.0;  ///< largest resident memory of its group the polls saw, MiB

  /// Ended by exit(0), within the limits.
  bool ok() const { return started && exit_code == 0 && !timed_out && !over_memory; }
  /// One line on how it ended: "exit code 3", "killed by signal 11 (Segmentation fault)",
  /// "killed after its wall-clock limit of 2 s", "could not start: ...".
  std::string Describe(const CommandSpec& spec) const;
};

/// Runs the command and waits for it, or kills its process group at a limit. Never throws for
/// the child's failures: they are in the result.
CommandResult RunCommand(const CommandSpec& spec);

/// The last `max_lines` lines of a text file (of its last 4 kB), for error messages; empty
/// when the file is missing or empty.
std::string TailOfFile(const std::filesystem::path& file, int max_lines = 8);

}  // namespace rockbench::external
