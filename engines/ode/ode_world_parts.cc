#include "engines/ode/ode_world_parts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

#include "engines/ode/ode_library.h"

namespace rockbench::ode {

double Norm2(const dReal* v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

OdeWorldCore::OdeWorldCore(const OdeSettings& settings, double gx_mps2, double gy_mps2,
                           double gz_mps2)
    : s_(settings) {
  AcquireOde();
  thread_ = std::this_thread::get_id();
  world_ = dWorldCreate();
  // A threading implementation of its own (see OdeWorld's class comment).
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  if (threading_ == nullptr) {
    dWorldDestroy(world_);
    ReleaseOde();
    throw std::runtime_error("ode: dThreadingAllocateSelfThreadedImplementation failed");
  }
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                       threading_);
  dWorldSetGravity(world_, gx_mps2, gy_mps2, gz_mps2);
  dWorldSetERP(world_, s_.erp);
  dWorldSetCFM(world_, s_.cfm);
  dWorldSetContactMaxCorrectingVel(world_, s_.contact_max_correcting_vel_mps);
  dWorldSetContactSurfaceLayer(world_, s_.contact_surface_layer_m);
  dWorldSetQuickStepNumIterations(world_, s_.quick_step_iterations);
  dWorldSetQuickStepW(world_, s_.quick_step_w);
  dWorldSetAutoDisableFlag(world_, 0);
  dWorldSetLinearDamping(world_, 0);
  dWorldSetAngularDamping(world_, 0);
  contacts_ = dJointGroupCreate(0);
}

OdeWorldCore::~OdeWorldCore() {
  if (contacts_) dJointGroupDestroy(contacts_);
  // dWorldDestroy destroys the bodies and the (non-group) joints.
  if (world_) dWorldDestroy(world_);
  if (threading_) dThreadingFreeImplementation(threading_);
  ReleaseOde();
}

bool OdeWorldCore::MayStep(double bound_rad) {
  if (!fault_.empty()) return false;  // the run has ended
  if (!(bound_rad <= kMaxStepRotation_rad)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "ODE's orientation update would overflow (|omega| dt up to %.3g rad, on "
                  "which ODE aborts): the step was not taken",
                  bound_rad);
    fault_ = buf;
    return false;
  }
  if (std::this_thread::get_id() != thread_) {
    AllocateForThisThread();
    thread_ = std::this_thread::get_id();
  }
  return true;
}

void OdeWorldCore::Advance(double dt_s) {
  int ok = 0;
  if (s_.stepper == OdeStepper::kQuickStep) {
    // QuickStep reorders its rows at random, drawing from ODE's one process-wide generator
    // (dRandInt). Each world keeps its own generator state and steps with it under a lock, so a
    // run does not depend on what other worlds, in this thread or another, drew before it
    // (measured before this: the same sweep gave different errors from run to run).
    std::lock_guard<std::mutex> lock(QuickStepMutex());
    dRandSetSeed(rand_seed_);
    ok = dWorldQuickStep(world_, dt_s);
    rand_seed_ = dRandGetSeed();
  } else {
    ok = dWorldStep(world_, dt_s);
  }
  dJointGroupEmpty(contacts_);
  if (!ok) throw std::runtime_error("ode: the step failed (out of memory)");
}

OdeFriction FrictionOf(double scene_mu, const OdeSettings& settings) {
  const bool scene_friction = std::isfinite(scene_mu);
  return {scene_friction ? scene_mu : settings.friction,
          scene_friction || settings.friction_pyramid};
}

void SetSurface(dSurfaceParameters* surface, const OdeSettings& settings, const OdeFriction& f) {
  dSurfaceParameters& sp = *surface;
  sp.mode = dContactSoftERP | dContactSoftCFM;
  sp.mu = f.mu;
  sp.soft_erp = settings.contact_erp;
  sp.soft_cfm = settings.contact_cfm;
  if (f.pyramid) sp.mode |= dContactApprox1;
  if (settings.restitution > 0.0) {
    sp.mode |= dContactBounce;
    sp.bounce = settings.restitution;
    sp.bounce_vel = 0.0;
  }
}

void SetUndampedBody(dBodyID body, const OdeSettings& settings) {
  dBodySetAutoDisableFlag(body, 0);
  dBodySetDamping(body, 0, 0);
  if (settings.finite_rotation) {
    dBodySetFiniteRotationMode(body, 1);
    dBodySetFiniteRotationAxis(body, 0, 0, 0);  // full finite rotation
  }
}

dBodyID MakeKinematicBody(dWorldID world, const double p_m[3], const double v_mps[3]) {
  dBodyID body = dBodyCreate(world);
  dBodySetKinematic(body);
  dBodySetPosition(body, p_m[0], p_m[1], p_m[2]);
  dBodySetLinearVel(body, v_mps[0], v_mps[1], v_mps[2]);
  return body;
}

nlohmann::json FiniteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json CommonSettings(const EngineInput& input, const OdeSettings& s, dWorldID world) {
  const double dt = input.time_step_s;
  nlohmann::json j;
  j["ode_version"] = dODE_VERSION;
  j["ode_configuration"] = dGetConfiguration();
  j["precision"] = "double";
  j["drive"] = DriveKindName(input.drive_kind);
  j["time_step_s"] = dt;
  j["output_interval_s"] = input.run.output_interval_s;
  j["substeps_per_sample"] = std::max(1.0, std::round(input.run.output_interval_s / dt));
  j["stepper"] = OdeStepperName(s.stepper);
  if (s.stepper == OdeStepper::kQuickStep) {
    j["quick_step_iterations"] = dWorldGetQuickStepNumIterations(world);
    j["quick_step_w"] = dWorldGetQuickStepW(world);
  }
  j["erp"] = dWorldGetERP(world);
  j["cfm"] = dWorldGetCFM(world);
  j["contact_erp"] = s.contact_erp;
  j["contact_cfm"] = s.contact_cfm;
  j["contact_max_correcting_vel_mps"] = FiniteOrNull(dWorldGetContactMaxCorrectingVel(world));
  j["contact_surface_layer_m"] = dWorldGetContactSurfaceLayer(world);
  j["friction"] = FiniteOrNull(s.friction);
  j["restitution"] = s.restitution;
  j["finite_rotation"] = s.finite_rotation;
  j["kinematic_highpass_hz"] = input.kinematic_highpass_hz;
  j["auto_disable"] = false;
  return j;
}

}  // namespace rockbench::ode
