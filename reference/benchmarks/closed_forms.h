#pragma once
/// Closed forms of rocking, beside the reference model and independent of it (in the manner of
/// Drake's multibody/benchmarks): they know the scene's vocabulary (one block's mass
/// properties) and nothing of reference/, so that the reference, the engines and the docs can
/// be checked against them. tests/reference/closed_forms_test.cc checks each one against an
/// independent evaluation (a second derivation, a limit, or the reference's own runs).
///
/// Sources: Housner, G. W. (1963), "The behavior of inverted pendulum structures during
/// earthquakes", Bulletin of the Seismological Society of America 53(2), 403-417; Roussis, P. C.
/// (1999), thesis (chapter 3 for one block, chapter 5 for the impacts of two blocks; its OCR
/// misprints subscripts, so every form here is derived again in closed_forms.cc and the
/// thesis's equation is cited only where the two agree).
///
/// Conventions: the thesis's (theta > 0 tilts right about the right-hand base corner). Angles
/// in rad, rates in rad/s, times in s, lengths in m, masses in kg, inertias in kg m^2,
/// accelerations in m/s^2. Rates and release angles are magnitudes where a sign would say
/// nothing (free rocking is symmetric). Every function throws std::domain_error for arguments
/// outside the form's validity (stated in its comment) rather than return a number that means
/// nothing.
#include <span>

#include "scene/rigid_block.h"
#include "scene/scene.h"

namespace rockbench::reference::benchmarks {

/// A rigid body rocking on a rigid base about either of two base corners, symmetric about the
/// vertical through its mass centre, with friction enough that it never slides: one
/// rectangular block (Housner), or the two-block stack locked together (the thesis's mode 3).
struct RockingBody {
  double m_kg = 0.0;      ///< mass, kg
  double b_m = 0.0;       ///< half the distance between the two pivot corners, m
  double h_m = 0.0;       ///< height of the mass centre above the base at rest, m
  double I_O_kgm2 = 0.0;  ///< moment of inertia about a pivot corner, kg m^2
  double g_mps2 = 9.81;   ///< gravity, m/s^2

  /// Pivot to mass centre, R = sqrt(b^2 + h^2), m.
  double R_m() const;
  /// Slenderness alpha = atan(b / h) (the thesis's theta_c), rad.
  double alpha_rad() const;
  /// Housner's frequency parameter p = sqrt(m g R / I_O), rad/s (the thesis's alpha, eq. 3.33);
  /// sqrt(3 g / (4 R)) for a uniform rectangle.
  double p_radps() const;
};

/// A uniform rectangular block of full width and height (m) and mass (kg): b = B / 2,
/// h = H / 2, I_O = (4/3) m R^2 (I_G = m (b^2 + h^2) / 3 plus m R^2).
RockingBody RectangularBlock(double width_m, double height_m, double mass_kg, double g_mps2);
/// The same from the scene's mass properties of one block.
RockingBody RectangularBlock(const BlockProps& block, double g_mps2);
/// The two blocks locked together (mode 3), block 2 centred on block 1, rocking about a base
/// corner of block 1: m = m1 + m2, b = b1, h = (m1 h1 + m2 (2 h1 + h2)) / m,
/// I_O = I_O1 + I_G2 + m2 (b1^2 + (2 h1 + h2)^2) (parallel axes; the thesis's I_O of eq. 5.18).
RockingBody LockedStack(const BlockProps& lower, const BlockProps& upper, double g_mps2);
/// A column of blocks (bottom first, each centred on the one below and no wider than it)
/// locked together, every interface above the ground closed ("rff..."), rocking about a base
/// corner of block 1: m = sum m_k, b = b_1, h = sum m_k y_k / m and I_O = sum (I_G,k + m_k
/// (b_1^2 + y_k^2)) (parallel axes), y_k = 2 (h_1 + ... + h_(k-1)) + h_k block k's mass centre
/// above the ground. One block is RectangularBlock, two LockedStack; N equal blocks are one
/// block N times as tall. An N-block stack tilted as one rocks as this body (FirstImpactTime_s,
/// FreeRockingImpactRate_radps, ... of it) until its first impact, as long as every closed
/// face's corners stay compressive. Throws for no block or a block wider than the one below.
RockingBody LockedColumn(std::span<const BlockProps> blocks, double g_mps2);
/// The same for a scene's blocks and gravity.
RockingBody LockedColumn(const Scene& scene);

// ---------------------------------------------------------------------------------------------
// 1. The impact of a rocking body on its other corner (Housner 1963; thesis eqs. 3.8, 3.9).

/// The coefficient of restitution of a corner impact, e = theta'+ / theta'-, for any body of
/// RockingBody's kind: e = 1 - 2 m b^2 / I_O, dimensionless. From the angular momentum about
/// the landing corner, which the impulse (acting there) leaves unchanged; before the impact the
/// body turns about the other corner, a distance 2 b away, so its momentum about the landing
/// corner is (I_O - 2 m b^2) theta'- (thesis eq. 3.8, where r sin(theta_c) = b), and after it
/// I_O theta'+. Assumes a perfectly plastic point impact (no bounce, no slip) that ends with
/// the body rocking about the landing corner; negative e (a squat body) means it cannot.
/// Equals 1 - M R^2 (1 - cos 2 alpha) / I_O; the thesis's eqs. 5.31 (the locked stack) and
/// 5.36 (block 2 alone on block 1) are this form.
double CornerImpactRestitution(const RockingBody& body);

/// Housner's coefficient for a uniform rectangle of slenderness alpha: e = 1 - (3/2) sin^2
/// alpha, dimensionless (thesis eq. 3.9): CornerImpactRestitution with I_O = (4/3) m R^2 and
/// b = R sin(alpha). Zero at H/B = 1/sqrt(2); negative below.
double HousnerRestitution(double alpha_rad);

// ---------------------------------------------------------------------------------------------
// 2. Free rocking: released from rest at theta0 (0 < theta0 < alpha), no base motion.
// Exact equation: theta'' = -p^2 sin(alpha - theta) for theta > 0 (thesis eq. 3.29, the
// ground at rest); energy: theta'^2 = 2 p^2 (cos(alpha - theta0) - cos(alpha - theta)).

/// |theta'| at theta = 0, arriving from rest at theta0 (energy, exact), rad/s:
/// 2 p sqrt(sin(alpha - theta0 / 2) sin(theta0 / 2)).
double FreeRockingImpactRate_radps(const RockingBody& body, double theta0_rad);

/// The amplitude (apex angle) reached leaving theta = 0 with |theta'| = rate (energy, exact),
/// rad: alpha - acos(cos(alpha) + rate^2 / (2 p^2)). Throws when the rate carries the body over
/// its top (the argument reaches 1).
double FreeRockingAmplitude_rad(const RockingBody& body, double rate_radps);

/// The amplitude after n impacts, from rest at theta0 (exact: energy is conserved between
/// impacts and each impact multiplies the rate by e = CornerImpactRestitution), rad:
/// cos(alpha - theta_n) = cos(alpha) + e^(2 n) (cos(alpha - theta0) - cos(alpha)). Needs e > 0.
double FreeRockingAmplitudeAfterImpacts_rad(const RockingBody& body, double theta0_rad, int n);

/// The exact time from rest at theta0 to the first impact (theta = 0), s, by quadrature of
/// t = integral_0^theta0 dtheta / sqrt(2 p^2 (cos(alpha - theta0) - cos(alpha - theta))).
/// The integrand's inverse-square-root end point at theta0 is removed by theta = theta0 - u^2:
/// t = integral_0^sqrt(theta0) 2 u du / sqrt(4 p^2 sin(alpha - theta0 + u^2/2) sin(u^2/2)),
/// smooth in u (the difference of cosines written as a product: no cancellation). Adaptive
/// Gauss-Kronrod (GSL QAG, 61 points) to 1e-13 relative. Also the time from an apex theta0
/// down to the next impact, and half of it the time between two impacts.
double FirstImpactTime_s(const RockingBody& body, double theta0_rad);

/// The same time in closed form: the motion of phi = alpha - theta is that of an inverted
/// pendulum, and with s = sin(phi / 2), then s = s0 / cos(u), and the reciprocal-modulus
/// transformation, t = (1/p) F(beta1 | k): Legendre's incomplete elliptic integral of the
/// first kind with modulus k = cos(phi0 / 2) and amplitude sin(beta1) = sqrt(1 - s0^2 / s1^2)
/// / k, s0 = sin((alpha - theta0) / 2), s1 = sin(alpha / 2), s. Evaluated by Carlson's R_F
/// (GSL): a check on the quadrature by another route. Its small-angle limit (k -> 1,
/// F -> atanh(sin beta1)) is HousnerFirstImpactTime_s.
double FirstImpactTimeElliptic_s(const RockingBody& body, double theta0_rad);

/// The time between the impact that leaves theta = 0 with |theta'| = rate and the next one,
/// exact, s: 2 FirstImpactTime_s(body, FreeRockingAmplitude_rad(body, rate)).
double FreeRockingHalfCycle_s(const RockingBody& body, double rate_radps);

/// Housner's linearised time to the first impact (small alpha: sin(alpha - theta) ~ alpha -
/// theta): theta = alpha - (alpha - theta0) cosh(p t), so t1 = (1/p) acosh(1 / (1 - theta0 /
/// alpha)), s; a quarter of Housner's period T = (4/p) acosh(1 / (1 - theta0 / alpha)). The
/// exact time (FirstImpactTime_s) is longer by a relative (phi0^2 / 16 + alpha sqrt(alpha^2 -
/// phi0^2) / (48 acosh(alpha / phi0))) + O(alpha^4), phi0 = alpha - theta0 (derivation in
/// closed_forms.cc).
double HousnerFirstImpactTime_s(const RockingBody& body, double theta0_rad);

/// The thesis's linearisation (eq. 3.32: sin(alpha - theta) ~ sin(alpha) - theta cos(alpha),
/// the lever arm cos(alpha)), which is the reference's `equations = "linearized"`:
/// theta'' = q^2 (theta - tan(alpha)), q = p sqrt(cos alpha), so the first impact is at
/// t1 = (1/q) acosh(tan(alpha) / (tan(alpha) - theta0)) (eq. 3.43 with 3.33-3.38; 4 t1 is
/// eq. 3.44's period), s. Needs theta0 < tan(alpha).
double LinearizedFirstImpactTime_s(const RockingBody& body, double theta0_rad);

/// In the same linearisation, the time between the impact that leaves theta = 0 with |theta'|
/// = rate and the next one, s: theta = tan(alpha) (1 - cosh(q t)) + (rate / q) sinh(q t) is
/// zero again at t = (2/q) atanh(rate / (q tan(alpha))). Needs rate < q tan(alpha).
double LinearizedHalfCycle_s(const RockingBody& body, double rate_radps);

/// Housner's linearised amplitude after n impacts (his free-rocking decay): the energy of the
/// linear equation, theta'^2 - p^2 (alpha - theta)^2, with theta' multiplied by e at each
/// impact, gives theta_n / alpha = 1 - sqrt(1 - e^(2n) (1 - (1 - theta0 / alpha)^2)), rad, e
/// the CornerImpactRestitution of the body.
double HousnerAmplitudeAfterImpacts_rad(const RockingBody& body, double theta0_rad, int n);

// ---------------------------------------------------------------------------------------------
// 3. Overturning by a rectangular pulse (Housner 1963): a base acceleration of magnitude a_p
// for a time t_d, in the direction that tips the body, from rest, no vertical motion.

/// The smallest a_p that overturns the body, in the thesis's linearisation (the reference's
/// `equations = "linearized"`), m/s^2:
///   a_p / (g tan alpha) = 1 / (1 - exp(-q t_d)),  q = p sqrt(cos alpha).
/// Derivation: during the pulse phi = theta obeys phi'' = q^2 (phi - tan(alpha) + a_p / g), so
/// from rest phi = d (cosh(q t) - 1) with d = a_p / g - tan(alpha) > 0 (the pulse must lift the
/// body: a_p > g tan(alpha)); phi grows monotonically, so no impact happens during the pulse.
/// After it the body is free, phi'' = q^2 (phi - tan(alpha)): it goes over the top (phi =
/// tan(alpha), the linear equation's unstable equilibrium) iff the growing exponential's
/// coefficient is not negative, phi'(t_d) >= q (tan(alpha) - phi(t_d)), i.e. d (sinh x + cosh
/// x - 1) >= tan(alpha), x = q t_d: d >= tan(alpha) / (exp(x) - 1). At the threshold phi(t_d)
/// / tan(alpha) = (cosh x - 1) / (exp(x) - 1) < 1: the pulse ends before the top, and a body
/// that does not go over falls back and rocks freely, losing energy at each impact, so it
/// never overturns later: the form is the minimum over all outcomes, not only "without an
/// impact". Limits: t_d -> infinity gives the static threshold g tan(alpha); t_d -> 0 gives
/// a_p t_d -> g tan(alpha) / q, a velocity step that carries the body to the top. Throws for
/// t_d <= 0.
double RectangularPulseOverturningAcceleration_mps2(const RockingBody& body, double duration_s);

/// Housner's small-angle form of the same threshold (sin(alpha - theta) ~ alpha - theta, lever
/// arm 1): a_p / (g alpha) = 1 / (1 - exp(-p t_d)), m/s^2. It is the form above with tan(alpha)
/// -> alpha and q -> p; the two differ by O(alpha^2) relative, as does either from the exact
/// nonlinear threshold.
double HousnerRectangularPulseOverturningAcceleration_mps2(const RockingBody& body,
                                                           double duration_s);

// ---------------------------------------------------------------------------------------------
// 4. The two-block impacts that happen with every angle zero, so that their coefficients are
// the geometry's alone (thesis section 5.3.2, "Impact in mode 3" and "Impact in mode 4"):
// the stack locked together (3a) landing on block 1's other corner, and block 2 alone (4a)
// landing on its other corner on a still block 1. Block 2 sits centred on block 1 (b2 <= b1).
// Each outcome conserves the angular momentum of the system about block 1's new ground pivot
// O1' (when block 1 rocks after the impact) and of block 2 about its new pivot O2' (when
// block 2 rocks on block 1): derived in closed_forms.cc. The mirror images (3b, 4b before)
// have the same coefficients. The thesis's outcome is the first of its two candidates whose
// rates do not drive a closed contact into its support (ThesisOutcome...); the reference also
// asks the impulses to push (reference/impact.h), which may reject it.

/// Post-impact rates over the pre-impact rate of the impacting motion, dimensionless.
struct RateRatios {
  double theta1 = 0.0;  ///< theta1'+ / (pre-impact rate)
  double theta2 = 0.0;  ///< theta2'+ / (pre-impact rate)
};

/// 3a -> 1b (thesis eq. 5.29): the stack lands on block 1's left corner and block 2 rocks on
/// its own left corner: theta1'+ = A theta1'-, theta2'+ = C theta1'-, with
///   A1 = I_O1 + m2 (2 h1 (2 h1 + h2) + b1 xi),  A2 = I_G2 + m2 (h2 (2 h1 + h2) + b1 b2),
///   A3 = m2 (2 h1 h2 + b2 xi),                   A4 = I_O2,
///   B1 = I_O - 2 M b1^2,                         B2 = I_G2 + m2 (h2 (2 h1 + h2) - b1 b2),
/// xi = b1 - b2, A = (A4 B1 - A2 B2) / (A1 A4 - A2 A3), C = (A1 B2 - A3 B1) / (A1 A4 - A2 A3).
RateRatios StackGroundImpact3aTo1b(const BlockProps& lower, const BlockProps& upper);

/// 3a -> 3b (thesis eq. 5.31): the stack rocks on, locked, about block 1's other corner:
/// theta'+ / theta'- = 1 - 2 M b1^2 / I_O, the CornerImpactRestitution of the LockedStack.
double StackGroundImpact3aTo3b(const BlockProps& lower, const BlockProps& upper);

/// 4a -> 1b (thesis eq. 5.34): block 2 lands on its left corner and lifts block 1 onto block
/// 1's left corner: theta1'+ = B theta2'-, theta2'+ = D theta2'-, with A1..A4 as for 3a -> 1b
/// and B1 = I_G2 + m2 (h2 (2 h1 + h2) - b1 b2) (block 2's momentum about O1'), B2 = I_O2 - 2 m2
/// b2^2 (about O2'): B = (A4 B1 - A2 B2) / (A1 A4 - A2 A3), D = (A1 B2 - A3 B1) / (A1 A4 -
/// A2 A3).
RateRatios TopBlockImpact4aTo1b(const BlockProps& lower, const BlockProps& upper);

/// 4a -> 4b (thesis eq. 5.36): block 1 stays still and block 2 rocks on about its other
/// corner: theta2'+ / theta2'- = 1 - 2 m2 b2^2 / I_O2, Housner's e of block 2 alone
/// (1 - 1.5 sin^2(theta_c2) for a rectangle).
double TopBlockImpact4aTo4b(const BlockProps& upper);

/// The thesis's rule after a 3a ground impact: 1b when its rates open both contacts the
/// right way (block 1 turns on about O1', A >= 0; block 2 leaves block 1's face, theta2'+ -
/// theta1'+ of the sign of theta1'-, C >= A), else 3b ("if theta2'+ > theta1'+ ... the system
/// rocks as one block", section 5.3.2).
bool ThesisOutcomeAfter3aIs1b(const BlockProps& lower, const BlockProps& upper);
/// The thesis's rule after a 4a interface impact: 1b when block 1 lifts onto its other corner
/// (B >= 0) and block 2 opens from it (D >= B), else 4b ("if theta1'+ > 0 ... block 1 continues
/// to remain still").
bool ThesisOutcomeAfter4aIs1b(const BlockProps& lower, const BlockProps& upper);

}  // namespace rockbench::reference::benchmarks
