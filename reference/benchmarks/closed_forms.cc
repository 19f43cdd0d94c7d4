#include "reference/benchmarks/closed_forms.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_ellint.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockbench::reference::benchmarks {
namespace {

void Require(bool ok, const char* function, const std::string& what) {
  if (!ok) throw std::domain_error(std::string(function) + ": " + what);
}

void RequireBody(const RockingBody& body, const char* function) {
  Require(body.m_kg > 0.0 && body.b_m > 0.0 && body.h_m > 0.0 && body.I_O_kgm2 > 0.0 &&
              body.g_mps2 > 0.0,
          function, "the body needs positive m, b, h, I_O and g");
}

// Free rocking from rest: 0 < theta0 < alpha.
void RequireRelease(const RockingBody& body, double theta0_rad, const char* function) {
  RequireBody(body, function);
  Require(theta0_rad > 0.0 && theta0_rad < body.alpha_rad(), function,
          "needs 0 < theta0 < alpha (at rest it stays; at or past alpha it overturns)");
}

// The stack's blocks: block 2 centred on block 1, on its top face (b2 <= b1).
void RequireStack(const BlockProps& lower, const BlockProps& upper, const char* function) {
  Require(lower.m > 0.0 && lower.b > 0.0 && lower.h > 0.0 && upper.m > 0.0 && upper.b > 0.0 &&
              upper.h > 0.0,
          function, "both blocks need positive m, b and h");
  Require(upper.b <= lower.b, function, "block 2 wider than block 1 is outside the model");
}

// GSL reports failures by status (never abort): the program's policy (src/study/fragility.cc
// turns the handler off the same way).
void GslHandlerOff() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

// The post-impact system of the two 1b outcomes (3a -> 1b, 4a -> 1b) at the configuration with
// every angle zero. Coordinates: origin at block 1's base centre, x right, y up; rates
// clockwise positive (the thesis's theta'); the angular momentum of a body about a point A,
// clockwise positive, is I_G theta' + m (r_y v_x - r_x v_y), r = G - A.
// In 1b block 1 turns about O1' = (-b1, 0) at u1 and block 2 about O2' = (-b2, 2 h1) at u2:
//   v_G1 = u1 (h1, -b1),   v_G2 = u1 (2 h1, -xi) + u2 (h2, -b2),   xi = b1 - b2,
// (a clockwise turn at rate w about P moves X at w ((X - P)_y, -(X - P)_x)). With G1 = (0, h1),
// G2 = (0, y2), y2 = 2 h1 + h2:
//   system about O1':   [I_O1 + m2 (2 h1 y2 + b1 xi)] u1 + [I_G2 + m2 (h2 y2 + b1 b2)] u2
//   block 2 about O2':  m2 (2 h1 h2 + b2 xi) u1 + I_O2 u2
// (the thesis's A1..A4 of eq. 5.29 with l cos(beta) = 2 h1, l sin(beta) = xi, r2 cos(theta_c2)
// = h2, r2 sin(theta_c2) = b2; the OCR prints I_G1 for A2's I_G2 and I_O1 for A4's I_O2).
struct OneB {
  double A1, A2, A3, A4;
};
OneB OneBSystem(const BlockProps& p1, const BlockProps& p2) {
  const double xi = p1.b - p2.b, y2 = 2.0 * p1.h + p2.h;
  return {p1.I_O + p2.m * (2.0 * p1.h * y2 + p1.b * xi), p2.I_G + p2.m * (p2.h * y2 + p1.b * p2.b),
          p2.m * (2.0 * p1.h * p2.h + p2.b * xi), p2.I_O};
}
// Solves A1 u1 + A2 u2 = B1, A3 u1 + A4 u2 = B2 (Cramer; the matrix is the kinetic-energy
// metric of mode 1b, positive definite, so the determinant is positive).
RateRatios SolveOneB(const OneB& a, double B1, double B2) {
  const double det = a.A1 * a.A4 - a.A2 * a.A3;
  return {(a.A4 * B1 - a.A2 * B2) / det, (a.A1 * B2 - a.A3 * B1) / det};
}

}  // namespace

double RockingBody::R_m() const {
  return std::hypot(b_m, h_m);
}
double RockingBody::alpha_rad() const {
  return std::atan2(b_m, h_m);
}
double RockingBody::p_radps() const {
  return std::sqrt(m_kg * g_mps2 * R_m() / I_O_kgm2);
}

RockingBody RectangularBlock(double width_m, double height_m, double mass_kg, double g_mps2) {
  return RectangularBlock(MakeBlockProps(width_m, height_m, mass_kg), g_mps2);
}

RockingBody RectangularBlock(const BlockProps& block, double g_mps2) {
  // I_O = I_G + m R^2 with I_G = m (b^2 + h^2) / 3: (4/3) m R^2.
  return {block.m, block.b, block.h,
          (4.0 / 3.0) * block.m * (block.b * block.b + block.h * block.h), g_mps2};
}

RockingBody LockedStack(const BlockProps& lower, const BlockProps& upper, double g_mps2) {
  RequireStack(lower, upper, "LockedStack");
  const double m = lower.m + upper.m;
  const double y2 = 2.0 * lower.h + upper.h;  // block 2's mass centre above the base
  // About block 1's base corner (b1, 0): block 1's own I_O, block 2's I_G plus m2 times the
  // squared distance from the corner to G2 = (0, y2).
  const double I_O = lower.I_O + upper.I_G + upper.m * (lower.b * lower.b + y2 * y2);
  return {m, lower.b, (lower.m * lower.h + upper.m * y2) / m, I_O, g_mps2};
}

RockingBody LockedColumn(std::span<const BlockProps> blocks, double g_mps2) {
  Require(!blocks.empty(), "LockedColumn", "needs at least one block");
  const double b1 = blocks[0].b;
  double m = 0.0, moment = 0.0, I_O = 0.0, base = 0.0;  // base: block k's base above the ground
  for (size_t k = 0; k < blocks.size(); ++k) {
    const BlockProps& p = blocks[k];
    Require(p.m > 0.0 && p.b > 0.0 && p.h > 0.0, "LockedColumn",
            "every block needs positive m, b and h");
    Require(k == 0 || p.b <= blocks[k - 1].b, "LockedColumn",
            "a block wider than the one below it is outside the model");
    const double y = base + p.h;  // its mass centre, at x = 0 above block 1's base centre
    m += p.m;
    moment += p.m * y;
    I_O += p.I_G + p.m * (b1 * b1 + y * y);  // about block 1's corner (b1, 0)
    base += 2.0 * p.h;
  }
  return {m, b1, moment / m, I_O, g_mps2};
}

RockingBody LockedColumn(const Scene& scene) {
  std::vector<BlockProps> props;
  props.reserve(scene.blocks.size());
  for (const BlockDef& d : scene.blocks) {
    props.push_back(MakeBlockProps(d.width_m, d.height_m, d.mass_kg));
  }
  return LockedColumn(props, scene.run.gravity_mps2);
}

// 1 -------------------------------------------------------------------------------------------

double CornerImpactRestitution(const RockingBody& body) {
  RequireBody(body, "CornerImpactRestitution");
  // Before: turning at w about O = (b, 0); G = (0, h) moves at w (h, b) (clockwise positive).
  // About the landing corner O' = (-b, 0), r = G - O' = (b, h): the momentum is
  // I_G w + m (h * w h - b * w b) = (I_G + m (h^2 - b^2)) w = (I_O - 2 m b^2) w.
  // After: I_O w+. The impulse acts at O': the two are equal.
  return 1.0 - 2.0 * body.m_kg * body.b_m * body.b_m / body.I_O_kgm2;
}

double HousnerRestitution(double alpha_rad) {
  // I_O = (4/3) m R^2, b = R sin(alpha): 2 m b^2 / I_O = (3/2) sin^2(alpha).
  const double s = std::sin(alpha_rad);
  return 1.0 - 1.5 * s * s;
}

// 2 -------------------------------------------------------------------------------------------

double FreeRockingImpactRate_radps(const RockingBody& body, double theta0_rad) {
  RequireRelease(body, theta0_rad, "FreeRockingImpactRate_radps");
  // cos(alpha - theta0) - cos(alpha) = 2 sin(alpha - theta0 / 2) sin(theta0 / 2).
  const double a = body.alpha_rad();
  return 2.0 * body.p_radps() *
         std::sqrt(std::sin(a - 0.5 * theta0_rad) * std::sin(0.5 * theta0_rad));
}

double FreeRockingAmplitude_rad(const RockingBody& body, double rate_radps) {
  RequireBody(body, "FreeRockingAmplitude_rad");
  const double a = body.alpha_rad(), p = body.p_radps();
  const double c = std::cos(a) + rate_radps * rate_radps / (2.0 * p * p);
  Require(c < 1.0, "FreeRockingAmplitude_rad", "the rate carries the body over its top");
  return a - std::acos(c);
}

double FreeRockingAmplitudeAfterImpacts_rad(const RockingBody& body, double theta0_rad, int n) {
  RequireRelease(body, theta0_rad, "FreeRockingAmplitudeAfterImpacts_rad");
  const double e = CornerImpactRestitution(body);
  Require(n >= 0 && (n == 0 || e > 0.0), "FreeRockingAmplitudeAfterImpacts_rad",
          "needs n >= 0 and, for an impact, e > 0");
  const double a = body.alpha_rad();
  // The energy above the upright position, cos(alpha - theta) - cos(alpha), times e^2 per impact.
  const double drop = 2.0 * std::sin(a - 0.5 * theta0_rad) * std::sin(0.5 * theta0_rad);
  return a - std::acos(std::cos(a) + std::pow(e, 2 * n) * drop);
}

double FirstImpactTime_s(const RockingBody& body, double theta0_rad) {
  RequireRelease(body, theta0_rad, "FirstImpactTime_s");
  GslHandlerOff();
  struct Params {
    double phi0, four_p2;  // alpha - theta0, 4 p^2
  };
  const double p = body.p_radps();
  Params prm{body.alpha_rad() - theta0_rad, 4.0 * p * p};
  gsl_function f;
  f.params = &prm;
  f.function = [](double u, void* v) {
    const Params& q = *static_cast<const Params*>(v);
    // theta = theta0 - u^2: cos(phi0) - cos(phi0 + u^2) = 2 sin(phi0 + u^2/2) sin(u^2/2), and
    // 2 u / sqrt(2 p^2 that) -> 2 / sqrt(2 p^2 sin(phi0)) as u -> 0.
    if (u == 0.0) return 2.0 / std::sqrt(0.5 * q.four_p2 * std::sin(q.phi0));
    const double x = 0.5 * u * u;
    return 2.0 * u / std::sqrt(q.four_p2 * std::sin(q.phi0 + x) * std::sin(x));
  };
  constexpr size_t kIntervals = 200;
  std::unique_ptr<gsl_integration_workspace, void (*)(gsl_integration_workspace*)> ws(
      gsl_integration_workspace_alloc(kIntervals), gsl_integration_workspace_free);
  double t = 0.0, err = 0.0;
  const int status = gsl_integration_qag(&f, 0.0, std::sqrt(theta0_rad), 0.0, 1e-13, kIntervals,
                                         GSL_INTEG_GAUSS61, ws.get(), &t, &err);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error(std::string("FirstImpactTime_s: quadrature failed: ") +
                             gsl_strerror(status));
  }
  return t;
}

double FirstImpactTimeElliptic_s(const RockingBody& body, double theta0_rad) {
  RequireRelease(body, theta0_rad, "FirstImpactTimeElliptic_s");
  GslHandlerOff();
  // phi = alpha - theta rises from phi0 to alpha with phi'' = p^2 sin(phi) (an inverted
  // pendulum), from rest:
  //   p t = integral_phi0^alpha dphi / sqrt(2 (cos(phi0) - cos(phi))).
  // cos(phi0) - cos(phi) = 2 (s^2 - s0^2), s = sin(phi/2), dphi = 2 ds / sqrt(1 - s^2):
  //   p t = integral_s0^s1 ds / (sqrt(1 - s^2) sqrt(s^2 - s0^2)).
  // s = s0 / cos(u): ds / (...) = du / sqrt(c0^2 - sin^2 u), c0 = cos(phi0 / 2), u up to
  // u1 = acos(s0 / s1); then sin(beta) = sin(u) / c0: du / sqrt(...) = dbeta / sqrt(1 - c0^2
  // sin^2 beta). So p t = F(beta1, k = c0), sin(beta1) = sin(u1) / c0, sin(u1) = sqrt(s1^2 -
  // s0^2) / s1 with s1 - s0 = 2 cos((alpha + phi0) / 4) sin(theta0 / 4) (no cancellation).
  const double a = body.alpha_rad(), phi0 = a - theta0_rad;
  const double s0 = std::sin(0.5 * phi0), s1 = std::sin(0.5 * a), c0 = std::cos(0.5 * phi0);
  const double s1_minus_s0 = 2.0 * std::cos(0.25 * (a + phi0)) * std::sin(0.25 * theta0_rad);
  const double sin_u1 = std::sqrt(s1_minus_s0 * (s1 + s0)) / s1;
  const double beta1 = std::asin(std::min(1.0, sin_u1 / c0));
  gsl_sf_result r;
  const int status = gsl_sf_ellint_F_e(beta1, c0, GSL_PREC_DOUBLE, &r);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error(std::string("FirstImpactTimeElliptic_s: ") + gsl_strerror(status));
  }
  return r.val / body.p_radps();
}

double FreeRockingHalfCycle_s(const RockingBody& body, double rate_radps) {
  return 2.0 * FirstImpactTime_s(body, FreeRockingAmplitude_rad(body, rate_radps));
}

double HousnerFirstImpactTime_s(const RockingBody& body, double theta0_rad) {
  RequireRelease(body, theta0_rad, "HousnerFirstImpactTime_s");
  // theta'' = p^2 (theta - alpha): alpha - theta = (alpha - theta0) cosh(p t), zero at the time
  // below. Linearisation error (the exact time's expansion): with phi = alpha - theta,
  //   2 (cos(phi0) - cos(phi)) = (phi^2 - phi0^2) (1 - (phi^2 + phi0^2) / 12 + O(phi^4)),
  // so p t = integral_phi0^alpha dphi (1 + (phi^2 + phi0^2) / 24) / sqrt(phi^2 - phi0^2)
  //        = acosh(alpha / phi0) (1 + phi0^2 / 16) + alpha sqrt(alpha^2 - phi0^2) / 48 + O(a^4)
  // (integral of phi^2 / sqrt(phi^2 - phi0^2) = (alpha / 2) sqrt(alpha^2 - phi0^2) + (phi0^2 /
  // 2) acosh(alpha / phi0)). Checked in closed_forms_test.cc.
  const double a = body.alpha_rad();
  return std::acosh(a / (a - theta0_rad)) / body.p_radps();
}

double LinearizedFirstImpactTime_s(const RockingBody& body, double theta0_rad) {
  RequireRelease(body, theta0_rad, "LinearizedFirstImpactTime_s");
  const double a = body.alpha_rad(), tan_a = std::tan(a);
  const double q = body.p_radps() * std::sqrt(std::cos(a));
  // theta'' = q^2 (theta - tan a): tan a - theta = (tan a - theta0) cosh(q t). theta0 < alpha <
  // tan(alpha) always holds (RequireRelease).
  return std::acosh(tan_a / (tan_a - theta0_rad)) / q;
}

double LinearizedHalfCycle_s(const RockingBody& body, double rate_radps) {
  RequireBody(body, "LinearizedHalfCycle_s");
  const double a = body.alpha_rad(), tan_a = std::tan(a);
  const double q = body.p_radps() * std::sqrt(std::cos(a));
  const double x = rate_radps / (q * tan_a);
  Require(x > 0.0 && x < 1.0, "LinearizedHalfCycle_s",
          "needs 0 < rate < q tan(alpha) (faster, the linear body goes over its top)");
  // tan a (1 - cosh y) + x tan a sinh y = 0, y = q t > 0: x = (cosh y - 1) / sinh y = tanh(y/2).
  return 2.0 * std::atanh(x) / q;
}

double HousnerAmplitudeAfterImpacts_rad(const RockingBody& body, double theta0_rad, int n) {
  RequireRelease(body, theta0_rad, "HousnerAmplitudeAfterImpacts_rad");
  const double e = CornerImpactRestitution(body);
  Require(n >= 0 && (n == 0 || e > 0.0), "HousnerAmplitudeAfterImpacts_rad",
          "needs n >= 0 and, for an impact, e > 0");
  // theta'' = p^2 (theta - alpha) conserves theta'^2 - p^2 (alpha - theta)^2: at theta = 0,
  // theta'^2 = p^2 (alpha^2 - (alpha - theta_k)^2) for the amplitude theta_k either side, and
  // each impact multiplies theta'^2 by e^2.
  const double a = body.alpha_rad(), u = 1.0 - theta0_rad / a;
  return a * (1.0 - std::sqrt(1.0 - std::pow(e, 2 * n) * (1.0 - u * u)));
}

// 3 -------------------------------------------------------------------------------------------

double RectangularPulseOverturningAcceleration_mps2(const RockingBody& body, double duration_s) {
  RequireBody(body, "RectangularPulseOverturningAcceleration_mps2");
  Require(duration_s > 0.0, "RectangularPulseOverturningAcceleration_mps2", "needs t_d > 0");
  const double a = body.alpha_rad();
  const double q = body.p_radps() * std::sqrt(std::cos(a));
  // 1 - exp(-x) without cancellation for a short pulse: -expm1(-x).
  return body.g_mps2 * std::tan(a) / -std::expm1(-q * duration_s);
}

double HousnerRectangularPulseOverturningAcceleration_mps2(const RockingBody& body,
                                                           double duration_s) {
  RequireBody(body, "HousnerRectangularPulseOverturningAcceleration_mps2");
  Require(duration_s > 0.0, "HousnerRectangularPulseOverturningAcceleration_mps2", "needs t_d > 0");
  return body.g_mps2 * body.alpha_rad() / -std::expm1(-body.p_radps() * duration_s);
}

// 4 -------------------------------------------------------------------------------------------

RateRatios StackGroundImpact3aTo1b(const BlockProps& lower, const BlockProps& upper) {
  RequireStack(lower, upper, "StackGroundImpact3aTo1b");
  // Before (3a): the stack turns at w about O1 = (b1, 0): v_G1 = w (h1, b1), v_G2 = w (y2, b1).
  //   System about O1' = (-b1, 0): r_G1 = (b1, h1), r_G2 = (b1, y2):
  //     [I_G1 + m1 (h1^2 - b1^2) + I_G2 + m2 (y2^2 - b1^2)] w = (I_O - 2 M b1^2) w   (B1)
  //   Block 2 about O2' = (-b2, 2 h1): r_G2 = (b2, h2): [I_G2 + m2 (h2 y2 - b1 b2)] w  (B2)
  // (the thesis's B2 = I_O2 + m2 l' (h2 cos(beta') - b2 sin(beta')), l' cos(beta') = 2 h1,
  // l' sin(beta') = b1 + b2, is the same number).
  const RockingBody stack = LockedStack(lower, upper, 1.0);
  const double y2 = 2.0 * lower.h + upper.h;
  const double B1 = stack.I_O_kgm2 - 2.0 * stack.m_kg * lower.b * lower.b;
  const double B2 = upper.I_G + upper.m * (upper.h * y2 - lower.b * upper.b);
  return SolveOneB(OneBSystem(lower, upper), B1, B2);
}

double StackGroundImpact3aTo3b(const BlockProps& lower, const BlockProps& upper) {
  return CornerImpactRestitution(LockedStack(lower, upper, 1.0));
}

RateRatios TopBlockImpact4aTo1b(const BlockProps& lower, const BlockProps& upper) {
  RequireStack(lower, upper, "TopBlockImpact4aTo1b");
  // Before (4a): block 1 still, block 2 turns at w about O2 = (b2, 2 h1): v_G2 = w (h2, b2).
  //   System about O1' = (-b1, 0), r_G2 = (b1, y2): [I_G2 + m2 (h2 y2 - b1 b2)] w       (B1)
  //   Block 2 about O2' = (-b2, 2 h1), r_G2 = (b2, h2): [I_G2 + m2 (h2^2 - b2^2)] w
  //     = (I_O2 - 2 m2 b2^2) w                                                          (B2)
  const double y2 = 2.0 * lower.h + upper.h;
  const double B1 = upper.I_G + upper.m * (upper.h * y2 - lower.b * upper.b);
  const double B2 = upper.I_O - 2.0 * upper.m * upper.b * upper.b;
  return SolveOneB(OneBSystem(lower, upper), B1, B2);
}

double TopBlockImpact4aTo4b(const BlockProps& upper) {
  Require(upper.m > 0.0 && upper.b > 0.0 && upper.h > 0.0, "TopBlockImpact4aTo4b",
          "the block needs positive m, b and h");
  return 1.0 - 2.0 * upper.m * upper.b * upper.b / upper.I_O;
}

bool ThesisOutcomeAfter3aIs1b(const BlockProps& lower, const BlockProps& upper) {
  const RateRatios r = StackGroundImpact3aTo1b(lower, upper);
  return r.theta1 >= 0.0 && r.theta2 >= r.theta1;
}

bool ThesisOutcomeAfter4aIs1b(const BlockProps& lower, const BlockProps& upper) {
  const RateRatios r = TopBlockImpact4aTo1b(lower, upper);
  return r.theta1 >= 0.0 && r.theta2 >= r.theta1;
}

}  // namespace rockbench::reference::benchmarks
