#pragma once
/// The external-engine protocol, version 1 (docs/external-engines.md; the input's JSON Schema is
/// engines/external/input.schema.json): the input file rockbench writes for one run and the poses
/// file the engine writes back.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "scene/engine_settings.h"
#include "scene/scene.h"

namespace rockbench::external {

/// An external engine's run that failed: it could not start, crashed, hung, ran out of memory or
/// wrote a poses file the protocol refuses. The message names the engine, and the file and line
/// at fault.
struct ExternalEngineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most steps an external engine's run may take when the scene has a base motion: its input
/// file holds the drive at every step (about 24 bytes of JSON text per value, two components),
/// and the engine must parse that whole document (Python's json holds each number in 32 bytes):
/// 2e7 steps are about 1 GB of text and 1.3 GB in the engine, within its default memory limit
/// of 4096 MiB. The run estimate refuses more up front (run/resource_estimate.h).
inline constexpr std::int64_t kMaxInputSteps = 20'000'000;

/// The input of one run: the blocks (geometry, mass, inertia, pose and velocity at t = 0, bottom
/// first), the pairs in contact and their friction, gravity, the step, steps, duration and
/// output interval, the base motion on the step grid (and its analytic form when the scene's
/// has one), the engine's settings and where to write the poses. Throws ExternalEngineError for
/// a run with a base motion of more than kMaxInputSteps steps, and when memory runs out while
/// building it (never an abort).
nlohmann::json InputJson(const std::string& engine, const Scene& scene, const EngineInput& input,
                         const EngineSettings& settings, std::int64_t output_every_steps,
                         const std::filesystem::path& poses_file,
                         const std::filesystem::path& contacts_file);

/// The poses an engine wrote, as the monitor reads them: one readout per output row (row j at
/// t = j * output_every_steps * time_step_s), velocities from the file or, where it gives none,
/// from central differences of the poses.
struct PoseRows {
  /// The rows read. When a row holds a value that is not finite (the engine's state blew up),
  /// reading stops there: that row is the last, its readout's engine_fault says "FILE:LINE:
  /// column C (NAME) is 'nan'", and the monitor ends the run there with status non_finite.
  std::vector<StepReadout> rows;
  bool velocities_given = false;     ///< the file had every block's vx, vy and omega columns
  std::int64_t stopped_at_line = 0;  ///< the line of a value that is not finite (0: none)
  std::int64_t bytes = 0;            ///< the file's size
};

/// The number of rows a run of `steps` steps writes at every `output_every_steps`-th step: t = 0,
/// then each whole multiple, then the last step when it is not one.
std::int64_t ExpectedRows(std::int64_t steps, std::int64_t output_every_steps);

/// The step index of row j.
std::int64_t RowStep(std::int64_t j, std::int64_t steps, std::int64_t output_every_steps);

/// The longest field of a poses file, bytes: a double's shortest exact text is at most 24
/// characters ("-2.2250738585072014e-308"); 64 leaves room for padding and extra digits.
inline constexpr std::int64_t kMaxPosesFieldBytes = 64;
/// Room in a poses file for its header line and comments, bytes.
inline constexpr std::int64_t kPosesHeaderBytes = std::int64_t{1} << 20;

/// The largest poses file a run can write, bytes: its rows x their fields (t_s and six per
/// block) x kMaxPosesFieldBytes, plus kPosesHeaderBytes. ReadPoses refuses a larger file before
/// reading it.
std::int64_t MaxPosesBytes(const EngineInput& input, std::int64_t output_every_steps);

/// Parses a poses file (CSV: a header `t_s,x1_m,y1_m,angle1_rad[,vx1_mps,vy1_mps,omega1_radps],
/// x2_m,...`, then one row per output time; lines starting with '#' are comments). Throws
/// ExternalEngineError "ENGINE: FILE:LINE: ..." for a missing or unknown column, a field that is
/// not a number (a field with anything after its number, a NUL byte included), a time that goes
/// backwards or is not the row's, fewer or more rows than promised; for a path that is not a
/// regular file (a FIFO, a device, a folder: refused without reading, so a FIFO cannot hang the
/// run) and for a file larger than MaxPosesBytes. Text from the file is quoted in messages
/// (non-printable bytes as \xNN, at most 60 characters). A number that is not finite (nan, inf) is
/// the engine's blow-up, not a fault of the file: PoseRows::rows.
PoseRows ReadPoses(const std::string& engine, const std::filesystem::path& file,
                   const EngineInput& input, std::int64_t output_every_steps);

/// Writes rows as a poses file (the header with every block's velocities, then one row per
/// readout, each number in its shortest exact form): what an engine written in C++ would write,
/// and what a replay of a built-in engine's steps writes.
void WritePoses(std::ostream& out, const std::vector<StepReadout>& rows);

/// The run input as the monitor sees an engine that writes every `output_every_steps`-th step:
/// the step that many times longer, the base motion sampled at the rows (an inertial window's
/// largest acceleration, so that a base that moved in it counts as moving).
EngineInput MonitorInput(const EngineInput& input, std::int64_t output_every_steps);

}  // namespace rockbench::external
