#pragma once
/// The stack beyond the thesis's assumptions (issue 24, docs/sliding.md): N rigid blocks with
/// unilateral contact and Coulomb friction at every interface, so that a block may rest, rock,
/// slide, slide and rock, or fly, over the ground or over the block below. For one block these
/// are the five modes of the thesis's chapter 3 (after Shenton & Jones 1991 and Ishiyama 1982).
///
/// Coordinates are maximal: block i's mass centre (x_i, y_i) (m) and its angle theta_i (rad,
/// the thesis's convention: > 0 tilted right, clockwise) at q[3i..3i+2], their rates at
/// v[3i..3i+2], in the base frame (translating with the ground, origin at block 1's base centre
/// at rest, x right, y up). The base's acceleration enters as the effective gravity (-xg'',
/// -(g + yg'')).
///
/// Contacts. Interface k is block k on its support (the ground for k = 0). It has two contact
/// slots, right (0) and left (1). A slot's point is the upper block's base corner on that side
/// while the corner lies over the support's top face; past the face's edge it is the support's
/// top corner on that side, on the upper block's base face; past both, the slot is empty. A
/// slot is closed (gap zero, its normal force a multiplier) or open. An interface with a closed
/// slot sticks (no relative tangential motion; its tangential force a multiplier, within the
/// cone |T| <= mu N of the interface's total normal force) or slips to the right or left (the
/// upper block relative to its support; T = -/+ mu N at each closed slot). Both closed slots of
/// a face share one tangential state: at a zero gap the two corners' tangential velocities are
/// equal.
///
/// Transitions without impact: the contact forces and the accelerations at an instant solve a
/// linear complementarity problem (LCP): every closed contact compressive, every opening one
/// accelerating apart, a sticking interface inside its cone, a slipping one's friction opposing
/// its slip (and, from a zero slip rate, its slip accelerating that way). With Coulomb friction
/// the LCP's matrix need not be positive definite, and a state can have no solution or several
/// (Painleve's paradoxes, Pfeiffer & Glocker 1996, "Multibody Dynamics with Unilateral
/// Contacts", ch. 5). Small problems (at most `exhaustive_limit` contact states) are enumerated
/// to the end and their solutions counted: none, or two different motions, is a stated status,
/// never a silent choice. Larger ones are solved by Lemke's method with the lexicographic rule
/// (lcp.h) on the LCP with the 2-D friction cone written as complementarity (docs/sliding.md),
/// its mode then checked by the same equations and conditions as an enumerated one; where
/// Lemke ends on a ray, or its mode fails the check, a bounded enumeration from its mode
/// follows (stated in `method`). Every solve is scaled (the rows to unit mass-metric norm), so
/// that blocks of very different masses (1e12) stay regular.
///
/// Infinite friction. A sticking interface whose normal force reaches zero while it still
/// carries a tangential force has no sticking continuation, and opening it would remove the
/// force that held it. Any finite mu slips there first: its limit as mu -> infinity is a slip
/// on one corner with a vanishing normal force and a finite friction force tau, which holds
/// the corner on its face (its normal row) and opposes the slip (tau >= 0). Where no state of
/// stick or open exists, Solve tries these limit slips (stated in the note); their slot_normal
/// is tau (the limit of mu N, whose sign is N's), their normal force zero.
/// Impacts: perfectly plastic in the normal direction and Coulomb in the tangential one (the
/// impact law with normal and tangential restitution zero of Glocker's set-valued force laws,
/// Pfeiffer & Glocker 1996 ch. 7; Moreau's velocity-level contact law). The impulses solve the
/// same complementarity problem at the velocity level: every contact at a zero gap either ends
/// with a zero normal velocity and a compressive impulse, or separates with none; an interface
/// either sticks after the impact within the impulse cone |P_T| <= mu P_N, or slips with P_T =
/// -/+ mu P_N against its slip after the impact. With mu infinite this is the thesis model's
/// impact (impact.h "Uniqueness"): the post-impact motion is the one that conserves the
/// generalized momenta of the configuration after it. Energy is never gained (an impact is the
/// projection of the velocities in the kinetic-energy metric, with friction dissipating only).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/mode.h"
#include "scene/scene.h"
#include "scene/vec2.h"

namespace rockbench::reference {

/// An interface's tangential state: the upper block sticks on its support, or slips to the
/// right (+1) or the left (-1) relative to it.
enum class Slip : int8_t { kLeft = -1, kStick = 0, kRight = 1 };

/// One interface's contact option in the search: which of its slots close and its tangential
/// state.
struct ContactOption {
  std::array<bool, 2> closed{false, false};
  Slip slip = Slip::kStick;
  bool operator==(const ContactOption&) const = default;
};

/// One block: half width b, half height h (m), mass (kg), central inertia (kg m^2), and the
/// friction coefficient of its base on its support (infinity: never slips).
struct UnilateralBlock {
  double b_m = 0.0, h_m = 0.0, mass_kg = 0.0, inertia_kgm2 = 0.0;
  double friction = 0.0;
};

/// The contact state of the whole stack: per interface, which slots are closed and its
/// tangential state (meaningful while a slot is closed).
struct ContactMode {
  std::vector<std::array<bool, 2>> closed;  ///< [interface][slot]: right 0, left 1
  std::vector<Slip> slip;                   ///< [interface]
  /// [interface][slot]: a closed slot's point is the support's corner (else the upper block's
  /// corner), fixed for the mode's life: its constraint continues smoothly past the face's edge
  /// (where an event ends the mode), so that a step's right-hand side never switches points.
  std::vector<std::array<bool, 2>> support_corner;
  explicit ContactMode(int interfaces = 0)
      : closed(static_cast<size_t>(interfaces), {false, false}),
        slip(static_cast<size_t>(interfaces), Slip::kStick),
        support_corner(static_cast<size_t>(interfaces), {false, false}) {}
  bool operator==(const ContactMode&) const = default;
  bool any_closed(int k) const { return closed[k][0] || closed[k][1]; }
};

/// One contact slot at a state: where it is and how it moves.
struct SlotKinematics {
  bool exists = false;         ///< the slot has a point (a corner over a face)
  bool upper_corner = true;    ///< the upper block's corner on its support's face (else the
                               ///< support's corner on the upper block's base)
  double gap_m = 0.0;          ///< normal gap (< 0: penetration)
  double gap_rate_mps = 0.0;   ///< its rate
  double slip_rate_mps = 0.0;  ///< the upper block's tangential velocity relative to the support
  double xi_m = 0.0;           ///< where the point is along its face, from the face's middle
  double extent_m = 0.0;       ///< the face's half length (infinity: the ground)
  /// Where the upper block's corner is along the support's face, and the support's corner
  /// along the upper block's base, from each face's middle, m (whichever the point is: the
  /// edges a sliding block passes).
  double xi_upper_corner_m = 0.0, xi_support_corner_m = 0.0;
  // Generalized directions of the normal and tangential force at the point on the upper block
  // (first three) and the support (last three; none for the ground), and the velocity-product
  // terms of the normal and tangential relative accelerations.
  std::array<double, 6> wn{}, wt{};
  double kappa_n = 0.0, kappa_t = 0.0;
};

/// What a complementarity problem gave.
struct ModeSolution {
  bool found = false;
  ContactMode mode;
  /// Accelerations (Solve: m/s^2, rad/s^2) or velocities after the impact (SolveImpact), per
  /// coordinate (3 per block).
  std::vector<double> result;
  /// Per interface: total normal force (N) or impulse (N s), and tangential one.
  std::vector<double> normal, tangential;
  /// Per slot [interface][slot]: normal force or impulse (0 when open).
  std::vector<std::array<double, 2>> slot_normal;
  /// Different motions found (enumerated: 0, 1 or more; first-found: 1).
  int solutions = 0;
  bool exhaustive = false;  ///< every contact state was tried
  long candidates = 0;      ///< contact states tried
  std::string note;
  /// How the state was found: "enumeration" (every state, counted), "preferred" (the hint's
  /// state checked first), "lemke", "lemke+search" (an enumeration from Lemke's mode), "search"
  /// (Lemke ended on a ray: an enumeration from the hint).
  std::string method;
  int lcp_pivots = 0;  ///< Lemke's pivots (0: not used)
};

/// The stack's mechanics in maximal coordinates.
class UnilateralStack {
 public:
  /// blocks bottom first (1..kUnilateralMaxBlocks), gravity g (m/s^2).
  UnilateralStack(std::vector<UnilateralBlock> blocks, double g_mps2);
  /// The scene's blocks and gravity.
  static UnilateralStack OfScene(const Scene& scene);

  int size() const { return n_; }
  int coordinates() const { return 3 * n_; }
  const UnilateralBlock& block(int i) const { return blocks_[i]; }
  double g_mps2() const { return g_; }
  /// Total weight M g, N.
  double weight_n() const { return weight_; }
  /// A length scale (the largest block half-diagonal), m, and a time scale sqrt(L / g), s.
  double length_scale_m() const { return length_; }

  /// The slots of interface k at (q, v): [0] right, [1] left. With `mode`, its closed slots
  /// keep the mode's points (ContactMode::support_corner) wherever they are, `exists` saying
  /// whether the point still lies on its face; the others are chosen by where they are.
  std::array<SlotKinematics, 2> Slots(int k, const double* q, const double* v,
                                      const ContactMode* mode = nullptr) const;

  /// The contact forces and accelerations of `mode` at (q, v) under the base acceleration (xg'',
  /// yg''), without checking any condition: accel (3N), per interface normal and tangential
  /// totals, per slot normal forces. False when its equations are singular.
  bool Accelerations(const ContactMode& mode, const double* q, const double* v, double xg_mps2,
                     double yg_mps2, double* accel, ModeSolution* forces = nullptr) const;

  /// The contact state at (q, v): the LCP over the slots in contact (gap <= gap_tol_m: at a
  /// zero gap, or a little past it) with a zero normal rate (|rate| <= rate_tol_mps), the
  /// others open. Problems of at most `exhaustive_limit` states are enumerated to the end
  /// (solutions counted; `hint`'s state first). Larger ones: `hint`'s state checked first, then
  /// Lemke's method (solutions = 1, exhaustive false).
  ModeSolution Solve(const double* q, const double* v, double xg_mps2, double yg_mps2,
                     const ContactMode& hint, double gap_tol_m, double rate_tol_mps,
                     long exhaustive_limit = 1000) const;

  /// A plastic impact with Coulomb friction at (q, v_minus): the velocities after it (result),
  /// over every slot in contact (gap <= gap_tol_m). The rest rule: a slot of interface k that
  /// would separate slower than RestSpeed(k, rest_rate_rel) stays closed (0: never). Solved as
  /// Solve.
  ModeSolution SolveImpact(const double* q, const double* v_minus, const ContactMode& hint,
                           double gap_tol_m, double rest_rate_rel,
                           long exhaustive_limit = 1000) const;

  /// The rest rule's separation speed at interface k, m/s: the chain's relative rate
  /// rest_rate_rel sqrt(g / R_k) (R_k from block k's base corner to the mass centre of blocks
  /// k..N at rest) times the distance between the interface's two contact points, so that a
  /// slot separates after an impact exactly when the chain's rocking would go on; and at least
  /// the speed of a fall through the rounding of a gap, sqrt(2 g 4 eps L) = 4.2e-8 sqrt(g L)
  /// (a gap is a few products of coordinates of size L): a slower separation is below what
  /// maximal coordinates resolve (docs/sliding.md, "the rest rule"). 0 when rest_rate_rel is 0.
  double RestSpeed(int k, double rest_rate_rel) const {
    if (!(rest_rate_rel > 0.0)) return 0.0;
    return std::max(rest_rate_rel * rest_speed_rel_[static_cast<size_t>(k)], resolved_speed_);
  }

  /// Puts (q, v) back on the constraints of `mode` (the drift of an integration that holds them
  /// at the acceleration level): the closed slots' gaps to zero (one Gauss-Newton step, in the
  /// mass metric), then their normal rates and the sticking interfaces' slip rates to zero (the
  /// velocities' projection in the kinetic-energy metric).
  void Project(const ContactMode& mode, double* q, double* v) const;

  /// Kinetic energy in the base frame plus m g y of every block, J.
  double Energy(const double* q, const double* v) const;

  /// Places the stack from the pivot chain's state: absolute angles theta and rates omega (N
  /// each) and configuration c (the chain's pivots), into q and v (3N each).
  void FromChain(const Configuration& c, const double* theta_rad, const double* omega_radps,
                 double* q, double* v) const;

  /// Interface k's slip u (the displacement along the support's face of the upper block's base
  /// corner on the side of its tilt, from where it stood at rest, m) and lift z (the height of
  /// the upper block's lowest base corner above the support's top-face line, m).
  void SlipAndLift(int k, const double* q, double* u_m, double* z_m) const;

  /// The chain's configuration letter of each interface for a mode at q: f both slots closed,
  /// r or l one, and an open interface by the sign of its relative tilt.
  Configuration ConfigurationOf(const ContactMode& mode, const double* q) const;

 private:
  // One complementarity problem: the slots at (q, v), which are in contact (`zero`), per
  // interface the sign of a slip already under way (acceleration level, a nonzero slip rate:
  // dynamic friction) or 0, the rows' base (M^-1 f, the rows' velocity terms added, or v- for
  // an impact) and the conditions' tolerances (forces to tol_force, rates or accelerations to
  // tol_motion; two solutions are one motion to 1e-6 of same_scale).
  struct Problem {
    std::vector<std::array<SlotKinematics, 2>> slots;
    std::vector<std::array<bool, 2>> zero;
    std::vector<int> slipping;
    std::vector<double> base;
    bool impact = false;
    double tol_force = 0.0, tol_motion = 0.0, rate_tol = 0.0, same_scale = 1.0;
  };
  // The per-interface options of p (with limit slips at infinite friction when `limit_slip`),
  // `preferred` first where it is one of them.
  std::vector<std::vector<ContactOption>> Options(const Problem& p,
                                                  const std::vector<ContactOption>& preferred,
                                                  bool limit_slip) const;
  // The state of p: enumerated (counted) when small, else the preferred state, Lemke, and a
  // bounded enumeration.
  ModeSolution Resolve(const Problem& p, const std::vector<ContactOption>& preferred,
                       bool limit_slip, long exhaustive_limit) const;
  // Enumeration over `options` by the number of interfaces that differ from the first option
  // of each, up to `cap` states; with `exhaustive`, every state tried and the motions counted.
  ModeSolution Search(const Problem& p, const std::vector<std::vector<ContactOption>>& options,
                      bool exhaustive, long cap) const;
  // `mode`'s equations solved and its conditions checked: false when singular or violated.
  bool Check(const Problem& p, const ContactMode& mode, ModeSolution* sol) const;
  // A force column of p's LCP: per slot in contact its normal force (with the friction of a
  // slip under way, or a limit slip's friction), per interface with static friction its
  // tangential force at its first slot in contact; the directions of its force (dir) and row,
  // the row's curvature term, and its scale (1 / the row's norm in the mass metric).
  struct ForceColumn {
    int k, j;
    bool tangential;
    std::array<double, 6> dir, row;
    double kappa, scale;
    int var;  // its LCP variable (tangential: T+, then T- and, finite mu, sigma)
  };
  // p's force columns (scale 1) and the number of the LCP's variables, *nv.
  std::vector<ForceColumn> ForceColumns(const Problem& p, int* nv) const;
  // Each column's scale, and the scaled couplings A (m x m, row-major: a row's coupling with
  // every force of its own or a neighbouring interface) and rows' values b at zero force;
  // returns the largest |b|.
  double ScaledCouplings(const Problem& p, std::vector<ForceColumn>* f, std::vector<double>* A,
                         std::vector<double>* b) const;
  // The LCP of the forces: z = (scaled normal forces; per tangential force T+, T-, sigma),
  // w = M z + q: w_n = A_n. F + b_n; w_+ = A_t. F + b_t + sigma; w_- = -(A_t. F + b_t) + sigma;
  // w_sigma = mu sum_j (s_j / s_t) N_j - T+ - T-, F the forces (T = T+ - T-).
  void ForceLcp(const std::vector<ForceColumn>& f, const std::vector<double>& A,
                const std::vector<double>& b, int nv, std::vector<double>* M,
                std::vector<double>* q) const;
  // The mode of the LCP's solution (z, w): a slot is closed where its force is positive, open
  // where it separates, the hint's where both are zero (to 1e-9 of the problem's scale); a
  // slip where sigma (the slip rate's size) is positive, its direction against the friction
  // force.
  void ModeOfLcp(const Problem& p, const ContactMode& hint, bool limit_slip,
                 const std::vector<ForceColumn>& f, const std::vector<double>& z,
                 const std::vector<double>& w, double b_max, ContactMode* mode) const;
  // Lemke's method on p's LCP: the mode its solution gives (false: Lemke found none).
  bool LemkeMode(const Problem& p, const ContactMode& hint, bool limit_slip, ContactMode* mode,
                 int* pivots) const;
  // One constraint of a mode's equations: interface k, the generalized direction of its force
  // (dir) and of its row (row: the upper block's three entries, then its support's), and the
  // row's value at x = 0 (row . x + rhs = 0).
  struct Constraint {
    int k;
    std::array<double, 6> dir, row;
    double rhs;
  };
  // M x = M base + sum_c dir_c lam_c with row_c . x + rhs_c = 0 (constraints ordered by
  // interface): x (3N) and lam (one per constraint); false when singular. Solved as the
  // augmented (KKT) system, scaled (each block's coordinates by M^-1/2, each row to unit norm in
  // the mass metric) and banded over the chain of blocks and interfaces: its condition number
  // is about the square root of that of the Schur complement W^T M^-1 W, which a light block
  // between heavy ones (a mass ratio of 1e12) makes singular to working precision.
  bool SolveConstrained(const std::vector<Constraint>& c, const double* base, double* x,
                        double* lam) const;
  // The candidate's equations solved: false when singular.
  bool SolveCandidate(const ContactMode& mode, const std::vector<std::array<SlotKinematics, 2>>& s,
                      const double* rhs_base, bool impact, ModeSolution* out) const;
  // w . M^-1 v for the rows w of interface kw and v of interface kv (6 entries each: the upper
  // block's three, then its support's).
  double Coupling(int kw, const std::array<double, 6>& w, int kv,
                  const std::array<double, 6>& v) const;
  ContactMode ModeOf(const Problem& p, const std::vector<ContactOption>& pick) const;

  std::vector<UnilateralBlock> blocks_;
  int n_ = 0;
  double g_ = 9.81, weight_ = 0.0, length_ = 1.0;
  // Per interface: RestSpeed at rest_rate_rel = 1, m/s; the slowest separation resolved, m/s.
  std::vector<double> rest_speed_rel_;
  double resolved_speed_ = 0.0;
};

}  // namespace rockbench::reference
