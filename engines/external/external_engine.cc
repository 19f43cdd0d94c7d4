#include "engines/external/external_engine.h"

#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <variant>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/external/command.h"
#include "engines/external/protocol.h"
#include "util/relayed_text.h"
#include "util/wall_limit.h"

namespace rockbench::external {
namespace {

// A folder of its own for one run, removed with everything in it when the run is over.
class RunFolder {
 public:
  explicit RunFolder(const std::string& engine) {
    std::error_code ec;
    std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / ("rockbench-" + engine + "-XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw ExternalEngineError(engine + ": cannot make a run folder under " + base.string());
    }
    path_ = pattern;
    // A signal or the wall-clock limit removes it too (util/wall_limit.h).
    RegisterTemporary(path_, /*folder=*/true);
  }
  ~RunFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
    ForgetTemporary(path_);
  }
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::string CommandText(const std::vector<std::string>& command) {
  std::string out;
  for (const std::string& a : command) out += (out.empty() ? "" : " ") + a;
  return out;
}

// The families of the manifest over `steps`, as sweep points or stress cases.
std::vector<SweepSetting> Points(const ExternalManifest& m, const std::vector<double>& steps,
                                 bool stress) {
  std::vector<SweepSetting> out;
  for (const ExternalFamily& f : m.families) {
    for (size_t i = 0; i < steps.size(); ++i) {
      SweepSetting p;
      p.family = f.name;
      p.label = TimeStepLabel(steps[i]);
      p.time_step_s = steps[i];
      p.settings = f.settings;
      p.settings.emplace_back(kTimeStepKey, steps[i]);
      p.id = f.id + "/dt=" + p.label;
      p.quick = stress && i == 0;
      out.push_back(std::move(p));
    }
  }
  return out;
}

// Throws the failure of the engine's command: what it did (exit, signal, limit) and what it
// wrote on standard error (its last lines, of its last 4 kB), relayed escaped and indented
// ("  | "): no escape sequence or carriage return reaches the terminal to rewrite a line, and
// no line of it reads as one of rockbench's own.
[[noreturn]] void ThrowFailedCommand(const std::string& name, const CommandSpec& spec,
                                     const CommandResult& proc) {
  const std::string said = TailOfFile(spec.stderr_file);
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(spec.stderr_file, ec);
  const std::string heading = !ec && bytes > said.size() + 2
                                  ? "its last words (the last " + std::to_string(said.size()) +
                                        " of " + std::to_string(bytes) + " bytes it wrote):"
                                  : std::string("its last words:");
  throw ExternalEngineError(name + ": its command (" + EscapedText(CommandText(spec.argv), 1024) +
                            ") " + proc.Describe(spec) +
                            (said.empty() ? std::string(", and said nothing")
                                          : ";\n" + heading + "\n" + RelayedLines(said)));
}

// The poses file read (ReadPoses); its texts (a header, a field) reach messages escaped and
// capped.
PoseRows ReadEscapedPoses(const std::string& name, const std::filesystem::path& poses_file,
                          const EngineInput& input, std::int64_t every) {
  PoseRows poses = [&] {
    try {
      return ReadPoses(name, poses_file, input, every);
    } catch (const ExternalEngineError& e) {
      throw ExternalEngineError(EscapedText(e.what()));
    }
  }();
  for (StepReadout& r : poses.rows) {
    if (!r.engine_fault.empty()) r.engine_fault = EscapedText(r.engine_fault);
  }
  return poses;
}

// The rows given to the monitor as the steps of `watched` (MonitorInput), until it stops.
void WatchRows(const EngineInput& watched, PoseRows* poses, Monitor* monitor) {
  for (size_t j = 0; j < poses->rows.size(); ++j) {
    StepReadout& r = poses->rows[j];
    ReadBaseMotion(watched, static_cast<std::int64_t>(j), &r);
    if (j == 0) {
      monitor->Start(r);
    } else if (!monitor->Step(static_cast<std::int64_t>(j), r)) {
      break;
    }
  }
}

// Friction from the scene, as every engine reports it: each interface's coefficient, the
// scene's where finite, else the engine's `friction` setting (null: none it states).
nlohmann::json InterfaceFrictionJson(const EngineSettingsSchema& schema,
                                     const EngineSettings& settings, const EngineInput& input) {
  constexpr char kFrictionKey[] = "friction";  // a manifest's key, if it has one
  const SettingDef* own = schema.Find(kFrictionKey);
  const double engine_mu = own != nullptr && std::holds_alternative<double>(own->default_value)
                               ? settings.Number(kFrictionKey)
                               : std::numeric_limits<double>::infinity();
  nlohmann::json mu = nlohmann::json::array();
  for (int k = 0; k < input.block_count(); ++k) {
    const double v = InterfaceFriction(input, k, engine_mu);
    mu.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
  }
  return mu;
}

}  // namespace

std::vector<SweepSetting> ExternalEngine::SweepGrid(bool quick) const {
  return Points(m_, quick ? m_.quick_steps_s : m_.sweep_steps_s, false);
}

std::vector<SweepSetting> ExternalEngine::StressGrid() const {
  return Points(m_, m_.stress_steps_s, true);
}

EngineResult ExternalEngine::Simulate(const Scene& scene, const GroundMotion& motion,
                                      const SimulateOptions& options) const {
  const auto start = std::chrono::steady_clock::now();
  if (!m_.missing_reason.empty()) {
    throw SceneError(m_.where + ": external engine " + m_.name +
                     " cannot run here: " + EscapedText(m_.missing_reason));
  }
  if (scene.block_count() > m_.max_blocks) {
    throw SceneError(scene.path.string() + ": engine " + m_.name + " simulates at most " +
                     std::to_string(m_.max_blocks) + " block" + (m_.max_blocks == 1 ? "" : "s") +
                     " (its manifest's max_blocks), the scene has " +
                     std::to_string(scene.block_count()));
  }
  const EngineSettings settings = ResolveEngineSettings(scene, m_.schema);
  const EngineInput input =
      MakeEngineInput(scene, motion, m_.name, settings, options.stop_at_rest_after_s);
  const ProtocolSettings protocol = ReadProtocolSettings(settings);
  const std::int64_t every = protocol.output_every_steps;

  RunFolder folder(m_.name);
  const std::filesystem::path input_file = folder.path() / "input.json";
  const std::filesystem::path poses_file = folder.path() / "poses.csv";
  const std::filesystem::path contacts_file = folder.path() / "contacts.csv";
  {
    const nlohmann::json j =
        InputJson(m_.name, scene, input, settings, every, poses_file, contacts_file);
    std::ofstream out(input_file, std::ios::binary);
    out << j.dump() << '\n';
    if (!out) throw ExternalEngineError(m_.name + ": cannot write " + input_file.string());
  }
  CommandSpec spec;
  spec.argv = m_.command;
  spec.argv.push_back(input_file.string());
  spec.working_dir = folder.path();
  spec.stderr_file = folder.path() / "stderr.txt";
  spec.wall_limit_s = protocol.wall_limit_s;
  spec.memory_limit_mib = protocol.memory_limit_mib;
  const CommandResult proc = RunCommand(spec);
  if (!proc.ok()) ThrowFailedCommand(m_.name, spec, proc);
  const auto read_start = std::chrono::steady_clock::now();
  PoseRows poses = ReadEscapedPoses(m_.name, poses_file, input, every);
  const auto monitor_start = std::chrono::steady_clock::now();

  // The monitor reads the rows as a fixed-step engine's steps.
  const EngineInput watched = MonitorInput(input, every);
  Monitor monitor(watched);
  WatchRows(watched, &poses, &monitor);
  monitor.Finish();
  const auto end = std::chrono::steady_clock::now();
  const double wall_s = std::chrono::duration<double>(end - start).count();

  EngineResult out;
  out.summary = monitor.Summary();
  out.summary["engine"] = m_.name;
  out.summary["settings"] = settings.ToJson();
  if (HasFiniteFriction(input)) {
    out.summary["settings"]["interface_friction"] =
        InterfaceFrictionJson(m_.schema, settings, input);
  }
  out.summary["wall_s"] = wall_s;
  out.summary["real_time_factor"] = wall_s > 0.0 ? monitor.last().t_s / wall_s : 0.0;
  out.summary["external"] = {
      {"protocol_version", kProtocolVersion},
      {"command", m_.command},
      {"process_wall_s", proc.wall_s},
      {"peak_resident_mib", proc.peak_rss_mib},
      {"rows", poses.rows.size()},
      {"poses_bytes", poses.bytes},
      {"velocities", poses.velocities_given ? "engine" : "differences of the poses"},
      {"overhead_s", wall_s - proc.wall_s},
      {"read_s", std::chrono::duration<double>(monitor_start - read_start).count()},
      {"monitor_s", std::chrono::duration<double>(end - monitor_start).count()}};
  if (input.drive_kind == DriveKind::kKinematic) {
    out.summary["kinematic"] = KinematicDriveJson(input);
  }
  out.outcome = monitor.Outcome();
  out.wall_s = wall_s;
  out.history = monitor.TakeHistory();
  char line[200];
  std::snprintf(line, sizeof line, "external, %s, dt %.3g s", DriveKindName(input.drive_kind),
                input.time_step_s);
  out.settings_line = line;
  return out;
}

}  // namespace rockbench::external
