#include "util/stop_request.h"

#include <atomic>

namespace rockbench {
namespace {

// Lock-free, so that a signal handler may set it.
std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

}  // namespace

void RequestStop() {
  g_stop_requested.store(true);
}

void ClearStopRequest() {
  g_stop_requested.store(false);
}

bool StopWasRequested() {
  return g_stop_requested.load(std::memory_order_relaxed);
}

void ThrowIfStopRequested() {
  if (StopWasRequested()) throw StopRequested();
}

}  // namespace rockbench
