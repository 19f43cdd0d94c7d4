#include "util/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

extern char** environ;

namespace rockbench {
namespace {

void CloseFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// The child's three pipes: stdin (we write in[1]), stdout and stderr (we read out[0], err[0]).
struct Pipes {
  int in[2] = {-1, -1}, out[2] = {-1, -1}, err[2] = {-1, -1};
  ~Pipes() {
    for (int* p : {in, out, err}) {
      CloseFd(p[0]);
      CloseFd(p[1]);
    }
  }
};

// Starts argv[0] (searched on PATH when it has no '/') with the pipes as its stdio. Returns
// the pid, or -1 with result->start_error set.
pid_t Spawn(const std::vector<std::string>& argv, const ProcessOptions& options, Pipes& p,
            ProcessResult* result) {
  if (::pipe2(p.in, O_CLOEXEC) != 0 || ::pipe2(p.out, O_CLOEXEC) != 0 ||
      ::pipe2(p.err, O_CLOEXEC) != 0) {
    result->start_error = std::string("pipe: ") + std::strerror(errno);
    return -1;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, p.in[0], 0);
  posix_spawn_file_actions_adddup2(&actions, p.out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, p.err[1], 2);
  if (!options.working_dir.empty()) {
    posix_spawn_file_actions_addchdir_np(&actions, options.working_dir.c_str());
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = argv[0].find('/') == std::string::npos
                     ? ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ)
                     : ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  CloseFd(p.in[0]);
  CloseFd(p.out[1]);
  CloseFd(p.err[1]);
  if (rc != 0) {
    result->start_error = argv[0] + ": " + std::strerror(rc);
    return -1;
  }
  return pid;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Feeds stdin, drains stdout and stderr until both close, and kills the child at the limit.
void Communicate(pid_t pid, Pipes& p, const ProcessOptions& options,
                 std::chrono::steady_clock::time_point start, ProcessResult* result) {
  size_t written = 0;
  if (options.stdin_text.empty()) CloseFd(p.in[1]);
  if (p.in[1] >= 0) ::fcntl(p.in[1], F_SETFL, O_NONBLOCK);
  char buf[65536];
  while (p.out[0] >= 0 || p.err[0] >= 0) {
    pollfd fds[3];
    int n = 0;
    int* owners[3];
    for (int* fd : {&p.out[0], &p.err[0]}) {
      if (*fd >= 0) {
        fds[n] = {*fd, POLLIN, 0};
        owners[n++] = fd;
      }
    }
    if (p.in[1] >= 0) {
      fds[n] = {p.in[1], POLLOUT, 0};
      owners[n++] = &p.in[1];
    }
    int wait_ms = -1;
    if (options.timeout_s > 0.0) {
      const double left = options.timeout_s - SecondsSince(start);
      if (left <= 0.0) {
        ::kill(pid, SIGKILL);
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
      int* fd = owners[i];
      if (fd == &p.in[1]) {
        const ssize_t w =
            ::write(*fd, options.stdin_text.data() + written, options.stdin_text.size() - written);
        if (w > 0) written += static_cast<size_t>(w);
        if (w < 0 && errno != EAGAIN && errno != EINTR) CloseFd(*fd);
        if (written >= options.stdin_text.size()) CloseFd(*fd);
        continue;
      }
      const ssize_t r = ::read(*fd, buf, sizeof buf);
      if (r > 0) {
        (fd == &p.out[0] ? result->out : result->err).append(buf, static_cast<size_t>(r));
      } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
        CloseFd(*fd);
      }
    }
  }
}

// Waits for the child; one that closed its outputs may still run, so the limit still holds.
int Reap(pid_t pid, const ProcessOptions& options, std::chrono::steady_clock::time_point start,
         ProcessResult* result) {
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, options.timeout_s > 0.0 ? WNOHANG : 0);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) break;
    if (w == 0) {
      if (SecondsSince(start) >= options.timeout_s && !result->timed_out) {
        ::kill(pid, SIGKILL);
        result->timed_out = true;
      }
      ::usleep(1000);
    }
  }
  return status;
}

}  // namespace

ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
  ProcessResult result;
  if (argv.empty()) {
    result.start_error = "no program given";
    return result;
  }
  Pipes pipes;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = Spawn(argv, options, pipes, &result);
  if (pid < 0) return result;
  result.started = true;
  Communicate(pid, pipes, options, start, &result);
  CloseFd(pipes.in[1]);
  CloseFd(pipes.out[0]);
  CloseFd(pipes.err[0]);
  const int status = Reap(pid, options, start, &result);
  result.wall_s = SecondsSince(start);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

std::filesystem::path SelfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe");
}

}  // namespace rockbench
