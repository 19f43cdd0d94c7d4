#include "harness/engines_bullet.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/engine_input.h"
#include "engines/bullet/float_helper.h"

namespace rockbench {

EngineRun RunBulletEngine(const Scene& scene, const GroundMotion& motion,
                          double stop_at_rest_after_s) {
  bullet::EngineInput input = bullet::MakeEngineInput(scene, motion);
  input.stop_at_rest_after_s = stop_at_rest_after_s;
  bullet::EngineOutput out;
  if (scene.bullet.precision == BulletPrecision::kDouble) {
    out = bullet::Simulate(input);
  } else {
    try {
      out = bullet::RunFloatHelper(input);
    } catch (const std::runtime_error& e) {
      throw SceneError(e.what());
    }
  }
  EngineRun run;
  run.engine = "bullet";
  run.history = std::move(out.history);
  run.summary = std::move(out.summary);
  run.wall_s = out.wall_s;

  const nlohmann::json& s = run.summary;
  const nlohmann::json& v = s["violations"];
  std::string flags;
  for (const char* f : {"sliding", "uplift", "penetration", "energy_growth", "blow_up"}) {
    if (v.value(f, false)) flags += std::string(flags.empty() ? "" : ",") + f;
  }
  char line[320];
  std::snprintf(
      line, sizeof line,
      "bullet (%s, %s, dt %.3g s, %d it): %s, peak |theta1| %.4g rad at %.3f s, %d "
      "impacts, flags: %s, %.3g ms",
      s["settings"].value("precision", "?").c_str(), s["settings"].value("drive", "?").c_str(),
      scene.bullet.time_step_s, scene.bullet.solver_iterations, s.value("status", "?").c_str(),
      s["peaks"]["theta1"].value("abs_rad", 0.0), s["peaks"]["theta1"].value("t_s", 0.0),
      s["impacts"].value("total", 0), flags.empty() ? "none" : flags.c_str(), run.wall_s * 1e3);
  run.one_line = line;
  return run;
}

}  // namespace rockbench
