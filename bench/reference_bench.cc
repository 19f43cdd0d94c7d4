// Performance of the reference model (issue 2): wall time, real-time factor and error of the
// default adaptive integrator against the thesis's fixed-step RK4, on the thesis's geometry.
// Results and the command to reproduce them: docs/performance-reference.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace {

using rockbench::GroundMotion;
using rockbench::LoadScene;
using rockbench::Scene;
namespace reference = rockbench::reference;

// Errors are compared on this common grid (s), as the issue asks.
constexpr double kGrid_s = 1e-3;

/// A scene of the benchmark: a file plus the overrides that set its duration (and record scale).
struct SceneCase {
  std::string name;
  std::string file;  ///< relative to the source tree
  std::vector<std::string> overrides;
};

/// A model configuration: overrides of the [model] table.
struct ModelCase {
  std::string name;
  std::vector<std::string> overrides;
  bool is_reference = false;  ///< the tight-tolerance run itself (timed, error vs a tighter run)
};

/// Max |theta| differences between two runs on the common grid.
struct Errors {
  double theta1_rad = 0.0, theta2_rad = 0.0;          ///< whole run
  double pre_theta1_rad = 0.0, pre_theta2_rad = 0.0;  ///< grid times before the first impact
};

/// Everything one benchmark needs, prepared outside the timed loop.
struct Prepared {
  Scene scene;
  GroundMotion motion;
  double simulated_s = 0.0;  ///< span this configuration's run covers (ends at an overturn)
  Errors errors;
  double first_impact_s = 0.0;  ///< first impact of the tight run (the end if none)
  reference::Summary summary;   ///< of one untimed run of this configuration
  reference::Summary tight_summary;
  bool is_reference = false;  ///< errors are the tight run's against a tighter one
};

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Time of the first ground or interface impact of a run; `end_s` if it has none.
double FirstImpact_s(const reference::Result& r, double end_s) {
  for (const rockbench::Event& ev : r.history.events) {
    if (ev.kind == "ground_impact" || ev.kind == "interface_impact") return ev.t_s;
  }
  return end_s;
}

// Max |theta1|, |theta2| differences on the grid k * kGrid_s over the common span of both
// trajectories (dense output), and separately over grid times strictly before `split_s`.
Errors CompareOnGrid(const reference::Result& a, const reference::Result& b, double split_s) {
  Errors e;
  const double end_s = std::min(a.trajectory.end_s(), b.trajectory.end_s());
  const long n = std::lround(std::floor(end_s / kGrid_s + 1e-9));
  for (long k = 0; k <= n; ++k) {
    const double t_s = std::min(k * kGrid_s, end_s);
    const rockbench::Sample sa = a.trajectory.At(t_s), sb = b.trajectory.At(t_s);
    const double d1 = std::abs(sa.theta_rad[0] - sb.theta_rad[0]);
    const double d2 =
        sa.blocks() >= 2 && sb.blocks() >= 2 ? std::abs(sa.theta_rad[1] - sb.theta_rad[1]) : 0.0;
    e.theta1_rad = std::max(e.theta1_rad, d1);
    e.theta2_rad = std::max(e.theta2_rad, d2);
    if (t_s < split_s) {
      e.pre_theta1_rad = std::max(e.pre_theta1_rad, d1);
      e.pre_theta2_rad = std::max(e.pre_theta2_rad, d2);
    }
  }
  return e;
}

Prepared Prepare(const SceneCase& sc, const ModelCase& mc) {
  const std::string path = std::string(ROCKBENCH_SOURCE_DIR) + "/" + sc.file;
  // The tight-tolerance run every configuration is compared with.
  const std::vector<std::string> tight = {"model.integrator=dopri5", "model.rtol=1e-12",
                                          "model.atol=1e-14", "model.events=located"};
  // The tight run's own check: a tighter one still.
  const std::vector<std::string> tighter = {"model.integrator=dopri5", "model.rtol=1e-13",
                                            "model.atol=1e-15", "model.events=located"};
  Prepared p;
  p.is_reference = mc.is_reference;
  p.scene = LoadScene(path, Concat(sc.overrides, mc.overrides));
  p.motion = GroundMotion::FromScene(p.scene);
  const Scene tight_scene = LoadScene(path, Concat(sc.overrides, tight));
  const reference::Result tight_run = reference::Simulate(tight_scene, p.motion);
  p.tight_summary = tight_run.summary;
  p.first_impact_s = FirstImpact_s(tight_run, tight_run.trajectory.end_s());
  if (mc.is_reference) {
    const Scene check = LoadScene(path, Concat(sc.overrides, tighter));
    const reference::Result check_run = reference::Simulate(check, p.motion);
    p.errors = CompareOnGrid(tight_run, check_run, p.first_impact_s);
    p.summary = tight_run.summary;
    p.simulated_s = tight_run.trajectory.end_s();
  } else {
    const reference::Result run = reference::Simulate(p.scene, p.motion);
    p.errors = CompareOnGrid(run, tight_run, p.first_impact_s);
    p.summary = run.summary;
    p.simulated_s = run.trajectory.end_s();
  }
  return p;
}

void RunBenchmark(benchmark::State& state, const Prepared& p) {
  for (auto _ : state) {
    reference::Result r = reference::Simulate(p.scene, p.motion);
    benchmark::DoNotOptimize(r);
  }
  const reference::Summary& s = p.summary;
  // Real-time factor: simulated seconds per wall second (the benchmark uses real time). A run
  // that overturns stops there, so sim_s can be shorter than the scene's duration.
  state.counters["rtf"] =
      benchmark::Counter(p.simulated_s, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["sim_s"] = p.simulated_s;
  state.counters["err_th1"] = p.errors.theta1_rad;
  state.counters["err_th2"] = p.errors.theta2_rad;
  state.counters["pre_err_th1"] = p.errors.pre_theta1_rad;
  state.counters["pre_err_th2"] = p.errors.pre_theta2_rad;
  state.counters["t_imp1"] = p.first_impact_s;
  state.counters["impacts"] = s.impacts();
  state.counters["ref_impacts"] = p.tight_summary.impacts();
  state.counters["steps"] = static_cast<double>(s.steps_accepted);
  state.counters["rejected"] = static_cast<double>(s.steps_rejected);
  state.counters["rhs"] = static_cast<double>(s.rhs_evaluations);
  std::string label = StatusText(s.status);
  if (p.is_reference) label.append(", errors vs rtol 1e-13");
  state.SetLabel(label);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const std::vector<SceneCase> scenes = {
      // The scene as given: block 2 overturns at 5.40 s in the accurate runs, where they stop.
      {"rinaldi228_20s", "scenes/thesis_rinaldi228.toml", {"run.duration=20"}},
      // The record at 0.7 of its amplitude: the stack rocks (2.5 s to 7.4 s) and does not
      // overturn, so every configuration covers the full 20 s of earthquake response.
      {"rinaldi228_x0.7_20s",
       "scenes/thesis_rinaldi228.toml",
       {"run.duration=20", "base.horizontal.scale=0.7"}},
      {"free_rocking_10s", "scenes/thesis_free_rocking.toml", {"run.duration=10"}},
  };
  const std::vector<ModelCase> models = {
      {"dopri5_rtol1e-8",
       {"model.integrator=dopri5", "model.rtol=1e-8", "model.atol=1e-10", "model.events=located"}},
      {"rk4_1ms_located", {"model.integrator=rk4", "model.step=0.001", "model.events=located"}},
      {"rk4_1ms_thesis", {"model.integrator=rk4", "model.step=0.001", "model.events=thesis"}},
      // Tighter settings of the default integrator, to show what RK4's accuracy costs it.
      {"dopri5_rtol1e-10",
       {"model.integrator=dopri5", "model.rtol=1e-10", "model.atol=1e-12", "model.events=located"}},
      {"dopri5_rtol1e-11",
       {"model.integrator=dopri5", "model.rtol=1e-11", "model.atol=1e-13", "model.events=located"}},
      // Dormand-Prince 8(5,3) at the default tolerance and both pairs at the witness's.
      {"dop853_rtol1e-12",
       {"model.integrator=dop853", "model.rtol=1e-12", "model.atol=1e-14", "model.events=located"}},
      {"dopri5_rtol1e-14",
       {"model.integrator=dopri5", "model.rtol=1e-14", "model.atol=1e-16", "model.events=located"}},
      {"dop853_rtol1e-14",
       {"model.integrator=dop853", "model.rtol=1e-14", "model.atol=1e-16", "model.events=located"}},
      {"dopri5_rtol1e-12_reference",
       {"model.integrator=dopri5", "model.rtol=1e-12", "model.atol=1e-14", "model.events=located"},
       true},
  };
  // Sliding and lift-off (issue 24, docs/sliding.md): the reference at its defaults on the
  // scenes that leave the thesis's assumptions, and the unilateral model run from t = 0 on the
  // target scene, whose motion the chain also follows (its errors are against the chain's tight
  // run: the two models' difference).
  const ModelCase defaults = {
      "dopri5_rtol1e-12_reference",
      {"model.integrator=dopri5", "model.rtol=1e-12", "model.atol=1e-14", "model.events=located"},
      true};
  const std::vector<std::pair<SceneCase, ModelCase>> sliding = {
      {{"squat_block_sliding_20s", "scenes/squat_block_sliding.toml", {}}, defaults},
      {{"rinaldi_vertical_mu0.6_20s", "scenes/rinaldi_with_vertical.toml", {}}, defaults},
      {{"top_block_slides_off", "scenes/top_block_slides_off.toml", {}}, defaults},
      {{"rinaldi228_x0.7_20s",
        "scenes/thesis_rinaldi228.toml",
        {"run.duration=20", "base.horizontal.scale=0.7"}},
       {"unilateral_from_t0",
        {"model.integrator=dopri5", "model.rtol=1e-12", "model.atol=1e-14", "model.events=located",
         "model.formulation=unilateral"}}},
  };
  // Prepared cases live until the benchmarks have run (registered lambdas point at them).
  std::vector<Prepared> prepared;
  prepared.reserve(scenes.size() * models.size() + sliding.size());
  try {
    for (const SceneCase& sc : scenes) {
      for (const ModelCase& mc : models) prepared.push_back(Prepare(sc, mc));
    }
    for (const auto& [sc, mc] : sliding) prepared.push_back(Prepare(sc, mc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reference_bench: %s\n", e.what());
    return 1;
  }
  size_t i = 0;
  for (const SceneCase& sc : scenes) {
    for (const ModelCase& mc : models) {
      const Prepared* p = &prepared[i++];
      benchmark::RegisterBenchmark((sc.name + "/" + mc.name).c_str(),
                                   [p](benchmark::State& st) { RunBenchmark(st, *p); })
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  for (const auto& [sc, mc] : sliding) {
    const Prepared* p = &prepared[i++];
    benchmark::RegisterBenchmark((sc.name + "/" + mc.name).c_str(),
                                 [p](benchmark::State& st) { RunBenchmark(st, *p); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
