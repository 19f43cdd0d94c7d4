#include "util/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "util/wall_limit.h"

extern char** environ;

namespace rockbench {
namespace {

void CloseFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

std::string ErrnoText(int err) {
  return std::strerror(err);
}

ExitStatus FromWaitStatus(int status) {
  ExitStatus s;
  if (WIFEXITED(status)) s.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) s.signal = WTERMSIG(status);
  return s;
}

// Appends to `text`, keeping at most the last `limit` bytes.
void AppendCapped(std::string& text, const char* data, size_t n, size_t limit) {
  text.append(data, n);
  if (text.size() > limit) text.erase(0, text.size() - limit);
}

// The child's side of the three standard streams: for fd 0, 1, 2 the caller's descriptor that
// becomes it (-1: inherited), all opened close-on-exec in the caller and closed there once the
// child started.
struct ChildFds {
  int fd[3] = {-1, -1, -1};
  ~ChildFds() {
    for (int& f : fd) CloseFd(f);
  }
};

// In a forked child: the only calls until exec are async-signal-safe. Writes errno to
// `report` and exits when something fails.
[[noreturn]] void ExecChild(const std::vector<char*>& args, const ChildFds& fds, const char* dir,
                            pid_t parent, bool own_group, int report) {
  if (own_group) ::setpgid(0, 0);
  // The child dies with the thread that started it (SpawnOptions::die_with_parent); a parent
  // already gone before prctl took effect is checked by hand.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);
  sigset_t none;
  sigemptyset(&none);
  struct sigaction dfl = {};
  dfl.sa_handler = SIG_DFL;
  ::sigaction(SIGPIPE, &dfl, nullptr);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  int err = 0;
  for (int target = 0; target < 3 && err == 0; ++target) {
    const int source = fds.fd[target];
    if (source < 0) continue;
    if (source == target) {
      if (::fcntl(target, F_SETFD, 0) != 0) err = errno;  // dup2 would keep close-on-exec
    } else if (::dup2(source, target) < 0) {
      err = errno;
    }
  }
  if (err == 0 && dir != nullptr && ::chdir(dir) != 0) err = errno;
  if (err == 0) {
    ::execve(args[0], args.data(), environ);
    err = errno;
  }
  (void)!::write(report, &err, sizeof err);
  ::_exit(127);
}

// Starts the child by fork and exec (die_with_parent: posix_spawn cannot set PR_SET_PDEATHSIG).
// Returns the pid, or -1 with *err set.
pid_t ForkExec(const std::vector<char*>& args, const ChildFds& fds, const char* dir, bool own_group,
               int* err) {
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    *err = errno;
    return -1;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) ExecChild(args, fds, dir, parent, own_group, report[1]);
  // Also here, so that a kill of the group right after the start cannot miss it.
  if (pid > 0 && own_group) ::setpgid(pid, pid);
  const int fork_errno = errno;
  ::close(report[1]);
  int exec_errno = 0;
  if (pid > 0) {
    ssize_t n;
    while ((n = ::read(report[0], &exec_errno, sizeof exec_errno)) < 0 && errno == EINTR) {
    }
    if (n != static_cast<ssize_t>(sizeof exec_errno)) exec_errno = 0;
  }
  ::close(report[0]);
  if (pid < 0) {
    *err = fork_errno;
    return -1;
  }
  if (exec_errno != 0) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    *err = exec_errno;
    return -1;
  }
  return pid;
}

// Starts the child by posix_spawn (posix_spawnp without a '/'). Returns the pid, or -1 with
// *err set.
pid_t Spawn(const std::vector<char*>& args, const ChildFds& fds, const char* dir, bool search,
            bool own_group, int* err) {
  // A process group of its own (SpawnOptions::own_process_group): its pid is the group's id.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  // The child starts with no signal blocked (the caller blocks the termination signals for its
  // handler thread, util/wall_limit.h) and SIGPIPE at its default (a study's pool ignores it).
  short flags = POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF;
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  if (own_group) {
    flags |= POSIX_SPAWN_SETPGROUP;
    posix_spawnattr_setpgroup(&attr, 0);
  }
  posix_spawnattr_setflags(&attr, flags);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  for (int target = 0; target < 3; ++target) {
    if (fds.fd[target] >= 0) posix_spawn_file_actions_adddup2(&actions, fds.fd[target], target);
  }
  if (dir != nullptr) posix_spawn_file_actions_addchdir_np(&actions, dir);
  pid_t pid = -1;
  const int rc = search ? ::posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ)
                        : ::posix_spawn(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    *err = rc;
    return -1;
  }
  return pid;
}

}  // namespace

std::string ExitStatus::Text() const {
  return signal != 0 ? "signal " + std::to_string(signal)
                     : "exit status " + std::to_string(exit_code);
}

struct Subprocess::State {
  pid_t pid = -1;
  bool started = false;
  bool own_group = false;  // SpawnOptions::own_process_group: Kill signals the whole group
  std::string start_error;
  int in = -1, out = -1, err = -1;  // the caller's ends of the kPipe streams
  std::thread out_reader, err_reader;
  std::string out_text, err_text;
  std::optional<ExitStatus> status;

  // Reads `fd` to its end into `text` (the last `limit` bytes), then closes it.
  static void Drain(int fd, std::string* text, size_t limit) {
    char buf[65536];
    for (;;) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      AppendCapped(*text, buf, static_cast<size_t>(n), limit);
    }
    ::close(fd);
  }

  // After the child ended: joins the readers, closes what is left.
  void Finish(int wait_status) {
    status = FromWaitStatus(wait_status);
    pid = -1;
    CloseFd(in);
    CloseFd(out);
    CloseFd(err);
    if (out_reader.joinable()) out_reader.join();
    if (err_reader.joinable()) err_reader.join();
  }
};

Subprocess::Subprocess() : state_(std::make_unique<State>()) {}

Subprocess::Subprocess(const std::vector<std::string>& argv, const SpawnOptions& options)
    : state_(std::make_unique<State>()) {
  // Nothing new starts while the process is ending (a signal, the wall-clock limit).
  HoldIfEnding();
  State& s = *state_;
  if (argv.empty()) {
    s.start_error = "no program given";
    return;
  }
  // The caller's ends, kept when the child starts; and the child's, closed here once it has.
  int parent_end[3] = {-1, -1, -1};
  ChildFds child;
  const auto fail = [&](std::string why) {
    for (int& f : parent_end) CloseFd(f);
    s.start_error = std::move(why);
  };
  const Stdio modes[3] = {options.in, options.out, options.err};
  for (int target = 0; target < 3; ++target) {
    if (target == 2 && !options.err_log.empty()) {
      child.fd[2] =
          ::open(options.err_log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
      if (child.fd[2] < 0) {
        fail(options.err_log.string() + ": cannot open: " + ErrnoText(errno));
        return;
      }
      continue;
    }
    switch (modes[target]) {
      case Stdio::kInherit:
        break;
      case Stdio::kNull:
        child.fd[target] = ::open("/dev/null", (target == 0 ? O_RDONLY : O_WRONLY) | O_CLOEXEC);
        if (child.fd[target] < 0) {
          fail("/dev/null: " + ErrnoText(errno));
          return;
        }
        break;
      case Stdio::kPipe:
      case Stdio::kCapture: {
        int p[2];
        if (::pipe2(p, O_CLOEXEC) != 0) {
          fail("pipe: " + ErrnoText(errno));
          return;
        }
        // stdin: the child reads p[0]; stdout and stderr: the child writes p[1].
        child.fd[target] = target == 0 ? p[0] : p[1];
        parent_end[target] = target == 0 ? p[1] : p[0];
        break;
      }
    }
  }

  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const char* dir = options.working_dir.empty() ? nullptr : options.working_dir.c_str();
  const bool search = argv[0].find('/') == std::string::npos;
  int err = 0;
  pid_t pid = -1;
  if (options.die_with_parent) {
    // fork + execve: the PATH search is done here, before the fork.
    std::string resolved = argv[0];
    if (search) {
      const std::optional<std::filesystem::path> found = FindProgram(argv[0]);
      if (!found) {
        fail(argv[0] + ": " + ErrnoText(ENOENT));
        return;
      }
      resolved = found->string();
    }
    args[0] = resolved.data();
    pid = ForkExec(args, child, dir, options.own_process_group, &err);
  } else {
    pid = Spawn(args, child, dir, search, options.own_process_group, &err);
  }
  if (pid < 0) {
    fail(argv[0] + ": " + ErrnoText(err));
    return;
  }

  s.pid = pid;
  s.started = true;
  s.own_group = options.own_process_group;
  s.in = parent_end[0];
  const size_t limit = options.capture_limit_bytes;
  if (modes[1] == Stdio::kCapture) {
    s.out_reader = std::thread(State::Drain, parent_end[1], &s.out_text, limit);
  } else {
    s.out = parent_end[1];
  }
  if (modes[2] == Stdio::kCapture && options.err_log.empty()) {
    s.err_reader = std::thread(State::Drain, parent_end[2], &s.err_text, limit);
  } else {
    s.err = parent_end[2];
  }
}

Subprocess::~Subprocess() {
  if (!state_) return;  // moved from
  if (running()) Kill(SIGKILL);
  Wait();
}

Subprocess::Subprocess(Subprocess&& other) noexcept = default;

Subprocess& Subprocess::operator=(Subprocess&& other) noexcept {
  if (this != &other) {
    if (state_ && running()) Kill(SIGKILL);
    if (state_) Wait();
    state_ = std::move(other.state_);
  }
  return *this;
}

bool Subprocess::started() const {
  return state_ && state_->started;
}

const std::string& Subprocess::start_error() const {
  return state_->start_error;
}

bool Subprocess::running() const {
  return state_ && state_->pid > 0;
}

pid_t Subprocess::pid() const {
  return state_ ? state_->pid : -1;
}

int Subprocess::stdin_fd() const {
  return state_->in;
}

int Subprocess::stdout_fd() const {
  return state_->out;
}

int Subprocess::stderr_fd() const {
  return state_->err;
}

int Subprocess::WriteStdin(const void* data, size_t size) {
  if (state_->in < 0) return EBADF;
  // SIGPIPE blocked while writing: a child that stopped reading gives EPIPE instead.
  sigset_t pipe_set, old_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old_set);
  const char* p = static_cast<const char*>(data);
  size_t left = size;
  int err = 0;
  while (left > 0) {
    const ssize_t n = ::write(state_->in, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  if (err == EPIPE && !sigismember(&old_set, SIGPIPE)) {
    // Consume the pending SIGPIPE before unblocking it.
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_set, nullptr);
  return err;
}

void Subprocess::CloseStdin() {
  CloseFd(state_->in);
}

void Subprocess::Kill(int sig) {
  if (running()) ::kill(state_->own_group ? -state_->pid : state_->pid, sig);
}

ExitStatus Subprocess::Wait() {
  State& s = *state_;
  if (s.status) return *s.status;
  if (!s.started) return ExitStatus{};
  CloseFd(s.in);
  CloseFd(s.out);
  CloseFd(s.err);
  int status = 0;
  pid_t w;
  while ((w = ::waitpid(s.pid, &status, 0)) < 0 && errno == EINTR) {
  }
  if (w < 0) status = 0xff00;  // not ours to wait for (ECHILD): reported as exit status 255
  s.Finish(status);
  return *s.status;
}

std::optional<ExitStatus> Subprocess::TryWait() {
  State& s = *state_;
  if (s.status) return s.status;
  if (!s.started) return ExitStatus{};
  int status = 0;
  pid_t w;
  while ((w = ::waitpid(s.pid, &status, WNOHANG)) < 0 && errno == EINTR) {
  }
  if (w == 0) return std::nullopt;
  if (w < 0) status = 0xff00;
  s.Finish(status);
  return s.status;
}

const std::string& Subprocess::captured_out() const {
  return state_->out_text;
}

const std::string& Subprocess::captured_err() const {
  return state_->err_text;
}

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Feeds stdin, drains stdout and stderr until both close, and kills the child at the limit.
void Communicate(Subprocess& child, const ProcessOptions& options,
                 std::chrono::steady_clock::time_point start, ProcessResult* result) {
  size_t written = 0;
  if (options.stdin_text.empty()) child.CloseStdin();
  if (child.stdin_fd() >= 0) ::fcntl(child.stdin_fd(), F_SETFL, O_NONBLOCK);
  bool out_open = true, err_open = true;
  char buf[65536];
  while (out_open || err_open) {
    pollfd fds[3];
    int n = 0;
    if (out_open) fds[n++] = {child.stdout_fd(), POLLIN, 0};
    if (err_open) fds[n++] = {child.stderr_fd(), POLLIN, 0};
    if (child.stdin_fd() >= 0) fds[n++] = {child.stdin_fd(), POLLOUT, 0};
    int wait_ms = -1;
    if (options.timeout_s > 0.0) {
      const double left = options.timeout_s - SecondsSince(start);
      if (left <= 0.0) {
        child.Kill(SIGKILL);
        result->timed_out = true;
        return;
      }
      wait_ms = static_cast<int>(left * 1000.0) + 1;
    }
    const int ready = ::poll(fds, static_cast<nfds_t>(n), wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) return;
    for (int i = 0; i < n; ++i) {
      if (fds[i].revents == 0) continue;
      const int fd = fds[i].fd;
      if (fd == child.stdin_fd()) {
        const ssize_t w =
            ::write(fd, options.stdin_text.data() + written, options.stdin_text.size() - written);
        if (w > 0) written += static_cast<size_t>(w);
        if ((w < 0 && errno != EAGAIN && errno != EINTR) || written >= options.stdin_text.size()) {
          child.CloseStdin();
        }
        continue;
      }
      const bool is_out = fd == child.stdout_fd();
      const ssize_t r = ::read(fd, buf, sizeof buf);
      if (r > 0) {
        (is_out ? result->out : result->err).append(buf, static_cast<size_t>(r));
      } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
        (is_out ? out_open : err_open) = false;
      }
    }
  }
}

}  // namespace

ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
  ProcessResult result;
  SpawnOptions spawn;
  spawn.in = spawn.out = spawn.err = Stdio::kPipe;
  spawn.working_dir = options.working_dir;
  const auto start = std::chrono::steady_clock::now();
  Subprocess child(argv, spawn);
  if (!child.started()) {
    result.start_error = child.start_error();
    return result;
  }
  result.started = true;
  // SIGPIPE on a child that stops reading its input early: EPIPE in Communicate instead.
  sigset_t pipe_set, old_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old_set);
  Communicate(child, options, start, &result);
  child.CloseStdin();
  if (!sigismember(&old_set, SIGPIPE)) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_set, nullptr);
  // A child that closed its outputs may still run, so the limit still holds.
  ExitStatus status;
  if (options.timeout_s > 0.0) {
    std::optional<ExitStatus> ended;
    while (!(ended = child.TryWait())) {
      if (SecondsSince(start) >= options.timeout_s && !result.timed_out) {
        child.Kill(SIGKILL);
        result.timed_out = true;
      }
      ::usleep(1000);
    }
    status = *ended;
  } else {
    status = child.Wait();
  }
  result.wall_s = SecondsSince(start);
  result.exit_code = status.exit_code;
  result.signal = status.signal;
  return result;
}

std::filesystem::path SelfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe");
}

std::filesystem::path BesideSelf(std::string_view name) {
  try {
    return SelfExecutable().parent_path() / name;
  } catch (const std::filesystem::filesystem_error&) {
    return {};
  }
}

std::optional<std::filesystem::path> FindProgram(const std::string& name) {
  auto executable = [](const std::filesystem::path& p) {
    struct stat st;
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) {
    if (executable(name)) return std::filesystem::path(name);
    return std::nullopt;
  }
  const char* path_env = std::getenv("PATH");
  const std::string path = path_env ? path_env : "/usr/local/bin:/usr/bin:/bin";
  size_t start = 0;
  while (start <= path.size()) {
    const size_t end = std::min(path.find(':', start), path.size());
    const std::string dir = path.substr(start, end - start);
    if (!dir.empty() && executable(std::filesystem::path(dir) / name)) {
      return std::filesystem::path(dir) / name;
    }
    start = end + 1;
  }
  return std::nullopt;
}

}  // namespace rockbench
