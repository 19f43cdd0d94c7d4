// A made-up body kind carried from a scene file through an engine's run and its history file to
// the comparison (issue 39): the per-body record holds what a kind lists, so a kind beyond the
// planar block needs a registration, not a field in every result type.
#include "scene/body_kind.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "compare/agreement.h"
#include "compare/body_quantity.h"
#include "engine/engine.h"
#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "run/engine_run.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"
#include "tests/common/scratch_dir_test.h"

namespace rockbench {
namespace {

using testing_util::ErrorOf;

// The made-up kind: not a rocking body but a linear pendulum hanging from its top, so that its
// state is not (theta, omega): a swing angle (rad, compared) and its rate (rad/s). It reads its
// initial swing from [initial] theta.
const BodyKind& Pendulum() {
  static const BodyKind& kind = [] {
    RegisterBodyKind(
        {"test_pendulum", {{"swing", "rad", true}, {"swing_rate", "rad/s", false}}, {}, "omega"});
    return *FindBodyKind("test_pendulum");
  }();
  return kind;
}

// The exact small-oscillation solution of body k of a scene: phi0 cos(sqrt(g / L) t), L its
// height.
double ExactSwing(const Scene& scene, int body, double t_s) {
  const double w = std::sqrt(scene.run.gravity_mps2 / scene.blocks[body - 1].height_m);
  return scene.initial.theta_rad[body - 1] * std::cos(w * t_s);
}

// An engine of the made-up kind: each body swings independently, integrated by the
// semi-implicit (symplectic) Euler method at step_s; `length_factor` != 1 makes it wrong.
class PendulumEngine : public Engine {
 public:
  PendulumEngine(double step_s, double length_factor = 1.0)
      : step_s_(step_s), length_factor_(length_factor) {}
  std::string name() const override { return "test_pendulum_engine"; }
  std::string version() const override { return "test"; }
  const EngineSettingsSchema& settings_schema() const override {
    static const EngineSettingsSchema schema{"test_pendulum_engine", {}};
    return schema;
  }
  std::vector<SweepSetting> SweepGrid(bool) const override { return {}; }
  std::vector<SweepSetting> StressGrid() const override { return {}; }
  std::vector<std::string> body_shapes() const override { return {"test_pendulum"}; }
  EngineResult Simulate(const Scene& scene, const GroundMotion&,
                        const SimulateOptions&) const override {
    const int n = scene.block_count();
    const BodyKind& kind = *FindBodyKind(scene.blocks[0].shape);
    EngineResult r;
    r.history.blocks = n;
    r.history.shape = kind.shape;
    std::vector<double> phi(n), rate(n), w2(n);
    for (int k = 0; k < n; ++k) {
      phi[k] = scene.initial.theta_rad[k];
      w2[k] = scene.run.gravity_mps2 / (length_factor_ * scene.blocks[k].height_m);
    }
    const long steps_per_output = std::lround(scene.run.output_interval_s / step_s_);
    const long outputs = std::lround(scene.run.duration_s / scene.run.output_interval_s);
    for (long i = 0; i <= outputs; ++i) {
      Sample s(n, kind);
      s.t_s = static_cast<double>(i) * scene.run.output_interval_s;
      for (int k = 0; k < n; ++k) {
        s.state[0][k] = phi[k];
        s.state[1][k] = rate[k];
      }
      r.history.samples.push_back(std::move(s));
      for (long j = 0; j < steps_per_output; ++j) {
        for (int k = 0; k < n; ++k) {
          rate[k] -= w2[k] * phi[k] * step_s_;
          phi[k] += rate[k] * step_s_;
        }
      }
    }
    return r;
  }

 private:
  double step_s_, length_factor_;
};

const std::string kScene =
    "[[block]]\nshape = \"test_pendulum\"\nwidth = 0.2\nheight = 1.0\ndensity = 1000.0\n"
    "[[block]]\nshape = \"test_pendulum\"\nwidth = 0.2\nheight = 0.25\ndensity = 1000.0\n"
    "[initial]\ntheta = [0.1, -0.05]\n[run]\nduration = 4.0\noutput_interval = 0.01\n";

TEST(BodyKind, ColumnsAreNamedOnceAndKindsAreChecked) {
  EXPECT_EQ(BodyColumn("theta", 3), "theta3");
  EXPECT_EQ(BodyColumn("tilt_x", 1), "tilt_x1");
  EXPECT_EQ(PlanarBlockKind().shape, "block");
  Pendulum();
  EXPECT_EQ(ErrorOf([] {
              RegisterBodyKind({"test_pendulum", {{"a", "rad", true}}, {}, "omega"});
            }),
            "body kind 'test_pendulum' is already registered");
  EXPECT_EQ(ErrorOf([] {
              RegisterBodyKind({"twice", {{"a", "rad"}, {"a", "rad"}}, {}, "omega"});
            }),
            "body kind 'twice' names 'a' twice");
  // The scene names the kind by the [[block]] table's shape, one kind a stack.
  EXPECT_EQ(ErrorOf([] {
              ParseScene(
                  "[[block]]\nshape = \"sphere\"\nwidth = 1\nheight = 1\n"
                  "density = 1\n",
                  "x.toml");
            }),
            "x.toml:2: block1.shape: expected a body kind (\"block\", \"cylinder\", \"test_pendulum\"), got "
            "\"sphere\"");
  EXPECT_NE(ErrorOf([] {
              ParseScene(
                  "[[block]]\nwidth = 1\nheight = 1\ndensity = 1\n"
                  "[[block]]\nshape = \"test_pendulum\"\nwidth = 1\n"
                  "height = 1\ndensity = 1\n",
                  "x.toml");
            }).find("block2.shape: every body of a stack is of one kind"),
            std::string::npos);
}

class MadeUpBody : public testing_util::ScratchDirTest {};

// From the scene file to the comparison: the kind's quantities are the history's columns, read
// back from its file, and compared under their own names.
TEST_F(MadeUpBody, IsCarriedFromTheSceneToTheComparison) {
  Pendulum();
  const Scene scene = LoadScene(Write("pendulum.toml", kScene));
  ASSERT_EQ(scene.block_count(), 2);
  EXPECT_EQ(scene.blocks[1].shape, "test_pendulum");
  const GroundMotion motion = GroundMotion::FromScene(scene);
  // An engine builds the kinds it says; the planar engines and the reference refuse it.
  const PendulumEngine engine(1e-3);
  EXPECT_EQ(ErrorOf([&] { CheckBuildsBodies(engine, scene); }), "no error");
  EXPECT_EQ(ErrorOf([&] { RunEngine("reference", scene, motion); }),
            (dir_ / "pendulum.toml").string() +
                ": block1.shape: the engine 'reference' builds bodies of shape \"block\", \"cylinder\", not "
                "\"test_pendulum\"");
  const EngineResult run = engine.Simulate(scene, motion, {});

  // The history file: the kind's columns, every body's, and back.
  const std::string csv = HistoryToCsv(run.history);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,swing1,swing2,swing_rate1,swing_rate2,mode");
  WriteFileAtomic(dir_ / "history.csv", csv);
  const History read = ReadHistoryCsv(dir_ / "history.csv");
  EXPECT_EQ(read.shape, "test_pendulum");
  ASSERT_EQ(read.samples.size(), run.history.samples.size());
  EXPECT_EQ(HistoryToCsv(read), csv);

  // The comparison against the closed form, per body, under the kind's name. The semi-implicit
  // Euler solution from rest is phi0 (cos(n theta) - (h / 2) sin(n theta)) + O(h^2), h = w dt,
  // cos(theta) = 1 - h^2 / 2, theta = h (1 + h^2 / 24 + ...): its error is at most
  // phi0 (h / 2 + w T h^2 / 24) to first order; 10% above it covers the next order.
  const double T = scene.run.duration_s, dt = 1e-3, tolerance_rad = 1e-3;
  EngineAgreement agreement;
  agreement.engine = "test_pendulum_engine";
  for (int k = 1; k <= 2; ++k) {
    BodyAgreement body;
    body.angle = CompareBodyQuantity(
        read, "swing", k, [&](double t) { return ExactSwing(scene, k, t); }, tolerance_rad, T);
    const double w = std::sqrt(scene.run.gravity_mps2 / scene.blocks[k - 1].height_m);
    const double h = w * dt, phi0 = std::abs(scene.initial.theta_rad[k - 1]);
    EXPECT_LT(body.angle.max_abs_error_rad, 1.1 * phi0 * (h / 2 + w * T * h * h / 24)) << k;
    // It is that error, not less than half of it: the comparison sees the method's error.
    EXPECT_GT(body.angle.max_abs_error_rad, 0.5 * phi0 * h / 2) << k;
    EXPECT_TRUE(body.angle.within_tolerance) << k;
    EXPECT_EQ(body.angle.horizon_s, T) << k;
    agreement.bodies.push_back(body);
  }
  const nlohmann::json json = AgreementJson(agreement);
  EXPECT_TRUE(json.contains("swing1")) << json.dump();
  EXPECT_TRUE(json.contains("swing2")) << json.dump();
  EXPECT_FALSE(json.contains("theta1")) << json.dump();
}

// The comparison of the made-up quantity converges at the method's order and catches a wrong
// engine: halving the step halves the error (the O(h) amplitude term dominates, to within the
// h^2 phase term: a ratio within 10% of 2); a pendulum 1% too long leaves the tolerance.
TEST_F(MadeUpBody, ItsComparisonSeesConvergenceAndAWrongEngine) {
  Pendulum();
  const Scene scene = LoadScene(Write("pendulum.toml", kScene));
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const auto error = [&](const PendulumEngine& engine, double tolerance_rad) {
    const History h = engine.Simulate(scene, motion, {}).history;
    return CompareBodyQuantity(
        h, "swing", 1, [&](double t) { return ExactSwing(scene, 1, t); }, tolerance_rad,
        scene.run.duration_s);
  };
  const double coarse = error(PendulumEngine(1e-3), 1e-3).max_abs_error_rad;
  const double fine = error(PendulumEngine(5e-4), 1e-3).max_abs_error_rad;
  EXPECT_NEAR(coarse / fine, 2.0, 0.2);
  // 1% longer: the phase drifts by w T / 200 = 0.063 rad in 4 s, an error of 0.0063 rad.
  const AngleAgreement wrong = error(PendulumEngine(1e-3, 1.01), 1e-3);
  EXPECT_FALSE(wrong.within_tolerance);
  EXPECT_LT(wrong.horizon_s, scene.run.duration_s);
  EXPECT_GT(wrong.max_abs_error_rad, 4e-3);
}

}  // namespace
}  // namespace rockbench
