#pragma once
/// A request to stop the work in progress, from a program that embeds rockbench's libraries and
/// keeps running after it (the Python module, on Ctrl-C): the thread pools start no new job, the
/// study's pool ends its workers, and a fixed-step engine stops at its next step, each by
/// throwing StopRequested. What was already written stays whole (files are renamed into place
/// only when complete; a study's journal holds whole rows). The command line does not use it:
/// a signal ends the process (util/wall_limit.h).
#include <stdexcept>

namespace rockbench {

/// Thrown by the work that saw a stop request.
struct StopRequested : std::runtime_error {
  StopRequested() : std::runtime_error("stopped on request (interrupted)") {}
};

/// Asks the work in progress, in every thread, to stop. Thread- and signal-safe.
void RequestStop();
/// Withdraws the request (before starting new work).
void ClearStopRequest();
/// Whether a stop was requested.
bool StopWasRequested();
/// Throws StopRequested when a stop was requested.
void ThrowIfStopRequested();

}  // namespace rockbench
