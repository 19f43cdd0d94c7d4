#pragma once
/// The reference run beyond the thesis's assumptions: from the instant an interface of the
/// stack would slip (its friction needs more than its coefficient) or lift off (a pivot or a
/// face would pull), the driver (simulate.cc) hands the run over to the unilateral model
/// (unilateral.h), which follows it to its end: event-driven, exact in the same sense as the
/// pivot chain (every slip start and stop, lift-off, landing and impact located on the
/// integrator's dense output, every mode the solution of its complementarity problem).
/// docs/sliding.md explains the model, its events and its sources.
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// Where the unilateral model takes over: the chain's state (absolute angles and rates, its
/// configuration) at t, and why.
struct UnilateralStart {
  double t_s = 0.0;
  Configuration config;
  std::vector<double> theta_rad, omega_radps;
  std::string reason;
  /// >= 0: the run is handed over at an impact of this interface (0: block 1 on the ground),
  /// the state being the one just before it; the unilateral model resolves that impact
  /// (Coulomb's law at the impulse level) before anything else.
  int impact_interface = -1;
};

/// An interface's impulse in an impact outcome, N s: normal (> 0 pushes the upper block away
/// from its support) and tangential (along the support's top face, > 0 to the right).
struct InterfaceImpulse {
  double normal_ns = 0.0, tangential_ns = 0.0;
};

/// The impulses the interfaces transmit in a pivot-chain impact (impact.h: plastic, no slip)
/// from the chain's state just before it (configuration `before`, rates omega_before) to its
/// outcome (`after`, omega_after), at angles theta (unchanged by the impact). Interface k's
/// impulse on block k is the momentum the blocks k..N gain, sum_(j >= k) m_j (v+_j - v-_j)
/// (gravity and the base's acceleration give no impulse): exact, whatever the impact law, and
/// computed without the chain's equations.
std::vector<InterfaceImpulse> ChainImpactImpulses(const Scene& scene, const Configuration& before,
                                                  const Configuration& after,
                                                  const double* theta_rad,
                                                  const double* omega_before_radps,
                                                  const double* omega_after_radps);

/// The first interface of `impulses` whose impulse Coulomb's law forbids: it pulls (normal <
/// -tol) or leaves the friction cone (|tangential| > mu normal + tol, mu the upper block's
/// `friction`), tol being 1e-9 of `impulse_scale_ns`; -1 when none does. `why` (optional) says
/// which and by how much.
int InterfaceOutsideCone(const Scene& scene, const std::vector<InterfaceImpulse>& impulses,
                         double impulse_scale_ns, std::string* why = nullptr);

/// The driver's step and event scales, s (the chain's: simulate.cc).
struct UnilateralSteps {
  double t_end_s = 0.0;
  double max_step_s = 0.0, min_step_s = 0.0, first_step_s = 0.0, event_tol_s = 0.0;
};

/// How the unilateral run ended: its last configuration, and whether the stack then stood at
/// rest (every interface closed and sticking, every rate zero).
struct UnilateralEnd {
  Configuration config;
  bool at_rest = false;
};

/// Whether the unilateral model can continue a scene's run (at most kUnilateralMaxBlocks
/// blocks, nonlinear equations, located events), and if not why.
bool UnilateralApplies(const Scene& scene, std::string* why = nullptr);

/// Continues `result` (its history, trajectory and summary, the samples up to next_sample
/// emitted) from `start` to the end of the run. The summary's status, peaks, impacts and
/// contact figures go on from where the chain left them.
UnilateralEnd ContinueUnilateral(const Scene& scene, const GroundMotion& motion,
                                 const UnilateralStart& start, const UnilateralSteps& steps,
                                 Result* result, long* next_sample);

}  // namespace rockbench::reference
