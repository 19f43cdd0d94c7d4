#pragma once
/// A wall-clock limit for a whole command (`--wall-limit SECONDS` of run, compare, render, ...),
/// and how the process ends early without leaving anything behind: the registry of the
/// temporary names it made, the end of every process it started (and of theirs), and the
/// termination signals (SIGTERM, SIGINT, SIGHUP) handled the same way as the limit.
///
/// Only names registered here are ever removed: a file or folder that merely looks like a
/// temporary of ours ("x.tmp.<pid>" made by someone else) is left alone.
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench {

/// Exit code of a command stopped by its wall-clock limit.
inline constexpr int kExitWallLimit = 3;

/// Records `path` as a temporary name this process has just created (exclusively: O_EXCL,
/// mkdir, mkdtemp; registered after, so that a name someone else holds is never ours): a file
/// (removed with unlink), or with `folder` a folder this process made (removed with everything
/// in it). Thread-safe. Once the process is ending (a signal, the wall-clock limit), the
/// calling thread is held here for good after registering: nothing new is made while the
/// process cleans up, and what it just made is removed.
void RegisterTemporary(const std::filesystem::path& path, bool folder = false);
/// Forgets `path` (renamed into place, or removed by its maker). Thread-safe.
void ForgetTemporary(const std::filesystem::path& path);
/// The names registered and not yet forgotten (tests, messages).
std::vector<std::filesystem::path> RegisteredTemporaries();
/// Removes every registered name that exists and forgets them all.
void RemoveRegisteredTemporaries();

/// Whether the process is ending (a termination signal or the wall-clock limit was taken):
/// threads must not start new work.
bool ProcessEnding();
/// Holds the calling thread for good when the process is ending (Subprocess calls it before
/// starting a child); returns at once otherwise.
void HoldIfEnding();

/// Makes this process the reaper of its orphaned descendants (PR_SET_CHILD_SUBREAPER): a
/// program an engine started and left behind (a daemon, a `setsid` helper) becomes this
/// process's child instead of init's, so EndDescendants finds it. Returns false when the kernel
/// refused.
bool BecomeSubreaper();
/// Every running process below this one (children, theirs, ...; found by the parent links in
/// /proc), zombies left out.
std::vector<int> Descendants();
/// Ends every descendant: SIGTERM, up to `grace_s` of wall time for them to go, then SIGKILL,
/// repeated until none is left (a descendant that started another meanwhile is found on the
/// next pass). Returns how many processes were signalled.
int EndDescendants(double grace_s = 0.5);

/// Handles SIGTERM, SIGINT and SIGHUP (those not ignored when the process started): a handler
/// hands the signal to a thread of its own, which says "rockbench: stopped by SIGNAME: its
/// processes ended and its temporary files removed" on stderr after ending every descendant
/// (EndDescendants) and removing the registered temporaries; the process then dies of the same
/// signal. Call it once, first in main.
void HandleTerminationSignals();

/// What the process does at its normal end (main): ends every descendant left running (an
/// engine's helper that outlived it) and removes any registered temporary still there.
void CleanUpAtExit();

/// Starts a watchdog: when `seconds` (> 0, finite) of wall time have passed, it ends every
/// descendant, removes this process's registered temporaries (RegisterTemporary: the names
/// WriteFileAtomic, the renders, a study and an external engine's run folder make; nothing
/// else under `out_dir` or anywhere), prints "rockbench COMMAND: error: wall-clock limit of S
/// s reached (--wall-limit); no output written for what was unfinished" on stderr, and ends
/// the process with kExitWallLimit. seconds <= 0: no limit. Call once per process. `out_dir`
/// is not searched (kept for the callers' sake).
void StartWallLimit(double seconds, const std::filesystem::path& out_dir,
                    const std::string& command);

}  // namespace rockbench
