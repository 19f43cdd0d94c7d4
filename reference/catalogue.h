#pragma once
/// The reference's public face for what callers outside the model need of it besides a run
/// (the stress catalogue, the reports): a stack's critical angle, the margin of a contact at
/// rest, the kinetic energy of a state. Each is the model's own rule (the thesis's geometry and
/// contact rule for one or two blocks, the pivot chain for N blocks), reached here so that no
/// caller reads the model's rooms (reference/thesis/, reference/chain/).
#include <memory>

#include "scene/block_values.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// The stack's slenderness angle, rad: the angle at block 1's base corner between the vertical
/// and the line to the mass centre of the whole stack (one block: atan(B / H), Housner's
/// critical angle of a block released from rest). One or two blocks (the thesis's geometry);
/// throws SceneError for a stack the thesis's geometry cannot hold (block 2 wider than block 1,
/// three or more blocks).
double CriticalAngle_rad(const Scene& scene);

/// The faces of a stack at rest: block 1 on the ground, block 2 on block 1.
enum class RestFace {
  kGround,     ///< block 1 on the ground (the whole stack tips about block 1's corner)
  kInterface,  ///< block 2 on block 1 (needs two blocks)
};

/// The smaller of the two corner normal forces (N, compression > 0) of `face` with the stack
/// at rest under a constant horizontal base acceleration xg'' = `xg_mps2` (m/s^2, no vertical
/// one), by the model's own contact rule (the rule of the thesis's initiation criteria 4.1 to
/// 4.4, with the scene's [model] equations). Negative: the face opens. One or two blocks
/// (throws SceneError otherwise, and for kInterface on one block).
double RestCornerForce_N(const Scene& scene, RestFace face, double xg_mps2);

/// The kinetic energy (base frame, J) of a stack in a contact configuration: the sum of
/// m v_G^2 / 2 + I_G w^2 / 2 over its blocks, computed directly from the model's kinematics (not
/// as total minus potential energy, which would cancel digits). One or two blocks by the
/// thesis's kinematics, N >= 3 by the pivot chain. Holds the stack's geometry between calls;
/// not thread-safe (one per thread).
class StackKinetics {
 public:
  /// The stack of `scene` (its blocks and gravity). Throws SceneError for a stack the model
  /// cannot hold.
  explicit StackKinetics(const Scene& scene);
  ~StackKinetics();
  StackKinetics(const StackKinetics&) = delete;
  StackKinetics& operator=(const StackKinetics&) = delete;

  /// At the absolute angles `theta_rad` (rad) and rates `omega_radps` (rad/s) of every block,
  /// in configuration `c` (a closed face's block moves with its support: the state need not be
  /// projected), J.
  double Kinetic_j(const Configuration& c, const BlockValues& theta_rad,
                   const BlockValues& omega_radps);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::reference
