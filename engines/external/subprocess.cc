#include "engines/external/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

namespace rockbench::external {
namespace {

// Resident memory of process `pid`, MiB (0 when it cannot be read: the process has ended).
double ResidentMiB(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;
  }
  return 0.0;
}

// Resident memory of every process of group `pgid`, MiB: the child and whatever it started.
double GroupResidentMiB(pid_t pgid) {
  double total = 0.0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::atoi(name.c_str()));
    if (getpgid(pid) == pgid) total += ResidentMiB(pid);
  }
  return total;
}

}  // namespace

std::filesystem::path FindProgram(const std::string& argv0) {
  if (argv0.empty()) return {};
  if (argv0.find('/') != std::string::npos) {
    return access(argv0.c_str(), X_OK) == 0 ? std::filesystem::path(argv0)
                                            : std::filesystem::path();
  }
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    std::string candidate = dir;
    candidate.push_back('/');
    candidate.append(argv0);
    struct stat st {};
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return {};
}

std::string ProcessResult::Describe(const ProcessSpec& spec) const {
  char buf[160];
  if (!started) return "could not start: " + error;
  if (timed_out) {
    std::snprintf(buf, sizeof buf, "killed after its wall-clock limit of %.3g s", spec.wall_limit_s);
    return buf;
  }
  if (over_memory) {
    std::snprintf(buf, sizeof buf, "killed at its memory limit of %.0f MiB (resident %.0f MiB)",
                  spec.memory_limit_mib, peak_rss_mib);
    return buf;
  }
  if (signal != 0) {
    std::snprintf(buf, sizeof buf, "killed by signal %d (%s)", signal, strsignal(signal));
    return buf;
  }
  return "exit code " + std::to_string(exit_code);
}

ProcessResult RunProcess(const ProcessSpec& spec) {
  ProcessResult r;
  if (spec.argv.empty()) {
    r.error = "empty command";
    return r;
  }
  const std::filesystem::path program = FindProgram(spec.argv[0]);
  if (program.empty()) {
    r.error = "no executable program '" + spec.argv[0] + "'" +
              (spec.argv[0].find('/') != std::string::npos ? "" : " in PATH");
    return r;
  }
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> args = spec.argv;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string prog = program.string(), dir = spec.working_dir.string();
  const int out = open(spec.stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err = open(spec.stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int in = open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (out < 0 || err < 0 || in < 0) {
    r.error = std::string("cannot open the output files in ") + dir + ": " + std::strerror(errno);
    for (int fd : {out, err, in}) {
      if (fd >= 0) close(fd);
    }
    return r;
  }
  // A pipe closed on exec tells the parent whether exec failed (and why).
  int status_pipe[2];
  if (pipe2(status_pipe, O_CLOEXEC) != 0) {
    r.error = std::string("pipe: ") + std::strerror(errno);
    close(out), close(err), close(in);
    return r;
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    r.error = std::string("fork: ") + std::strerror(errno);
    close(out), close(err), close(in), close(status_pipe[0]), close(status_pipe[1]);
    return r;
  }
  if (pid == 0) {
    // The child: its own process group (killed as one), its folder, its files.
    setpgid(0, 0);
    if (chdir(dir.c_str()) == 0 && dup2(in, 0) >= 0 && dup2(out, 1) >= 0 && dup2(err, 2) >= 0) {
      execv(prog.c_str(), argv.data());
    }
    const int e = errno;
    [[maybe_unused]] ssize_t w = write(status_pipe[1], &e, sizeof e);
    _exit(127);
  }
  setpgid(pid, pid);  // also here: no race with the first poll
  close(out), close(err), close(in), close(status_pipe[1]);
  int exec_errno = 0;
  const ssize_t got = read(status_pipe[0], &exec_errno, sizeof exec_errno);
  close(status_pipe[0]);
  r.started = got != static_cast<ssize_t>(sizeof exec_errno);
  if (!r.started) r.error = "cannot run " + prog + ": " + std::strerror(exec_errno);

  int status = 0;
  // The end is polled from 0.1 ms, doubling up to poll_s (a short run is not kept waiting); the
  // memory every 50 ms (a scan of /proc).
  double poll_s = 1e-4, next_memory_s = 0.0;
  for (;;) {
    struct rusage usage {};
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) {
      r.wall_s = elapsed;
      // The kernel's own peak of the child's resident set (kB).
      r.peak_rss_mib = std::max(r.peak_rss_mib, static_cast<double>(usage.ru_maxrss) / 1024.0);
      break;
    }
    double rss = 0.0;
    if (elapsed >= next_memory_s) {
      rss = GroupResidentMiB(pid);
      if (rss > r.peak_rss_mib) r.peak_rss_mib = rss;
      next_memory_s = elapsed + 0.05;
    }
    const bool over_time = elapsed > spec.wall_limit_s;
    const bool over_memory = rss > spec.memory_limit_mib;
    if (over_time || over_memory) {
      r.timed_out = over_time;
      r.over_memory = !over_time && over_memory;
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.wall_s = elapsed;
      return r;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
    poll_s = std::min(2.0 * poll_s, spec.poll_s);
  }
  // Whatever the child left running in its group goes with it.
  kill(-pid, SIGKILL);
  if (WIFEXITED(status)) {
    r.exited = true;
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  return r;
}

std::string TailOfFile(const std::filesystem::path& file, int max_lines) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff from = size > 4096 ? size - 4096 : 0;
  in.seekg(from);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  size_t pos = text.size();
  for (int n = 0; n < max_lines && pos != std::string::npos && pos > 0; ++n) {
    pos = text.rfind('\n', pos - 1);
  }
  return pos == std::string::npos || pos == 0 ? text : text.substr(pos + 1);
}

}  // namespace rockbench::external
