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
  EngineResult out = RunFixedStepWorld(input, world);
  out.summary["engine"] = "bullet";
  out.summary["settings"] = world.Settings();
  if (input.drive_kind == DriveKind::kKinematic) {
    const DriveSamples& d = input.drive;
    nlohmann::json k;
    k["baseline"] = input.kinematic_highpass_hz > 0.0
                        ? "zero-phase Butterworth high-pass (u minus forward-backward "
                          "2nd-order low-pass of u)"
                        : "none";
    k["highpass_hz"] = input.kinematic_highpass_hz;
    k["raw_peak_displacement_x_m"] = d.raw_peak_x_m;
    k["raw_peak_displacement_y_m"] = d.raw_peak_y_m;
    k["peak_displacement_x_m"] = d.peak_x_m;
    k["peak_displacement_y_m"] = d.peak_y_m;
    k["correction_max_accel_x_mps2"] = d.correction_max_x_mps2;
    k["correction_max_accel_y_mps2"] = d.correction_max_y_mps2;
    out.summary["kinematic"] = k;
  }
  return out;
}

}  // namespace rockbench::bullet
