// Single precision through the helper program rockbench-bullet-float: it really runs Bullet in
// float, agrees with the in-process double engine to float accuracy, and failures are clear
// errors, never crashes.
#include "engines/bullet/float_helper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "engines/bullet/bullet_engine.h"
#include "run/engine_run.h"
#include "tests/common/housner_scene.h"

namespace rockbench::bullet {
namespace {

Scene Housner(BulletPrecision p) {
  Scene s = testing_util::HousnerHalfAngleRelease(2.0);
  SetEngineSetting(s, "bullet", "precision",
                   std::string(p == BulletPrecision::kFloat ? "float" : "double"));
  SetEngineSetting(s, "bullet", "split_impulse_threshold", 0.0);
  return s;
}

// Restores an environment variable when the test ends.
class EnvGuard {
 public:
  explicit EnvGuard(const char* name) : name_(name) {
    if (const char* v = std::getenv(name)) {
      had_ = true;
      old_ = v;
    }
  }
  ~EnvGuard() {
    if (had_) {
      setenv(name_, old_.c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  bool had_ = false;
  std::string old_;
};

TEST(FloatHelperTest, RunsBulletInSinglePrecisionCloseToDouble) {
  const BulletInput fin = MakeBulletInput(Housner(BulletPrecision::kFloat), GroundMotion());
  const EngineResult f = RunFloatHelper(fin);
  EXPECT_EQ(f.summary["settings"]["precision"], "float");
  EXPECT_EQ(f.summary["status"], "completed");
  EXPECT_GT(f.wall_s, 0.0);
  const BulletInput din = MakeBulletInput(Housner(BulletPrecision::kDouble), GroundMotion());
  const EngineResult d = Simulate(din);
  EXPECT_EQ(std::string(CompiledPrecision()), "double");
  ASSERT_EQ(f.history.samples.size(), d.history.samples.size());
  double worst = 0.0;
  for (size_t k = 0; k < d.history.samples.size(); ++k) {
    ASSERT_EQ(f.history.samples[k].t_s, d.history.samples[k].t_s);
    worst = std::max(
        worst, std::abs(f.history.samples[k].theta_rad[0] - d.history.samples[k].theta_rad[0]));
  }
  // Measured 5.7e-5 rad over 2 s at dt = 1e-4 (float rounding of ~1e-7 relative per step,
  // amplified at the impact); float is not double: the difference is not zero either.
  EXPECT_LT(worst, 2e-4);
  EXPECT_GT(worst, 1e-9);
  // Same impacts.
  ASSERT_EQ(f.history.events.size(), d.history.events.size());
  for (size_t k = 0; k < d.history.events.size(); ++k) {
    EXPECT_EQ(f.history.events[k].kind, d.history.events[k].kind);
    EXPECT_NEAR(f.history.events[k].t_s, d.history.events[k].t_s, 1e-3);
  }
}

TEST(FloatHelperTest, TheHarnessRoutesFloatScenesToTheHelper) {
  const EngineRun run = RunEngine("bullet", Housner(BulletPrecision::kFloat), GroundMotion());
  EXPECT_EQ(run.engine, "bullet");
  EXPECT_EQ(run.summary["settings"]["precision"], "float");
  EXPECT_NE(run.one_line.find("float"), std::string::npos) << run.one_line;
  const EngineRun dbl = RunEngine("bullet", Housner(BulletPrecision::kDouble), GroundMotion());
  EXPECT_EQ(dbl.summary["settings"]["precision"], "double");
}

TEST(FloatHelperTest, MissingHelperIsAClearError) {
  EnvGuard guard("ROCKBENCH_BULLET_FLOAT_HELPER");
  setenv("ROCKBENCH_BULLET_FLOAT_HELPER", "/nonexistent/rockbench-bullet-float", 1);
  try {
    RunEngine("bullet", Housner(BulletPrecision::kFloat), GroundMotion());
    ADD_FAILURE() << "ran without a helper";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/rockbench-bullet-float"), std::string::npos)
        << e.what();
  }
}

TEST(FloatHelperTest, HelperFailureIsAnErrorNotACrash) {
  // The helper refuses a double-precision input (it is the float engine): exit status 2.
  const BulletInput din = MakeBulletInput(Housner(BulletPrecision::kDouble), GroundMotion());
  try {
    RunFloatHelper(din);
    ADD_FAILURE() << "the float helper accepted a double input";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exit status 2"), std::string::npos) << e.what();
  }
  // And the in-process double engine refuses a float input.
  const BulletInput fin = MakeBulletInput(Housner(BulletPrecision::kFloat), GroundMotion());
  EXPECT_THROW(Simulate(fin), std::invalid_argument);
}

}  // namespace
}  // namespace rockbench::bullet
