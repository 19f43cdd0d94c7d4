#include "util/wall_limit.h"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
  // hold spaces and parentheses (the last ')' ends it). readdir itself: a process that ends
  // while the folder is read must not cut the listing short.
  std::multimap<int, int> children;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return {};
  while (const dirent* entry = ::readdir(proc)) {
    const std::string name = entry->d_name;
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const int fd = ::open(("/proc/" + name + "/stat").c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;  // gone meanwhile
    char buf[1024];
    const ssize_t n = ::read(fd, buf, sizeof buf - 1);
    ::close(fd);
    if (n <= 0) continue;
    const std::string stat(buf, static_cast<size_t>(n));
    const size_t close = stat.rfind(')');
    if (close == std::string::npos || close + 4 >= stat.size()) continue;
    const char state = stat[close + 2];
    if (state == 'Z' || state == 'X' || state == 'x') continue;
    const int ppid = std::atoi(stat.c_str() + close + 4);
    children.emplace(ppid, std::atoi(name.c_str()));
  }
  ::closedir(proc);
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

namespace {

// The termination signals' self-pipe: the handler (on whatever thread the kernel chose) writes
// the signal's number, the cleanup thread reads it.
int g_signal_pipe[2] = {-1, -1};

void OnTerminationSignal(int sig) {
  const int saved = errno;
  const unsigned char s = static_cast<unsigned char>(sig);
  (void)!::write(g_signal_pipe[1], &s, 1);
  errno = saved;
}

}  // namespace

void HandleTerminationSignals() {
  if (::pipe2(g_signal_pipe, O_CLOEXEC) != 0) return;
  for (const int sig : {SIGTERM, SIGINT, SIGHUP}) {
    // A signal ignored when the process started (nohup, a background job's SIGINT) stays so.
    struct sigaction old = {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa = {};
    sa.sa_handler = OnTerminationSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(sig, &sa, nullptr);
  }
  std::thread([] {
    unsigned char s = 0;
    while (::read(g_signal_pipe[0], &s, 1) != 1) {
    }
    const int sig = s;
    if (!ClaimEnd()) HoldForever();
    CleanUpForEnd();
    const char* name = sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP";
    WriteStderr(std::string("rockbench: stopped by ") + name +
                ": its processes ended and its temporary files removed\n");
    // Die of the same signal (a shell sees why): its default action, delivered to this thread.
    struct sigaction dfl = {};
    dfl.sa_handler = SIG_DFL;
    ::sigaction(sig, &dfl, nullptr);
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
