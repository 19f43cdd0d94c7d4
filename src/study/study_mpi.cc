// A study on several MPI ranks: rank 0 hands out runs and writes the rows (study_mpi.h).
#include "study/study_mpi.h"

#include <cstdint>
#include <cstdlib>
#include <string>

#ifdef ROCKBENCH_HAVE_MPI
#include <mpi.h>
#endif

namespace rockbench {

int LaunchedRanks() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* v = std::getenv(var)) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  }
  return 1;
}

#ifndef ROCKBENCH_HAVE_MPI

bool MpiBuilt() {
  return false;
}

std::string MpiMissingReason() {
  return ROCKBENCH_MPI_MISSING;
}

MpiSession::MpiSession() {
  throw SceneError("this rockbench was built without MPI (" + MpiMissingReason() +
                   "); run the study without mpirun, or rebuild with libopenmpi-dev");
}
MpiSession::~MpiSession() = default;
void MpiSession::Barrier() const {}
double MpiSession::Broadcast(double v) const {
  return v;
}
void MpiSession::Abort(int exit_code) const {
  std::exit(exit_code);
}

std::unique_ptr<StudyScheduler> MakeMpiRootScheduler(const MpiSession&, std::vector<StudyTask>,
                                                     MembersJournal&,
                                                     std::function<void(int64_t, int64_t)>) {
  return nullptr;
}

std::unique_ptr<StudyScheduler> MakeMpiRankScheduler(const MpiSession&) {
  return nullptr;
}

#else

namespace {

// Message tags: a rank asks for a run, rank 0 answers with one (member -1: none left), a rank
// sends a row (its JSON text).
constexpr int kTagRequest = 1, kTagTask = 2, kTagRow = 3;

class RootScheduler : public LocalScheduler {
 public:
  RootScheduler(const MpiSession& session, std::vector<StudyTask> tasks, MembersJournal& journal,
                std::function<void(int64_t, int64_t)> progress)
      : LocalScheduler(std::move(tasks), journal, std::move(progress)),
        active_ranks_(session.size() - 1) {}

  void Service() override {
    int flag = 0;
    MPI_Status status;
    while (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status) == MPI_SUCCESS &&
           flag) {
      if (status.MPI_TAG == kTagRequest) {
        MPI_Recv(nullptr, 0, MPI_BYTE, status.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        int64_t task[2] = {-1, 0};
        if (const std::optional<StudyTask> t = Next()) {
          task[0] = t->member;
          task[1] = t->engine;
          ++outstanding_;
        } else {
          --active_ranks_;
        }
        MPI_Send(task, 2, MPI_INT64_T, status.MPI_SOURCE, kTagTask, MPI_COMM_WORLD);
      } else {
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string text(static_cast<size_t>(length), '\0');
        MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagRow, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        --outstanding_;
        Done(MemberRowFromJson(nlohmann::json::parse(text)));
      }
    }
  }

  double service_interval_s() const override { return 0.002; }

  bool Finished() override { return active_ranks_ == 0 && outstanding_ == 0; }

 private:
  int active_ranks_ = 0;
  int64_t outstanding_ = 0;  // runs handed to other ranks whose rows have not come back
};

// A rank keeps one request in flight: it asks for its next run as soon as it receives one, so
// that rank 0's answer (rank 0 serves requests between its own runs, every 2 ms) arrives while
// this run is being computed instead of after it. A rank that dies loses the run it holds in
// reserve with the ones in flight.
class RankScheduler : public StudyScheduler {
 public:
  std::optional<StudyTask> Next() override {
    if (stopped_) return std::nullopt;
    if (!requested_) Request();
    int64_t task[2];
    MPI_Recv(task, 2, MPI_INT64_T, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    requested_ = false;
    if (task[0] < 0) {
      stopped_ = true;
      return std::nullopt;
    }
    Request();
    return StudyTask{task[0], static_cast<int>(task[1])};
  }

  void Done(const MemberRow& row) override {
    const std::string text = MemberRowToJson(row).dump();
    MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kTagRow, MPI_COMM_WORLD);
  }

 private:
  void Request() {
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagRequest, MPI_COMM_WORLD);
    requested_ = true;
  }

  bool stopped_ = false;
  bool requested_ = false;  // a request sent whose answer has not been received
};

}  // namespace

bool MpiBuilt() {
  return true;
}

std::string MpiMissingReason() {
  return {};
}

MpiSession::MpiSession() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

void MpiSession::Barrier() const {
  MPI_Barrier(MPI_COMM_WORLD);
}

double MpiSession::Broadcast(double v) const {
  MPI_Bcast(&v, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return v;
}

void MpiSession::Abort(int exit_code) const {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);
}

std::unique_ptr<StudyScheduler> MakeMpiRootScheduler(
    const MpiSession& session, std::vector<StudyTask> tasks, MembersJournal& journal,
    std::function<void(int64_t, int64_t)> progress) {
  return std::make_unique<RootScheduler>(session, std::move(tasks), journal, std::move(progress));
}

std::unique_ptr<StudyScheduler> MakeMpiRankScheduler(const MpiSession&) {
  return std::make_unique<RankScheduler>();
}

#endif

}  // namespace rockbench
