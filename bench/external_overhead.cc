// The external-engine protocol's overhead (docs/external-engines.md): Bullet's own steps are
// recorded in process, then replayed through the protocol by a command that only copies them
// to the poses file. The replay's wall time beyond its command's own (writing the input, starting
// the command, reading the poses and the monitor's pass over them) is the protocol's cost; the
// in-process Bullet run (which runs the same monitor) is beside it. Median of 5 runs each.
//   external_overhead [SCENE ...]   (default: Housner's block and the thesis stack)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/rocking_world.h"
#include "engines/external/external_engine.h"
#include "engines/external/protocol.h"
#include "motion/ground_motion.h"
#include "run/engine_run.h"
#include "tests/common/bullet_steps.h"

using namespace rockbench;

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void Measure(const std::string& file, const std::string& dt) {
  const Scene s = LoadScene(file, {"bullet.time_step=" + dt});
  const GroundMotion motion = GroundMotion::FromScene(s);
  const bullet::BulletInput in = bullet::MakeBulletInput(s, motion);
  const std::vector<StepReadout> steps = testing_util::RecordBulletSteps(in);
  const auto dir = std::filesystem::temp_directory_path() / "rockbench_external_overhead";
  std::filesystem::create_directories(dir);
  const auto saved = dir / "bullet_poses.csv";
  {
    std::ofstream out(saved);
    external::WritePoses(out, steps);
  }
  ExternalEngineRef ref;
  ref.name = "replay";
  ref.where = "bench";
  ref.base_dir = dir;
  ref.command = {"sh", "-c", "cp '" + saved.string() + "' \"$(dirname \"$0\")/poses.csv\""};
  const external::ExternalEngine replay(external::LoadManifest(ref));
  Scene rs = s;
  rs.engine_tables["replay"].values["time_step"] = RawSetting{std::stod(dt), "bench"};
  std::vector<double> bullet_s, total_s, process_s, overhead_s, read_s, monitor_s;
  for (int i = 0; i < 5; ++i) {
    bullet_s.push_back(RunEngine("bullet", s, motion).wall_s);
    const EngineResult r = replay.Simulate(rs, motion, {});
    const auto& x = r.summary.at("external");
    total_s.push_back(r.wall_s);
    process_s.push_back(x.at("process_wall_s").get<double>());
    overhead_s.push_back(x.at("overhead_s").get<double>());
    read_s.push_back(x.at("read_s").get<double>());
    monitor_s.push_back(x.at("monitor_s").get<double>());
  }
  std::printf("%-28s %6s %8zu %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f %8.1f\n",
              std::filesystem::path(file).filename().c_str(), dt.c_str(), steps.size(),
              Median(bullet_s) * 1e3, Median(total_s) * 1e3, Median(process_s) * 1e3,
              Median(overhead_s) * 1e3, Median(read_s) * 1e3, Median(monitor_s) * 1e3,
              static_cast<double>(std::filesystem::file_size(saved)) / 1e6);
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) scenes.push_back(argv[i]);
  if (scenes.empty()) {
    scenes = {std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/housner_free_rocking.toml",
              std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/thesis_free_rocking.toml"};
  }
  std::printf("%-28s %6s %8s %10s %10s %10s %10s %10s %10s %8s\n", "scene", "dt_s", "rows",
              "bullet_ms", "replay_ms", "command_ms", "overhd_ms", "read_ms", "monitor_ms",
              "poses_MB");
  for (const std::string& f : scenes) {
    for (const char* dt : {"1e-3", "1e-4"}) Measure(f, dt);
  }
}
