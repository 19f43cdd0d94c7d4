// The pool of worker processes, the worker's loop and the journal of a study.
#include "study/study_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "files/atomic_file.h"
#include "run/engine_run.h"
#include "scene/history.h"
#include "scene/limits.h"
#include "util/stop_request.h"
#include "util/subprocess.h"
#include "util/wall_limit.h"

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
      // An embedding program's stop request (util/stop_request.h): a busy worker gets SIGTERM,
      // whose handler ends its engines and removes its temporary files; its run has no row.
      if (StopWasRequested()) {
        for (Worker& w : workers_) {
          if (w.task && w.process.running()) w.process.Kill(SIGTERM);
          if (w.process.started()) StopWorker(w, false);
          w.task.reset();
        }
        throw StopRequested();
      }
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

namespace {

// The cells of one line (its newline left out): members.csv's cells hold no ',' (TextCell).
std::vector<std::string_view> Cells(std::string_view line) {
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  std::vector<std::string_view> cells;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

std::optional<int64_t> MemberNumber(std::string_view cell, const StudyDef& study) {
  int64_t m = -1;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), m);
  if (r.ec != std::errc() || r.ptr != cell.data() + cell.size()) return std::nullopt;
  if (m < 0 || m >= study.member_count()) return std::nullopt;
  return m;
}

// One row of the journal as read back.
struct JournalRow {
  int64_t member = 0;
  int engine = 0;  // index into StudyDef::engines
  size_t line = 0;
  std::string text;  // with its newline
};

// The journal's text read back: its rows (complete, of this study, a run's first), and the
// length of a last line cut short (0: none).
struct JournalScan {
  std::vector<JournalRow> rows;
  size_t cut_short_bytes = 0;
  std::vector<std::string> notes;
};

// Reads members.csv's text after its header; throws SceneError naming `name`:LINE for a line
// that is not a row of this study as it is now.
JournalScan ScanJournal(const StudyDef& study, const std::string& text, const std::string& name) {
  const std::string header = MembersCsvHeader(study);
  const std::vector<std::string_view> columns = Cells(header);
  const size_t engine_column =
      static_cast<size_t>(std::find(columns.begin(), columns.end(), "engine") - columns.begin());
  JournalScan scan;
  std::vector<std::vector<size_t>> first_line(static_cast<size_t>(study.member_count()),
                                              std::vector<size_t>(study.engines.size(), 0));
  const auto refuse = [&](size_t line, const std::string& why) {
    throw SceneError(name + ":" + std::to_string(line) + ": " + why +
                     "; no row was dropped: repair the line, or run the study into another "
                     "--out folder");
  };
  size_t line = 1;
  for (size_t pos = header.size(); pos < text.size();) {
    ++line;
    const size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) {
      // A kill in the middle of an append leaves the beginning of a row: its member number
      // (whole, or its first digits) and maybe more cells.
      const std::string_view tail(text.data() + pos, text.size() - pos);
      const std::string_view first = Cells(tail).front();
      const bool digits = !first.empty() && first.size() <= 19 &&
                          first.find_first_not_of("0123456789") == std::string_view::npos;
      if (!digits) {
        refuse(line, "a last line without its end that is not the beginning of a row (" +
                         Excerpt(tail, 60) + ")");
      }
      scan.cut_short_bytes = tail.size();
      scan.notes.push_back(name + ":" + std::to_string(line) +
                           ": the last line is cut short (a run killed while its row was "
                           "written): removed, its run is made again");
      break;
    }
    const std::string_view text_line(text.data() + pos, nl + 1 - pos);
    pos = nl + 1;
    if (text_line.find_first_not_of(" \t\r\n") == std::string_view::npos) {
      scan.notes.push_back(name + ":" + std::to_string(line) + ": a blank line, skipped");
      continue;
    }
    const std::vector<std::string_view> cells = Cells(text_line);
    if (cells.size() != columns.size()) {
      refuse(line, "not a row of this study: " + std::to_string(cells.size()) + " cells, the " +
                       "header has " + std::to_string(columns.size()) + " (" +
                       Excerpt(text_line, 60) + ")");
    }
    const std::optional<int64_t> member = MemberNumber(cells[0], study);
    if (!member) {
      refuse(line, "member \"" + Excerpt(cells[0], 40) + "\": not a member of this study (0 to " +
                       std::to_string(study.member_count() - 1) + ")");
    }
    const std::string_view engine_name = cells[engine_column];
    const auto e = std::find(study.engines.begin(), study.engines.end(), engine_name);
    if (e == study.engines.end()) {
      std::string list;
      for (const std::string& n : study.engines) list += (list.empty() ? "" : ", ") + n;
      refuse(line, "member " + std::to_string(*member) + ": engine \"" + Excerpt(engine_name, 40) +
                       "\" is not one of the study's (" + list +
                       "): the study was edited since this row was made");
    }
    // The row's axis values against those the study gives its member now.
    const std::string expected_line =
        MembersCsvLine(study, FailedRow(*member, std::string(engine_name), "", ""));
    const std::vector<std::string_view> expected = Cells(expected_line);
    for (size_t k = 0; k < study.axes.size(); ++k) {
      if (cells[1 + k] != expected[1 + k]) {
        refuse(line, "member " + std::to_string(*member) + " (" + std::string(engine_name) +
                         ") was run with " + study.axes[k].key + " = " + Excerpt(cells[1 + k], 40) +
                         ", the study gives it " + Excerpt(expected[1 + k], 40) +
                         " now: the study was edited since this row was made");
      }
    }
    const int engine = static_cast<int>(e - study.engines.begin());
    size_t& first = first_line[static_cast<size_t>(*member)][static_cast<size_t>(engine)];
    if (first != 0) {
      scan.notes.push_back(name + ":" + std::to_string(line) + ": a second row of member " +
                           std::to_string(*member) + ", engine " + std::string(engine_name) +
                           " (line " + std::to_string(first) + " is kept), skipped");
      continue;
    }
    first = line;
    scan.rows.push_back({*member, engine, line, std::string(text_line)});
  }
  return scan;
}

// FNV-1a, 64 bits, in hex: a file's fingerprint.
std::string Fnv1a64(const std::string& bytes) {
  uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

// Holds DIR/members.lock (flock, exclusive) and writes this process's pid in it; throws
// SceneError naming the folder and the holder's pid when another process holds it.
int LockStudyFolder(const std::filesystem::path& dir) {
  const std::filesystem::path lock = dir / "members.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw SceneError(Excerpt(lock.string(), 200) + ": cannot open: " + std::strerror(errno));
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char buf[32] = {};
    const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
    std::string holder(buf, n > 0 ? static_cast<size_t>(n) : 0);
    while (!holder.empty() && holder.back() == '\n') holder.pop_back();
    if (holder.empty() || holder.find_first_not_of("0123456789") != std::string::npos) {
      holder = "unknown";
    }
    ::close(fd);
    if (err == EWOULDBLOCK) {
      throw SceneError(Excerpt(dir.string(), 200) + ": another rockbench ensemble (pid " + holder +
                       ") is writing this study folder (it holds " + Excerpt(lock.string(), 200) +
                       "): wait for it to end, or use another --out folder");
    }
    throw SceneError(Excerpt(lock.string(), 200) + ": cannot lock: " + std::strerror(err));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
    const int err = errno;
    ::close(fd);
    throw SceneError(Excerpt(lock.string(), 200) + ": cannot write: " + std::strerror(err));
  }
  return fd;
}

// Compares DIR/members.study with the study's inputs now: throws SceneError naming the first
// that differs.
void CheckStudyInputs(const StudyDef& study, const std::filesystem::path& file,
                      std::vector<std::string>* notes) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    notes->push_back(Excerpt(file.string(), 200) +
                     ": absent (a folder made before rockbench kept it): the base scene, `set`, "
                     "combine and blocks could not be compared with the rows'; their axis "
                     "values were");
    return;
  }
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
      if (!l.empty() && l[0] != '#') out.push_back(l);
    }
    return out;
  };
  const std::vector<std::string> was = lines(ReadAll(file));
  const std::vector<std::string> now = lines(StudyInputsText(study));
  for (size_t k = 0; k < std::max(was.size(), now.size()); ++k) {
    const std::string a = k < was.size() ? was[k] : "(none)";
    const std::string b = k < now.size() ? now[k] : "(none)";
    if (a == b) continue;
    throw SceneError(Excerpt(file.string(), 200) + ":" + std::to_string(k + 2) + ": " +
                     Excerpt(a, 120) + " when the rows were made, the study gives " +
                     Excerpt(b, 120) +
                     " now: the study was edited since; resume with the study the folder was "
                     "made with, or run it into another --out folder");
  }
}

}  // namespace

std::string StudyInputsText(const StudyDef& study) {
  std::string t =
      "# The inputs of members.csv's rows that its columns do not show; rockbench ensemble "
      "--resume compares them with the study's.\n";
  std::string bytes;
  {
    std::ifstream in(study.scene_path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    bytes = s.str();
  }
  t += "scene_bytes_fnv1a64 = " + Fnv1a64(bytes) + "\n";
  for (const std::string& o : study.overrides) t += "set = " + nlohmann::json(o).dump() + "\n";
  t += std::string("combine = ") + (study.combine == StudyCombine::kZip ? "zip" : "product") + "\n";
  t += "blocks = " + std::to_string(study.blocks) + "\n";
  // A cylinder study says so (a planar study's file has no such line).
  if (study.cylinder) t += "body = cylinder\n";
  // Paired axes (zip_with): how the values were paired is an input the rows show only in part.
  for (const StudyAxis& a : study.axes) {
    if (a.zip_with >= 0) {
      t += "zip_with = " + nlohmann::json(a.key + " with " + study.axes[a.zip_with].key).dump() +
           "\n";
    }
  }
  t += "min_impact_rate_radps = " + ShortestText(study.min_impact_rate_radps) + "\n";
  return t;
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
  // One writer per folder: held until the journal closes (the process ends).
  lock_fd_ = LockStudyFolder(dir);
  try {
    const bool exists = std::filesystem::exists(path_);
    if (exists && !resume) {
      throw SceneError(Excerpt(path_.string(), 200) +
                       ": exists (use --resume to go on with it, or another --out folder)");
    }
    if (exists) {
      const std::string text = ReadAll(path_);
      if (text.compare(0, header.size(), header) != 0) {
        throw SceneError(Excerpt(path_.string(), 200) +
                         ":1: not this study's members.csv (expected the header " +
                         header.substr(0, header.size() - 1) + ")");
      }
      CheckStudyInputs(study, dir / "members.study", &notes_);
      JournalScan scan = ScanJournal(study, text, Excerpt(path_.string(), 200));
      for (const JournalRow& r : scan.rows) {
        done_.push_back({r.member, r.engine});
        done_by_member_[r.member][r.engine] = true;
      }
      notes_.insert(notes_.end(), scan.notes.begin(), scan.notes.end());
      // Only a last line cut short is removed (appends start on a line of their own).
      if (scan.cut_short_bytes > 0) {
        std::filesystem::resize_file(path_, text.size() - scan.cut_short_bytes);
      }
    } else {
      WriteFileAtomic(dir / "members.study", StudyInputsText(study));
    }
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw SceneError(Excerpt(path_.string(), 200) + ": cannot write: " + std::strerror(errno));
    if (!exists) {
      if (::write(fd_, header.data(), header.size()) != static_cast<ssize_t>(header.size())) {
        throw SceneError(Excerpt(path_.string(), 200) + ": cannot write: " + std::strerror(errno));
      }
    }
  } catch (...) {
    CloseFd(fd_);
    CloseFd(lock_fd_);
    throw;
  }
}

MembersJournal::~MembersJournal() {
  CloseFd(fd_);
  CloseFd(lock_fd_);
}

bool MembersJournal::Has(const StudyTask& t) const {
  return done_by_member_[t.member][t.engine];
}

void MembersJournal::Append(const MemberRow& row) {
  // A run ended by the process's own end (a signal, the wall-clock limit) is no row: the
  // thread is held until the process ends (util/wall_limit.h), and a resume makes the run.
  HoldIfEnding();
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
  if (text.compare(0, header.size(), header) != 0) {
    throw SceneError(Excerpt(path_.string(), 200) + ":1: the header changed while the study ran");
  }
  JournalScan scan = ScanJournal(study_, text, Excerpt(path_.string(), 200));
  std::vector<JournalRow>& rows = scan.rows;
  std::stable_sort(rows.begin(), rows.end(), [](const JournalRow& a, const JournalRow& b) {
    return std::pair(a.member, a.engine) < std::pair(b.member, b.engine);
  });
  const auto total = static_cast<size_t>(study_.member_count()) * study_.engines.size();
  if (rows.size() != total) {
    throw SceneError(Excerpt(path_.string(), 200) + ": " + std::to_string(rows.size()) +
                     " rows of " + std::to_string(total) + " runs");
  }
  // Written to a registered temporary name and renamed (util/wall_limit.h).
  std::string sorted = header;
  for (const JournalRow& r : rows) sorted += r.text;
  WriteFileAtomic(path_, sorted);
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

void WriteStudyJson(const StudyDef& study, const std::filesystem::path& dir, int ranks, int jobs,
                    double wall_s, double serial_s, int64_t resumed_rows) {
  nlohmann::json j = {{"study", study.path.string()},
                      {"title", study.title},
                      {"scene", study.scene_path.string()},
                      {"members", study.member_count()},
                      {"engines", study.engines},
                      {"ranks", ranks},
                      {"jobs_per_rank", jobs},
                      {"wall_s", wall_s},
                      {"serial_s", serial_s},
                      {"rows_resumed", resumed_rows}};
  // N >= 3 blocks: how many (members.csv has their columns); one and two blocks: no key.
  if (study.blocks >= 3) j["blocks"] = study.blocks;
  // A cylinder study: its body (a planar study has no key).
  if (study.cylinder) j["body"] = "cylinder";
  for (const StudyAxis& a : study.axes) {
    nlohmann::json values = nlohmann::json::array();
    for (const AxisValue& v : a.values) values.push_back(v.text);
    nlohmann::json axis = {{"key", a.key}, {"values", values}, {"derived", a.derived}};
    if (a.zip_with >= 0) axis["zip_with"] = study.axes[a.zip_with].key;
    j["axes"].push_back(axis);
  }
  // Written to a registered temporary name and renamed (util/wall_limit.h).
  WriteFileAtomic(dir / "study.json", j.dump(2) + "\n");
}

double StudyClock_s() {
  return Now_s();
}

void RunStudyHere(const StudyDef& study, const LocalStudyOptions& options, double start_s) {
  MembersJournal journal(study, options.out_dir, options.resume);
  // What the resume let through (a blank line, a row cut short, a second row of a run).
  if (options.note) {
    for (const std::string& note : journal.notes()) options.note(note);
  }
  std::vector<StudyTask> tasks = PendingTasks(study, journal);
  const double serial_start_s = StudyClock_s() - start_s;
  LocalScheduler scheduler(std::move(tasks), journal, options.progress);
  RunWorkerPool(study, scheduler, options.pool);
  const double merge_start_s = StudyClock_s();
  journal.Finish();
  const double merge_s = StudyClock_s() - merge_start_s;
  WriteStudyJson(study, options.out_dir, 1, options.pool.jobs, StudyClock_s() - start_s,
                 serial_start_s + merge_s, journal.rows_at_open());
}

}  // namespace rockbench
