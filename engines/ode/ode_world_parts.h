#pragma once
/// What the ODE worlds share, whatever they hold (the planar stack, OdeWorld in ode_world.h; the
/// cylinder, OdeCylinderWorld in ode_cylinder_world.h): the world with the [ode] settings and
/// its own threading implementation, the step (its overflow guard, the thread's data, the
/// stepper with the world's own generator state, the contact joints dropped), a contact's
/// surface, an undamped body, the kinematic ground body and the settings both write.
#include <ode/ode.h>

#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "engines/common/engine_input.h"
#include "engines/ode/ode_settings.h"

#if !defined(dDOUBLE)
#error "rockbench's ODE engine needs ODE built in double precision (dDOUBLE)"
#endif

namespace rockbench::ode {

static_assert(sizeof(dReal) == sizeof(double), "ODE must be double precision");

/// ODE adds 0.5 dt (omega x q) to each body's orientation quaternion q and normalises it: once
/// |omega| dt passes about 1e154 the squared norm overflows, and ODE aborts the process on the
/// quaternion it cannot normalise (assertion in dxNormalize4). A step whose bound on |omega| dt
/// exceeds this is not taken; 1e100 rad leaves 54 orders of magnitude for how loosely the bound
/// holds, and 96 above any real step (|omega| dt < 1e4).
inline constexpr double kMaxStepRotation_rad = 1e100;

/// |v| of a 3-vector (+inf past the range of a double: then the bound is exceeded anyway).
double Norm2(const dReal* v);

/// An ODE world for one run: the library acquired (AcquireOde), a threading implementation of
/// its own (see OdeWorld's class comment), gravity (gx, gy, gz) m/s^2 until the drive sets it,
/// the [ode] table's erp, cfm, contact_max_correcting_vel, contact_surface_layer and QuickStep
/// parameters, no auto-disable, no damping, and a joint group for the contacts of a step.
/// Destroys the contact group, the world (with its bodies and joints) and the threading
/// implementation and releases the library; geoms are the owner's, destroyed before.
class OdeWorldCore {
 public:
  /// Throws std::runtime_error when ODE cannot be initialised.
  OdeWorldCore(const OdeSettings& settings, double gx_mps2, double gy_mps2, double gz_mps2);
  ~OdeWorldCore();
  OdeWorldCore(const OdeWorldCore&) = delete;
  OdeWorldCore& operator=(const OdeWorldCore&) = delete;

  dWorldID world() const { return world_; }
  dJointGroupID contacts() const { return contacts_; }
  /// Why a step was not taken; empty: every step was.
  const std::string& fault() const { return fault_; }

  /// Before a step's contacts: false, with fault() saying why, when a step was already refused
  /// or `bound_rad` (a bound on |omega| dt in the step) exceeds kMaxStepRotation_rad; else
  /// allocates ODE's data for the calling thread when it is not the last one's, and true.
  bool MayStep(double bound_rad);
  /// dWorldStep, or dWorldQuickStep with this world's own state of ODE's generator under the
  /// process-wide lock, of dt_s; then the contact joints are dropped. Throws std::runtime_error
  /// when the step fails (out of memory).
  void Advance(double dt_s);

 private:
  OdeSettings s_;
  dxThreadingImplementation* threading_ = nullptr;
  dWorldID world_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  unsigned long rand_seed_ = 0;  // this world's state of ODE's generator (QuickStep's order)
  std::string fault_;
  std::thread::id thread_;  // last thread that allocated ODE's per-thread data for this world
};

/// A contact's Coulomb coefficient and law: the scene's finite coefficient with Coulomb's
/// pyramid (dContactApprox1), else the settings' friction and friction_pyramid.
struct OdeFriction {
  double mu = 0.0;
  bool pyramid = false;
};
OdeFriction FrictionOf(double scene_mu, const OdeSettings& settings);

/// A contact's surface: soft ERP and CFM (contact_erp, contact_cfm), the friction `f`, and a
/// bounce of the settings' restitution (none at 0). The friction directions are the caller's.
void SetSurface(dSurfaceParameters* surface, const OdeSettings& settings, const OdeFriction& f);

/// A dynamic body as both worlds have it: never auto-disabled, no damping, and the exact
/// rotation of a step when finite_rotation is on.
void SetUndampedBody(dBodyID body, const OdeSettings& settings);

/// A kinematic body at p_m moving with v_mps (the kinematic drive's ground).
dBodyID MakeKinematicBody(dWorldID world, const double p_m[3], const double v_mps[3]);

/// JSON has no infinity: null stands for ODE's dInfinity (no cap, never slips).
nlohmann::json FiniteOrNull(double v);

/// The settings both worlds write to summary.json: ODE's version and configuration, drive,
/// steps, stepper, the world's and contacts' parameters read back, friction, restitution,
/// finite rotation, the kinematic high-pass and auto-disable.
nlohmann::json CommonSettings(const EngineInput& input, const OdeSettings& settings,
                              dWorldID world);

}  // namespace rockbench::ode
