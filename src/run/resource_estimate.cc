#include "run/resource_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <system_error>
#include <variant>

#include "engines/external/external_engine.h"
#include "engines/external/protocol.h"
#include "run/engine_registry.h"
#include "scene/engine_settings.h"

namespace rockbench {
namespace {

// Measured on the release build (docs/limits.md, "Estimates"): peak bytes per unit of each
// term, rounded up.
// A history row of any run: its Sample (48 B), its CSV text (about 110 B) and the comparison's
// copies: 220 B measured with 2e6 rows.
constexpr double kRowBytes = 256.0;
// One reference step: a Trajectory segment (about 300 B) and its vector's growth: 400 B
// measured with 2e6 rk4 steps.
constexpr double kReferenceStepBytes = 600.0;
// One engine step: the drive's samples (two doubles) and slack: 17 to 19 B measured.
constexpr double kEngineStepBytes = 32.0;
// A record file: its text, its lines and its samples: 8 B per byte of file.
constexpr double kRecordBytesPerFileByte = 8.0;
// A synthetic motion: the generator's work arrays (38 B per sample measured) and copies.
constexpr double kSyntheticSampleBytes = 128.0;
// CPU time per step: the reference's (2.3 us measured for rk4 with dense output, more for
// dopri5 with event location) and an engine's (25 us measured for Bullet with two blocks).
constexpr double kReferenceStepCpu_s = 5e-6;
constexpr double kEngineStepCpu_s = 30e-6;
// An external engine's step in rockbench's own process: the drive's samples, its input file's
// JSON nodes and text: 100 B measured (peak RSS 2.55 GB with 2.5e7 steps of a harmonic base
// motion, 2026-11-28).
constexpr double kExternalStepBytes = 128.0;
// An engine's CPU time per step: its two-block figure (kEngineStepCpu_s unless measured higher),
// growing with the blocks n as (n / 2)^p1 up to 8 blocks, then by (n / 8)^p2. Measured on a
// stack of 0.5 m cubes under a 0.05 g harmonic base motion at 2, 8 and 32 blocks (CPU time of
// 2000 steps at 1e-4 s, 2026-11-28; docs/limits.md), slopes rounded up, at least 1:
//   Bullet 1.11, 1.11; MuJoCo 1.11, 1.65; ODE world_step 1.70, 3.49 (its dense LCP);
//   ODE quick_step 0.95, 1.11 (48 to 55 us per two-block step: 80 us); DART 1.65, 2.37;
//   Siconos 2.54 (40 us; at 32 blocks its stack fell apart at once: the first slope for both);
//   Box2D 0.37, 0.79; Rapier 1.10, 1.26 (its Node start-up taken out).
// Checked at 64 blocks: ODE world_step 187 ms per step (estimated 528), quick_step 2.0 ms (3.9),
// Bullet 0.63 ms (1.9).
struct BlockScaling {
  const char* engine;
  double to_8, beyond_8;
  double step_cpu_s = kEngineStepCpu_s;
};
constexpr BlockScaling kBlockScaling[] = {
    {"bullet", 1.2, 1.2},         {"mujoco", 1.2, 1.7}, {"ode", 1.8, 3.5},   {"dart", 1.7, 2.4},
    {"siconos", 2.6, 2.6, 45e-6}, {"box2d", 1.0, 1.0},  {"rapier", 1.2, 1.3}};
// ODE's iterative stepper (ode.stepper = "quick_step").
constexpr BlockScaling kOdeQuickStep = {"ode", 1.0, 1.2, 80e-6};
// An engine not measured (an external one): the steepest slopes measured, an upper bound; its
// run is killed at its wall_limit_s all the same, which bounds the estimate of each run.
constexpr BlockScaling kUnmeasured = {"", 2.6, 3.5};
// The reference's largest step (reference/simulate.cc: kMaxStepRel, kMaxStepMotion): 0.05
// sqrt(R / g) and 1/16 of the motion's period. R of block 1 alone is at most the stack's, so
// the step count is an upper bound.
constexpr double kMaxStepRel = 0.05;
constexpr double kMaxStepMotion = 1.0 / 16.0;

std::string Count(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", n);
  return buf;
}

std::string Duration(double s) {
  char buf[48];
  if (!std::isfinite(s)) return "an unbounded time";
  if (s >= 3600.0) {
    std::snprintf(buf, sizeof buf, "%.3g h", s / 3600.0);
  } else if (s >= 60.0) {
    std::snprintf(buf, sizeof buf, "%.3g min", s / 60.0);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g s", s);
  }
  return buf;
}

// Samples of a base-motion component, and the key that sets their number.
struct MotionSize {
  double samples = 0.0, bytes = 0.0;
  std::string key, what;
};

MotionSize SizeOf(const MotionDef& m) {
  MotionSize size;
  if (m.from_samples()) {
    // Given in the scene: its samples are already in memory once (the scene's copy).
    size.samples = static_cast<double>(m.samples.size());
    size.bytes = size.samples * kSyntheticSampleBytes;
    size.key = m.key + ".samples";
    size.what = Count(size.samples) + " samples given in the scene";
  } else if (m.kind == MotionKind::kFile) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(m.file, ec);
    const double b = ec ? 0.0 : static_cast<double>(bytes);
    size.bytes = b * kRecordBytesPerFileByte;
    // Every value takes at least two bytes.
    size.samples = b / 2.0;
    size.key = m.key + ".file";
    size.what = "a record file of " + ByteText(b);
  } else if (m.kind == MotionKind::kKanaiTajimi) {
    size.samples = std::ceil(m.synthetic.duration_s / m.synthetic.dt_s) + 1.0;
    size.bytes = size.samples * kSyntheticSampleBytes;
    size.key = m.key + ".dt";
    size.what = Count(size.samples) + " synthetic samples (duration_s / dt)";
  }
  return size;
}

// The shortest period of the analytic components (s), +inf for none.
double ShortestPeriod(const Scene& scene) {
  double period = std::numeric_limits<double>::infinity();
  for (const auto* m : {&scene.horizontal, &scene.vertical}) {
    if (!*m) continue;
    const MotionKind k = (*m)->kind;
    if (k == MotionKind::kHarmonic || k == MotionKind::kSinePulse ||
        k == MotionKind::kCosinePulse || k == MotionKind::kRicker) {
      period = std::min(period, 1.0 / (*m)->frequency_hz);
    }
  }
  return period;
}

// An engine's CPU time per step with `blocks` blocks, s.
double StepCpu_s(const std::string& name, const EngineSettings& settings, int blocks) {
  BlockScaling p = kUnmeasured;
  for (const BlockScaling& b : kBlockScaling) {
    if (name == b.engine) p = b;
  }
  if (name == "ode" && settings.Choice("stepper") == "quick_step") p = kOdeQuickStep;
  const double n = blocks;
  return p.step_cpu_s * std::pow(std::clamp(n / 2.0, 1.0, 4.0), p.to_8) *
         std::pow(std::max(1.0, n / 8.0), p.beyond_8);
}

}  // namespace

const EstimateTerm* RunEstimate::largest_bytes() const {
  const EstimateTerm* best = nullptr;
  for (const EstimateTerm& t : terms) {
    if (best == nullptr || t.bytes > best->bytes) best = &t;
  }
  return best;
}

const EstimateTerm* RunEstimate::largest_cpu() const {
  const EstimateTerm* best = nullptr;
  for (const EstimateTerm& t : terms) {
    if (best == nullptr || t.cpu_s > best->cpu_s) best = &t;
  }
  return best;
}

namespace {

// The engines of `names` that step on a fixed step of their table (a `time_step` key: the
// physics engines), each once. The reference has no such table: it is always run, and counted
// by its own term (ReferenceTerm).
std::vector<std::string> SteppedEngines(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const std::string& name : names) {
    const Engine* engine = FindEngine(name);
    if (engine == nullptr || std::find(out.begin(), out.end(), name) != out.end()) continue;
    const auto& defs = engine->settings_schema().settings;
    if (std::any_of(defs.begin(), defs.end(),
                    [](const SettingDef& d) { return d.key == "time_step"; })) {
      out.push_back(name);
    }
  }
  return out;
}

// The base motion's terms, read once (members perturb copies: one per concurrent member), into
// `e`; returns the record samples inside the run (each a step boundary of the reference).
double AddMotionTerms(const Scene& scene, double concurrent_ref, RunEstimate& e) {
  double record_breakpoints = 0.0;
  for (const auto* m : {&scene.horizontal, &scene.vertical}) {
    if (!*m) continue;
    const MotionSize size = SizeOf(**m);
    if (size.bytes <= 0.0) continue;
    e.terms.push_back({size.key, size.what, size.bytes * (1.0 + concurrent_ref), 0.0});
    record_breakpoints = std::max(record_breakpoints, size.samples);
  }
  return record_breakpoints;
}

// The reference's steps: rk4's fixed step, or at least one per largest step and per record
// sample inside the run; its nominal run, its convergence witness and `members` members
// (`concurrent_ref` of them held at once).
EstimateTerm ReferenceTerm(const Scene& scene, int members, double concurrent_ref,
                           double record_breakpoints) {
  const double duration = scene.run.duration_s;
  double ref_steps = 0.0;
  // The convergence witness (run/reference_witness.h, WitnessModel) takes 10 times the steps of
  // the thesis's event scheme, 4 times rk4's, and about as many as dopri5's or dop853's.
  double witness = 1.0;
  std::string ref_key, ref_what;
  if (scene.model.events == EventScheme::kThesis) witness = 10.0;
  if (scene.model.integrator == Integrator::kRk4) {
    if (scene.model.events != EventScheme::kThesis) witness = 4.0;
    ref_steps = std::ceil(duration / scene.model.step_s);
    ref_key = "model.step";
    ref_what = Count(ref_steps) + " rk4 steps (run.duration / model.step)";
  } else {
    const double r1 = 0.5 * std::hypot(scene.blocks.at(0).width_m, scene.blocks.at(0).height_m);
    const double max_step = std::min(kMaxStepRel * std::sqrt(r1 / scene.run.gravity_mps2),
                                     kMaxStepMotion * ShortestPeriod(scene));
    ref_steps = std::ceil(duration / max_step) + record_breakpoints;
    ref_key = "run.duration";
    ref_what = Count(ref_steps) + " reference steps";
  }
  return {ref_key,
          ref_what + " in the nominal run, its convergence witness (" + Count(witness) +
              " x) and " + Count(std::max(members, 0)) + " members",
          ref_steps * kReferenceStepBytes * (1.0 + witness + concurrent_ref),
          ref_steps * kReferenceStepCpu_s * (1.0 + witness + std::max(members, 0))};
}

// One engine's fixed steps in its nominal run and `engine_members` members (`concurrent_eng`
// of them held at once); nothing when its table does not resolve (the engine's own check
// names the problem) or has no positive step. An external engine's step that its input cannot
// hold sets `refusal` (when empty).
std::optional<EstimateTerm> EngineTerm(const Scene& scene, const std::string& name,
                                       int engine_members, double concurrent_eng,
                                       std::string& refusal) {
  const Engine* engine = FindEngine(name);
  const double duration = scene.run.duration_s;
  double dt = 0.0;
  // A solver's iterations past its default cost in proportion (an upper bound: some stop
  // early when they converge); the key that raised them is the one named.
  double iterations = 1.0;
  double step_cpu_s = kEngineStepCpu_s;
  std::string key = name + ".time_step";
  const auto* external = dynamic_cast<const external::ExternalEngine*>(engine);
  double run_limit_s = std::numeric_limits<double>::infinity();
  try {
    const EngineSettingsSchema& schema = engine->settings_schema();
    const EngineSettings settings = ResolveEngineSettings(scene, schema);
    dt = settings.Number("time_step");
    step_cpu_s = StepCpu_s(name, settings, scene.block_count());
    if (external != nullptr) run_limit_s = settings.Number("wall_limit_s");
    for (const SettingDef& def : schema.settings) {
      const auto* fallback = std::get_if<std::int64_t>(&def.default_value);
      if (fallback == nullptr || def.key.find("iterations") == std::string::npos) continue;
      const double ratio =
          static_cast<double>(settings.Integer(def.key)) / std::max<double>(1.0, *fallback);
      if (ratio > iterations) {
        iterations = ratio;
        key = name + "." + def.key;
      }
    }
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (!(dt > 0.0)) return std::nullopt;
  const double steps = std::ceil(duration / dt);
  // An external engine's input holds the base motion at every step: past its cap the run is
  // refused here, before anything is built.
  if (external != nullptr && (scene.horizontal || scene.vertical) &&
      steps > static_cast<double>(external::kMaxInputSteps) && refusal.empty()) {
    refusal = name + ".time_step: a step of " + ShortestText(dt) + " s over run.duration " +
              ShortestText(duration) + " s is " + Count(steps) +
              " steps, each a row of the base motion in the external engine's input file, more "
              "than the " +
              Count(static_cast<double>(external::kMaxInputSteps)) +
              " its input may hold (docs/limits.md): coarsen the step or shorten the run";
  }
  const double runs = 1.0 + std::max(engine_members, 0);
  std::string what = Count(steps) + " " + name + " steps (run.duration / " + name +
                     ".time_step) in " + Count(runs) + " runs";
  if (iterations > 1.0) what += ", " + Count(iterations) + " times the default iterations";
  if (step_cpu_s != kEngineStepCpu_s) {
    what += ", " + Count(step_cpu_s * 1e6) + " us per step with " +
            std::to_string(scene.block_count()) + " block" + (scene.block_count() == 1 ? "" : "s");
  }
  // A run is killed at the wall-clock limit of its table (external engines).
  const double cpu_per_run = std::min(steps * step_cpu_s * iterations, run_limit_s);
  if (cpu_per_run == run_limit_s) what += ", each stopped at its wall_limit_s";
  const double step_bytes = external != nullptr ? kExternalStepBytes : kEngineStepBytes;
  return EstimateTerm{key, what, steps * step_bytes * (1.0 + concurrent_eng), cpu_per_run * runs};
}

}  // namespace

RunEstimate EstimateRun(const Scene& scene, const std::vector<std::string>& run_engines,
                        int members, int engine_members, int jobs) {
  // The reference is always run and estimated (its nominal run, witness and members); the
  // list's engines that step on a table's time step are the physics engines.
  const std::vector<std::string> engines = SteppedEngines(run_engines);
  RunEstimate e;
  const int threads = std::max(1, jobs);
  // Members run `threads` at a time; each holds one run.
  const double concurrent_ref = std::min<double>(std::max(members, 0), threads);
  const double concurrent_eng = std::min<double>(std::max(engine_members, 0), threads);
  const double record_breakpoints = AddMotionTerms(scene, concurrent_ref, e);

  // History rows at the output interval, of every run held at once (nominal runs, the
  // reference's convergence witness, concurrent members).
  const double rows = std::ceil(scene.run.duration_s / scene.run.output_interval_s) + 1.0;
  const double runs_held = 2.0 + static_cast<double>(engines.size()) + concurrent_ref +
                           concurrent_eng * static_cast<double>(engines.size());
  e.terms.push_back({"run.output_interval",
                     Count(rows) + " history rows of " + ByteText(kRowBytes) + " in " +
                         Count(runs_held) + " runs held at once",
                     rows * kRowBytes * runs_held, 0.0});
  e.terms.push_back(ReferenceTerm(scene, members, concurrent_ref, record_breakpoints));
  for (const std::string& name : engines) {
    if (auto t = EngineTerm(scene, name, engine_members, concurrent_eng, e.refusal)) {
      e.terms.push_back(std::move(*t));
    }
  }
  for (const EstimateTerm& t : e.terms) {
    e.bytes += t.bytes;
    e.cpu_s += t.cpu_s;
  }
  // The nominal runs are serial; the members share the threads.
  e.wall_s = e.cpu_s / std::min<double>(threads, 1.0 + std::max(members, engine_members));
  return e;
}

void CheckRunEstimate(const RunEstimate& estimate, const ResourceBudget& budget,
                      const std::string& where) {
  if (!estimate.refusal.empty()) throw SceneError(where + ": " + estimate.refusal);
  if (const EstimateTerm* t = estimate.largest_bytes(); t != nullptr) {
    CheckMemoryEstimate(estimate.bytes, budget, where, t->key, t->what);
  }
  if (const EstimateTerm* t = estimate.largest_cpu();
      t != nullptr && !(estimate.wall_s <= budget.wall_s)) {
    throw SceneError(where + ": " + t->key + ": needs an estimated " + Duration(estimate.wall_s) +
                     " (" + t->what + "), more than the time budget of " + Duration(budget.wall_s) +
                     ": shorten or coarsen it, or give a longer --wall-limit SECONDS");
  }
}

}  // namespace rockbench
