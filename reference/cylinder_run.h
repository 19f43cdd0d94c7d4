#pragma once
/// The reference's run of a cylinder scene (shape "cylinder", docs/three-d.md): rest on the face,
/// onset, rocking-rolling on a rim point (cylinder_model.h), landings, and the boundaries of the
/// model (overturn, lift-off, slip), located as the planar model locates its events.
#include <optional>
#include <string>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "reference/cylinder/cylinder_model.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::reference::cylinder {

/// What a cylinder run tallies.
struct CylinderSummary {
  RunStatus status = RunStatus::kCompleted;
  std::string status_detail;  ///< why, for assumption_violated and non_finite
  double end_s = 0.0;         ///< last simulated time, s
  double peak_tilt_rad = 0.0, peak_tilt_t_s = 0.0;
  int landings = 0;     ///< plastic impacts of the face on the base
  int initiations = 0;  ///< onsets from rest
  int rests = 0;        ///< landings that came to rest
  /// Overturn (tilt reached model.overturn_angle): when, and the azimuth toward which the top
  /// fell, wrapped to (-pi, pi] (rad, from +x toward +y).
  std::optional<double> overturn_t_s;
  double overturn_azimuth_rad = 0.0;
  /// The landing rule: a pass lands at the downward crossing of this tilt (asin of
  /// model.landing_clearance_rel), or at tilt 0 in a planar run (`planar`).
  double landing_tilt_rad = 0.0;
  bool planar = false;  ///< the motion keeps one vertical plane exactly (no azimuth or spin)
  /// On the rim: the largest |F_t| / N the rolling needed and the smallest N / (m g).
  double friction_needed = 0.0;
  double min_normal_rel = 0.0;
  /// Rim passes near upright that turned above the landing tilt (rolling round the rim): their
  /// count and the smallest tilt they reached, rad.
  int passes = 0;
  double min_pass_tilt_rad = 0.0;
  long steps_accepted = 0, steps_rejected = 0;
};

struct CylinderResult {
  History history;  ///< shape "cylinder": CylinderKind's columns; events
  CylinderSummary summary;
};

/// Runs the cylinder of `scene` (one body of shape "cylinder") under `motion`. The integrator,
/// its tolerances, the rest rule and the overturn angle are the scene's [model] settings, as for
/// the planar model.
CylinderResult SimulateCylinder(const Scene& scene, const GroundMotion& motion);

/// The body of a cylinder scene.
CylinderBody BodyOf(const Scene& scene);

}  // namespace rockbench::reference::cylinder
