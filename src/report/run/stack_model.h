#pragma once
/// The rigid-block model of a run's stack, as the report evaluates it on any run's samples
/// (engines included): energy above rest and the contact reactions with the friction they need.
/// One or two blocks: the thesis's geometry and equations (reference/observables.h); N >= 3
/// blocks: the pivot chain (reference/stack_contacts.h), the same model (docs/n-blocks.md).
#include <optional>
#include <vector>

#include "reference/chain/stack_contacts.h"
#include "reference/thesis/geometry.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::report {

class StackModel {
 public:
  explicit StackModel(const Scene& scene);

  int blocks() const { return blocks_; }
  /// The stack's weight M g, N.
  double weight_n() const { return weight_n_; }
  /// Kinetic energy in the base frame plus potential energy above the rest position, J.
  double EnergyAboveRest_j(const Sample& s) const;

  /// Per interface (0: block 1 on the ground; k: block k + 1 on block k): the normal force (N,
  /// compression > 0) and the friction coefficient |T|/N it needs (0 when N <= 0).
  struct Contacts {
    std::vector<double> normal_n, mu;
  };
  /// The reactions of the sample's configuration at its state under the base acceleration
  /// (xg'', yg'') (m/s^2).
  Contacts Reactions(const Sample& s, double xg_mps2, double yg_mps2) const;

  /// The thesis's geometry (one or two blocks); nullopt for N >= 3.
  const std::optional<reference::Geometry>& thesis() const { return geo_; }

 private:
  int blocks_ = 1;
  double weight_n_ = 0.0;
  Equations equations_ = Equations::kNonlinear;
  std::optional<reference::Geometry> geo_;
  // The chain keeps a workspace (N >= 3).
  mutable std::optional<reference::StackContacts> chain_;
  mutable std::vector<double> acc_;
  double rest_energy_j_ = 0.0;
};

}  // namespace rockbench::report
