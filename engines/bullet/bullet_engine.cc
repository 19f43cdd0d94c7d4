#include "engines/bullet/bullet_engine.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "engines/bullet/monitor.h"
#include "engines/bullet/rocking_world.h"

namespace rockbench::bullet {

EngineOutput Simulate(const EngineInput& input) {
  const bool want_double = input.config.precision == BulletPrecision::kDouble;
  if (want_double != (std::string(CompiledPrecision()) == "double")) {
    throw std::invalid_argument(std::string("bullet: this engine library is ") +
                                CompiledPrecision() + " precision, the input asks for " +
                                (want_double ? "double" : "float"));
  }
  const auto start = std::chrono::steady_clock::now();
  RockingWorld world(input);
  Monitor monitor(input);
  monitor.Start(world.Read(0));
  for (std::int64_t n = 0; n < input.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    if (!monitor.Step(n + 1, world.Read(n + 1))) break;
  }
  monitor.Finish();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  EngineOutput out;
  out.summary = monitor.Summary();
  out.summary["engine"] = "bullet";
  out.summary["settings"] = world.Settings();
  out.summary["wall_s"] = wall_s;
  out.summary["real_time_factor"] = wall_s > 0.0 ? monitor.last().t_s / wall_s : 0.0;
  if (input.config.drive == BulletDrive::kKinematic) {
    const DriveSamples& d = input.drive;
    nlohmann::json k;
    k["baseline"] = input.config.kinematic_highpass_hz > 0.0
                        ? "zero-phase Butterworth high-pass (u minus forward-backward "
                          "2nd-order low-pass of u)"
                        : "none";
    k["highpass_hz"] = input.config.kinematic_highpass_hz;
    k["raw_peak_displacement_x_m"] = d.raw_peak_x_m;
    k["raw_peak_displacement_y_m"] = d.raw_peak_y_m;
    k["peak_displacement_x_m"] = d.peak_x_m;
    k["peak_displacement_y_m"] = d.peak_y_m;
    k["correction_max_accel_x_mps2"] = d.correction_max_x_mps2;
    k["correction_max_accel_y_mps2"] = d.correction_max_y_mps2;
    out.summary["kinematic"] = k;
  }
  out.wall_s = wall_s;
  out.history = monitor.TakeHistory();
  return out;
}

}  // namespace rockbench::bullet
