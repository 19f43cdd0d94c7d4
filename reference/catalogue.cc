// The reference's public face for callers besides a run: critical angle, rest contact margin,
// kinetic energy (reference/catalogue.h).
#include "reference/catalogue.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "reference/chain/stack_chain.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "reference/thesis/transitions.h"

namespace rockbench::reference {

double CriticalAngle_rad(const Scene& scene) {
  if (scene.block_count() > 2) {
    throw SceneError("the stack's critical angle: the thesis's geometry holds one or two blocks");
  }
  return MakeGeometry(scene).theta_c;
}

double RestCornerForce_N(const Scene& scene, RestFace face, double xg_mps2) {
  if (scene.block_count() > 2) {
    throw SceneError(
        "a face's corner forces at rest: the thesis's geometry holds one or two "
        "blocks");
  }
  if (face == RestFace::kInterface && scene.block_count() != 2) {
    throw SceneError("the corner forces of block 2 on block 1: the scene has one block");
  }
  const Geometry geo = MakeGeometry(scene);
  const Reactions r =
      EvaluateContacts(geo, Mode::kRest, State{}, xg_mps2, 0.0, scene.model.equations).reactions;
  return face == RestFace::kGround ? std::min(r.ground_left, r.ground_right)
                                   : std::min(r.interface_left, r.interface_right);
}

struct StackKinetics::Impl {
  int blocks = 0;
  Geometry geo;                     // one or two blocks
  std::optional<StackChain> chain;  // N >= 3
};

StackKinetics::StackKinetics(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  impl_->blocks = scene.block_count();
  if (impl_->blocks <= 2) {
    impl_->geo = MakeGeometry(scene);
    return;
  }
  std::vector<BlockSize> sizes;
  for (const BlockDef& b : scene.blocks) sizes.push_back({b.width_m, b.height_m, b.mass_kg});
  impl_->chain.emplace(MakeStackGeometry(sizes, scene.run.gravity_mps2));
}

StackKinetics::~StackKinetics() = default;

double StackKinetics::Kinetic_j(const Configuration& c, const BlockValues& theta_rad,
                                const BlockValues& omega_radps) {
  double ke = 0.0;
  if (impl_->blocks <= 2) {
    // The thesis's state: block 2's values are block 1's for one block.
    const Geometry& geo = impl_->geo;
    const size_t top = theta_rad.size() >= 2 && omega_radps.size() >= 2 ? 1 : 0;
    State s{theta_rad[0], theta_rad[top], omega_radps[0], omega_radps[top]};
    if (!geo.two_blocks) {
      s.theta2 = s.theta1;
      s.omega2 = s.omega1;
    }
    const BodyVelocities v = Velocities(geo, ModeOfConfiguration(c).value_or(Mode::kRest), s);
    const double m[2] = {geo.block1.m, geo.block2.m};
    const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
    for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
      ke += 0.5 * m[b] * Dot(v.vG[b], v.vG[b]) + 0.5 * IG[b] * v.w[b] * v.w[b];
    }
    return ke;
  }
  StackChain& chain = *impl_->chain;
  chain.Place(c, theta_rad.data(), omega_radps.data());
  for (int b = 0; b < impl_->blocks; ++b) {
    const BodyMotion m = chain.Body(b);
    const BlockProps& p = chain.geometry().blocks[static_cast<size_t>(b)];
    ke += 0.5 * p.m * Dot(m.vG, m.vG) + 0.5 * p.I_G * m.w_radps * m.w_radps;
  }
  return ke;
}

}  // namespace rockbench::reference
