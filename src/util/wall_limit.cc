#include "util/wall_limit.h"

#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace rockbench {
namespace {

// The temporary names of this process, each with whether it is a folder.
struct Registry {
  std::mutex mutex;
  std::vector<std::pair<std::filesystem::path, bool>> names;
};

Registry& TheRegistry() {
  static Registry* registry = new Registry;  // never destroyed: used until _exit
  return *registry;
}

// Set once, by the first of a termination signal, the wall-clock limit and the normal end.
std::atomic<bool> g_ending{false};

[[noreturn]] void HoldForever() {
  for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
}

// Claims the end of the process: false when another thread already did (it ends the process).
bool ClaimEnd() {
  bool expected = false;
  return g_ending.compare_exchange_strong(expected, true);
}

// Removes the registered names that exist; with `forget`, empties the registry.
void RemoveRegistered(bool forget) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::error_code ec;
  for (const auto& [path, folder] : r.names) {
    if (folder) {
      std::filesystem::remove_all(path, ec);
    } else {
      ::unlink(path.c_str());
    }
  }
  if (forget) r.names.clear();
}

// What a signal or the limit does before the process ends: its descendants ended, then its
// temporaries removed in three passes 50 ms apart (a thread may have been creating one: it is
// held at its next registration, and a write in flight lands between two passes).
void CleanUpForEnd() {
  EndDescendants(0.5);
  for (int pass = 0; pass < 3; ++pass) {
    if (pass > 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    RemoveRegistered(/*forget=*/pass == 2);
  }
}

void WriteStderr(const std::string& text) {
  (void)!::write(STDERR_FILENO, text.data(), text.size());
}

double Now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void RegisterTemporary(const std::filesystem::path& path, bool folder) {
  {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.names.emplace_back(path, folder);
  }
  // Registered first: the ending's next removal pass takes it.
  if (g_ending.load()) HoldForever();
}

void ForgetTemporary(const std::filesystem::path& path) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  const auto it = std::find_if(r.names.rbegin(), r.names.rend(),
                               [&](const auto& n) { return n.first == path; });
  if (it != r.names.rend()) r.names.erase(std::next(it).base());
}

std::vector<std::filesystem::path> RegisteredTemporaries() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::filesystem::path> out;
  for (const auto& n : r.names) out.push_back(n.first);
  return out;
}

void RemoveRegisteredTemporaries() {
  RemoveRegistered(/*forget=*/true);
}

bool ProcessEnding() {
  return g_ending.load();
}

void HoldIfEnding() {
  if (g_ending.load()) HoldForever();
}

bool BecomeSubreaper() {
  return ::prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0;
}

std::vector<int> Descendants() {
  // Every live process's parent, from /proc/PID/stat: "PID (COMM) STATE PPID ...", COMM may
  // hold spaces and parentheses (the last ')' ends it).
  std::multimap<int, int> children;
  std::error_code ec;
  for (std::filesystem::directory_iterator it("/proc", ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(it->path() / "stat");
    std::string stat;
    if (!std::getline(in, stat)) continue;  // gone meanwhile
    const size_t close = stat.rfind(')');
    if (close == std::string::npos || close + 4 >= stat.size()) continue;
    const char state = stat[close + 2];
    if (state == 'Z' || state == 'X' || state == 'x') continue;
    const int ppid = std::atoi(stat.c_str() + close + 4);
    children.emplace(ppid, std::atoi(name.c_str()));
  }
  std::vector<int> out;
  std::vector<int> todo{static_cast<int>(::getpid())};
  while (!todo.empty()) {
    const int p = todo.back();
    todo.pop_back();
    const auto [lo, hi] = children.equal_range(p);
    for (auto c = lo; c != hi; ++c) {
      // A pid seen twice (a parent link read mid-change) is taken once.
      if (std::find(out.begin(), out.end(), c->second) != out.end()) continue;
      out.push_back(c->second);
      todo.push_back(c->second);
    }
  }
  return out;
}

int EndDescendants(double grace_s) {
  int signalled = 0;
  std::vector<int> left = Descendants();
  if (left.empty()) return 0;
  // First SIGTERM (a rockbench worker removes its own temporaries), and the grace period.
  for (const int pid : left) signalled += ::kill(pid, SIGTERM) == 0 ? 1 : 0;
  const double until_s = Now_s() + grace_s;
  while (!(left = Descendants()).empty() && Now_s() < until_s) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Then SIGKILL, until none is left (one may have started another before it died; a process
  // orphaned meanwhile is re-parented to this one, the subreaper).
  for (int round = 0; round < 200 && !left.empty(); ++round) {
    for (const int pid : left) signalled += ::kill(pid, SIGKILL) == 0 ? 1 : 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    left = Descendants();
  }
  return signalled;
}

void HandleTerminationSignals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&set, sig);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    if (!ClaimEnd()) HoldForever();
    CleanUpForEnd();
    const char* name = sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP";
    WriteStderr(std::string("rockbench: stopped by ") + name +
                ": its processes ended and its temporary files removed\n");
    // Die of the same signal (a shell sees why): its default action, delivered to this thread.
    ::signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    ::raise(sig);
    ::_exit(128 + sig);
  }).detach();
}

void CleanUpAtExit() {
  if (!ClaimEnd()) HoldForever();
  if (!Descendants().empty()) EndDescendants(0.5);
  RemoveRegistered(/*forget=*/true);
}

void StartWallLimit(double seconds, const std::filesystem::path& /*out_dir*/,
                    const std::string& command) {
  if (!(seconds > 0.0) || !std::isfinite(seconds)) return;
  std::thread([seconds, command] {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    if (!ClaimEnd()) HoldForever();
    CleanUpForEnd();
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", seconds);
    WriteStderr("rockbench " + command + ": error: wall-clock limit of " + limit +
                " s reached (--wall-limit); no output written for what was unfinished\n");
    ::_exit(kExitWallLimit);
  }).detach();
}

}  // namespace rockbench
