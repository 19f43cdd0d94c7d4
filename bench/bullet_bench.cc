// Bullet engine benchmarks (results in docs/bullet.md):
//  - the adapter's per-step overhead (drive update, state read-out, event detection) against
//    bare stepSimulation on the same world and the same motion, measured side by side;
//  - the real-time factor of the whole engine on the thesis's scenes at 1 ms and 0.1 ms.
// Run: build/bench/bullet_bench [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/rocking_world.h"
#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "motion/ground_motion.h"
#include "scene/scene.h"

namespace {

using rockbench::GroundMotion;
using rockbench::Scene;
namespace bt = rockbench::bullet;

const std::filesystem::path kScenes = std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "scenes";

// The thesis's free-rocking example (two blocks from 0.15 rad), first `seconds` of it.
bt::BulletInput ThesisInput(double dt, double seconds) {
  char step[64], dur[64];
  std::snprintf(step, sizeof step, "bullet.time_step=%.17g", dt);
  std::snprintf(dur, sizeof dur, "run.duration=%.17g", seconds);
  const Scene s = rockbench::LoadScene(kScenes / "thesis_free_rocking.toml",
                                       {"bullet.split_impulse_threshold=0", step, dur});
  return bt::MakeBulletInput(s, GroundMotion::FromScene(s));
}

// Bare: stepSimulation alone, the world built outside the timing.
double BareSeconds(const bt::BulletInput& in) {
  bt::RockingWorld world(in);
  btDiscreteDynamicsWorld* w = world.world();
  const btScalar dt = btScalar(in.time_step_s);
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t n = 0; n < in.steps; ++n) w->stepSimulation(dt, 0);
  benchmark::DoNotOptimize(world.block1()->getCenterOfMassTransform());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Adapter: what Simulate does per step (drive update, step, read-out, monitor).
double AdapterSeconds(const bt::BulletInput& in) {
  bt::RockingWorld world(in);
  rockbench::Monitor monitor(in);
  monitor.Start(world.Read(0));
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t n = 0; n < in.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    if (!monitor.Step(n + 1, world.Read(n + 1))) break;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  benchmark::DoNotOptimize(monitor.last());
  return s;
}

// The two loops alternated in one benchmark, so both see the same machine state; counters give
// the time per step of each and the adapter's overhead in percent.
void BM_AdapterOverhead(benchmark::State& state) {
  const bt::BulletInput in = ThesisInput(1e-4, 1.0);  // 10000 steps, impacts included
  double bare = 0.0, adapter = 0.0;
  for (auto _ : state) {
    bare += BareSeconds(in);
    adapter += AdapterSeconds(in);
  }
  const double steps = static_cast<double>(in.steps) * static_cast<double>(state.iterations());
  state.counters["bare_us_per_step"] = 1e6 * bare / steps;
  state.counters["adapter_us_per_step"] = 1e6 * adapter / steps;
  state.counters["overhead_pct"] = 100.0 * (adapter - bare) / bare;
}
BENCHMARK(BM_AdapterOverhead)->Unit(benchmark::kMillisecond)->Iterations(10);

void BM_BareStep(benchmark::State& state) {
  const bt::BulletInput in = ThesisInput(1e-4, 1.0);
  double total = 0.0;
  for (auto _ : state) {
    const double s = BareSeconds(in);
    total += s;
    state.SetIterationTime(s);
  }
  state.counters["us_per_step"] = 1e6 * total / (in.steps * double(state.iterations()));
}
BENCHMARK(BM_BareStep)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_AdapterStep(benchmark::State& state) {
  const bt::BulletInput in = ThesisInput(1e-4, 1.0);
  double total = 0.0;
  for (auto _ : state) {
    const double s = AdapterSeconds(in);
    total += s;
    state.SetIterationTime(s);
  }
  state.counters["us_per_step"] = 1e6 * total / (in.steps * double(state.iterations()));
}
BENCHMARK(BM_AdapterStep)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

// The adapter's own work per step alone (drive update, read-out, monitor) on a world whose
// state is frozen mid-rocking: a direct measure of the overhead, compared with
// bare_us_per_step above.
void BM_AdapterWorkOnly(benchmark::State& state) {
  const bt::BulletInput in = ThesisInput(1e-4, 1.0);
  bt::RockingWorld world(in);
  for (int n = 0; n < 3000; ++n) world.Step();  // into the rocking motion (0.3 s)
  rockbench::Monitor monitor(in);
  monitor.Start(world.Read(0));
  std::int64_t n = 0;
  for (auto _ : state) {
    world.ApplyDrive(n % in.steps);
    const rockbench::StepReadout r = world.Read(n % in.steps + 1);
    benchmark::DoNotOptimize(monitor.Step(n + 1, r));
    ++n;
  }
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_AdapterWorkOnly);

// Whole runs: real-time factor = simulated seconds / wall seconds.
void RealTime(benchmark::State& state, const char* scene, double dt) {
  char step[64];
  std::snprintf(step, sizeof step, "bullet.time_step=%.17g", dt);
  const Scene s = rockbench::LoadScene(kScenes / scene, {"bullet.split_impulse_threshold=0", step});
  const bt::BulletInput in = bt::MakeBulletInput(s, GroundMotion::FromScene(s));
  double wall = 0.0, simulated = 0.0;
  for (auto _ : state) {
    const rockbench::EngineResult out = bt::Simulate(in);
    wall += out.wall_s;
    simulated += out.history.samples.back().t_s;
    state.SetIterationTime(out.wall_s);
  }
  state.counters["real_time_factor"] = simulated / wall;
  state.counters["simulated_s"] = simulated / double(state.iterations());
}
void BM_ThesisFreeRocking_1ms(benchmark::State& s) {
  RealTime(s, "thesis_free_rocking.toml", 1e-3);
}
void BM_ThesisFreeRocking_100us(benchmark::State& s) {
  RealTime(s, "thesis_free_rocking.toml", 1e-4);
}
void BM_ThesisRinaldi_1ms(benchmark::State& s) {
  RealTime(s, "thesis_rinaldi228.toml", 1e-3);
}
void BM_ThesisRinaldi_100us(benchmark::State& s) {
  RealTime(s, "thesis_rinaldi228.toml", 1e-4);
}
BENCHMARK(BM_ThesisFreeRocking_1ms)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_ThesisFreeRocking_100us)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_ThesisRinaldi_1ms)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_ThesisRinaldi_100us)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
