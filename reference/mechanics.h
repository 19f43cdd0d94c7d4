#pragma once
/// The two formulations of the stack's mechanics the reference's driver (simulate.cc) runs on,
/// behind one interface:
/// - ThesisMechanics: the thesis's explicit equations of motion, criteria and impact laws for
///   one or two blocks (modes.h, transitions.h, impact.h), on the state y = (theta1, theta2,
///   omega1, omega2) (one block: theta2 = theta1, omega2 = omega1). The default for one or two
///   blocks: it is the cheaper (docs/performance-reference.md).
/// - ChainMechanics<Cap>: the N-block pivot chain (stack_chain.h, stack_contacts.h) for up to
///   Cap blocks, on y = (theta_1..theta_Cap, omega_1..omega_Cap), the entries beyond the stack's
///   N blocks zero. Any N; for two blocks it agrees with ThesisMechanics to rounding
///   (tests/reference/stack_chain_test.cc, stack_contacts_test.cc, mechanics_test.cc).
/// The driver asks each the same questions: the accelerations of a configuration, its contact
/// margins, the configuration a state must move in, what an impact leaves, the energy.
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "reference/chain/stack_contacts.h"
#include "reference/integration/integrator.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "reference/thesis/modes.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// The contact conditions of a configuration at a state: the margins (normalised by the total
/// weight; negative: a face must open, or a pivot pulls) and, per interface (0: the ground),
/// the normal force (N) and the friction coefficient it needs.
template <size_t Cap>
struct MarginsN {
  double face = 1.0;   ///< smallest face-corner force / (M g); 1 when no interface is closed
  double point = 1.0;  ///< smallest pivot normal force / (M g); 1 when none is open
  std::array<double, Cap> normal_n{};
  std::array<double, Cap> mu{};
};

/// The configuration a state must move in.
struct Selection {
  Configuration config;
  bool consistent = true;
  std::string note;  ///< why none is consistent, when that is not uplift
};

/// What an impact leaves.
template <size_t D>
struct ImpactN {
  Configuration config;
  VecN<D> y{};  ///< the state after (angles unchanged)
  bool admissible = true;
  int admissible_outcomes = 1;  ///< different admissible motions; > 1: ambiguous
  bool settled = false;
  double energy_before_j = 0.0, energy_after_j = 0.0;
  std::string note;
};

/// The thesis's one or two blocks.
class ThesisMechanics {
 public:
  static constexpr size_t kCap = 2;
  using Y = Vec4;
  using Margins = MarginsN<kCap>;
  using Impact = ImpactN<4>;

  explicit ThesisMechanics(const Scene& scene);
  int blocks() const { return geo_.two_blocks ? 2 : 1; }
  /// Components of the error norm: all four (one block's are mirrored, as they always were).
  int active() const { return 4; }
  /// sqrt(R / g), R block 1's base corner to the stack's mass centre, s.
  double time_scale_s() const;
  const Geometry& geometry() const { return geo_; }
  /// The state of the scene's [initial].
  Y Initial(const InitialState& in) const;

  // Rhs, Project and Land are inline: the driver's inner loops call them at every stage and
  // every dense-output evaluation.
  /// (omega, theta'') of configuration c at y under (xg'', yg'').
  Y Rhs(const Configuration& c, const Y& y, double xg, double yg) const {
    const Mode mode = *ModeOfConfiguration(c);
    const auto acc = ModeAccelerations(geo_, mode, {y[0], y[1], y[2], y[3]}, UsedTilts(mode, y), xg,
                                       yg, equations_);
    return {y[2], y[3], acc[0], acc[1]};
  }
  /// y on c's constraints (a closed interface's block takes its support's angle and rate; one
  /// block's mirror).
  Y Project(const Configuration& c, const Y& y) const {
    Y p = y;
    if (!geo_.two_blocks || c[1] == Contact::kFace) {
      p[1] = p[0];
      p[3] = p[2];
    }
    if (c[0] == Contact::kFace) {
      p[0] = 0.0;
      p[2] = 0.0;
    }
    return p;
  }
  /// y with interface k's gap closed exactly (it lands), the blocks resting on faces above it
  /// landing with it.
  Y Land(const Configuration& c, Y y, int interface) const {
    const bool ground_moves = c[0] != Contact::kFace;
    const bool interface_moves = geo_.two_blocks && c[1] != Contact::kFace;
    if (interface == 0) {
      y[0] = 0.0;
      if (!interface_moves) y[1] = 0.0;
    } else {
      y[1] = ground_moves ? y[0] : 0.0;
    }
    return y;
  }
  Margins Evaluate(const Configuration& c, const Y& y, double xg, double yg) const;
  /// The same from c's accelerations at y already computed (an integrator's last stage f).
  Margins EvaluateWithRhs(const Configuration& c, const Y& y, const Y& f, double xg,
                          double yg) const;
  Selection Select(const Y& y, double xg, double yg) const;
  /// Whether any configuration's contact forces at y are not finite (an absurd base
  /// acceleration), and the first such value.
  bool NonFiniteForces(const Y& y, double xg, double yg, double* value) const;
  Impact ResolveImpact(const Configuration& c, const Y& y, int interface, double rest_rel) const;
  double Energy(const Configuration& c, const Y& y) const;

 private:
  // sin and cos of an angle. The right-hand side takes them and keeps the last two (it is rarely
  // asked twice at one state); the contact forces look there first (bit for bit: the driver asks
  // for them at a state whose right-hand side it just took, a step's end, and a closed
  // interface's two angles are equal).
  struct SinCos1 {
    double sin = 0.0, cos = 1.0;
  };
  SinCos1 SinCosKept(double theta) const {
    const SinCos1 sc{std::sin(theta), std::cos(theta)};
    memo_bits_[memo_next_] = std::bit_cast<uint64_t>(theta);
    memo_[memo_next_] = sc;
    memo_next_ ^= 1;
    return sc;
  }
  SinCos1 SinCosOf(double theta) const {
    const uint64_t bits = std::bit_cast<uint64_t>(theta);
    if (memo_bits_[0] == bits) return memo_[0];
    if (memo_bits_[1] == bits) return memo_[1];
    return SinCosKept(theta);
  }
  // Both angles' tilts.
  Tilts TiltsAt(const Y& y) const {
    const SinCos1 a = SinCosOf(y[0]), b = SinCosOf(y[1]);
    return {a.sin, a.cos, b.sin, b.cos};
  }
  // The tilts the mode's equations use (as ModeAccelerations without tilts takes them: mode 3
  // theta1's, mode 4 theta2's, none for the linearized equations); the others stay at zero.
  Tilts UsedTilts(Mode mode, const Y& y) const {
    Tilts tl;
    if (equations_ == Equations::kLinearized) return tl;
    const Contacts c = ContactsOf(mode);
    if (c.ground != Contact::kFace) {
      const SinCos1 a = SinCosKept(y[0]);
      tl.sin1 = a.sin;
      tl.cos1 = a.cos;
    }
    if (c.interface != Contact::kFace && geo_.two_blocks) {
      const SinCos1 b = SinCosKept(y[1]);
      tl.sin2 = b.sin;
      tl.cos2 = b.cos;
    }
    return tl;
  }

  Geometry geo_;
  Equations equations_;
  // The memo's angles, as bits; at first a NaN's, which no memo lookup trusts (SinCosOf of
  // that NaN gives the NaN's sin and cos, as computing them would).
  mutable std::array<uint64_t, 2> memo_bits_{kNoAngle, kNoAngle};
  mutable std::array<SinCos1, 2> memo_{SinCos1{kNoAngleValue, kNoAngleValue},
                                       SinCos1{kNoAngleValue, kNoAngleValue}};
  mutable int memo_next_ = 0;
  static constexpr uint64_t kNoAngle = 0x7ff8dead0000beefull;
  static constexpr double kNoAngleValue = std::numeric_limits<double>::quiet_NaN();
};

/// The N-block chain, up to Cap blocks.
template <size_t Cap>
class ChainMechanics {
 public:
  static constexpr size_t kCap = Cap;
  using Y = VecN<2 * Cap>;
  using Margins = MarginsN<Cap>;
  using Impact = ImpactN<2 * Cap>;

  /// The scene's stack (ValidateScene has checked it: at most Cap blocks, nonlinear equations).
  explicit ChainMechanics(const Scene& scene);
  int blocks() const { return n_; }
  int active() const { return 2 * n_; }
  double time_scale_s() const;
  Y Initial(const InitialState& in) const;

  Y Rhs(const Configuration& c, const Y& y, double xg, double yg) const;
  Y Project(const Configuration& c, const Y& y) const;
  Y Land(const Configuration& c, Y y, int interface) const;
  Margins Evaluate(const Configuration& c, const Y& y, double xg, double yg) const;
  Margins EvaluateWithRhs(const Configuration& c, const Y& y, const Y& f, double xg,
                          double yg) const {
    (void)f;  // the loads come out of the recursion again (it is O(N), as the right-hand side)
    return Evaluate(c, y, xg, yg);
  }
  Selection Select(const Y& y, double xg, double yg) const;
  bool NonFiniteForces(const Y& y, double xg, double yg, double* value) const;
  Impact ResolveImpact(const Configuration& c, const Y& y, int interface, double rest_rel) const;
  double Energy(const Configuration& c, const Y& y) const;

 private:
  int n_ = 0;
  // The chain keeps a workspace: the mechanics' questions are const to the driver.
  mutable StackContacts contacts_;
};

/// The N-block chain's geometry of a scene (its blocks, bottom first, and gravity).
StackGeometry StackGeometryOf(const Scene& scene);

extern template class ChainMechanics<2>;
extern template class ChainMechanics<4>;
extern template class ChainMechanics<8>;
extern template class ChainMechanics<16>;
extern template class ChainMechanics<32>;
extern template class ChainMechanics<64>;

}  // namespace rockbench::reference
