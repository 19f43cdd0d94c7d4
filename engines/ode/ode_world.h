#pragma once
/// The ODE scene of one block or two stacked blocks: the same semantics as Bullet's
/// RockingWorld (engines/bullet/rocking_world.h), so that the Monitor reads both alike.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/ode/ode_settings.h"

// ODE's handles (ode/common.h), declared here so that this header does not pull in ODE.
struct dxBody;
struct dxGeom;
struct dxJoint;

namespace rockbench::ode {

class OdeWorldCore;

/// An ODE world holding a static (inertial drive) or kinematic (kinematic drive) ground box and
/// N box blocks placed by the pivot chain (PlaceStack), each held in the x-y plane by a
/// Plane2D joint. Contacts come from dCollide on the pairs of neighbours (block 1 - ground,
/// block k - block k - 1; with two blocks also block 2 - ground, as before issue 23) into a
/// joint group emptied after every step. Keeps a reference to `input`, which must outlive it.
///
/// Threads: ODE 0.16.2 as Debian builds it has no TLS ("ODE_EXT_ou" is missing from
/// dGetConfiguration()), and its library reference count (dInitODE2/dCloseODE) is a plain
/// static counter. OdeWorld keeps its own count under a mutex: the first live world calls
/// dInitODE2, the last one dCloseODE, and every thread that builds or steps a world calls
/// dAllocateODEDataForThread under that mutex. Each world has its own self-threaded threading
/// implementation: ODE's default one is a single process-wide object built on fake (no-op)
/// locks; ODE's threading_impl.h says to give each world its own when worlds are stepped in
/// parallel, and four raw ODE worlds stepped at once on the default one aborted with "assertion
/// failed in WaitWakeup() [threading_fake_sync.h:83]". With that, no collision space and each
/// world's own step memory, worlds in different threads share nothing mutable (measured: 40 runs
/// in 4 concurrent threads were bit-identical to sequential runs; QuickStep worlds step one at a
/// time, each with its own state of ODE's random generator). One world must not be used by
/// two threads at once; it may move from one thread to another between steps.
class OdeWorld {
 public:
  /// Throws std::invalid_argument for impossible settings (non-positive step, negative
  /// friction, ...) and std::runtime_error when ODE cannot be initialised.
  OdeWorld(const EngineInput& input, const OdeSettings& settings);
  ~OdeWorld();
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// (-xg''(t_n), -(g + yg''(t_n)), 0). Kinematic drive: the ground at u(t_n) moving with
  /// (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One fixed step: contact joints from dCollide at the current poses, dWorldStep (or
  /// dWorldQuickStep), then the contact joints are dropped. A step whose rotation could
  /// overflow ODE's orientation update (StepRotationBound_rad above kMaxStepRotation_rad: ODE
  /// would abort) is not taken: it is read as StepReadout::engine_fault, and the monitor ends
  /// the run there (status non_finite).
  void Step();
  /// The state after n steps, read from the bodies (ODE's body position is the mass centre).
  StepReadout Read(std::int64_t n) const;
  /// Settings in use (ours and the ODE values they set) for summary.json.
  nlohmann::json Settings() const;

  /// Contact points created in the last step: block 1 - ground, between blocks (every
  /// interface), block 2 - ground (two blocks only, once block 2 has fallen off).
  int last_contacts_ground() const { return contacts_ground_; }
  int last_contacts_interface() const { return contacts_interface_; }
  int last_contacts_block2_ground() const { return contacts_block2_ground_; }

 private:
  // Contact joints between geoms a and b (bodies body_a, body_b; null: the static ground) at
  // the current poses; returns their number. `scene_mu`: the pair's Coulomb coefficient from the
  // scene (finite: Coulomb's pyramid, dContactApprox1, with that mu), infinite: the settings'
  // friction and friction_pyramid.
  int Collide(dxGeom* a, dxGeom* b, dxBody* body_a, dxBody* body_b, double scene_mu);
  // A bound on |omega| dt any block can reach in the next step, rad: the fastest point of a
  // block (|v| + |omega| times its half-diagonal) plus the effective gravity (and, kinematic, the
  // ground's speed) times dt, over the smallest half-size of a block, times dt. Contact impulses
  // turn a block at most that fast about a point of its outline.
  double StepRotationBound_rad() const;

  const EngineInput& in_;
  OdeSettings s_;
  double dt_ = 0.0;
  bool kinematic_ = false;
  double ground_half_depth_m_ = 0.0;
  // The world, its contact joints and its step (ode_world_parts.h).
  std::unique_ptr<OdeWorldCore> core_;
  dxBody* ground_body_ = nullptr;  // kinematic drive only
  dxGeom* ground_geom_ = nullptr;
  // Per block, bottom first.
  std::vector<dxBody*> bodies_;
  std::vector<dxGeom*> geoms_;
  std::vector<dxJoint*> planes_;
  int contacts_ground_ = 0, contacts_interface_ = 0, contacts_block2_ground_ = 0;
};

}  // namespace rockbench::ode
