// `rockbench stress --out DIR [--quick] [--case PATTERN ...] [--jobs N] [--list]`: the stress
// catalogue (src/stress/stress.h, docs/stress.md). Every (case, engine) runs in a child
// process, `rockbench stress --run-case NAME --engine E` (hidden options), which prints one
// JSON row; DIR/stress.csv is written atomically, rows in catalogue order.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "files/atomic_file.h"
#include "run/engine_registry.h"
#include "run/parallel.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "stress/stress.h"

namespace rockbench::cli {
namespace {

struct StressCliOptions {
  std::string out;
  bool quick = false;
  bool list = false;
  std::vector<std::string> cases;
  int jobs = 0;
  std::string run_case;
  std::string engine = "reference";
  LimitOptions limits;
};

// The child: one case, one engine, one JSON line on stdout.
void RunChild(const StressCliOptions& opt) {
  for (const StressCase& c : StressCatalogue()) {
    if (c.name != opt.run_case) continue;
    if (std::find(c.engines.begin(), c.engines.end(), opt.engine) == c.engines.end()) {
      throw SceneError("--engine '" + opt.engine + "': case " + c.name + " runs " + [&] {
        std::string e;
        for (const std::string& n : c.engines) e += (e.empty() ? "" : ", ") + n;
        return e;
      }());
    }
    const StressRow row = RunStressCaseHere(c, opt.engine);
    std::printf("%s\n", StressRowToJson(row).dump().c_str());
    return;
  }
  throw SceneError("--run-case '" + opt.run_case + "': no such case (see --list)");
}

void List(const std::vector<StressCase>& cases) {
  for (const StressCase& c : cases) {
    std::string engines;
    for (const std::string& e : c.engines) engines += (engines.empty() ? "" : ",") + e;
    std::printf("%-44s %-17s %-6s %s\n", c.name.c_str(), engines.c_str(),
                c.hidden ? "hidden" : (c.quick ? "quick" : ""), c.description.c_str());
  }
}

void Execute(const StressCliOptions& opt) {
  if (!opt.run_case.empty()) {
    RunChild(opt);
    return;
  }
  const std::vector<StressCase> catalogue = StressCatalogue();
  if (opt.list) {
    List(opt.cases.empty() && !opt.quick ? catalogue
                                         : SelectStressCases(catalogue, opt.cases, opt.quick));
    return;
  }
  if (opt.out.empty()) throw SceneError("--out: expected an output folder (or --list)");
  StartLimits(opt.limits, opt.out, "stress");
  const std::vector<StressCase> cases = SelectStressCases(catalogue, opt.cases, opt.quick);
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);
  StressRunOptions ro;
  ro.jobs = opt.jobs;
  const auto start = std::chrono::steady_clock::now();
  // Progress on a terminal only (runs done, elapsed, remaining); quiet otherwise.
  ProgressLine line("stress runs");
  auto progress = [&](int done, int total, const StressRow&) { line.Update(done, total); };
  const std::vector<StressRow> rows = RunStress(cases, ro, progress);
  WriteFileAtomic(out / "stress.csv", StressCsv(rows));
  // Summary: the reference's invariants and every engine's statuses.
  int ref_bad = 0;
  std::map<std::string, std::map<std::string, int>> statuses;
  for (const StressRow& r : rows) {
    ++statuses[r.engine][r.status];
    if (IsReference(r.engine) &&
        (!r.finished || r.nan || (r.energy_impacts > 0 && !(r.max_energy_gain_rel <= 1e-9)))) {
      ++ref_bad;
      std::fprintf(stderr, "warning: reference %s: %s%s%s\n", r.case_name.c_str(), r.status.c_str(),
                   r.nan ? ", non-finite values" : "",
                   r.energy_impacts > 0 && !(r.max_energy_gain_rel <= 1e-9) ? ", energy gain" : "");
    }
  }
  std::printf("%zu rows from %zu cases in %.1f s; outputs in %s (stress.csv)\n", rows.size(),
              cases.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              out.string().c_str());
  for (const auto& [engine, counts] : statuses) {
    std::string line;
    for (const auto& [status, n] : counts) {
      line += (line.empty() ? "" : ", ") + status + " " + std::to_string(n);
    }
    std::printf("  %s: %s\n", engine.c_str(), line.c_str());
  }
  if (ref_bad > 0) std::printf("  reference: %d rows break an invariant (see stderr)\n", ref_bad);
}

}  // namespace

void RegisterStress(CLI::App& app) {
  auto opt = std::make_shared<StressCliOptions>();
  auto* cmd = app.add_subcommand(
      "stress",
      "Stiff and extreme cases with the reference and every engine, isolated (stress.csv)");
  cmd->add_option("--out,-o", opt->out, "Output folder (writes stress.csv)");
  cmd->add_flag("--quick", opt->quick, "The CI subset of the catalogue");
  cmd->add_option("--case", opt->cases,
                  "Select cases by name prefix or glob (repeatable; selftest/* only by name)");
  cmd->add_option("--jobs,-j", opt->jobs, "Child processes at once (default: hardware threads)")
      ->check(CLI::Range(1, 4096));
  cmd->add_flag("--list", opt->list, "Print the catalogue (or the selected cases) and exit");
  // The child's options (re-executed by the command itself).
  cmd->add_option("--run-case", opt->run_case, "Run one case in this process")->group("");
  cmd->add_option("--engine", opt->engine, "Engine of --run-case")->group("");
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt] { Execute(*opt); });
}

}  // namespace rockbench::cli
