// Cost of the N-block reference (issue 23): one right-hand side of the pivot chain's equations
// of motion (reference/stack_chain.h, the articulated-body recursion) for N = 1 to 20 blocks,
// every interface open (the most work) and the stack locked on one pivot, with and without the
// interface loads. The growth with N is the recursion's: linear. Results: docs/performance-
// reference.md, "N blocks".
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "reference/stack_chain.h"

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

BENCHMARK(BM_RhsAllOpen)->Arg(1)->Arg(2)->Arg(3)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_RhsAllOpenWithLoads)->Arg(1)->Arg(2)->Arg(3)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_RhsLocked)->Arg(1)->Arg(2)->Arg(3)->Arg(5)->Arg(10)->Arg(20);

}  // namespace

BENCHMARK_MAIN();
