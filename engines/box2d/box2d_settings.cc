#include "engines/box2d/box2d_settings.h"

#include <string>

namespace rockbench::box2d_engine {
namespace {

// The [box2d] table: each key once, bound to the Box2dSettings member it sets.
const SettingsTable<Box2dSettings>& Box2dTable() {
  using R = SettingRange;
  using S = Box2dSettings;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("box2d");
    AddTimeStepSetting(t.unbound(), "1/60 s (testbed)", "fixed step of b2World::Step (a float)");
    AddDriveSetting(t.unbound());
    t.Integer("velocity_iterations", &S::velocity_iterations, 1, 100000, "8 (testbed)",
              "sequential-impulse iterations of the contact velocities per step");
    t.Integer("position_iterations", &S::position_iterations, 0, 100000, "3 (testbed)",
              "position-correction iterations per step, at most (it stops once within 3 slops)");
    t.Number("friction", &S::friction, R::kNonNegative, "", "0.2 (b2FixtureDef)",
             "Coulomb coefficient where the scene's is infinite; Box2D has no unbounded friction");
    t.Number("restitution", &S::restitution, R::kUnitInterval, "", "0 (b2FixtureDef)",
             "the impact loses energy by the geometry, as in the model");
    t.Number("restitution_threshold", &S::restitution_threshold_mps, R::kNonNegative, "m/s",
             "1 m/s of Box2D's (b2FixtureDef)",
             "no bounce below this approach speed, in the scene's m/s; nothing with restitution 0");
    t.Number("length_scale", &S::length_scale, R::kPositive, "", "1 (none)",
             "Box2D simulates every length times this: its 1 cm skin and 5 mm slop shrink by it",
             {.min = 1e-3});
    t.Flag("warm_starting", &S::warm_starting, "true",
           "contact impulses start from the last step's");
    t.Flag("continuous", &S::continuous, "true",
           "time of impact against the ground (b2World::SetContinuousPhysics)");
    t.Flag("bullet", &S::bullet, "false", "blocks as bullets: time of impact between blocks too");
    t.Number("ground_depth", &S::ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(t.unbound());
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& Box2dSettingsSchema() {
  return Box2dTable().schema();
}

Box2dRun MakeBox2dRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  return MakeEngineRunInput(scene, motion, Box2dTable(), stop_at_rest_after_s);
}

}  // namespace rockbench::box2d_engine
