#pragma once
/// The ODE scene of the 3-D cylinder (shape "cylinder", docs/cylinder-3d.md): one body with
/// ODE's own cylinder geom on a ground plane, satisfying CylinderWorld
/// (engines/common/cylinder_world.h). ODE's world is z up, as the cylinder's: no axis mapping.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "engines/common/cylinder_world.h"
#include "engines/common/engine_input.h"
#include "engines/ode/ode_settings.h"

// ODE's handles (ode/common.h), declared here so that this header does not pull in ODE.
struct dxBody;
struct dxGeom;
struct dContact;

namespace rockbench::ode {

class OdeWorldCore;

/// Most contact points dCollideCylinderPlane makes (ODE 0.16.2, collision_cylinder_plane.cpp),
/// and OdeCylinderWorld's completion of it near upright: tilted, the deepest point of each cap's
/// rim (the lowest rim point, exact; the top cap's only once it is under the plane too); with
/// the axis within about 4.5e-4 rad of the normal (|cos(tilt) - 1| < 1e-7), four points of the
/// lower cap's rim, 90 degrees apart, those under the plane (ODE's: none while the cap's centre
/// is above the plane; see OdeSettings::cylinder_upright_rim).
inline constexpr int kCylinderPlaneMaxContacts = 4;

/// An ODE world holding a solid cylinder (dCreateCylinder, its axis the body's z, the
/// CylinderBodyDef's mass and inertia set explicitly) on the plane z = base height
/// (dCreatePlane). Inertial drive: the plane is still and the base acceleration tilts gravity.
/// Kinematic drive: the plane follows the base's height, and the contacts are attached to a
/// kinematic body moving with the base's velocity (a plane has no body of its own; the contact
/// rows take the relative velocity of their two bodies, so friction carries the base's
/// horizontal motion). Contacts come from dCollide at every step into a joint group emptied after
/// it. ODE's library and threads: as OdeWorld (ode_world.h); one world is used by one thread at
/// a time. Keeps a reference to `input`, which must outlive it.
class OdeCylinderWorld {
 public:
  /// Throws std::invalid_argument for an input it cannot run (a kinematic drive without its
  /// samples) and std::runtime_error when ODE cannot be initialised.
  OdeCylinderWorld(const EngineInput& input, const OdeSettings& settings);
  ~OdeCylinderWorld();
  OdeCylinderWorld(const OdeCylinderWorld&) = delete;
  OdeCylinderWorld& operator=(const OdeCylinderWorld&) = delete;

  /// Sets the base motion for step n (t_n to t_{n+1}). Inertial: gravity (-a_x, -a_y,
  /// -(g + a_z)) with a = CylinderDriveAccel(n). Kinematic: the plane at u_n's height, the
  /// ground body at u_n moving with (u_{n+1} - u_n) / dt.
  void ApplyDrive(std::int64_t n);
  /// One fixed step: contact joints from dCollide at the current pose, dWorldStep (or
  /// dWorldQuickStep), then the contact joints are dropped. A step whose rotation could overflow
  /// ODE's orientation update (as OdeWorld::Step) is not taken: ReadPose is then not finite and
  /// the monitor ends the run (status non_finite).
  void Step();
  /// The pose after the last step, relative to the base (kinematic: minus u_n and the ground's
  /// velocity during the last step; ODE's body position is the mass centre).
  CylinderPose ReadPose() const;
  /// Settings in use (ours and the ODE values they set) for summary.json.
  nlohmann::json Settings() const;

  /// Contact points created in the last step.
  int last_contacts() const { return contacts_; }
  /// Why the last step was not taken; empty: every step was.
  const std::string& fault() const;

 private:
  // The contact points with the plane at the current pose into `contact` (room for
  // kCylinderPlaneMaxContacts): dCollideCylinderPlane's, completed near upright when
  // OdeSettings::cylinder_upright_rim is on. Returns their number.
  int Collide(dContact* contact) const;
  // A bound on |omega| dt the cylinder can reach in the next step, rad (as OdeWorld's).
  double StepRotationBound_rad() const;

  const EngineInput& in_;
  OdeSettings s_;
  CylinderBodyDef body_def_;
  double dt_ = 0.0;
  bool kinematic_ = false;
  double mu_ = 0.0;         // the contact's Coulomb coefficient (scene's, else the table's)
  bool pyramid_ = false;    // dContactApprox1
  std::int64_t steps_ = 0;  // steps taken
  int max_contacts_ = 0;    // points asked of dCollide
  int contacts_ = 0;        // points of the last step
  // The world, its contact joints and its step (ode_world_parts.h).
  std::unique_ptr<OdeWorldCore> core_;
  dxBody* body_ = nullptr;
  dxGeom* geom_ = nullptr;
  dxGeom* plane_ = nullptr;
  dxBody* ground_body_ = nullptr;  // kinematic drive only
};

}  // namespace rockbench::ode
