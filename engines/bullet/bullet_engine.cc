#include "engines/bullet/bullet_engine.h"

#include <stdexcept>
#include <string>

#include "engines/bullet/rocking_world.h"
#include "engines/common/fixed_step.h"

namespace rockbench::bullet {

EngineResult Simulate(const BulletInput& input) {
  const bool want_double = input.config.precision == BulletPrecision::kDouble;
  if (want_double != (std::string(CompiledPrecision()) == "double")) {
    throw std::invalid_argument(std::string("bullet: this engine library is ") +
                                CompiledPrecision() + " precision, the input asks for " +
                                (want_double ? "double" : "float"));
  }
  RockingWorld world(input);
  return RunEngineWorld("bullet", input, world);
}

}  // namespace rockbench::bullet
