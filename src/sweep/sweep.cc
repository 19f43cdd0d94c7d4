#include "sweep/sweep.h"

#include <sys/utsname.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <initializer_list>
#include <mutex>
#include <thread>

#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/wall_clock.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {

std::vector<SweepPoint> SweepGrid(bool quick, const std::vector<std::string>& engines) {
  std::vector<SweepPoint> grid;
  for (const std::string& name : engines) {
    const Engine* engine = FindEngine(name);
    if (engine == nullptr) continue;
    for (SweepSetting& setting : engine->SweepGrid(quick)) {
      SweepPoint s;
      s.engine = name;
      s.setting = std::move(setting);
      grid.push_back(std::move(s));
    }
  }
  // An adaptive pair at each rtol, with atol a hundredth of it.
  auto add_adaptive = [&grid](Integrator integrator, std::initializer_list<double> rtols) {
    for (double rtol : rtols) {
      SweepPoint s;
      s.engine = "reference";
      s.integrator = integrator;
      s.rtol = rtol;
      s.atol = rtol * 1e-2;
      grid.push_back(s);
    }
  };
  if (quick) {
    add_adaptive(Integrator::kDopri5, {1e-4, 1e-6, 1e-8});
  } else {
    add_adaptive(Integrator::kDopri5, {1e-4, 1e-6, 1e-8, 1e-10, 1e-12});
    // The higher-order pair on the full grid only, from rtol 1e-6 to the default.
    add_adaptive(Integrator::kDop853, {1e-6, 1e-8, 1e-10, 1e-12});
  }
  const std::vector<double> rk4 =
      quick ? std::vector<double>{1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4};
  for (double h : rk4) grid.push_back(ReferenceRk4Point(h));
  return grid;
}

SweepPoint ReferenceRk4Point(double step_s) {
  SweepPoint s;
  s.engine = "reference";
  s.integrator = Integrator::kRk4;
  s.rk4_step_s = step_s;
  return s;
}

Scene SceneForPoint(const Scene& base, const SweepPoint& p) {
  Scene s = base;
  if (!IsReference(p.engine)) {
    for (const auto& [key, value] : p.setting.settings) SetEngineSetting(s, p.engine, key, value);
  } else {
    s.model.integrator = p.integrator;
    if (p.integrator != Integrator::kRk4) {
      s.model.rtol = p.rtol;
      s.model.atol = p.atol;
    } else {
      s.model.step_s = p.rk4_step_s;
    }
  }
  return s;
}

std::vector<SweepRow> RunSweep(const Scene& scene, const GroundMotion& motion,
                               const SweepOptions& options, const SweepProgress& progress,
                               SweepBaseline* baseline_out) {
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
  const auto start = std::chrono::steady_clock::now();
  const reference::Result baseline = reference::Simulate(tight, motion);
  if (baseline_out) {
    baseline_out->wall_s = SecondsSince(start);
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
    const SweepPoint& p = r.point;
    if (!IsReference(p.engine)) {
      std::string settings;
      for (const auto& [key, value] : p.setting.settings) {
        if (key == "time_step") continue;
        settings += (settings.empty() ? "" : ";") + key + "=" + SettingText(value);
      }
      std::erase(settings, '"');
      std::snprintf(buf, sizeof buf, "%s,%s,%s,%.9g,%s,,,,,", p.engine.c_str(),
                    p.setting.family.c_str(), p.setting.label.c_str(), p.setting.time_step_s,
                    settings.c_str());
    } else if (p.integrator != Integrator::kRk4) {
      std::snprintf(buf, sizeof buf, "reference,reference %s,%s,,,%s,%.3g,%.3g,,",
                    IntegratorName(p.integrator), TimeStepLabel(p.rtol).c_str(),
                    IntegratorName(p.integrator), p.rtol, p.atol);
    } else {
      std::snprintf(buf, sizeof buf, "reference,reference RK4,%s,,,%s,,,%.9g,",
                    TimeStepLabel(p.rk4_step_s).c_str(), IntegratorName(p.integrator),
                    p.rk4_step_s);
    }
    out += buf;
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
