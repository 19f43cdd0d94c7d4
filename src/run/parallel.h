#pragma once
/// Runs independent jobs on a pool of threads, with progress on a terminal.
#include <cstdio>
#include <functional>
#include <string>

namespace rockbench {

/// Calls job(i) for i in [0, n) on `threads` threads (0: the hardware's). Each index runs once;
/// results go wherever job(i) writes them (a slot per index keeps them in order, whatever the
/// thread count). The first exception thrown by a job is rethrown after every thread stopped;
/// once a stop is requested (util/stop_request.h) no job starts, and StopRequested is thrown.
void ParallelFor(int n, int threads, const std::function<void(int)>& job,
                 const std::function<void(int done, int total)>& progress = {});

/// A progress line on standard error ("label: 12/64, 3.87/s, 3.1 s elapsed, about 2.0 s left")
/// (done, total, rate per second, elapsed and remaining time) that
/// redraws itself in place, only when standard error is a terminal; quiet otherwise.
class ProgressLine {
 public:
  explicit ProgressLine(std::string label);
  /// Draws on `out` when `terminal` (for tests).
  ProgressLine(std::string label, std::FILE* out, bool terminal);
  ~ProgressLine();
  /// Draws done/total (at most every 0.1 s, and always at done == total).
  void Update(int done, int total);

 private:
  std::string label_;
  std::FILE* out_ = stderr;
  bool terminal_ = false;
  bool drawn_ = false;
  double start_s_ = 0.0, last_draw_s_ = -1.0;
};

}  // namespace rockbench
