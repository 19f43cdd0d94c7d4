// The Bullet engine behind the engine interface (src/scene/engine.h): double precision in
// this process, single precision through the helper program (float_helper.h).
#include <LinearMath/btScalar.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "engines/bullet/bullet_cylinder.h"
#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/float_helper.h"
#include "scene/body_kind.h"

namespace rockbench {
namespace bullet {
namespace {

std::string StepText(double dt_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", dt_s);
  return buf;
}

class BulletEngine final : public Engine {
 public:
  std::string name() const override { return "bullet"; }

  std::string version() const override {
    char buf[96];
    std::snprintf(buf, sizeof buf, "Bullet %d.%02d (bullet-float64 in process, float helper)",
                  BT_BULLET_VERSION / 100, BT_BULLET_VERSION % 100);
    return buf;
  }

  const EngineSettingsSchema& settings_schema() const override { return BulletSettingsSchema(); }

  /// The planar block and, in double precision, the cylinder (cylinder_world.h).
  std::vector<std::string> body_shapes() const override {
    return {PlanarBlockKind().shape, std::string(kCylinderShape)};
  }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    const std::vector<double> steps =
        quick ? std::vector<double>{1.0 / 60.0, 1e-3, 1e-4}
              : std::vector<double>{1.0 / 60.0, 5e-3, 1e-3, 5e-4, 1e-4, 5e-5, 1e-5};
    const std::vector<std::int64_t> iterations =
        quick ? std::vector<std::int64_t>{10, 50} : std::vector<std::int64_t>{4, 10, 50, 200};
    std::vector<SweepSetting> grid;
    for (const char* precision : {"double", "float"}) {
      for (double dt : steps) {
        for (std::int64_t it : iterations) {
          SweepSetting s;
          s.family =
              std::string("Bullet ") + precision + " (" + std::to_string(it) + " iterations)";
          s.label = TimeStepLabel(dt);
          s.time_step_s = dt;
          s.settings = {
              {"precision", std::string(precision)}, {"time_step", dt}, {"solver_iterations", it}};
          grid.push_back(std::move(s));
        }
      }
    }
    return grid;
  }

  std::vector<SweepSetting> StressGrid() const override {
    struct Step {
      const char* label;
      double dt_s;
    };
    const Step steps[] = {{"1/60", 1.0 / 60.0}, {"1e-3", 1e-3}, {"1e-4", 1e-4}, {"1e-5", 1e-5}};
    std::vector<SweepSetting> grid;
    for (const std::string precision : {"double", "float"}) {
      for (const Step& st : steps) {
        for (std::int64_t it : {1, 10, 50, 200}) {
          SweepSetting s;
          s.family = "Bullet " + precision + " (" + std::to_string(it) + " iterations)";
          s.label = st.label;
          s.time_step_s = st.dt_s;
          s.settings = {
              {"precision", precision}, {"time_step", st.dt_s}, {"solver_iterations", it}};
          s.id = precision + "/dt=" + st.label + "/it=" + std::to_string(it);
          s.quick = (precision == "float" && st.dt_s > 0.01 && it == 1) ||
                    (precision == "double" && st.dt_s == 1e-3 && it == 200);
          grid.push_back(std::move(s));
        }
      }
    }
    return grid;
  }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const BulletInput input = MakeBulletInput(scene, motion, options.stop_at_rest_after_s);
    EngineResult out;
    if (scene.three_dimensional()) {
      // The cylinder: in process, double precision only (the float helper builds blocks).
      if (input.config.precision != BulletPrecision::kDouble) {
        throw SceneError((scene.path.empty() ? std::string("scene") : scene.path.string()) +
                         ": bullet.precision: the cylinder (block1.shape = \"cylinder\") is "
                         "built in double precision only; \"float\" builds blocks");
      }
      out = SimulateCylinder(input);
    } else if (input.config.precision == BulletPrecision::kDouble) {
      out = bullet::Simulate(input);
    } else {
      try {
        out = RunFloatHelper(input);
      } catch (const std::runtime_error& e) {
        throw SceneError(e.what());
      }
    }
    out.settings_line =
        std::string(input.config.precision == BulletPrecision::kDouble ? "double" : "float") +
        ", " + DriveKindName(input.drive_kind) + ", dt " + StepText(input.time_step_s) + " s, " +
        std::to_string(input.config.solver_iterations) + " it";
    return out;
  }
};

}  // namespace
}  // namespace bullet

namespace engine_registry {
std::unique_ptr<Engine> Make_bullet() {
  return std::make_unique<bullet::BulletEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
