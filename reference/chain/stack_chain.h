#pragma once
/// The pivot chain of a stack of N rigid blocks (issue 23; the thesis's chapter-7 future work):
/// positions, velocities, the exact nonlinear equations of motion of every contact
/// configuration, the contact loads at every interface, energy and momentum, for any N.
///
/// Blocks i = 0..N-1 from the bottom (block i + 1 in the text), each centred on the one below at
/// rest and no wider than it. Interface k is block k on its support (the ground for k = 0, block
/// k - 1 above it): closed on its face, or rocking about block k's right or left base corner
/// (scene/mode.h Configuration). The state is every block's ABSOLUTE angle theta_i and rate
/// omega_i, thesis sign convention (theta > 0: tilted right, clockwise); a closed interface has
/// theta_k = theta_{k-1} and omega_k = omega_{k-1} (theta_{-1} = 0: the ground). The generalized
/// coordinates are the relative angles theta_k - theta_{k-1} of the open interfaces.
///
/// The equations of motion are assembled by the articulated-body recursion (Featherstone 2008,
/// "Rigid Body Dynamics Algorithms", ch. 7) on planar spatial vectors: one outward pass
/// (velocities), one inward pass (articulated inertias), one outward pass (accelerations), each
/// O(N); a closed interface is a weld that passes its subtree's inertia down unchanged. Cost per
/// right-hand side: O(N) (measured in bench/reference_bench.cc, docs/performance-reference.md).
/// The same recursion with the blocks' momenta as applied impulses gives the post-impact rates
/// (perfectly plastic impacts: the generalized momenta of the post-impact configuration are
/// conserved). The interface loads follow from Newton-Euler on the blocks above each interface.
///
/// Frame: the base frame (translating with the ground), origin at block 1's base centre at rest,
/// x right, y up; SI units. The base's acceleration (xg'', yg'') enters as effective gravity
/// (-xg'', -(g + yg'')).
#include <vector>

#include "scene/mode.h"
#include "scene/rigid_block.h"
#include "scene/scene.h"
#include "scene/vec2.h"

namespace rockbench::reference {

/// The blocks of a stack, bottom first, and gravity.
struct StackGeometry {
  double g = 9.81;                 ///< gravity, m/s^2
  std::vector<BlockProps> blocks;  ///< bottom first
  int size() const { return static_cast<int>(blocks.size()); }
};

/// The geometry of blocks given by full width B, height H (m) and mass m (kg), bottom first.
struct BlockSize {
  double width_m = 0.0, height_m = 0.0, mass_kg = 0.0;
};
StackGeometry MakeStackGeometry(const std::vector<BlockSize>& blocks, double g_mps2 = 9.81);

/// The load one interface carries: the force of the support on the blocks above it, in the
/// support's top-face frame (normal n = (sin theta_{k-1}, cos theta_{k-1}), tangent t = (cos
/// theta_{k-1}, -sin theta_{k-1})); for a closed face, also its split into the normal forces at
/// the two base corners of block k. Forces N (or impulses N s, ImpactImpulses).
struct InterfaceLoad {
  double normal_n = 0.0;      ///< compression > 0
  double tangential_n = 0.0;  ///< along t (+x of the face)
  double left_n = 0.0;        ///< face only: normal force at block k's left base corner
  double right_n = 0.0;       ///< face only: at the right one
};

/// The chain of one stack, with its workspace: every operation is O(N) and allocates nothing
/// after construction. Not thread-safe (one per thread).
class StackChain {
 public:
  explicit StackChain(StackGeometry geometry);

  const StackGeometry& geometry() const { return geo_; }
  int size() const { return n_; }

  /// Places the chain in configuration `c` (size() interfaces) at the absolute angles theta
  /// and rates omega (size() each; a closed interface's values are taken from its support:
  /// the state need not be projected). Every query below is about the last placement.
  void Place(const Configuration& c, const double* theta_rad, const double* omega_radps);

  /// The absolute angular accelerations theta_i'' (rad/s^2) of every block under the base
  /// acceleration (xg'', yg'') (m/s^2), into theta_dd[0..size()-1] (a closed interface's block
  /// gets its support's). With `loads` (size() entries), also every interface's load.
  void Accelerations(double xg_mps2, double yg_mps2, double* theta_dd,
                     InterfaceLoad* loads = nullptr);

  /// The mass centre (m), its velocity (m/s) and the counter-clockwise rate (rad/s) of block i.
  BodyMotion Body(int i) const;
  /// Pivot of interface k: block k's corner on its support (for a closed face, the corner on
  /// the side of the interface below, the right one on the ground), m.
  Vec2 Pivot(int k) const { return pivot_[k]; }

  /// Kinetic energy in the base frame plus m g y_G, J, of every block (per_block: size()
  /// entries, may be null), and their sum.
  double Energy(double* per_block_j = nullptr) const;

  /// The rates just after a perfectly plastic impact that leaves the stack in configuration
  /// `after` (at the same angles): the generalized momenta of `after` are conserved, so the
  /// impulses act only at `after`'s contacts. Call after Place(before, theta, omega_minus);
  /// writes omega_plus (size()) and, with `impulses` (size() entries), the impulse each
  /// interface takes (N s, in InterfaceLoad's components). The chain is then placed in `after`
  /// with those rates.
  void ImpactRates(const Configuration& after, double* omega_plus,
                   InterfaceLoad* impulses = nullptr);

  /// Newton-Euler on the blocks above each interface: the loads that give the blocks the
  /// mass-centre accelerations aG (m/s^2) and counter-clockwise angular accelerations alpha
  /// (rad/s^2) under effective gravity g_eff (m/s^2), at the current placement; with velocity
  /// jumps for accelerations and g_eff = 0, the impulses of an impact. loads: size() entries.
  void LoadsFor(const Vec2* aG, const double* alpha, Vec2 g_eff, InterfaceLoad* loads);

 private:
  // Planar spatial vectors about the origin (Featherstone's 6-D vectors cut to the plane):
  // a motion (w: counter-clockwise rate, x, y: velocity of the body point at the origin), a
  // force (w: moment about the origin, x, y: force).
  struct Spatial {
    double w = 0.0, x = 0.0, y = 0.0;
  };
  // A symmetric 3x3 spatial inertia.
  struct Inertia {
    double ww = 0.0, wx = 0.0, wy = 0.0, xx = 0.0, xy = 0.0, yy = 0.0;
  };
  static Spatial Times(const Inertia& I, const Spatial& v);
  void Recursion(const Spatial& base_accel, bool with_velocities, const Spatial* applied,
                 double* rel_acc);
  // Each interface's force_ in its support's frame, and a closed face's corner forces.
  void Resolve(InterfaceLoad* loads) const;

  StackGeometry geo_;
  int n_ = 0;
  Configuration config_;
  // Per block: tilt, pivot, mass centre, joint axis, spatial velocity, velocity-product
  // acceleration, articulated inertia and bias, spatial acceleration.
  std::vector<double> theta_, sin_, cos_, zero_;
  std::vector<Vec2> pivot_, G_;
  std::vector<Spatial> S_, v_, c_, pA_, a_, U_;
  // The force of each interface (Accelerations, LoadsFor, ImpactRates) and the blocks' momenta
  // before an impact.
  std::vector<Spatial> force_, momenta_;
  std::vector<Inertia> IA_;
  std::vector<double> D_, u_, qd_;
};

}  // namespace rockbench::reference
