// Fuzz target poses_reader: an external engine's poses file as rockbench reads it back
// (rockbench::external::ReadPoses, engines/external/protocol.h). Input: one byte choosing the run
// (1 to 3 blocks; poses every 1, 2 or 3 steps of a 0.005 s run at 1e-3 s: 6, 4 or 3 rows), then
// the file's bytes. The contract (issue 38): the reader returns the rows the run promised, or
// throws ExternalEngineError; a message shows the file's text quoted (no control byte, no byte
// past ASCII) and cut (a message of bounded length); the rows it returns have finite values but
// in a last row that carries the engine's fault, at the rows' times. Anything else is a finding.
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "engines/external/protocol.h"
#include "motion/ground_motion.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

using rockbench::external::ExpectedRows;
using rockbench::external::ExternalEngineError;
using rockbench::external::PoseRows;
using rockbench::external::ReadPoses;
using rockbench::external::RowStep;

// The run input of `blocks` blocks (a stack of 0.5 m x 1 m blocks, 0.005 s at 1e-3 s).
const rockbench::EngineInput& Input(int blocks) {
  static const auto make = [](int n) {
    std::string text;
    for (int k = 0; k < n; ++k) text += "[[block]]\nwidth = 0.5\nheight = 1.0\ndensity = 2000.0\n";
    text += "[run]\nduration = 0.005\noutput_interval = 0.001\n";
    const rockbench::Scene s = rockbench::ParseScene(text, "fuzz.toml");
    return rockbench::MakeEngineInput(s, rockbench::GroundMotion(), "fuzz", 1e-3,
                                      rockbench::DriveKind::kInertial, 0.0);
  };
  static const rockbench::EngineInput inputs[3] = {make(1), make(2), make(3)};
  return inputs[blocks - 1];
}

// The longest message: the engine, the path, the line and a field of at most 60 bytes shown as
// up to 4 characters each, and the reader's own words.
constexpr size_t kMaxMessage = 2000;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int blocks = 1 + data[0] % 3;
  const std::int64_t every = 1 + (data[0] / 3) % 3;
  const rockbench::EngineInput& input = Input(blocks);
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("rockbench_fuzz_poses_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      << rockbench::fuzz::Text(data + 1, size - 1);
  try {
    const PoseRows p = ReadPoses("fuzz", file, input, every);
    const std::int64_t expected = ExpectedRows(input.steps, every);
    const bool fault = p.stopped_at_line != 0;
    if (static_cast<std::int64_t>(p.rows.size()) > expected ||
        (!fault && static_cast<std::int64_t>(p.rows.size()) != expected) || p.rows.empty()) {
      rockbench::fuzz::Finding("poses_reader: " + std::to_string(p.rows.size()) +
                               " rows read of the " + std::to_string(expected) + " promised");
    }
    if (fault && p.rows.back().engine_fault.empty()) {
      rockbench::fuzz::Finding(
          "poses_reader: a run stopped on a value that is not finite, and "
          "its last row does not say so");
    }
    const size_t finite_rows = p.rows.size() - (fault ? 1 : 0);
    for (size_t j = 0; j < p.rows.size(); ++j) {
      const rockbench::StepReadout& r = p.rows[j];
      const double t =
          static_cast<double>(RowStep(static_cast<std::int64_t>(j), input.steps, every)) *
          input.time_step_s;
      if (r.t_s != t)
        rockbench::fuzz::Finding("poses_reader: row " + std::to_string(j) + " is not at its time");
      if (j >= finite_rows) continue;
      for (const rockbench::BodyReadout& b : r.blocks) {
        for (const double v : {b.x_m, b.y_m, b.cos_phi, b.sin_phi, b.vx_mps, b.vy_mps, b.w_radps}) {
          if (!std::isfinite(v)) {
            rockbench::fuzz::Finding("poses_reader: row " + std::to_string(j) +
                                     " holds a value that is not finite");
          }
        }
      }
    }
  } catch (const ExternalEngineError& e) {
    const std::string what = e.what();
    if (what.size() > kMaxMessage) {
      rockbench::fuzz::Finding("poses_reader: a message of " + std::to_string(what.size()) +
                               " bytes");
    }
    for (const char c : what) {
      const unsigned char u = static_cast<unsigned char>(c);
      if (u < 0x20 || u >= 0x7f) {
        rockbench::fuzz::Finding("poses_reader: a message with the file's byte " +
                                 std::to_string(u) + " unquoted: " + what.substr(0, 200));
      }
    }
  } catch (const std::exception& e) {
    rockbench::fuzz::Finding(std::string("poses_reader: an exception other than "
                                         "ExternalEngineError escaped: ") +
                             std::string(e.what()).substr(0, 2000));
  }
  return 0;
}
