#include "scene/scene.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include "scene/body_kind.h"
#include "scene/limits.h"
#include "scene/scene_rules.h"

namespace rockbench {

using namespace scene_rules;  // NOLINT: the rules are this file's vocabulary

void RequireAtMostTwoBlocks(const Scene& scene, std::string_view who) {
  const int n = scene.block_count();
  if (n <= 2) return;
  throw SceneError(FileLabel(scene.path) + ": " + std::string(who) + ": N-block scenes (" +
                   std::to_string(n) + " blocks) are not simulated yet (issue 23); 1 or 2 blocks");
}

void RequirePlanarBodies(const Scene& scene, std::string_view who) {
  if (!scene.three_dimensional()) return;
  throw SceneError(FileLabel(scene.path) + ": block1.shape: " + std::string(who) +
                   " takes planar blocks only so far; a cylinder (a body rocking in 3-D) is run "
                   "by `rockbench run SCENE -e reference -e ENGINE`, which writes both histories "
                   "(docs/three-d.md)");
}

bool IsAt2File(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".at2";
}

SyntheticMotionDef MotionDef::SyntheticProcess() const {
  SyntheticMotionDef d = synthetic;
  d.target_peak_mps2 = amplitude_g * kStandardGravity_mps2;
  return d;
}

std::optional<Formulation> ParseFormulation(std::string_view text) {
  if (text == "thesis") return Formulation::kThesis;
  if (text == "chain") return Formulation::kChain;
  if (text == "unilateral") return Formulation::kUnilateral;
  return std::nullopt;
}

const char* IntegratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::kDopri5:
      return "dopri5";
    case Integrator::kDop853:
      return "dop853";
    case Integrator::kRk4:
      return "rk4";
  }
  return "rk4";
}

std::string_view MotionKindName(MotionKind kind) {
  switch (kind) {
    case MotionKind::kFile:
      return "file";
    case MotionKind::kHarmonic:
      return "harmonic";
    case MotionKind::kSinePulse:
      return "sine_pulse";
    case MotionKind::kCosinePulse:
      return "cosine_pulse";
    case MotionKind::kRectangularPulse:
      return "rectangular_pulse";
    case MotionKind::kRicker:
      return "ricker";
    case MotionKind::kKanaiTajimi:
      return "kanai_tajimi";
  }
  return "file";
}

std::string_view AccelUnitsName(AccelUnits units) {
  switch (units) {
    case AccelUnits::kG:
      return "g";
    case AccelUnits::kMps2:
      return "m/s2";
    case AccelUnits::kCmps2:
      return "cm/s2";
  }
  return "g";
}

double AccelUnitsToMps2(AccelUnits units) {
  switch (units) {
    case AccelUnits::kG:
      return kStandardGravity_mps2;
    case AccelUnits::kMps2:
      return 1.0;
    case AccelUnits::kCmps2:
      return 0.01;
  }
  return 1.0;
}

double BodyVolume_m3(const BlockDef& body) {
  if (body.shape == kCylinderShape) {
    return 0.25 * std::numbers::pi * body.diameter_m * body.diameter_m * body.height_m;
  }
  return body.width_m * body.height_m * body.depth_m;
}

bool Scene::three_dimensional() const {
  return !blocks.empty() && blocks[0].shape == kCylinderShape;
}

bool Scene::has_finite_friction() const {
  for (const BlockDef& b : blocks) {
    if (std::isfinite(b.friction)) return true;
  }
  return false;
}

std::string ShortestText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

std::string SampleAccelProblem(const MotionDef& def, AccelUnits units, double value) {
  const double a_mps2 = value * (AccelUnitsToMps2(units) * def.scale);
  if (std::abs(a_mps2) <= limits::kMaxAccel_g * kStandardGravity_mps2) return "";
  const std::string scaled =
      def.scale != 1.0 ? " times " + def.key + ".scale = " + ShortestText(def.scale) : "";
  const bool same = def.scale == 1.0 && units == AccelUnits::kG;
  return " = " + ShortestText(value) + " " + std::string(AccelUnitsName(units)) + scaled +
         (same ? "" : " is " + GText(a_mps2 / kStandardGravity_mps2) + " g") +
         "; expected an acceleration with magnitude at most " + ShortestText(limits::kMaxAccel_g) +
         " g (far above any recorded ground motion, about 4 g; docs/limits.md)";
}

namespace {

// The checks of ValidateScene, one group of keys a method, in the order a reader meets them;
// each throws SceneError naming the file and the key.
class Validator {
 public:
  explicit Validator(const Scene& scene)
      : scene_(scene), file_(FileLabel(scene.path)), n_(scene.block_count()) {}

  // The blocks: how many, each one's size, mass and friction, each narrower than the one below.
  void Blocks() const {
    const Scene& scene = scene_;
    const int n = n_;
    if (n == 0) fail("block1", "missing (the scene has no blocks; the lower block is required)");
    if (n > kMaxBlocks) {
      fail("block" + std::to_string(kMaxBlocks + 1),
           "expected at most " + std::to_string(kMaxBlocks) +
               " blocks (the most a stack may have), got " + std::to_string(n));
    }
    for (int k = 1; k <= n; ++k) block(scene.blocks[k - 1], "block" + std::to_string(k));
    // One kind of body, a registered one (scene/body_kind.h).
    for (int k = 1; k <= n; ++k) {
      const std::string& shape = scene.blocks[k - 1].shape;
      if (FindBodyKind(shape) == nullptr || shape != scene.blocks[0].shape) {
        fail("block" + std::to_string(k) + ".shape",
             "expected a registered body kind, the same for every body (block1's is \"" +
                 Excerpt(scene.blocks[0].shape) + "\"), got \"" + Excerpt(shape) + "\"");
      }
    }
    if (scene.three_dimensional()) Cylinder();
    for (int k = 2; k <= n; ++k) {
      if (scene.blocks[k - 1].width_m > scene.blocks[k - 2].width_m) {
        fail("block" + std::to_string(k) + ".width", WiderThanBelow(scene, k));
      }
    }
  }

  // A cylinder: one body, its diameter its width and depth; its initial state in its own keys,
  // the tilt >= 0 and below the overturn angle; no transverse motion for a planar scene.
  void Cylinder() const {
    const BlockDef& b = scene_.blocks[0];
    if (n_ != 1) {
      fail("block2", "a cylinder stands alone: the 3-D model is one cylinder on its base, got " +
                         std::to_string(n_) + " bodies");
    }
    limit("block1.diameter", b.diameter_m, kLengthLimit, Rule::kPositive, "m");
    if (b.width_m != b.diameter_m || b.depth_m != b.diameter_m) {
      fail("block1.diameter", "a cylinder's width and depth are its diameter (" +
                                  ShortestText(b.diameter_m) + " m), got " +
                                  ShortestText(b.width_m) + " and " + ShortestText(b.depth_m));
    }
    const InitialState& in = scene_.initial;
    if (in.theta_rad[0] != 0.0 || in.omega_radps[0] != 0.0) {
      fail("initial.theta1", "not used by a cylinder (its state: tilt, azimuth and their rates)");
    }
    const double tilt = in.tilt_rad[0];
    if (!(tilt >= 0.0 && tilt < scene_.model.overturn_rad)) {
      fail("initial.tilt", "expected a tilt >= 0 and below model.overturn_angle (" +
                               ShortestText(scene_.model.overturn_rad) + " rad), got " +
                               ShortestText(tilt));
    }
    check("initial.azimuth", in.azimuth_rad[0], Rule::kFinite, "rad");
    limit("initial.tilt_rate", in.tilt_rate_radps[0], kRateLimit, Rule::kFinite, "rad/s");
    limit("initial.azimuth_rate", in.azimuth_rate_radps[0], kRateLimit, Rule::kFinite, "rad/s");
    limit("initial.spin_rate", in.spin_rate_radps[0], kRateLimit, Rule::kFinite, "rad/s");
  }

  // The initial angles are finite and the rates within their limit.
  void InitialRates() const {
    const int n = n_;
    const InitialState& in = scene_.initial;
    if (!scene_.three_dimensional()) {
      for (int k = 1; k <= kMaxBlocks; ++k) {
        if (in.tilt_rad[k - 1] != 0.0 || in.azimuth_rad[k - 1] != 0.0 ||
            in.tilt_rate_radps[k - 1] != 0.0 || in.azimuth_rate_radps[k - 1] != 0.0 ||
            in.spin_rate_radps[k - 1] != 0.0) {
          fail("initial.tilt", "only for a cylinder (shape = \"cylinder\"); a block's state is "
                               "theta and omega");
        }
      }
    }
    for (int k = 1; k <= n; ++k) {
      const std::string i = std::to_string(k);
      check("initial.theta" + i, in.theta_rad[k - 1], Rule::kFinite, "rad");
      limit("initial.omega" + i, in.omega_radps[k - 1], kRateLimit, Rule::kFinite, "rad/s");
    }
  }

  // The model's overturn angle and formulation, and what each formulation takes.
  void Model() const {
    const Scene& scene = scene_;
    const int n = n_;
    limit("model.overturn_angle", scene.model.overturn_rad, kOverturnLimit, Rule::kPositive, "rad");
    if (scene.model.formulation == Formulation::kThesis && n > 2) {
      fail("model.formulation",
           "\"thesis\" is the thesis's equations of one or two blocks; this "
           "scene has " +
               std::to_string(n) + " (use \"chain\", or leave the key out)");
    }
    // Sliding and lift-off: the unilateral model's reach (docs/sliding.md).
    for (int k = 1; k <= n; ++k) {
      if (std::isfinite(scene.blocks[k - 1].friction) && n > kUnilateralMaxBlocks) {
        fail("block" + std::to_string(k) + ".friction",
             "a finite friction needs the unilateral model (sliding), which takes at most " +
                 std::to_string(kUnilateralMaxBlocks) + " blocks; this stack has " +
                 std::to_string(n) + " (leave the key out: no sliding)");
      }
    }
    if (scene.model.formulation == Formulation::kUnilateral) {
      if (n > kUnilateralMaxBlocks) {
        fail("model.formulation", "\"unilateral\" takes at most " +
                                      std::to_string(kUnilateralMaxBlocks) +
                                      " blocks; this stack has " + std::to_string(n));
      }
      if (scene.model.equations == Equations::kLinearized) {
        fail("model.equations",
             "the unilateral model solves the nonlinear equations (use \"nonlinear\")");
      }
      if (scene.model.events == EventScheme::kThesis) {
        fail("model.events", "the unilateral model locates its events (use \"located\")");
      }
    }
    if (scene.model.equations == Equations::kLinearized &&
        (n > 2 || scene.model.formulation == Formulation::kChain)) {
      fail("model.equations",
           "\"linearized\" is the thesis's linearization of its equations of "
           "one or two blocks (section 4.3.3); the N-block chain solves the "
           "nonlinear ones (use \"nonlinear\")");
    }
  }

  // The initial angles below the overturn angle; no entry for a block the scene does not have.
  void InitialAngles() const {
    const Scene& scene = scene_;
    const int n = n_;
    const InitialState& in = scene.initial;
    for (int k = 1; k <= n; ++k) {
      const std::string name = "theta" + std::to_string(k);
      const double v = in.theta_rad[k - 1];
      if (!(std::abs(v) < scene.model.overturn_rad)) {
        fail("initial." + name, "expected |" + name + "| below model.overturn_angle (" +
                                    ShortestText(scene.model.overturn_rad) +
                                    " rad; the block would have overturned), got " +
                                    ShortestText(v));
      }
    }
    // The entries of blocks the scene does not have.
    for (int k = n + 1; k <= kMaxBlocks; ++k) {
      if (in.theta_rad[k - 1] == 0.0 && in.omega_radps[k - 1] == 0.0) continue;
      const std::string i = std::to_string(k);
      if (n == 1 && k == 2) {
        fail("initial.theta2",
             "must be 0 with omega2 in a single-block scene (there is no block2)");
      }
      fail(in.theta_rad[k - 1] != 0.0 ? "initial.theta" + i : "initial.omega" + i,
           "must be 0: the scene has " + std::to_string(n) + (n == 1 ? " block" : " blocks") +
               " (no block " + i + ")");
    }
  }

  // One base-motion component: its scale and start, and the keys of its kind.
  void Motion(const MotionDef& d) const {
    const std::string p = d.key.empty() ? std::string("base") : d.key;
    check(p + ".scale", d.scale, Rule::kFinite, "");
    check(p + ".phase_deg", d.phase_deg, Rule::kFinite, "degrees");
    if (d.phase_deg != 0.0 && d.kind != MotionKind::kHarmonic) {
      fail(p + ".phase_deg", "only for kind = \"harmonic\"");
    }
    limit(p + ".start_s", d.start_s, kDurationLimit, Rule::kNonNegative, "s");
    if (d.kind != MotionKind::kFile && !d.samples.empty()) {
      fail(p, "give one of file, kind or samples, not several (kind = \"" +
                  std::string(MotionKindName(d.kind)) + "\" and samples)");
    }
    if (d.samples_resolution && d.samples.empty()) {
      fail(p + ".resolution", "only for samples = [...]");
    }
    if (d.kind == MotionKind::kFile && !d.samples.empty()) {
      Samples(d, p);
      return;
    }
    if (d.kind == MotionKind::kFile) {
      if (d.file.empty()) fail(p + ".file", "expected a file path");
      if (const std::string problem = InputFileProblem(d.file, "record file"); !problem.empty()) {
        fail(p + ".file", problem);
      }
      const bool at2 = IsAt2File(d.file);
      if (!at2 && !d.units_given) {
        fail(p + ".units",
             "missing; a plain record file must state its units: " + ChoiceList(kUnits));
      }
      if (at2 && d.dt_s != 0.0) fail(p + ".dt", "not allowed for an AT2 file");
      if (!at2) check(p + ".dt", d.dt_s, Rule::kNonNegative, "s");
      return;
    }
    if (d.kind == MotionKind::kKanaiTajimi) {
      limit(p + ".amplitude_g", d.amplitude_g, kAccelLimit, Rule::kNonNegative, "g");
      limit(p + ".duration_s", d.synthetic.duration_s, kDurationLimit, Rule::kPositive, "s");
      const std::string problem = SyntheticMotionProblem(d.SyntheticProcess());
      if (!problem.empty()) fail(p, problem);
      return;
    }
    limit(p + ".amplitude_g", d.amplitude_g, kAccelLimit, Rule::kFinite, "g");
    if (!Within(d.amplitude_g * d.scale, kAccelLimit)) {
      fail(p + ".scale", "amplitude_g * scale = " + GText(d.amplitude_g * d.scale) +
                             " g; expected an acceleration (g)" + LimitText(kAccelLimit));
    }
    if (d.kind != MotionKind::kRectangularPulse) {
      limit(p + ".frequency_hz", d.frequency_hz, kFrequencyLimit, Rule::kPositive, "Hz");
    }
    if (d.kind == MotionKind::kRectangularPulse) {
      limit(p + ".duration_s", d.duration_s, kDurationLimit, Rule::kPositive, "s");
    } else if (d.kind == MotionKind::kHarmonic &&
               d.duration_s != std::numeric_limits<double>::infinity()) {
      // A harmonic lasts duration_s, or forever (+inf, the default).
      limit(p + ".duration_s", d.duration_s, kDurationLimit, Rule::kPositive, "s");
    }
  }

  // A record given by its samples: no file, at least two finite samples within the acceleration
  // limit, their units and interval, at most a day long.
  void Samples(const MotionDef& d, const std::string& p) const {
    if (!d.file.empty())
      fail(p, "give one of file, kind or samples, not several (file and samples)");
    const size_t n = d.samples.size();
    if (n < 2) {
      fail(p + ".samples",
           "expected at least 2 samples (a record lasts from its first sample to "
           "its last), got " +
               std::to_string(n));
    }
    if (!d.units_given) {
      fail(p + ".units", "missing; samples must state their units: " + ChoiceList(kUnits));
    }
    if (d.dt_s == 0.0) fail(p + ".dt", "missing; samples need their sample interval dt (s)");
    if (d.samples_resolution) {
      check(p + ".resolution", *d.samples_resolution, Rule::kNonNegative, "in the samples' units");
    }
    limit(p + ".dt", d.dt_s, kSampleIntervalLimit, Rule::kPositive, "s");
    for (size_t i = 0; i < n; ++i) {
      const std::string key = p + ".samples[" + std::to_string(i) + "]";
      check(key, d.samples[i], Rule::kFinite, "");
      if (const std::string problem = SampleAccelProblem(d, d.units, d.samples[i]);
          !problem.empty()) {
        throw SceneError(file_ + ": " + key + problem);
      }
    }
    if (static_cast<double>(n - 1) * d.dt_s > limits::kMaxDuration_s) {
      fail(p + ".samples", std::to_string(n) + " samples at dt = " + ShortestText(d.dt_s) +
                               " s last more than a day (" + ShortestText(limits::kMaxDuration_s) +
                               " s; docs/limits.md)");
    }
  }

  // The run's duration, output interval and gravity; the model's tolerances; the comparison's
  // settings.
  void RunAndCompare() const {
    const Scene& scene = scene_;
    limit("run.duration", scene.run.duration_s, kDurationLimit, Rule::kPositive, "s");
    check("run.output_interval", scene.run.output_interval_s, Rule::kPositive, "s");
    limit("run.gravity", scene.run.gravity_mps2, kGravityLimit, Rule::kPositive, "m/s^2");
    if (scene.run.output_interval_s > scene.run.duration_s) {
      fail("run.output_interval", "must not exceed run.duration (" +
                                      ShortestText(scene.run.duration_s) + " s), got " +
                                      ShortestText(scene.run.output_interval_s));
    }
    const ModelConfig& m = scene.model;
    limit("model.rtol", m.rtol, kRtolLimit, Rule::kPositive, "");
    limit("model.atol", m.atol, kAtolLimit, Rule::kPositive, "rad, rad/s");
    check("model.step", m.step_s, Rule::kPositive, "s");
    check("model.rest_rate_rel", m.rest_rate_rel, Rule::kNonNegative, "");
    check("model.landing_clearance_rel", m.landing_clearance_rel, Rule::kNonNegative, "");
    if (m.landing_clearance_rel > 0.5) {
      fail("model.landing_clearance_rel",
           "expected a clearance relative to the diameter from 0 to 0.5, got " +
               ShortestText(m.landing_clearance_rel));
    }
    const CompareConfig& c = scene.compare;
    if (c.tolerance_rad) {
      limit("compare.tolerance", *c.tolerance_rad, kToleranceLimit, Rule::kPositive, "rad");
    }
    if (c.members < 0) fail("compare.members", "expected a non-negative integer");
    if (c.engine_members < 0) fail("compare.engine_members", "expected a non-negative integer");
    check("compare.amplitude_rel", c.amplitude_rel, Rule::kUnitInterval, "");
    limit("compare.sample_precision", c.sample_precision, kSamplePrecisionLimit, Rule::kNonNegative,
          "");
    check("compare.initial_rel", c.initial_rel, Rule::kUnitInterval, "");
  }

 private:
  void check(const std::string& key, double v, Rule rule, std::string_view unit) const {
    if (!Satisfies(v, rule)) {
      throw SceneError(file_ + ": " + key + ": expected " + Expectation(rule, unit) + ", got " +
                       ShortestText(v));
    }
  }
  [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
    throw SceneError(file_ + ": " + key + ": " + msg);
  }
  void limit(const std::string& key, double v, const Limit& lim, Rule rule,
             std::string_view unit) const {
    check(key, v, rule, unit);
    if (!Within(v, lim)) {
      throw SceneError(file_ + ": " + key + ": expected " + Expectation(rule, unit) +
                       LimitText(lim) + ", got " + ShortestText(v));
    }
  }
  void block(const BlockDef& b, const std::string& p) const {
    limit(p + ".width", b.width_m, kLengthLimit, Rule::kPositive, "m");
    limit(p + ".height", b.height_m, kLengthLimit, Rule::kPositive, "m");
    limit(p + ".depth", b.depth_m, kLengthLimit, Rule::kPositive, "m");
    limit(p + ".mass", b.mass_kg, kMassLimit, Rule::kPositive, "kg");
    check(p + ".density", b.density_kgpm3, Rule::kNonNegative, "kg/m^3");
    check(p + ".friction", b.friction, Rule::kNonNegativeOrInfinite, "");
    if (std::isfinite(b.friction) && b.friction > kMaxFiniteFriction) {
      fail(p + ".friction",
           std::string("expected ") + kFrictionRange + ", got " + ShortestText(b.friction));
    }
    if (b.density_kgpm3 != 0.0) {
      limit(p + ".density", b.density_kgpm3, kDensityLimit, Rule::kPositive, "kg/m^3");
    }
  }

  const Scene& scene_;
  const std::string file_;
  const int n_;
};

}  // namespace

void ValidateScene(const Scene& scene) {
  const Validator v(scene);
  v.Blocks();
  v.InitialRates();
  v.Model();
  v.InitialAngles();
  if (scene.transverse && !scene.three_dimensional()) {
    throw SceneError(FileLabel(scene.path) +
                     ": base.transverse: only for bodies rocking in 3-D (shape = \"cylinder\")");
  }
  for (const auto* m : {&scene.horizontal, &scene.transverse, &scene.vertical}) {
    if (*m) v.Motion(**m);
  }
  v.RunAndCompare();
}

}  // namespace rockbench
