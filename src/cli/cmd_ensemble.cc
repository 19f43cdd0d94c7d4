// `rockbench ensemble STUDY.toml --out DIR [--jobs N] [--resume] [--keep-histories]`, and the
// same under `mpirun -n N`: every (member, run) of a study in a worker process
// (`rockbench ensemble STUDY --worker`, hidden), rows to DIR/members.csv as they finish, the
// file in member order at the end, and DIR/study.json (src/study/study_runner.h,
// docs/ensemble.md).
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "files/atomic_file.h"
#include "run/parallel.h"
#include "scene/history.h"
#include "scene/limits.h"
#include "scene/scene.h"
#include "study/study.h"
#include "study/study_mpi.h"
#include "study/study_runner.h"

namespace rockbench::cli {
namespace {

struct EnsembleCliOptions {
  std::string study;
  std::string out;
  int jobs = 0;
  bool resume = false;
  bool keep_histories = false;
  bool list = false;
  bool worker = false;
  LimitOptions limits;  // --memory-budget (every run, workers included), --wall-limit (the study)
  long long worker_parent = -1;  // the pool's pid: the worker ends when that process ends
  // Tests of the isolation: the worker crashes (SIGSEGV) or hangs on this member.
  long long crash_member = -1, hang_member = -1;
};

// The worker: runs on standard input, rows on standard output.
void RunWorker(const StudyDef& study, const EnsembleCliOptions& opt) {
  std::optional<std::filesystem::path> keep;
  if (opt.keep_histories) keep = std::filesystem::path(opt.out);
  if (opt.crash_member < 0 && opt.hang_member < 0) {
    RunWorkerLoop(study, stdin, stdout, keep);
    return;
  }
  // Self-test: read one run at a time and fail on the named member.
  long long member = 0;
  int engine = 0;
  while (std::fscanf(stdin, "%lld %d", &member, &engine) == 2) {
    if (member == opt.crash_member) {
      // No core file for a deliberate crash, and the default action (a sanitizer's handler
      // would turn the signal into an exit status).
      const rlimit none{0, 0};
      ::setrlimit(RLIMIT_CORE, &none);
      std::fflush(nullptr);
      std::signal(SIGSEGV, SIG_DFL);
      std::raise(SIGSEGV);
    }
    if (member == opt.hang_member) {
      while (true) std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    const std::string line = std::to_string(member) + " " + std::to_string(engine) + "\n";
    std::FILE* one = fmemopen(const_cast<char*>(line.data()), line.size(), "r");
    RunWorkerLoop(study, one, stdout, keep);
    std::fclose(one);
  }
}

void List(const StudyDef& study) {
  std::printf("%s: %lld members x %zu runs (", study.path.string().c_str(),
              static_cast<long long>(study.member_count()), study.engines.size());
  for (size_t i = 0; i < study.engines.size(); ++i) {
    std::printf("%s%s", i ? ", " : "", study.engines[i].c_str());
  }
  std::printf(")\n");
  for (const StudyAxis& a : study.axes) {
    const std::string zipped =
        a.zip_with >= 0 ? ", zipped with " + study.axes[a.zip_with].key : std::string();
    std::printf("  %s: %zu values (%s ... %s)%s%s\n", a.key.c_str(), a.values.size(),
                a.values.front().text.c_str(), a.values.back().text.c_str(),
                a.derived ? ", derived" : "", zipped.c_str());
  }
}

void RunStudy(const EnsembleCliOptions& opt, double start_s) {
  // The memory budget holds for every run (a worker is given it); the wall-clock limit for the
  // whole study (its members have the study's wall_limit_s).
  ResourceBudget budget;
  budget.memory_bytes = opt.limits.memory_budget_gib * 1024.0 * 1024 * 1024;
  SetProcessBudget(budget);
  if (opt.worker) {
    // A worker does not outlive its pool (killed, or stopped by --wall-limit): the kernel kills
    // it when the parent ends; a parent already gone ends it now.
    if (opt.worker_parent > 0) {
      // SIGTERM: the worker's handler ends its engines and removes its temporary files first
      // (util/wall_limit.h, main.cc).
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != static_cast<pid_t>(opt.worker_parent)) return;
    }
    // Its parent checked every value of the study: the worker reads it and builds member 0.
    RunWorker(LoadStudy(opt.study, StudyCheck::kFirstMember), opt);
    return;
  }
  const StudyDef study = LoadStudy(opt.study);
  if (opt.list) {
    List(study);
    return;
  }
  if (opt.out.empty()) throw SceneError("--out: required (the study's folder)");
  if (opt.jobs < 0) throw SceneError("--jobs: expected 1 or more (0: every core)");
  const std::filesystem::path dir(opt.out);
  StartLimits(opt.limits, dir, "ensemble");
  const int ranks = LaunchedRanks();
  std::unique_ptr<MpiSession> session;
  if (ranks > 1) session = std::make_unique<MpiSession>();
  const bool root = !session || session->rank() == 0;
  // Under MPI one worker per rank unless told (start one rank per core).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int jobs = opt.jobs > 0 ? opt.jobs : (session ? 1 : cores);
  WorkerPoolOptions pool;
  pool.jobs = jobs;
  pool.out_dir = dir;
  pool.keep_histories = opt.keep_histories;
  pool.worker_log = dir / "workers.log";
  pool.memory_budget_gib = opt.limits.memory_budget_gib;
  if (opt.crash_member >= 0) {
    pool.extra_worker_args = {"--selftest-crash-member", std::to_string(opt.crash_member)};
  }
  if (opt.hang_member >= 0) {
    pool.extra_worker_args = {"--selftest-hang-member", std::to_string(opt.hang_member)};
  }
  if (!session) {
    LocalStudyOptions local;
    local.out_dir = dir;
    local.resume = opt.resume;
    local.pool = pool;
    local.note = [](const std::string& note) {
      std::fprintf(stderr, "rockbench ensemble: note: %s\n", note.c_str());
    };
    ProgressLine line("ensemble");
    local.progress = [&line](int64_t done, int64_t total) {
      line.Update(static_cast<int>(done), static_cast<int>(total));
    };
    RunStudyHere(study, local, start_s);
    std::fprintf(stderr, "ensemble: %lld members x %zu runs in %s\n",
                 static_cast<long long>(study.member_count()), study.engines.size(),
                 (dir / "members.csv").string().c_str());
    return;
  }
  // Under MPI: rank 0 holds the journal, every rank runs a pool.
  if (!root) {
    session->Barrier();  // rank 0 has opened the journal (and created the folder)
    std::unique_ptr<StudyScheduler> s = MakeMpiRankScheduler(*session);
    RunWorkerPool(study, *s, pool);
    session->Barrier();
    return;
  }
  std::unique_ptr<MembersJournal> opened;
  try {
    opened = std::make_unique<MembersJournal>(study, dir, opt.resume);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rockbench ensemble: %s\n", e.what());
    session->Abort(kExitBadInput);  // the other ranks wait for rank 0
  }
  MembersJournal& journal = *opened;
  // What the resume let through (a blank line, a row cut short, a second row of a run).
  for (const std::string& note : journal.notes()) {
    std::fprintf(stderr, "rockbench ensemble: note: %s\n", note.c_str());
  }
  std::vector<StudyTask> tasks = PendingTasks(study, journal);
  const double serial_start_s = StudyClock_s() - start_s;
  ProgressLine line("ensemble");
  auto progress = [&](int64_t done, int64_t total) {
    line.Update(static_cast<int>(done), static_cast<int>(total));
  };
  session->Barrier();
  std::unique_ptr<StudyScheduler> s =
      MakeMpiRootScheduler(*session, std::move(tasks), journal, progress);
  RunWorkerPool(study, *s, pool);
  const double merge_start_s = StudyClock_s();
  journal.Finish();
  const double merge_s = StudyClock_s() - merge_start_s;
  WriteStudyJson(study, dir, ranks, jobs, StudyClock_s() - start_s, serial_start_s + merge_s,
                 journal.rows_at_open());
  session->Barrier();
  std::fprintf(stderr, "ensemble: %lld members x %zu runs in %s\n",
               static_cast<long long>(study.member_count()), study.engines.size(),
               (dir / "members.csv").string().c_str());
}

}  // namespace

void RegisterEnsemble(CLI::App& app) {
  auto opt = std::make_shared<EnsembleCliOptions>();
  auto* cmd = app.add_subcommand(
      "ensemble", "Run a study (members x runs) on every core, or under mpirun on many ranks");
  cmd->add_option("study", opt->study, "The study file (TOML; docs/ensemble.md)")->required();
  cmd->add_option("--out", opt->out, "Output folder: members.csv, study.json");
  cmd->add_option("--jobs", opt->jobs, "Worker processes (per rank under MPI); 0: every core");
  cmd->add_flag("--resume", opt->resume, "Go on with DIR/members.csv, skipping its rows");
  cmd->add_flag("--keep-histories", opt->keep_histories,
                "Write each run's history.csv and events.csv under DIR/members/ID/ENGINE/");
  cmd->add_flag("--list", opt->list, "Print the study's members and axes, run nothing");
  cmd->add_flag("--worker", opt->worker)->group("");
  cmd->add_option("--worker-parent", opt->worker_parent)->group("");
  cmd->add_option("--selftest-crash-member", opt->crash_member)->group("");
  cmd->add_option("--selftest-hang-member", opt->hang_member)->group("");
  AddLimitOptions(cmd, &opt->limits);
  cmd->callback([opt] {
    const double start_s = StudyClock_s();
    try {
      RunStudy(*opt, start_s);
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr,
                   "rockbench ensemble: out of memory (std::bad_alloc) reading or scheduling "
                   "the study %s\n",
                   Excerpt(opt->study, 200).c_str());
      throw CLI::RuntimeError(kExitBadInput);
    } catch (const std::exception& e) {
      // Messages name their values in excerpts; this keeps any other one to a few lines.
      constexpr size_t kMaxMessageChars = 2000;
      const std::string what = e.what();
      std::fprintf(
          stderr, "rockbench ensemble: %s\n",
          what.size() > kMaxMessageChars ? Excerpt(what, kMaxMessageChars).c_str() : what.c_str());
      throw CLI::RuntimeError(kExitBadInput);
    }
  });
}

}  // namespace rockbench::cli
