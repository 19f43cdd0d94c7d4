// The cylinder reference's cost (issue 41: under 10 ms for 20 s of a record): the nominal run
// (no witness) of the shipped scenes, the scene and its record read once outside the timing.
// Results: docs/three-d.md.
#include <benchmark/benchmark.h>

#include <string>

#include "motion/ground_motion.h"
#include "reference/cylinder_run.h"
#include "scene/scene.h"

namespace {

using rockbench::GroundMotion;
using rockbench::LoadScene;
using rockbench::Scene;

void RunScene(benchmark::State& state, const std::string& file) {
  const Scene scene = LoadScene(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/three_d/" + file);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  long steps = 0;
  for (auto _ : state) {
    const auto r = rockbench::reference::cylinder::SimulateCylinder(scene, motion);
    steps = r.summary.steps_accepted;
    benchmark::DoNotOptimize(r.history.samples.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["simulated_s"] = scene.run.duration_s;
}

void BM_CylinderKobe20s(benchmark::State& state) { RunScene(state, "cylinder_kobe.toml"); }
void BM_CylinderRotatingHarmonic6s(benchmark::State& state) {
  RunScene(state, "cylinder_rotating_harmonic.toml");
}
void BM_CylinderFreeWobbling4s(benchmark::State& state) {
  RunScene(state, "cylinder_free_wobbling.toml");
}

BENCHMARK(BM_CylinderKobe20s)->Unit(benchmark::kMillisecond)->Repetitions(5);
BENCHMARK(BM_CylinderRotatingHarmonic6s)->Unit(benchmark::kMillisecond)->Repetitions(5);
BENCHMARK(BM_CylinderFreeWobbling4s)->Unit(benchmark::kMillisecond)->Repetitions(5);

}  // namespace

BENCHMARK_MAIN();
