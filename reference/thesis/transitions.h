#pragma once
/// Mode changes without impact (thesis 4.3.1 initiation, 4.3.4 transitions) and the validity
/// monitor. A face contact (block 1 flat on the ground, or block 2 flat on block 1) holds while
/// the normal forces at both of its corners are compressive; when one becomes tensile the face
/// opens about the other corner. This one rule gives the thesis's initiation criteria 4.1-4.4
/// (from rest) and its transition criteria 4.47-4.54 (from modes 3 and 4) and is evaluated in
/// every mode, free rocking included.
#include <string>

#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// The mode a state must move in at time t: contacts with a nonzero gap are kept; a closed
/// contact (zero gap and zero relative rate) stays closed (a face) if its corner forces allow
/// it, else it opens about the corner whose opening acceleration is positive. Closed contacts
/// are preferred. consistent = false when no combination satisfies the contact conditions
/// (for example a tensile normal force: uplift, which the model excludes).
struct ModeSelection {
  Mode mode = Mode::kRest;
  bool consistent = true;
};
ModeSelection SelectMode(const Geometry& geo, const State& s, double xg_mps2, double yg_mps2,
                         Equations equations);

/// Whether `mode` satisfies the contact conditions at (s, xg, yg): closed faces carry
/// compressive corner forces, point contacts compressive normal forces, and every contact that
/// is closed in s but open in `mode` accelerates open. SelectMode returns the first consistent
/// mode; the contact problem has a positive-definite mass matrix, so at most one is consistent.
bool ModeConsistent(const Geometry& geo, Mode mode, const State& s, double xg_mps2, double yg_mps2,
                    Equations equations);

/// Event function of the contact conditions of `mode` at (s, xg, yg), normalized by the total
/// weight: the smallest of the face corner forces and point normal forces, in units of M g.
/// Negative: a face must open (transition) or a point contact would pull (violation).
struct ContactMargins {
  double face = 1.0;   ///< smallest face-corner force / (M g); 1 when the mode has no face
  double point = 1.0;  ///< smallest point-contact normal force / (M g); 1 when none
  double mu_ground = 0.0, mu_interface = 0.0;  ///< |T| / N needed at each contact
  Reactions reactions;
};
ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s, double xg_mps2,
                                double yg_mps2, Equations equations);
/// The same from the mode's accelerations already computed at this state and base motion.
ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s,
                                const std::array<double, 2>& acc, double xg_mps2, double yg_mps2);
/// The same with the state's tilts already taken (TiltsOf(s)).
ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts,
                                const std::array<double, 2>& acc, double xg_mps2, double yg_mps2);

/// The thesis's initiation criteria from rest (eqs. 4.1 to 4.4; 4.4, missing from the text,
/// mirrors 4.3): the mode motion starts in, or rest. For cross-checking SelectMode.
Mode ThesisInitiation(const Geometry& geo, double xg_mps2, double yg_mps2);

}  // namespace rockbench::reference
