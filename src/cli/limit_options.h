#pragma once
/// The options every long command takes: --memory-budget GIB and --wall-limit SECONDS
/// (docs/limits.md).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "scene/limits.h"

namespace rockbench::cli {

struct LimitOptions {
  double memory_budget_gib = limits::kDefaultMemoryBudget_bytes / (1024.0 * 1024 * 1024);
  double wall_limit_s = 0.0;  ///< 0: none
};

/// Adds --memory-budget and --wall-limit to `cmd`.
void AddLimitOptions(CLI::App* cmd, LimitOptions* opt);

/// Sets this process's budget (SetProcessBudget) and starts the wall-clock limit (temporary
/// files under `out_dir` are removed when it fires); returns the budget. Throws SceneError
/// when `out_dir` (the command's --out) names a file or lies under one.
ResourceBudget StartLimits(const LimitOptions& opt, const std::filesystem::path& out_dir,
                           const std::string& command);

}  // namespace rockbench::cli
