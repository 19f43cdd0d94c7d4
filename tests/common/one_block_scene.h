#pragma once
// The smallest scene an engine's input can be built from, for tests of the input's checks.
#include "scene/scene.h"

namespace rockbench::testing_util {

/// One block 1 m wide, 4 m high and 1 m deep, of 10000 kg, in a run of 1 s.
inline Scene OneBlockScene() {
  Scene s;
  s.blocks = {{1.0, 4.0, 1.0, 10000.0, 0.0}};
  s.run.duration_s = 1.0;
  return s;
}

}  // namespace rockbench::testing_util
