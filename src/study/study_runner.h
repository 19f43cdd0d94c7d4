#pragma once
/// Runs a study: every (member, run) in a worker process under the study's wall-clock limit, its
/// row appended to DIR/members.csv as soon as it is done, and at the end the file rewritten in
/// member order. A worker that crashes or hangs costs only its run (a row with its status) and
/// is replaced. `--resume` skips the rows already in the file; a study killed at any moment and
/// resumed ends with the same file as one never interrupted (wall times aside). Under MPI the
/// ranks share the runs through rank 0 (study/study_mpi.h), which alone writes the file.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "study/study.h"
#include "study/study_member.h"

namespace rockbench {

/// One run of a study: a member and one of the study's engines.
struct StudyTask {
  int64_t member = 0;
  int engine = 0;  ///< index into StudyDef::engines
};

/// Where a process gets its runs and leaves its rows: locally, or through MPI.
class StudyScheduler {
 public:
  virtual ~StudyScheduler() = default;
  /// The next run for this process; nullopt: none left for it.
  virtual std::optional<StudyTask> Next() = 0;
  /// A run of this process is done.
  virtual void Done(const MemberRow& row) = 0;
  /// Called on every turn of the pool's loop (MPI: answer the other ranks).
  virtual void Service() {}
  /// The longest the pool may wait between two calls of Service(), s.
  virtual double service_interval_s() const { return 0.5; }
  /// Whether the process may stop once Next() gave nullopt and its workers are idle (rank 0
  /// waits for every other rank's rows).
  virtual bool Finished() { return true; }
};

/// How the pool runs its workers.
struct WorkerPoolOptions {
  /// The program run as `PROGRAM ensemble STUDY --worker [--out DIR --keep-histories]`; empty:
  /// SelfExecutable().
  std::filesystem::path executable;
  int jobs = 1;                   ///< workers at once (>= 1)
  double wall_limit_s = 0;        ///< a run is killed after this (0: the study's)
  std::filesystem::path out_dir;  ///< with keep_histories: histories under out_dir/members/ID
  bool keep_histories = false;
  std::filesystem::path worker_log;  ///< the workers' standard error is appended here
  /// The memory budget given to each worker (--memory-budget GIB); 0: the worker's default.
  double memory_budget_gib = 0.0;
  /// Added to a worker's arguments (tests: a hidden crash or hang).
  std::vector<std::string> extra_worker_args;
};

/// Runs the scheduler's runs on a pool of worker processes until it has none left.
void RunWorkerPool(const StudyDef& study, StudyScheduler& scheduler,
                   const WorkerPoolOptions& options);

/// What a worker does: reads "MEMBER ENGINE_INDEX" lines on `in`, answers each with one line of
/// JSON (MemberRowToJson) on `out`, until end of input. With `keep_dir`, each run's histories go
/// to keep_dir/members/ID/<engine>/.
void RunWorkerLoop(const StudyDef& study, std::FILE* in, std::FILE* out,
                   const std::optional<std::filesystem::path>& keep_dir);

/// The journal DIR/members.csv, and what keeps it the study's own: DIR/members.lock (held with
/// flock for as long as the journal is open: a second writer is refused, naming the holder's
/// pid) and DIR/members.study (the study's inputs that the rows do not show: the base scene's
/// bytes, `set`, `combine`, blocks and the impact rate; written with the file, compared on
/// resume).
class MembersJournal {
 public:
  /// Opens (or creates) DIR/members.csv, holding DIR/members.lock. An existing file is an error
  /// unless `resume`, and then must have this study's header. On resume every complete row is
  /// kept, or the journal is refused (SceneError naming the file and line): a line that is not
  /// a row of this study (cells, member, engine), a row whose axis values are not the ones the
  /// study gives its member now (the study was edited: the axis, the row's value and the
  /// study's), or DIR/members.study differing from the study (naming the input). Only a blank
  /// line (skipped), a second row of one run (the first kept) and a last line cut short by a
  /// kill (a row's beginning: removed from the file, its run made again) are let through, each
  /// said in notes(). Throws SceneError.
  MembersJournal(const StudyDef& study, const std::filesystem::path& dir, bool resume);
  ~MembersJournal();
  MembersJournal(const MembersJournal&) = delete;
  MembersJournal& operator=(const MembersJournal&) = delete;
  /// Whether the file already holds this run's row.
  bool Has(const StudyTask& task) const;
  /// Rows already in the file when it was opened.
  int64_t rows_at_open() const { return static_cast<int64_t>(done_.size()); }
  /// What the opening let through, one line each ("DIR/members.csv:7: a blank line, skipped").
  const std::vector<std::string>& notes() const { return notes_; }
  /// Appends a row (one write: a kill leaves at most one line cut short).
  void Append(const MemberRow& row);
  /// Rewrites the file in member order (then engine order), atomically, without blank lines
  /// and second rows of a run. Throws SceneError when a run of the study has no row.
  void Finish();

 private:
  const StudyDef& study_;
  std::filesystem::path path_;
  std::vector<std::vector<bool>> done_by_member_;  // [member][engine]
  std::vector<StudyTask> done_;
  std::vector<std::string> notes_;
  int fd_ = -1;
  int lock_fd_ = -1;
};

/// DIR/members.study's text for `study`: one "key = value" line per input the rows do not show.
std::string StudyInputsText(const StudyDef& study);

/// The runs of the study not yet in the journal, in member order.
std::vector<StudyTask> PendingTasks(const StudyDef& study, const MembersJournal& journal);

/// The local scheduler: the pending runs in order, rows to the journal, progress to `progress`.
class LocalScheduler : public StudyScheduler {
 public:
  LocalScheduler(std::vector<StudyTask> tasks, MembersJournal& journal,
                 std::function<void(int64_t done, int64_t total)> progress = {});
  std::optional<StudyTask> Next() override;
  void Done(const MemberRow& row) override;

 private:
  std::vector<StudyTask> tasks_;
  size_t next_ = 0;
  int64_t done_ = 0;
  MembersJournal& journal_;
  std::function<void(int64_t, int64_t)> progress_;
};

/// Writes DIR/study.json (atomically): the study, its members, engines and axes, how it ran
/// (ranks, jobs per rank), its wall time and serial part (s), and the rows a resume kept.
void WriteStudyJson(const StudyDef& study, const std::filesystem::path& dir, int ranks, int jobs,
                    double wall_s, double serial_s, int64_t resumed_rows);

/// How RunStudyHere runs a study.
struct LocalStudyOptions {
  std::filesystem::path out_dir;  ///< members.csv, members.lock, members.study, study.json
  bool resume = false;            ///< go on with out_dir/members.csv (MembersJournal)
  WorkerPoolOptions pool;         ///< its jobs (>= 1), worker program, kept histories
  /// Called with each note of the resume (MembersJournal::notes), and with runs done / total.
  std::function<void(const std::string& note)> note;
  std::function<void(int64_t done, int64_t total)> progress;
};

/// Runs a study on this machine, as `rockbench ensemble` does without MPI: opens the journal,
/// runs the pending runs on the worker pool, rewrites members.csv in member order and writes
/// study.json. `start_s` is the steady-clock time (s) the study's wall time counts from. A stop
/// request (util/stop_request.h) ends the workers and throws StopRequested, leaving the
/// journal's whole rows for a resume. Throws SceneError as MembersJournal and the pool do.
void RunStudyHere(const StudyDef& study, const LocalStudyOptions& options, double start_s);

/// The steady clock, s (the start of RunStudyHere's wall time).
double StudyClock_s();

}  // namespace rockbench
