#pragma once
/// A wall-clock limit for a whole command (`--wall-limit SECONDS` of run, compare, render, ...).
#include <filesystem>
#include <string>

namespace rockbench {

/// Exit code of a command stopped by its wall-clock limit.
inline constexpr int kExitWallLimit = 3;

/// Starts a watchdog: when `seconds` (> 0, finite) of wall time have passed, it removes this
/// process's temporary files under `out_dir` (every name holding ".tmp.<pid>" or ".tmp<pid>",
/// the names WriteFileAtomic and the renders write to before renaming), prints
/// "rockbench COMMAND: error: wall-clock limit of S s reached (--wall-limit); no output
/// written for what was unfinished" on stderr, and ends the process with kExitWallLimit (child
/// processes it started see their pipes close). seconds <= 0: no limit. Call once per process.
void StartWallLimit(double seconds, const std::filesystem::path& out_dir,
                    const std::string& command);

}  // namespace rockbench
