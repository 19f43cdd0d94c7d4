#include "sweep/sweep.h"

#include <sys/utsname.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <fstream>
#include <mutex>
#include <thread>

#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {

std::vector<SweepPoint> SweepGrid(bool quick, const std::vector<std::string>& engines) {
  // The engines named, then the reference every row is compared with; each once, at its last
  // place.
  std::vector<std::string> names = engines;
  names.push_back(TheReference().name());
  std::vector<SweepPoint> grid;
  for (size_t k = 0; k < names.size(); ++k) {
    if (std::find(names.begin() + static_cast<std::ptrdiff_t>(k) + 1, names.end(), names[k]) !=
        names.end()) {
      continue;
    }
    const Engine* engine = FindEngine(names[k]);
    if (engine == nullptr) continue;
    for (SweepSetting& setting : engine->SweepGrid(quick)) {
      SweepPoint s;
      s.engine = names[k];
      s.setting = std::move(setting);
      grid.push_back(std::move(s));
    }
  }
  return grid;
}

SweepPoint ReferenceRk4Point(double step_s) {
  return {TheReference().name(), ReferenceEngine::Rk4Point(step_s)};
}

SweepPoint ReferenceTolerancePoint(Integrator integrator, double rtol) {
  return {TheReference().name(), ReferenceEngine::TolerancePoint(integrator, rtol)};
}

Scene SceneForPoint(const Scene& base, const SweepPoint& p) {
  const Engine* engine = FindEngine(p.engine);
  if (engine == nullptr) throw SceneError("unknown engine '" + p.engine + "'");
  return engine->SceneForSetting(base, p.setting);
}

std::vector<SweepRow> RunSweep(const Scene& scene, const GroundMotion& motion,
                               const SweepOptions& options, const SweepProgress& progress,
                               SweepBaseline* baseline_out) {
  RequirePlanarBodies(scene, "sweep");
  if (options.repeat < 1) throw SceneError("--repeat: expected a positive integer");
  if (options.threads < 0) throw SceneError("--threads: expected a non-negative integer");
  const std::vector<SweepPoint> grid =
      options.points.empty()
          ? SweepGrid(options.quick, options.engines.empty() ? BuiltEngineNames() : options.engines)
          : options.points;

  // The tight reference every row is compared with.
  Scene tight = scene;
  tight.model.integrator = Integrator::kDopri5;
  tight.model.rtol = kSweepTightRtol;
  tight.model.atol = kSweepTightAtol;
  SimulateOptions tight_options;
  tight_options.check_convergence = false;  // the tight run is itself the check
  const EngineResult tight_run = TheReference().Simulate(tight, motion, tight_options);
  const reference::Result& baseline = ReferenceResultOf(tight_run.extension.get())->used();
  if (baseline_out) {
    baseline_out->wall_s = tight_run.wall_s;
    baseline_out->status = baseline.summary.status;
    const reference::Summary& bs = baseline.summary;
    baseline_out->peak_theta_rad.assign(bs.peak_theta_rad.begin(), bs.peak_theta_rad.end());
    baseline_out->peak_theta_t_s.assign(bs.peak_theta_t_s.begin(), bs.peak_theta_t_s.end());
    baseline_out->overturn_block = baseline.summary.overturn_block.value_or(0);
    baseline_out->overturn_t_s = baseline.summary.overturn_t_s;
  }

  std::vector<SweepRow> rows(grid.size());
  std::atomic<size_t> next{0};
  std::mutex progress_mutex;
  int done = 0;
  auto worker = [&] {
    for (;;) {
      const size_t i = next.fetch_add(1);
      if (i >= grid.size()) return;
      SweepRow& row = rows[i];
      row.point = grid[i];
      try {
        const Scene s = SceneForPoint(scene, grid[i]);
        EngineRun first;
        double best = 0.0;
        for (int r = 0; r < options.repeat; ++r) {
          EngineRun run = RunEngine(grid[i].engine, s, motion);
          if (r == 0 || run.wall_s < best) best = run.wall_s;
          if (r == 0) first = std::move(run);
        }
        first.wall_s = best;
        row.wall_s = best;
        row.agreement = CompareWithReference(scene, baseline, first);
      } catch (const std::exception& e) {
        row.error = e.what();
      }
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(++done, static_cast<int>(grid.size()), grid[i]);
      }
    }
  };
  unsigned n_threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                           : std::max(1u, std::thread::hardware_concurrency());
  n_threads =
      std::min<unsigned>(n_threads, static_cast<unsigned>(std::max<size_t>(1, grid.size())));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < n_threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return rows;
}

namespace {

// A point's columns engine, family, setting, time_step_s, settings, integrator, rtol, atol,
// rk4_step_s (each followed by its comma): an engine's table settings (besides its step), or
// the integrator settings of a point that has them (the reference's).
std::string PointColumns(const SweepPoint& p) {
  char buf[1024];
  const SweepSetting& st = p.setting;
  if (!st.integrator) {
    std::string settings;
    for (const auto& [key, value] : st.settings) {
      if (key == "time_step") continue;
      settings += (settings.empty() ? "" : ";") + key + "=" + SettingText(value);
    }
    std::erase(settings, '"');
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%.9g,%s,,,,,", p.engine.c_str(), st.family.c_str(),
                  st.label.c_str(), st.time_step_s, settings.c_str());
  } else if (st.integrator->integrator != Integrator::kRk4) {
    std::snprintf(buf, sizeof buf, "%s,%s,%s,,,%s,%.3g,%.3g,,", p.engine.c_str(), st.family.c_str(),
                  st.label.c_str(), IntegratorName(st.integrator->integrator), st.integrator->rtol,
                  st.integrator->atol);
  } else {
    std::snprintf(buf, sizeof buf, "%s,%s,%s,,,%s,,,%.9g,", p.engine.c_str(), st.family.c_str(),
                  st.label.c_str(), IntegratorName(st.integrator->integrator),
                  st.integrator->step_s);
  }
  return buf;
}

}  // namespace

std::string SweepCsv(const std::vector<SweepRow>& rows, int blocks) {
  // The theta columns of blocks 1 and 2 always (one block's theta2 columns empty), and of
  // blocks 3..N when the stack has them.
  const int theta_blocks = std::clamp(blocks, 2, kMaxBlocks);
  std::string out =
      "engine,family,setting,time_step_s,settings,integrator,rtol,atol,rk4_step_s,status,"
      "wall_s,";
  for (int b = 1; b <= theta_blocks; ++b) {
    const std::string th = BodyColumn("theta", b);
    for (const char* col : {"_max_abs_error_rad,", "_rms_error_rad,", "_horizon_s,",
                            "_peak_rel_error,", "_peak_time_error_s,"}) {
      out.append(th).append(col);
    }
  }
  out +=
      "impacts_reference,impacts_engine,impacts_matched,max_abs_impact_time_error_s,"
      "overturn_agree,final_agree,error\n";
  char buf[1024];
  for (const SweepRow& r : rows) {
    out += PointColumns(r.point);
    if (!r.error.empty()) {
      // Keep the CSV one line per row: no commas or newlines inside the message.
      std::string msg = r.error;
      std::replace(msg.begin(), msg.end(), ',', ';');
      std::replace(msg.begin(), msg.end(), '\n', ' ');
      // The status, wall time and error columns before the message: 18 for one or two blocks.
      out.append("error").append(static_cast<size_t>(18 + 5 * (theta_blocks - 2)), ',');
      out.append(msg).append("\n");
      continue;
    }
    const EngineAgreement& a = r.agreement;
    std::snprintf(buf, sizeof buf, "%s,%.6g,", StatusText(a.status), r.wall_s);
    out += buf;
    for (int b = 1; b <= theta_blocks; ++b) {
      if (b <= a.blocks()) {
        const AngleAgreement& t = a.angle(b);
        std::snprintf(buf, sizeof buf, "%.6e,%.6e,%.9g,%.6e,%.6e,", t.max_abs_error_rad,
                      t.rms_error_rad, t.horizon_s, t.peak_rel_error, t.peak_time_error_s);
        out += buf;
      } else {
        out += ",,,,,";
      }
    }
    std::snprintf(buf, sizeof buf, "%d,%d,%d,%.6e,%d,%d,\n", a.impacts.reference_impacts,
                  a.impacts.engine_impacts, a.impacts.matched, a.impacts.max_abs_time_error_s,
                  a.overturn_agree ? 1 : 0, a.final_agree ? 1 : 0);
    out += buf;
  }
  return out;
}

std::string MachineDescription() {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      cpu = line.substr(line.find(':') + 1);
      cpu.erase(0, cpu.find_first_not_of(" \t"));
      break;
    }
  }
  std::string out =
      cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
  struct utsname u;
  if (uname(&u) == 0) out += std::string(", ") + u.sysname + " " + u.machine;
  return out;
}

nlohmann::json SweepJson(const Scene& scene, const std::vector<std::string>& overrides,
                         const SweepOptions& options, const SweepBaseline& baseline,
                         const std::vector<SweepRow>& rows) {
  nlohmann::json j;
  j["scene"]["path"] = scene.path.string();
  j["scene"]["title"] = scene.title;
  j["scene"]["overrides"] = overrides;
  j["simulated_duration_s"] = scene.run.duration_s;
  j["two_blocks"] = scene.block_count() == 2;
  // N >= 3 blocks: how many (one and two blocks say it by two_blocks alone).
  if (scene.block_count() >= 3) j["blocks"] = scene.block_count();
  j["options"]["quick"] = options.quick;
  j["options"]["repeat"] = options.repeat;
  j["options"]["threads"] = options.threads;
  j["tight_reference"]["integrator"] = "dopri5";
  j["tight_reference"]["rtol"] = kSweepTightRtol;
  j["tight_reference"]["atol"] = kSweepTightAtol;
  j["tight_reference"]["wall_s"] = baseline.wall_s;
  j["tight_reference"]["status"] = StatusText(baseline.status);
  // Blocks 1 and 2 always (0 for one block's block 2), then every block of the stack.
  for (int k = 0; k < std::max(2, baseline.blocks()); ++k) {
    const std::string th = BodyColumn("peak_theta", k + 1);
    const bool has = k < baseline.blocks();
    j["tight_reference"][th + "_rad"] = has ? baseline.peak_theta_rad[k] : 0.0;
    j["tight_reference"][th + "_t_s"] = has ? baseline.peak_theta_t_s[k] : 0.0;
  }
  if (baseline.overturn_block > 0) {
    j["tight_reference"]["overturn_block"] = baseline.overturn_block;
    j["tight_reference"]["overturn_t_s"] = baseline.overturn_t_s;
  } else {
    j["tight_reference"]["overturn_block"] = nullptr;
  }
  int failed = 0;
  for (const SweepRow& r : rows) failed += r.error.empty() ? 0 : 1;
  j["runs"] = rows.size();
  j["failed"] = failed;
  j["machine"] = MachineDescription();
  return j;
}

}  // namespace rockbench
