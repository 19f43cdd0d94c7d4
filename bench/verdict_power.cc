// Power and false-alarm rate of the statistical verdict (src/compare/verdict_power.h) on the
// shipped scenes, for a range of ensemble sizes. Not a timing benchmark: it prints, per scene and
// size, how often a synthetic engine with a 5% peak bias is detected and how often an unbiased
// one is flagged. Results are recorded in docs/verdicts.md.
//
//   build/bench/verdict_power [--trials T] [--bias B] [SCENE ...]
#include "compare/verdict_power.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace rockbench;
  PowerConfig base;
  std::vector<std::string> scenes;
  std::vector<std::pair<int, int>> sizes = {{16, 8}, {32, 16}, {64, 16}, {64, 32}, {128, 64}};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--trials" && i + 1 < argc) {
      base.trials = std::atoi(argv[++i]);
    } else if (a == "--bias" && i + 1 < argc) {
      base.bias = std::atof(argv[++i]);
    } else if (a == "--sizes" && i + 1 < argc) {
      sizes.clear();
      std::string list = argv[++i];
      size_t pos = 0;
      while (pos < list.size()) {
        const size_t comma = list.find(',', pos);
        const std::string item = list.substr(pos, comma == std::string::npos ? comma : comma - pos);
        const size_t x = item.find('x');
        sizes.push_back(
            {std::atoi(item.substr(0, x).c_str()), std::atoi(item.substr(x + 1).c_str())});
        if (comma == std::string::npos) break;
        pos = comma + 1;
      }
    } else {
      scenes.push_back(a);
    }
  }
  if (scenes.empty()) {
    for (const char* s : {"thesis_rinaldi228", "harmonic", "kobe_stack_vertical"}) {
      scenes.push_back(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/" + s + ".toml");
    }
  }
  std::printf("scene,reference_members,engine_members,bias,trials,power,false_alarm_rate\n");
  for (const std::string& path : scenes) {
    const Scene scene = LoadScene(path);
    const GroundMotion motion = GroundMotion::FromScene(scene);
    for (const auto& [n, m] : sizes) {
      PowerConfig c = base;
      c.reference_members = n;
      c.engine_members = m;
      const PowerEstimate e = EstimateVerdictPower(scene, motion, c);
      std::printf("%s,%d,%d,%g,%d,%.3f,%.3f\n", path.c_str(), n, m, c.bias, e.trials, e.power(),
                  e.false_alarm_rate());
      std::fflush(stdout);
    }
  }
  return 0;
}
