#include "engines/box2d/box2d_settings.h"

#include <string>

namespace rockbench::box2d_engine {

const EngineSettingsSchema& Box2dSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "box2d";
    const Box2dSettings d;
    AddTimeStepSetting(s, "1/60 s (testbed)", "fixed step of b2World::Step (a float)");
    AddDriveSetting(s);
    s.Integer("velocity_iterations", d.velocity_iterations, 1, 100000, "8 (testbed)",
              "sequential-impulse iterations of the contact velocities per step");
    s.Integer("position_iterations", d.position_iterations, 0, 100000, "3 (testbed)",
              "position-correction iterations per step, at most (it stops once within 3 slops)");
    s.Number("friction", d.friction, R::kNonNegative, "", "0.2 (b2FixtureDef)",
             "Coulomb coefficient where the scene's is infinite; Box2D has no unbounded friction");
    s.Number("restitution", d.restitution, R::kUnitInterval, "", "0 (b2FixtureDef)",
             "the impact loses energy by the geometry, as in the model");
    s.Number("restitution_threshold", d.restitution_threshold_mps, R::kNonNegative, "m/s",
             "1 m/s of Box2D's (b2FixtureDef)",
             "no bounce below this approach speed, in the scene's m/s; nothing with restitution 0");
    s.Number("length_scale", d.length_scale, R::kPositive, "", "1 (none)",
             "Box2D simulates every length times this: its 1 cm skin and 5 mm slop shrink by it",
             {.min = 1e-3});
    s.Flag("warm_starting", d.warm_starting, "true", "contact impulses start from the last step's");
    s.Flag("continuous", d.continuous, "true",
           "time of impact against the ground (b2World::SetContinuousPhysics)");
    s.Flag("bullet", d.bullet, "false", "blocks as bullets: time of impact between blocks too");
    s.Number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(s);
    return s;
  }();
  return kSchema;
}

Box2dRun MakeBox2dRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, Box2dSettingsSchema());
  Box2dRun run;
  run.input = MakeEngineInput(scene, motion, "box2d", set, stop_at_rest_after_s);
  Box2dSettings& s = run.settings;
  s.velocity_iterations = static_cast<int>(set.Integer("velocity_iterations"));
  s.position_iterations = static_cast<int>(set.Integer("position_iterations"));
  s.friction = set.Number("friction");
  s.restitution = set.Number("restitution");
  s.restitution_threshold_mps = set.Number("restitution_threshold");
  s.length_scale = set.Number("length_scale");
  s.warm_starting = set.Flag("warm_starting");
  s.continuous = set.Flag("continuous");
  s.bullet = set.Flag("bullet");
  s.ground_depth_m = set.Number("ground_depth");
  return run;
}

}  // namespace rockbench::box2d_engine
