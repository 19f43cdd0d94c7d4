#include "cli/limit_options.h"

#include "scene/scene.h"
#include "util/wall_limit.h"

namespace rockbench::cli {
namespace {

// Refuses an output folder `out` that names a file (or lies under one), saying so: creating it
// would fail with a bare "filesystem error: cannot create directories: Not a directory".
void CheckOutFolder(const std::filesystem::path& out) {
  for (std::filesystem::path p = out; !p.empty(); p = p.parent_path()) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(p, ec);
    if (std::filesystem::exists(st)) {
      if (std::filesystem::is_directory(st)) return;
      throw SceneError("--out " + out.string() + ": " + p.string() +
                       " exists and is not a folder: give the name of a folder (it is created "
                       "when missing)");
    }
    if (p == p.parent_path()) return;
  }
}

}  // namespace

void AddLimitOptions(CLI::App* cmd, LimitOptions* opt) {
  cmd->add_option("--memory-budget", opt->memory_budget_gib,
                  "Memory the command may use, GiB: a run estimated to need more is refused "
                  "before it starts (docs/limits.md)")
      ->capture_default_str()
      ->check(CLI::Range(1.0 / 1024, 1024.0 * 1024));
  cmd->add_option("--wall-limit", opt->wall_limit_s,
                  "Stop after this many seconds of wall time (exit 3, no partial output); a run "
                  "estimated to take longer is refused up front. Default: none (the estimate "
                  "is held to 6 hours)")
      ->check(CLI::Range(1e-3, 1e7));
}

ResourceBudget StartLimits(const LimitOptions& opt, const std::filesystem::path& out_dir,
                           const std::string& command) {
  CheckOutFolder(out_dir);
  ResourceBudget budget;
  budget.memory_bytes = opt.memory_budget_gib * 1024.0 * 1024 * 1024;
  if (opt.wall_limit_s > 0.0) budget.wall_s = opt.wall_limit_s;
  SetProcessBudget(budget);
  StartWallLimit(opt.wall_limit_s, out_dir, command);
  return budget;
}

}  // namespace rockbench::cli
