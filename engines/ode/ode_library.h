#pragma once
/// ODE's process-wide state, shared by every ODE world of the process (the planar OdeWorld and
/// the OdeCylinderWorld): the library's reference count and the per-thread data (see OdeWorld's
/// class comment, ode_world.h), and the lock under which QuickStep worlds step one at a time.
#include <mutex>

namespace rockbench::ode {

/// The first live world initialises the library (dInitODE2), and every call allocates ODE's
/// data for the calling thread. Throws std::runtime_error when ODE cannot be initialised.
void AcquireOde();
/// The last live world closes the library (dCloseODE).
void ReleaseOde();
/// ODE's per-thread data for the calling thread (a world stepped in another thread than the one
/// that built it). Throws std::runtime_error on failure.
void AllocateForThisThread();
/// QuickStep reorders its rows at random, drawing from ODE's one process-wide generator
/// (dRandInt): worlds step with QuickStep under this lock, each with its own generator state.
std::mutex& QuickStepMutex();

}  // namespace rockbench::ode
