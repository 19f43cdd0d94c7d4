// Cost of the N-block reference (issue 23), for N = 1 to 20 blocks:
// - one right-hand side of the pivot chain's equations of motion (reference/stack_chain.h, the
//   articulated-body recursion), every interface open (the most work) and the stack locked on
//   one pivot, with and without the interface loads: the recursion's growth, linear;
// - whole runs (reference::Simulate, the chain formulation, default tolerances) of a column of N
//   equal drums in free rocking and under a shipped record, reported per simulated second;
// - the six-drum column of issue 23 (tapering drums), 20 s of record.
// Results: docs/performance-reference.md, "N blocks".
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/chain/stack_chain.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace {

namespace reference = rockbench::reference;
using rockbench::Configuration;
using rockbench::Contact;

// N equal drums (B 0.9 m, H 0.85 m, marble), tilted a little at every interface.
struct Stack {
  explicit Stack(int n, bool all_open) : chain(Geometry(n)), config(n), theta(n), omega(n) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> rel(0.001, 0.01), rate(-0.5, 0.5);
    double t = 0.0, w = 0.0;
    for (int k = 0; k < n; ++k) {
      if (all_open || k == 0) {
        config.set(k, Contact::kRight);
        t += rel(rng);
        w += rate(rng);
      }
      theta[k] = t;
      omega[k] = w;
    }
  }
  static reference::StackGeometry Geometry(int n) {
    return reference::MakeStackGeometry(
        std::vector<reference::BlockSize>(n, {0.9, 0.85, 2700 * 0.9 * 0.85 * 0.9}));
  }
  reference::StackChain chain;
  Configuration config;
  std::vector<double> theta, omega;
};

void Rhs(benchmark::State& state, bool all_open, bool loads) {
  const int n = static_cast<int>(state.range(0));
  Stack s(n, all_open);
  std::vector<double> acc(n);
  std::vector<reference::InterfaceLoad> out(n);
  for (auto _ : state) {
    s.chain.Place(s.config, s.theta.data(), s.omega.data());
    s.chain.Accelerations(-1.5, 0.3, acc.data(), loads ? out.data() : nullptr);
    benchmark::DoNotOptimize(acc.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_block"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * n,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_RhsAllOpen(benchmark::State& state) {
  Rhs(state, true, false);
}
void BM_RhsAllOpenWithLoads(benchmark::State& state) {
  Rhs(state, true, true);
}
void BM_RhsLocked(benchmark::State& state) {
  Rhs(state, false, false);
}

// The block counts every N-block benchmark runs.
void BlockCounts(benchmark::internal::Benchmark* b) {
  for (const int n : {1, 2, 3, 5, 10, 20}) b->Arg(n);
}

BENCHMARK(BM_RhsAllOpen)->Apply(BlockCounts);
BENCHMARK(BM_RhsAllOpenWithLoads)->Apply(BlockCounts);
BENCHMARK(BM_RhsLocked)->Apply(BlockCounts);

// How a column moves.
enum class ColumnMotion {
  kFreeRocking,        // released tilted together by 0.04 rad, the top drum by 0.045, 10 s
  kLockedFreeRocking,  // released tilted together by 0.04 rad, 10 s
  kRecord,             // Sylmar Converter Sta 142 x 0.35, 20 s
};

// A column of n drums 0.85 m tall (marble), the chain formulation: equal drums 0.9 m wide and
// deep, or tapering from 0.96 m by 0.02 m a drum (the six-drum column of issue 23). Free
// rocking with the top drum further: the drums rock on each other after the first impacts, and
// from 5 drums the run leaves the model within 0.05 s (docs/n-blocks.md, "Where the model
// ends"). Locked: the column rocks as one body, inside the model for the whole 10 s at every N
// (the cost of the chain and of the per-interface event checks, one degree of freedom).
// Record: Northridge 1994 Sylmar Converter Sta 142 at 0.35 of its amplitude, 20 s. A run that
// stops early reports how far it got in simulated_s.
rockbench::Scene ColumnScene(int n, ColumnMotion motion, bool taper = false) {
  const bool record = motion == ColumnMotion::kRecord;
  std::string toml;
  for (int k = 0; k < n; ++k) {
    const std::string width = taper ? std::to_string(0.96 - 0.02 * k) : "0.9";
    toml += "[[block]]\nwidth = ";
    toml += width;
    toml += "\nheight = 0.85\ndensity = 2700.0\ndepth = ";
    toml += width;
    toml += "\n";
  }
  toml += "[model]\nformulation = \"chain\"\n";
  if (record) {
    toml += "[base.horizontal]\n";
    toml += "file = \"../records/northridge1994_sylmar_converter_sta_142.AT2\"\n";
    toml += "scale = 0.35\n[run]\nduration = 20.0\n";
  } else {
    toml += "[initial]\ntheta = [";
    const bool locked = motion == ColumnMotion::kLockedFreeRocking;
    for (int k = 0; k < n; ++k) toml += k + 1 < n ? "0.04, " : (locked ? "0.04]\n" : "0.045]\n");
    toml += "[run]\nduration = 10.0\n";
  }
  return rockbench::ParseScene(toml, ROCKBENCH_SOURCE_DIR "/scenes/column_bench.toml");
}

// One whole run a timed iteration; counters: simulated seconds, events, and the cost per
// simulated second.
void RunScene(benchmark::State& state, const rockbench::Scene& scene) {
  const rockbench::GroundMotion motion = rockbench::GroundMotion::FromScene(scene);
  double simulated_s = 0.0;
  size_t events = 0;
  for (auto _ : state) {
    const reference::Result r = reference::Simulate(scene, motion);
    simulated_s = r.history.samples.empty() ? 0.0 : r.history.samples.back().t_s;
    events = r.history.events.size();
    benchmark::DoNotOptimize(r.summary.peak_theta_rad.data());
  }
  state.counters["simulated_s"] = simulated_s;
  state.counters["events"] = static_cast<double>(events);
  state.counters["s_per_simulated_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * simulated_s,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_ColumnFreeRocking(benchmark::State& state) {
  RunScene(state, ColumnScene(static_cast<int>(state.range(0)), ColumnMotion::kFreeRocking));
}
void BM_LockedColumnFreeRocking(benchmark::State& state) {
  RunScene(state, ColumnScene(static_cast<int>(state.range(0)), ColumnMotion::kLockedFreeRocking));
}
void BM_ColumnUnderRecord(benchmark::State& state) {
  RunScene(state, ColumnScene(static_cast<int>(state.range(0)), ColumnMotion::kRecord));
}
void BM_SixTaperingDrumsUnderRecord(benchmark::State& state) {
  RunScene(state, ColumnScene(6, ColumnMotion::kRecord, true));
}

BENCHMARK(BM_ColumnFreeRocking)->Apply(BlockCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LockedColumnFreeRocking)->Apply(BlockCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ColumnUnderRecord)->Apply(BlockCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SixTaperingDrumsUnderRecord)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
