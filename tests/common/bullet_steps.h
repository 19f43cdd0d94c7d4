#pragma once
// Bullet's world stepped by hand, every step's readout kept: what the external protocol's tests
// and its overhead benchmark replay.
#include <cstdint>
#include <vector>

#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/rocking_world.h"

namespace rockbench::testing_util {

/// The readouts of Bullet's world on `in`, from step 0 to in.steps (in.steps + 1 of them).
inline std::vector<StepReadout> RecordBulletSteps(const bullet::BulletInput& in) {
  std::vector<StepReadout> steps;
  bullet::RockingWorld world(in);
  steps.push_back(world.Read(0));
  for (std::int64_t n = 0; n < in.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    steps.push_back(world.Read(n + 1));
  }
  return steps;
}

}  // namespace rockbench::testing_util
