#pragma once
/// Child processes, the one way the project starts them (every folder may use src/util): a
/// program run to the end with what it printed collected and a wall-clock limit (RunProcess: for
/// gnuplot, the stress catalogue's isolated cases, the report's browser check), and a program
/// that runs beside the caller with pipes to it (Subprocess: a study's workers, ffmpeg reading
/// frames, Bullet's single-precision helper). Plus where the running program is
/// (SelfExecutable, BesideSelf) and the PATH search (FindProgram). A child starts with no signal
/// blocked and SIGPIPE at its default; none starts once the process is ending
/// (util/wall_limit.h: the constructor holds the calling thread).
#include <sys/types.h>

#include <csignal>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockbench {

/// How a child process ended.
struct ExitStatus {
  int exit_code = -1;  ///< the exit status when it exited normally, else -1
  int signal = 0;      ///< the signal that ended it, else 0
  bool ok() const { return exit_code == 0; }
  /// "exit status 3" or "signal 9" ("exit status 0" for a success).
  std::string Text() const;
};

/// Where one of a child's standard streams goes.
enum class Stdio {
  kInherit,  ///< the caller's own
  kPipe,     ///< a pipe to the caller: Subprocess::stdin_fd(), stdout_fd(), stderr_fd()
  kNull,     ///< /dev/null
  /// Output streams: read by a thread of the Subprocess into a string (Subprocess::captured_out,
  /// captured_err), so that a child that prints much never blocks on a full pipe.
  kCapture,
};

/// How to start a Subprocess.
struct SpawnOptions {
  Stdio in = Stdio::kInherit, out = Stdio::kInherit, err = Stdio::kInherit;
  /// Not empty: the child's standard error is appended to this file (created when missing,
  /// mode 0644) whatever `err` says; a file that cannot be opened is a start error.
  std::filesystem::path err_log;
  std::filesystem::path working_dir;  ///< empty: the caller's
  /// kCapture keeps at most the last this many bytes of each captured stream, bytes.
  std::size_t capture_limit_bytes = std::size_t{1} << 30;
  /// The child is killed (SIGKILL) when the thread that started it ends, the whole process
  /// with it (PR_SET_PDEATHSIG, set before exec): a wall-clock limit or a kill of the caller
  /// must not leave the child writing files. A child that must outlive a worker thread of the
  /// caller must not ask for this.
  bool die_with_parent = false;
  /// The child leads a process group of its own (its pid is the group's id), and Kill signals
  /// the whole group: a command that starts programs of its own (a shell, a language runtime)
  /// is ended with them.
  bool own_process_group = false;
};

/// A running child process, started by the constructor. Move-only; the destructor kills
/// (SIGKILL) a child that was not waited for, and reaps it. Not thread-safe: one thread uses it.
class Subprocess {
 public:
  /// No process (started() false, start_error() empty).
  Subprocess();
  /// Starts argv[0] (searched on PATH when it has no '/') with argv. Never throws for a program
  /// that cannot start: started() is false and start_error() says why.
  Subprocess(const std::vector<std::string>& argv, const SpawnOptions& options);
  ~Subprocess();
  Subprocess(Subprocess&&) noexcept;
  Subprocess& operator=(Subprocess&&) noexcept;
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  /// The child was started.
  bool started() const;
  /// Why it was not: "ARGV0: No such file or directory" ("pipe: ..." and the like for the
  /// caller's own failures, "LOG: cannot open: ..." for SpawnOptions::err_log).
  const std::string& start_error() const;
  /// Started and not yet waited for.
  bool running() const;
  pid_t pid() const;  ///< -1 when not running

  /// The caller's ends of the kPipe streams (-1 otherwise, and once closed): write to
  /// stdin_fd, read (or poll) stdout_fd and stderr_fd.
  int stdin_fd() const;
  int stdout_fd() const;
  int stderr_fd() const;

  /// Writes all of `size` bytes to the child's standard input (kPipe), retrying interrupted
  /// writes. SIGPIPE is blocked on this thread meanwhile: a child that stopped reading gives
  /// EPIPE, not the end of the caller. Returns 0, or the errno of the failed write.
  int WriteStdin(const void* data, std::size_t size);
  int WriteStdin(std::string_view text) { return WriteStdin(text.data(), text.size()); }
  /// Closes the caller's end of the child's standard input: the child reads end of input.
  void CloseStdin();

  /// Sends `sig` to a running child, and to its process group with own_process_group (no
  /// effect once it was waited for).
  void Kill(int sig = SIGKILL);
  /// Closes the caller's pipe ends (the child reads end of input; one still writing gets
  /// EPIPE), waits for the child to end (retrying interrupted waits) and for the capture
  /// threads. Returns how it ended; again after that: the same answer. {-1, 0} when it was
  /// never started.
  ExitStatus Wait();
  /// Without blocking: how it ended, once it has (then as Wait()), or nullopt while it runs.
  std::optional<ExitStatus> TryWait();

  /// What the kCapture streams printed (the last SpawnOptions::capture_limit_bytes), complete
  /// once Wait() returned.
  const std::string& captured_out() const;
  const std::string& captured_err() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// RunProcess's options.
struct ProcessOptions {
  std::filesystem::path working_dir;  ///< empty: the caller's
  double timeout_s = 0.0;             ///< > 0: killed (SIGKILL) after this wall time, s
  std::string stdin_text;             ///< written to the child's standard input, then closed
};

/// What RunProcess saw.
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

/// Runs argv[0] (searched on PATH when it has no '/') with argv to its end, collecting both
/// outputs. Never throws for the child's failures; they are in the result.
ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options = {});

/// The path of the running executable (/proc/self/exe, the one place it is read). Throws
/// std::filesystem::filesystem_error when it cannot be read.
std::filesystem::path SelfExecutable();

/// The program `name` in the running executable's folder (rockbench-bullet-float beside
/// rockbench), whether or not it exists; empty when /proc/self/exe cannot be read.
std::filesystem::path BesideSelf(std::string_view name);

/// The program `name` on PATH (or `name` itself when it contains a '/'): a regular file we may
/// execute, or nullopt.
std::optional<std::filesystem::path> FindProgram(const std::string& name);

}  // namespace rockbench
