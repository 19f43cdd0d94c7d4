#pragma once
/// A study on several MPI ranks (`mpirun -n N rockbench ensemble ...`). Rank 0 reads the
/// journal, hands out runs one at a time to whichever rank asks (its own workers included), and
/// alone writes members.csv; the other ranks run their runs on their own worker pools and send
/// each row to rank 0 as soon as it is done. Rows depend only on (study, member, engine), so the
/// file is the same at any number of ranks. Built only when CMake found MPI (FindMPI); a build
/// without it says so and refuses to run under mpirun.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "study/study_runner.h"

namespace rockbench {

/// Whether this build has MPI, and if not, why ("MPI not found at configure time ...").
bool MpiBuilt();
std::string MpiMissingReason();

/// The number of ranks the launcher started (OMPI_COMM_WORLD_SIZE, PMI_SIZE or
/// PMIX_SIZE / SLURM_NTASKS under srun); 1 when not launched by mpirun or srun.
int LaunchedRanks();

/// MPI_Init and MPI_Finalize around a study. Throws SceneError when the build has no MPI.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Every rank waits here for the others.
  void Barrier() const;
  /// Rank 0's value of `v` on every rank.
  double Broadcast(double v) const;
  /// Ends every rank (a rank that cannot go on: the others would wait for it).
  [[noreturn]] void Abort(int exit_code) const;

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0's scheduler: `tasks` (the journal's pending runs) for itself and the other ranks,
/// rows to `journal`, progress as on one machine.
std::unique_ptr<StudyScheduler> MakeMpiRootScheduler(
    const MpiSession& session, std::vector<StudyTask> tasks, MembersJournal& journal,
    std::function<void(int64_t done, int64_t total)> progress);

/// Another rank's scheduler: asks rank 0 for runs, sends it the rows.
std::unique_ptr<StudyScheduler> MakeMpiRankScheduler(const MpiSession& session);

}  // namespace rockbench
