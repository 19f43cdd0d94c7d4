#include "engines/external/command.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

#include "util/subprocess.h"

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

std::string CommandResult::Describe(const CommandSpec& spec) const {
  char buf[160];
  if (!started) return "could not start: " + start_error;
  if (timed_out) {
    std::snprintf(buf, sizeof buf, "killed after its wall-clock limit of %.3g s",
                  spec.wall_limit_s);
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

CommandResult RunCommand(const CommandSpec& spec) {
  CommandResult r;
  SpawnOptions options;
  options.in = Stdio::kNull;
  options.out = Stdio::kNull;
  options.err = Stdio::kNull;
  options.err_log = spec.stderr_file;
  options.working_dir = spec.working_dir;
  options.own_process_group = true;
  // A rockbench that is killed takes the engine with it.
  options.die_with_parent = true;
  const auto start = std::chrono::steady_clock::now();
  Subprocess child(spec.argv, options);
  if (!child.started()) {
    r.start_error = child.start_error();
    return r;
  }
  r.started = true;
  const pid_t group = child.pid();
  // The end is polled from 0.1 ms, doubling up to 5 ms (a short run is not kept waiting); the
  // memory every 50 ms.
  double poll_s = 1e-4, next_memory_s = 0.0;
  for (;;) {
    const std::optional<ExitStatus> done = child.TryWait();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done) {
      r.wall_s = elapsed;
      r.exit_code = done->exit_code;
      r.signal = done->signal;
      break;
    }
    if (elapsed >= next_memory_s) {
      const double rss = GroupResidentMiB(group);
      r.peak_rss_mib = std::max(r.peak_rss_mib, rss);
      r.over_memory = rss > spec.memory_limit_mib;
      next_memory_s = elapsed + 0.05;
    }
    r.timed_out = elapsed > spec.wall_limit_s;
    if (r.timed_out || r.over_memory) {
      if (r.timed_out) r.over_memory = false;
      child.Kill(SIGKILL);
      child.Wait();
      r.wall_s = elapsed;
      return r;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
    poll_s = std::min(2.0 * poll_s, 5e-3);
  }
  // Whatever it left running in its group goes with it.
  ::kill(-group, SIGKILL);
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
