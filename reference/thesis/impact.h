#pragma once
/// Impacts (thesis chapter 5): perfectly plastic point impacts, post-impact rates from the
/// conservation of angular momentum. For a post-impact mode with contacts C, the impulses act
/// only at the contacts of C, so they do no work on the motions C allows: the generalized
/// momenta of the post-impact mode are conserved, J+^T M_b J+ u+ = J+^T M_b V-. This is exactly
/// the pair of laws chapter 5 writes for each case (system about the new ground pivot, block 2
/// about its pivot), e.g. eq. 5.12 + 5.13 for 1a -> 2b, and reduces to 5.31, 5.36 and Housner's
/// e = 1 - 1.5 sin^2(theta_c) in the one-degree-of-freedom cases.
#include <cmath>
#include <string>
#include <vector>

#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "scene/mode.h"

namespace rockbench::reference {

/// Uniqueness. Take the bodies' velocities v (3 per block) with the mass matrix M, at every
/// contact corner of the impact instant a normal velocity g = G_n^T v, and at every interface the
/// no-slip condition G_t^T v = 0 (at a zero gap it is the same condition at either corner of the
/// face, since the corners lie on the tangent). An outcome that passes both checks satisfies
/// M (v+ - v-) = G_t mu + G_n lambda, G_t^T v+ = 0, lambda >= 0, g+ >= 0, lambda g+ = 0:
/// the optimality conditions of min (v - v-)^T M (v - v-) / 2 subject to G_t^T v = 0,
/// G_n^T v >= 0, a strictly convex problem (M positive definite) with a single minimiser. So at
/// most one post-impact motion is admissible; the model's "no admissible outcome" is the case
/// where that minimiser lifts an interface off entirely (beyond the model: issue 24). Two outcomes
/// that pass the checks only within their tolerances (impulses >= -1e-9 p, rates >= -1e-12 w)
/// differ, by the same conditions, by (v1 - v2)^T M (v1 - v2) <= sum(eps_g |lambda| + eps_lambda
/// |g|), about 1e-9 of twice the kinetic energy: rates within sqrt(1e-9) ~ 3e-5 of their scale. Two
/// admissible outcomes whose rates differ by more than kSameImpactMotion of the sum of |omega-| are
/// two motions: the impact is reported ambiguous (which the argument above says is a defect).
inline constexpr double kSameImpactMotion = 1e-4;
/// Whether two outcomes' rates (n of each, rad/s) are one motion: each pair within
/// kSameImpactMotion of rate_scale (the sum of |omega-|).
inline bool SameImpactMotion(const double* a, const double* b, int n, double rate_scale) {
  for (int i = 0; i < n; ++i) {
    if (!(std::abs(a[i] - b[i]) <= kSameImpactMotion * rate_scale)) return false;
  }
  return true;
}

enum class ImpactKind {
  kGround,     ///< block 1 (or the stack) reaches theta1 = 0
  kInterface,  ///< block 2 reaches theta2 = theta1 (mode 1, 2) or theta2 = 0 (mode 4)
};

/// One candidate outcome of an impact.
struct ImpactOutcome {
  Mode mode = Mode::kRest;
  State state;                       ///< post-impact state (angles unchanged)
  bool velocity_admissible = false;  ///< no body moves into another after the impact
  bool impulse_admissible = false;   ///< every closed contact's impulse pushes (normal >= 0)
  double min_normal_impulse = 0.0;   ///< smallest normal impulse at a closed contact, N s
  double energy_after_j = 0.0;
};

struct ImpactResult {
  ImpactOutcome chosen;
  std::vector<ImpactOutcome> candidates;  ///< in order of preference (thesis's first)
  bool admissible = true;                 ///< false: no candidate passed both checks (see note)
  bool settled = false;                   ///< the rest rule closed a contact (see RestRate)
  /// Different motions among the candidates admissible in velocities and impulses, each taken
  /// after the rest rule (two that leave the same rates are one). More than one: the impact is
  /// ambiguous, the model does not say which follows; the first in the order is chosen and the
  /// note says so.
  int admissible_outcomes = 0;
  double energy_before_j = 0.0;
  std::string note;
};

/// The thesis's candidate post-impact modes first (e.g. 1a interface: 2a then 3a), then the
/// other contact combinations the geometry allows (so that, e.g., a squat block whose Housner
/// coefficient is negative can come to rest).
std::vector<Mode> ImpactCandidates(Mode before, ImpactKind kind, bool two_blocks);

/// Post-impact rates for a given post-impact mode by conservation of generalized momentum.
State PostImpactState(const Geometry& geo, Mode before, const State& pre, Mode after);

/// The rest rule's threshold at a contact, rad/s: `rest_rate_rel` times sqrt(g / R), R the
/// distance from the contact's pivot to the mass centre of what rests on it. At the ground that
/// is the stack (block 1 carries block 2 whether block 2 rocks or not; for one block, the
/// block): geo.R. At the interface it is block 2: block2.r. sqrt(g / R) is the rate scale of
/// rocking about that pivot (Housner's p = sqrt(3 g / (4 R)) for one block), so the rule is
/// the same for every size of the same shape (a scene scaled by k in length, its time by
/// sqrt(k), settles at the same impacts).
double RestRate(const Geometry& geo, ImpactKind contact, double rest_rate_rel);

/// The rest rule's radii of a stack of n blocks (bottom first), m: R_k from block k's base
/// corner to the mass centre of blocks k..N at rest. `props(k)` gives block k's half width and
/// half height (m) and its mass (kg), as {b, h, m}.
template <class Props>
std::vector<double> RestRadii_m(int n, const Props& props) {
  std::vector<double> r(static_cast<size_t>(n), 0.0);
  double m_above = 0.0, moment_above = 0.0;  // mass and first moment about block k's base
  for (int k = n - 1; k >= 0; --k) {
    const auto [b, h, m] = props(k);
    // Shifting the base up by block k's height moves the blocks above by 2 h_k.
    moment_above += m_above * 2.0 * h + m * h;
    m_above += m;
    r[static_cast<size_t>(k)] = std::hypot(b, moment_above / m_above);
  }
  return r;
}

/// Resolves an impact at state `pre` (the gap coordinate exactly zero). Chooses the first
/// candidate that is admissible both in velocities and in impulses; if none is, the first that is
/// admissible in velocities (the thesis's check) and reports admissible = false; if none is even
/// that, the blocks stop (rest of the contacts that closed). `rest_rate_rel` is the rest rule: a
/// contact that would open with a relative rate below RestRate(geo, that contact,
/// rest_rate_rel) stays closed instead (0: never).
ImpactResult ResolveImpact(const Geometry& geo, Mode before, const State& pre, ImpactKind kind,
                           double rest_rate_rel);

}  // namespace rockbench::reference
