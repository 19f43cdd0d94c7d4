#pragma once
/// Runs an external engine's command as a child process in its own folder, under a wall-clock
/// and a memory limit, and says how it ended. POSIX (fork, exec, waitpid, /proc).
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench::external {

/// What to run and within which limits.
struct ProcessSpec {
  /// The program (a path, or a name looked up in PATH) and its arguments.
  std::vector<std::string> argv;
  std::filesystem::path working_dir;  ///< the child's current folder
  /// Standard output and error go to these files (created or truncated).
  std::filesystem::path stdout_file, stderr_file;
  double wall_limit_s = 600.0;  ///< killed (with its process group) past this wall time, s
  /// Killed once its resident memory (VmRSS of the child and, read from /proc, every process of
  /// its group) exceeds this, MiB. Resident, not virtual: a WebAssembly or JIT runtime reserves
  /// far more address space than it touches, so an address-space limit would kill it at start.
  double memory_limit_mib = 4096.0;
  /// How often the child is polled for its end and its memory, s.
  double poll_s = 0.005;
};

/// How it ended.
struct ProcessResult {
  bool started = false;       ///< false: the program could not be run (see error)
  bool exited = false;        ///< ended by exit(): exit_code is set
  int exit_code = 0;          ///< the exit status when exited
  int signal = 0;             ///< the signal that ended it (0: none)
  bool timed_out = false;     ///< killed at the wall-clock limit
  bool over_memory = false;   ///< killed at the memory limit
  double wall_s = 0.0;        ///< from start to end, s
  double peak_rss_mib = 0.0;  ///< largest resident memory seen by the polls, MiB
  std::string error;          ///< why it could not be started ("no such program: nodee")

  /// Ended by exit(0), within the limits.
  bool ok() const { return started && exited && exit_code == 0 && !timed_out && !over_memory; }
  /// One line on how it ended: "exit code 3", "killed by signal 11 (Segmentation fault)",
  /// "killed after its wall-clock limit of 2 s", "could not start: ...".
  std::string Describe(const ProcessSpec& spec) const;
};

/// The program's full path: argv0 itself when it holds a '/', else the first executable of that
/// name in PATH; empty when there is none.
std::filesystem::path FindProgram(const std::string& argv0);

/// Runs the command and waits for it (or kills it at a limit). Never throws for the child's
/// failures: they are in the result.
ProcessResult RunProcess(const ProcessSpec& spec);

/// The last `max_lines` lines of a text file (at most 4 kB), for error messages; empty when
/// the file is missing or empty.
std::string TailOfFile(const std::filesystem::path& file, int max_lines = 8);

}  // namespace rockbench::external
