#include "harness/engines.h"

#include <chrono>
#include <cstdio>

#include "harness/convergence.h"
#include "harness/summary.h"
#include "reference/simulate.h"
#ifdef ROCKBENCH_HAVE_BULLET
#include "harness/engines_bullet.h"
#endif

namespace rockbench {

std::vector<std::string> AvailableEngines() {
  std::vector<std::string> names = {"reference"};
#ifdef ROCKBENCH_HAVE_BULLET
  names.push_back("bullet");
#endif
  return names;
}

EngineRun RunEngine(const std::string& name, const Scene& scene, const GroundMotion& motion,
                    const RunEngineOptions& options) {
  if (name == "reference") {
    const CheckedReference checked = RunCheckedReference(scene, motion, options.reference_witness);
    EngineRun run = ReferenceRunOf(scene, checked);
    const reference::Summary& s = checked.used().summary;
    char line[256];
    std::snprintf(line, sizeof line,
                  "reference: %s, peak |theta1| %.4g rad at %.3f s, peak |theta2| %.4g rad at "
                  "%.3f s, %d impacts, %.3g ms",
                  s.status.c_str(), s.peak_theta1_rad, s.peak_theta1_t_s, s.peak_theta2_rad,
                  s.peak_theta2_t_s, s.impacts_ground + s.impacts_interface, run.wall_s * 1e3);
    run.one_line = line;
    if (checked.check && !checked.check->converged) {
      run.one_line += "\n  WARNING: " + ConvergenceWarning(*checked.check);
    }
    return run;
  }
#ifdef ROCKBENCH_HAVE_BULLET
  if (name == "bullet") return RunBulletEngine(scene, motion, options.stop_at_rest_after_s);
#endif
  std::string known;
  for (const auto& n : AvailableEngines()) known += (known.empty() ? "" : ", ") + n;
  throw SceneError("unknown engine '" + name + "' (this build has: " + known + ")");
}

void WriteEngineFiles(const EngineRun& run, const std::filesystem::path& out_dir) {
  const auto dir = out_dir / run.engine;
  std::filesystem::create_directories(dir);
  WriteFileAtomic(dir / "history.csv", HistoryToCsv(run.history));
  WriteFileAtomic(dir / "events.csv", EventsToCsv(run.history));
}

}  // namespace rockbench
