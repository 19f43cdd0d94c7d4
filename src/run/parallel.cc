#include "run/parallel.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "util/stop_request.h"

namespace rockbench {
namespace {

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void ParallelFor(int n, int threads, const std::function<void(int)>& job,
                 const std::function<void(int, int)>& progress) {
  if (n <= 0) return;
  unsigned count = threads > 0 ? static_cast<unsigned>(threads)
                               : std::max(1u, std::thread::hardware_concurrency());
  count = std::min<unsigned>(count, static_cast<unsigned>(n));
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::exception_ptr error;
  int done = 0;
  auto worker = [&] {
    for (;;) {
      if (failed.load()) return;
      const int i = next.fetch_add(1);
      if (i >= n) return;
      try {
        // No new job once a stop is requested (util/stop_request.h).
        ThrowIfStopRequested();
        job(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, n);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < count; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

ProgressLine::ProgressLine(std::string label)
    : ProgressLine(std::move(label), stderr, isatty(STDERR_FILENO) == 1) {}

ProgressLine::ProgressLine(std::string label, std::FILE* out, bool terminal)
    : label_(std::move(label)), out_(out), terminal_(terminal), start_s_(NowSeconds()) {}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fprintf(out_, "\n");
}

void ProgressLine::Update(int done, int total) {
  if (!terminal_) return;
  const double now = NowSeconds();
  if (done < total && now - last_draw_s_ < 0.1) return;
  last_draw_s_ = now;
  const double elapsed = now - start_s_;
  const double left = done > 0 ? elapsed * (total - done) / done : 0.0;
  const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
  std::fprintf(out_, "\r%s: %d/%d, %.3g/s, %.1f s elapsed, about %.1f s left   ", label_.c_str(),
               done, total, rate, elapsed, left);
  std::fflush(out_);
  drawn_ = true;
}

}  // namespace rockbench
