// rockbench-bullet-float: the single-precision Bullet engine as a program of its own, run by
// rockbench for scenes with [bullet] precision = "float" (see engines/bullet/float_helper.h).
// Usage: rockbench-bullet-float --input IN --output OUT (files in engines/bullet/protocol.h).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/protocol.h"

int main(int argc, char** argv) {
  std::string in_path, out_path;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--input") == 0 && i + 1 < argc) {
      in_path = argv[++i];
    } else if (std::strcmp(argv[i], "--output") == 0 && i + 1 < argc) {
      out_path = argv[++i];
    } else if (std::strcmp(argv[i], "--precision") == 0) {
      std::printf("%s\n", rockbench::bullet::CompiledPrecision());
      return 0;
    } else {
      std::fprintf(stderr,
                   "usage: rockbench-bullet-float --input IN --output OUT\n"
                   "  (run by rockbench for [bullet] precision = \"float\"; not meant for "
                   "direct use)\n");
      return 2;
    }
  }
  if (in_path.empty() || out_path.empty()) {
    std::fprintf(stderr, "rockbench-bullet-float: --input and --output are required\n");
    return 2;
  }
  try {
    const rockbench::bullet::BulletInput input =
        rockbench::bullet::ParseInput(rockbench::bullet::ReadBinaryFile(in_path));
    const rockbench::EngineResult output = rockbench::bullet::Simulate(input);
    rockbench::bullet::WriteBinaryFile(out_path, rockbench::bullet::SerializeOutput(output));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rockbench-bullet-float: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
