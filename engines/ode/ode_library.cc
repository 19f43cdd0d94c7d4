#include "engines/ode/ode_library.h"

#include <ode/ode.h>

#include <stdexcept>

namespace rockbench::ode {
namespace {

// Process-wide ODE library state. dInitODE2 / dCloseODE use an unguarded static counter in
// ODE 0.16, and ODE's documentation allows dInitODE2 only once until dCloseODE: the first live
// world initialises the library, the last one closes it, under this mutex. The same mutex
// guards dAllocateODEDataForThread (whose bookkeeping is global in a build without TLS).
std::mutex g_ode_mutex;
int g_ode_worlds = 0;

}  // namespace

void AcquireOde() {
  std::lock_guard<std::mutex> lock(g_ode_mutex);
  if (g_ode_worlds == 0 && !dInitODE2(0)) throw std::runtime_error("ode: dInitODE2 failed");
  ++g_ode_worlds;
  if (!dAllocateODEDataForThread(dAllocateMaskAll)) {
    if (--g_ode_worlds == 0) dCloseODE();
    throw std::runtime_error("ode: dAllocateODEDataForThread failed");
  }
}

void ReleaseOde() {
  std::lock_guard<std::mutex> lock(g_ode_mutex);
  if (--g_ode_worlds == 0) dCloseODE();
}

void AllocateForThisThread() {
  std::lock_guard<std::mutex> lock(g_ode_mutex);
  if (!dAllocateODEDataForThread(dAllocateMaskAll)) {
    throw std::runtime_error("ode: dAllocateODEDataForThread failed");
  }
}

std::mutex& QuickStepMutex() {
  static std::mutex quick_step_mutex;
  return quick_step_mutex;
}

}  // namespace rockbench::ode
