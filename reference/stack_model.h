#pragma once
/// The model's facts about a stack, evaluated on any run's samples (the engines' included): the
/// energy above rest, the contact reactions with the friction they need, and the margin of the
/// faces of the stack at rest under a base acceleration. One or two blocks: the thesis's
/// geometry and equations (reference/thesis/observables.h); N >= 3 blocks: the pivot chain
/// (reference/chain/stack_contacts.h), the same model (docs/n-blocks.md). Part of the
/// reference's public face: the reports and the comparison use it instead of the model's rooms.
#include <memory>
#include <vector>

#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench::reference {

class StackModel {
 public:
  /// The stack of `scene` (its blocks, gravity and [model] equations).
  explicit StackModel(const Scene& scene);
  ~StackModel();
  StackModel(const StackModel&) = delete;
  StackModel& operator=(const StackModel&) = delete;

  int blocks() const;
  /// The stack's weight M g, N.
  double weight_n() const;
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

  /// The face margin of the stack at rest (every face closed) under the base acceleration
  /// (xg'', yg'') (m/s^2), by the model's contact rule: > 0 while every face holds. Not
  /// thread-safe (the chain keeps a workspace).
  double RestFaceMargin(double xg_mps2, double yg_mps2) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::reference
