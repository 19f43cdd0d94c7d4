#pragma once
/// What a fixed-step engine world holds of its run whatever the engine: the run input, its own
/// settings and whether the drive is kinematic (engines/common/fixed_step.h runs the world).
#include "engines/common/engine_input.h"

namespace rockbench {

/// A world's base: keeps a reference to the run input (which must outlive the world), a copy of
/// the engine's settings and the drive kind. Not copyable (a world owns its engine's state).
template <typename Settings>
class WorldBase {
 public:
  WorldBase(const WorldBase&) = delete;
  WorldBase& operator=(const WorldBase&) = delete;

 protected:
  WorldBase(const EngineInput& input, const Settings& settings)
      : in_(input), s_(settings), kinematic_(input.drive_kind == DriveKind::kKinematic) {}
  ~WorldBase() = default;

  const EngineInput& in_;
  Settings s_;
  /// The kinematic drive (the ground moves by the displacement samples); else inertial (the
  /// base acceleration as a body force).
  bool kinematic_ = false;
};

}  // namespace rockbench
