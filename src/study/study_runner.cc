// The pool of worker processes, the worker's loop and the journal of a study.
#include "study/study_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "run/engine_run.h"
#include "scene/limits.h"
#include "util/subprocess.h"

namespace rockbench {
namespace {

double Now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void CloseFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// One worker process: the child (its standard input takes runs, its standard output gives
// rows back) and the run it is on.
struct Worker {
  Subprocess process;
  std::string buffer;  // what it printed past the last complete line
  std::optional<StudyTask> task;
  double started_s = 0.0;
};

// Starts a worker, its standard error appended to `log` when given; throws SceneError when it
// cannot.
Worker StartWorker(const std::vector<std::string>& argv, const std::filesystem::path& log) {
  SpawnOptions options;
  options.in = Stdio::kPipe;
  options.out = Stdio::kPipe;
  options.err_log = log;
  Worker w;
  w.process = Subprocess(argv, options);
  if (!w.process.started()) {
    throw SceneError("cannot start the worker " + w.process.start_error());
  }
  return w;
}

// Ends a worker: closes its pipes (it exits at end of input) or kills it; returns the signal
// that ended it (0 for a normal exit).
int StopWorker(Worker& w, bool kill) {
  if (kill) w.process.Kill(SIGKILL);
  const ExitStatus status = w.process.Wait();
  w.process = Subprocess();
  w.buffer.clear();
  return status.signal;
}

bool SendTask(Worker& w, const StudyTask& t) {
  const std::string line = std::to_string(t.member) + " " + std::to_string(t.engine) + "\n";
  if (w.process.WriteStdin(line) != 0) return false;
  w.task = t;
  w.started_s = Now_s();
  return true;
}

// The pool: up to `jobs` workers, started when there is work and replaced when one fails.
class Pool {
 public:
  Pool(const StudyDef& study, StudyScheduler& scheduler, const WorkerPoolOptions& o)
      : study_(study), scheduler_(scheduler), options_(o), workers_(std::max(1, o.jobs)) {
    const std::filesystem::path exe = o.executable.empty() ? SelfExecutable() : o.executable;
    // The worker ends itself when this process ends (a kill, the wall-clock limit): it is told
    // its parent's pid (cmd_ensemble.cc, PR_SET_PDEATHSIG).
    argv_ = {exe.string(), "ensemble",        std::filesystem::absolute(study.path).string(),
             "--worker",   "--worker-parent", std::to_string(::getpid())};
    if (o.keep_histories) {
      argv_.insert(argv_.end(), {"--out", o.out_dir.string(), "--keep-histories"});
    }
    if (o.memory_budget_gib > 0.0) {
      char budget[64];
      std::snprintf(budget, sizeof budget, "%.17g", o.memory_budget_gib);
      argv_.insert(argv_.end(), {"--memory-budget", budget});
    }
    argv_.insert(argv_.end(), o.extra_worker_args.begin(), o.extra_worker_args.end());
    wall_limit_s_ = o.wall_limit_s > 0.0 ? o.wall_limit_s : study.wall_limit_s;
  }
  ~Pool() {
    for (Worker& w : workers_) {
      if (w.process.running()) StopWorker(w, w.task.has_value());
    }
  }

  void Run() {
    bool exhausted = false;
    while (true) {
      scheduler_.Service();
      for (Worker& w : workers_) {
        if (exhausted || w.task) continue;
        const std::optional<StudyTask> t = scheduler_.Next();
        if (!t) {
          exhausted = true;
          break;
        }
        Dispatch(w, *t);
      }
      const bool busy = std::any_of(workers_.begin(), workers_.end(),
                                    [](const Worker& w) { return w.task.has_value(); });
      if (!busy && exhausted && scheduler_.Finished()) break;
      Wait(busy);
    }
  }

 private:
  void Dispatch(Worker& w, const StudyTask& t) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      if (!w.process.running()) w = StartWorker(argv_, options_.worker_log);
      if (SendTask(w, t)) return;
      StopWorker(w, true);  // it died between runs: start another
    }
    Finish(w, FailedRow(t.member, study_.engines[t.engine], "error",
                        "the worker would not take the run"));
  }

  void Finish(Worker& w, const MemberRow& row) {
    w.task.reset();
    scheduler_.Done(row);
  }

  // Waits for rows (or a deadline, or the scheduler's next turn) and handles them.
  void Wait(bool busy) {
    std::vector<pollfd> fds;
    std::vector<Worker*> owners;
    double next_deadline = Now_s() + scheduler_.service_interval_s();
    for (Worker& w : workers_) {
      if (!w.task) continue;
      fds.push_back({w.process.stdout_fd(), POLLIN, 0});
      owners.push_back(&w);
      next_deadline = std::min(next_deadline, w.started_s + wall_limit_s_);
    }
    // Until the first deadline or the scheduler's next turn (MPI ranks wait on rank 0).
    const int wait_ms = std::max(0, static_cast<int>((next_deadline - Now_s()) * 1000.0) + 1);
    if (!busy) {
      ::usleep(static_cast<useconds_t>(wait_ms) * 1000);
      return;
    }
    const int ready = ::poll(fds.data(), fds.size(), wait_ms);
    if (ready < 0 && errno != EINTR) throw SceneError(std::string("poll: ") + std::strerror(errno));
    for (size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents != 0) Read(*owners[i]);
    }
    const double now = Now_s();
    for (Worker* w : owners) {
      if (w->task && now - w->started_s > wall_limit_s_) TimedOut(*w);
    }
  }

  void Read(Worker& w) {
    char buf[65536];
    const ssize_t n = ::read(w.process.stdout_fd(), buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return;
    if (n <= 0) {
      Died(w);
      return;
    }
    w.buffer.append(buf, static_cast<size_t>(n));
    const size_t nl = w.buffer.find('\n');
    if (nl == std::string::npos) return;
    const std::string line = w.buffer.substr(0, nl);
    w.buffer.erase(0, nl + 1);
    const StudyTask t = *w.task;
    const std::string& engine = study_.engines[t.engine];
    MemberRow row;
    try {
      row = MemberRowFromJson(nlohmann::json::parse(line));
      if (row.member != t.member || row.engine != engine) throw std::runtime_error("not its run");
    } catch (const std::exception& e) {
      row = FailedRow(t.member, engine, "error", std::string("unreadable row: ") + e.what());
      StopWorker(w, true);
    }
    Finish(w, row);
  }

  void Died(Worker& w) {
    const StudyTask t = *w.task;
    const int sig = StopWorker(w, false);
    const std::string status =
        sig != 0 ? "crash (signal " + std::to_string(sig) + ")" : std::string("error");
    const std::string detail = sig != 0 ? std::string("the worker died of ") + strsignal(sig)
                                        : std::string("the worker exited without a row");
    Finish(w, FailedRow(t.member, study_.engines[t.engine], status, detail));
  }

  void TimedOut(Worker& w) {
    const StudyTask t = *w.task;
    StopWorker(w, true);
    char detail[128];
    std::snprintf(detail, sizeof detail, "killed after the study's wall-clock limit of %g s",
                  wall_limit_s_);
    MemberRow row = FailedRow(t.member, study_.engines[t.engine], "wall_limit", detail);
    row.wall_s = wall_limit_s_;
    Finish(w, row);
  }

  const StudyDef& study_;
  StudyScheduler& scheduler_;
  WorkerPoolOptions options_;
  std::vector<Worker> workers_;
  std::vector<std::string> argv_;
  double wall_limit_s_ = 0.0;
};

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

void RunWorkerPool(const StudyDef& study, StudyScheduler& scheduler,
                   const WorkerPoolOptions& options) {
  // A worker that dies must not take the pool with it (a write to its pipe).
  ::signal(SIGPIPE, SIG_IGN);
  Pool pool(study, scheduler, options);
  pool.Run();
}

void RunWorkerLoop(const StudyDef& study, std::FILE* in, std::FILE* out,
                   const std::optional<std::filesystem::path>& keep_dir) {
  long long member = 0;
  int engine = 0;
  while (std::fscanf(in, "%lld %d", &member, &engine) == 2) {
    MemberRow row;
    if (engine < 0 || engine >= static_cast<int>(study.engines.size()) || member < 0 ||
        member >= study.member_count()) {
      row = FailedRow(member, "?", "error", "no such run");
    } else {
      std::optional<std::filesystem::path> dir;
      if (keep_dir) dir = *keep_dir / "members" / std::to_string(member);
      row = RunMemberHere(study, member, study.engines[engine], dir);
    }
    std::fprintf(out, "%s\n", MemberRowToJson(row).dump().c_str());
    std::fflush(out);
  }
}

MembersJournal::MembersJournal(const StudyDef& study, const std::filesystem::path& dir, bool resume)
    : study_(study), path_(dir / "members.csv") {
  done_by_member_.assign(static_cast<size_t>(study.member_count()),
                         std::vector<bool>(study.engines.size(), false));
  const std::string header = MembersCsvHeader(study);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw SceneError(Excerpt(dir.string(), 200) + ": cannot create the folder: " + ec.message());
  const bool exists = std::filesystem::exists(path_);
  if (exists && !resume) {
    throw SceneError(Excerpt(path_.string(), 200) +
                     ": exists (use --resume to go on with it, or another --out folder)");
  }
  size_t keep = 0;
  if (exists) {
    const std::string text = ReadAll(path_);
    if (text.compare(0, header.size(), header) != 0) {
      throw SceneError(Excerpt(path_.string(), 200) +
                       ":1: not this study's members.csv (expected the header " +
                       header.substr(0, header.size() - 1) + ")");
    }
    keep = header.size();
    for (size_t pos = header.size(); pos < text.size();) {
      const size_t nl = text.find('\n', pos);
      if (nl == std::string::npos) break;  // a line cut short: dropped
      const std::optional<RowKey> key = MembersCsvKey(study, text.substr(pos, nl + 1 - pos));
      if (!key) break;
      const int e =
          static_cast<int>(std::find(study.engines.begin(), study.engines.end(), key->engine) -
                           study.engines.begin());
      if (!done_by_member_[key->member][e]) done_.push_back({key->member, e});
      done_by_member_[key->member][e] = true;
      pos = nl + 1;
      keep = pos;
    }
    std::filesystem::resize_file(path_, keep);
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw SceneError(Excerpt(path_.string(), 200) + ": cannot write: " + std::strerror(errno));
  if (!exists) {
    if (::write(fd_, header.data(), header.size()) != static_cast<ssize_t>(header.size())) {
      throw SceneError(Excerpt(path_.string(), 200) + ": cannot write: " + std::strerror(errno));
    }
  }
}

MembersJournal::~MembersJournal() {
  CloseFd(fd_);
}

bool MembersJournal::Has(const StudyTask& t) const {
  return done_by_member_[t.member][t.engine];
}

void MembersJournal::Append(const MemberRow& row) {
  const std::string line = MembersCsvLine(study_, row);
  if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
    throw SceneError(Excerpt(path_.string(), 200) + ": cannot write: " + std::strerror(errno));
  }
  const int e = static_cast<int>(
      std::find(study_.engines.begin(), study_.engines.end(), row.engine) - study_.engines.begin());
  if (e < static_cast<int>(study_.engines.size())) done_by_member_[row.member][e] = true;
}

void MembersJournal::Finish() {
  CloseFd(fd_);
  const std::string text = ReadAll(path_);
  const std::string header = MembersCsvHeader(study_);
  std::vector<std::pair<std::pair<int64_t, int>, std::string>> rows;
  for (size_t pos = header.size(); pos < text.size();) {
    const size_t nl = text.find('\n', pos);
    const std::string line = text.substr(pos, nl + 1 - pos);
    const std::optional<RowKey> key = MembersCsvKey(study_, line);
    if (!key)
      throw SceneError(Excerpt(path_.string(), 200) + ": an unreadable row: " + Excerpt(line, 200));
    const int e =
        static_cast<int>(std::find(study_.engines.begin(), study_.engines.end(), key->engine) -
                         study_.engines.begin());
    rows.push_back({{key->member, e}, line});
    pos = nl + 1;
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto total = static_cast<size_t>(study_.member_count()) * study_.engines.size();
  if (rows.size() != total) {
    throw SceneError(Excerpt(path_.string(), 200) + ": " + std::to_string(rows.size()) +
                     " rows of " + std::to_string(total) + " runs");
  }
  // A temporary name holding ".tmp.<pid>": the wall-clock limit removes it (util/wall_limit.h).
  const std::filesystem::path tmp = path_.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << header;
    for (const auto& r : rows) out << r.second;
    if (!out) throw SceneError(Excerpt(tmp.string(), 200) + ": cannot write");
  }
  std::filesystem::rename(tmp, path_);
}

std::vector<StudyTask> PendingTasks(const StudyDef& study, const MembersJournal& journal) {
  std::vector<StudyTask> tasks;
  for (int64_t m = 0; m < study.member_count(); ++m) {
    for (int e = 0; e < static_cast<int>(study.engines.size()); ++e) {
      if (!journal.Has({m, e})) tasks.push_back({m, e});
    }
  }
  return tasks;
}

LocalScheduler::LocalScheduler(std::vector<StudyTask> tasks, MembersJournal& journal,
                               std::function<void(int64_t, int64_t)> progress)
    : tasks_(std::move(tasks)), journal_(journal), progress_(std::move(progress)) {}

std::optional<StudyTask> LocalScheduler::Next() {
  if (next_ >= tasks_.size()) return std::nullopt;
  return tasks_[next_++];
}

void LocalScheduler::Done(const MemberRow& row) {
  journal_.Append(row);
  ++done_;
  if (progress_) progress_(done_, static_cast<int64_t>(tasks_.size()));
}

}  // namespace rockbench
