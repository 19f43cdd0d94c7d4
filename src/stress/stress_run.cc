// One stress case run: the reference or an engine on the case's scene in this process (what a
// child does), its row, and the pool of child processes that runs the whole catalogue.
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>
#include <mutex>
#include <thread>

#include "compare/agreement.h"
#include "engine/outcome.h"
#include "engines/common/monitor.h"
#include "motion/ground_motion.h"
#include "reference/catalogue.h"
#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"
#include "run/wall_clock.h"
#include "stress/stress.h"
#include "util/format.h"
#include "util/subprocess.h"

namespace rockbench {
namespace {

bool Finite(double v) {
  return std::isfinite(v);
}

bool HistoryHasNonFinite(const History& h) {
  const auto all_finite = [](const BlockValues& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return Finite(x); });
  };
  for (const Sample& s : h.samples) {
    if (!Finite(s.t_s) || !all_finite(s.theta_rad) || !all_finite(s.omega_radps)) return true;
  }
  for (const Event& e : h.events) {
    for (double v : {e.t_s, e.energy_before_j, e.energy_after_j}) {
      if (!Finite(v)) return true;
    }
    if (!all_finite(e.omega_before_radps) || !all_finite(e.omega_after_radps)) return true;
  }
  return false;
}

// Any impact: "ground_impact", "interface_impact", "interface2_impact" ... (N >= 3 blocks).
bool IsImpact(const Event& e) {
  return ImpactInterface(e.kind) >= 0;
}

// Event count, impact count and the smallest time between consecutive impacts.
void CountEvents(const History& h, StressRow* row) {
  row->events = static_cast<int>(h.events.size());
  double last = std::numeric_limits<double>::quiet_NaN();
  for (const Event& e : h.events) {
    if (!IsImpact(e)) continue;
    ++row->impacts;
    if (!std::isnan(last)) {
      const double gap = e.t_s - last;
      if (row->min_event_gap_s < 0.0 || gap < row->min_event_gap_s) row->min_event_gap_s = gap;
    }
    last = e.t_s;
  }
}

// The potential energy of the case's whole stack tilted by `tilt_rad` about block 1's corner,
// to first order: M g b1 tilt, J.
double TiltEnergy_j(const Scene& scene, double tilt_rad) {
  double mass_kg = 0.0;
  for (const BlockDef& b : scene.blocks) mass_kg += b.mass_kg;
  return mass_kg * scene.run.gravity_mps2 * 0.5 * scene.blocks.at(0).width_m * tilt_rad;
}

// Peaks of every block into the row (block k at k - 1).
void SetPeaks(const std::vector<double>& peaks, StressRow* row) {
  row->peak_theta_rad = peaks;
}

// Linear interpolation of a history's angles at t (clamped to its ends).
Sample AnglesAt(const History& h, double t) {
  if (h.samples.empty()) return Sample(h.blocks);
  auto it = std::lower_bound(h.samples.begin(), h.samples.end(), t,
                             [](const Sample& s, double tt) { return s.t_s < tt; });
  if (it == h.samples.begin()) return h.samples.front();
  if (it == h.samples.end()) return h.samples.back();
  const Sample& b = *it;
  const Sample& a = *(it - 1);
  const double w = b.t_s > a.t_s ? (t - a.t_s) / (b.t_s - a.t_s) : 1.0;
  Sample s = b;
  for (size_t k = 0; k < s.theta_rad.size() && k < a.theta_rad.size(); ++k) {
    s.theta_rad[k] = a.theta_rad[k] + w * (b.theta_rad[k] - a.theta_rad[k]);
  }
  return s;
}

// Keeps the largest gain (a NaN, once seen, stays: it must show).
void RecordGain(double gain, StressRow* row) {
  const double cur = row->max_energy_gain_rel;
  if (row->energy_impacts == 0 || (!std::isnan(cur) && (std::isnan(gain) || gain > cur))) {
    row->max_energy_gain_rel = gain;
  }
  ++row->energy_impacts;
}

// Energy across each impact of a run that carries the model's dense solution (the reference's
// extension): the configuration does not jump, so E_after - E_before is the change of kinetic
// energy, computed directly at the impact's angles (the post-event state of the dense
// solution) with the rates the event records before and after.
void DenseImpactEnergies(const StressCase& c, const reference::Result& r, StressRow* row) {
  reference::StackKinetics kinetic(c.scene);
  const reference::Summary& s = r.summary;
  for (const Event& e : r.history.events) {
    if (!IsImpact(e)) continue;
    if (s.unilateral_from_s && e.t_s >= *s.unilateral_from_s) {
      // The unilateral model's impacts (sliding and flying blocks: the rates alone do not give
      // the kinetic energy) carry the stack's energy before and after, which only the kinetic
      // part changes: the gain relative to that energy.
      RecordGain((e.energy_after_j - e.energy_before_j) / std::abs(e.energy_before_j), row);
      continue;
    }
    const Sample at = r.trajectory.At(e.t_s);
    const double ke_before = kinetic.Kinetic_j(e.mode_before, at.theta_rad, e.omega_before_radps);
    const double ke_after = kinetic.Kinetic_j(e.mode_after, at.theta_rad, e.omega_after_radps);
    if (!(ke_before > 0.0)) continue;
    RecordGain((ke_after - ke_before) / ke_before, row);
  }
  if (s.impacts_energy_gain > 0) {
    row->detail += (row->detail.empty() ? "" : "; ") + std::to_string(s.impacts_energy_gain) +
                   " impacts flagged ENERGY GAIN by the model";
  }
}

// The engines' monitor resolves tilts above MonitorConfig::angle_enter_rad (1e-5 rad); a block
// tilted by a small angle a holds about M g b1 a of potential energy, so impacts with less
// kinetic energy than M g b1 1e-5 are below what the monitor can see and are left out.
const double kEngineResolvedTilt_rad = MonitorConfig{}.angle_enter_rad;

// Energy across each impact of a run that has its history alone (an engine's): the monitor
// records E = kinetic (base frame) + potential one step before the crossing step and one step
// after it; the scale is the kinetic energy before, from the recorded rates at the impact's
// angles (history interpolated).
void SampledImpactEnergies(const StressCase& c, const History& history, StressRow* row) {
  reference::StackKinetics kinetic(c.scene);
  const double floor_j = TiltEnergy_j(c.scene, kEngineResolvedTilt_rad);
  for (const Event& e : history.events) {
    if (!IsImpact(e)) continue;
    const Sample at = AnglesAt(history, e.t_s);
    const double ke_before = kinetic.Kinetic_j(e.mode_before, at.theta_rad, e.omega_before_radps);
    if (!(ke_before > floor_j)) continue;
    RecordGain((e.energy_after_j - e.energy_before_j) / ke_before, row);
  }
}

// The row's agreement with the reference on the same scene.
void SetAgreement(const EngineAgreement& a, StressRow* row) {
  row->has_agreement = true;
  for (const BodyAgreement& body : a.bodies) {
    row->max_abs_error_rad.push_back(body.angle.max_abs_error_rad);
    row->peak_rel_error.push_back(body.angle.peak_rel_error);
  }
  row->impacts_matched = a.impacts.matched;
  row->reference_impacts = a.impacts.reference_impacts;
}

// One engine's run of the case (the reference's as any other's, through the engine
// interface): status, peaks, events, the energy across impacts and, for a run that is not the
// reference's own solution, its agreement with the reference.
StressRow RunCase(const StressCase& c, const std::string& engine, StressRow row) {
  const GroundMotion motion = GroundMotion::FromScene(c.scene);
  SimulateOptions options;
  options.check_convergence = false;  // the stress catalogue checks the model's own solution
  const EngineRun run = RunEngine(engine, c.scene, motion, options);
  row.wall_s = run.wall_s;
  const RunOutcome& o = run.outcome;
  row.status = StatusText(o.status);
  row.detail = run.summary.value("status_detail", "");
  // A run that ended non_finite or blew up failed (its figures are those of its finite part).
  row.finished = !IsNonFinite(o.status) && o.status != RunStatus::kBlowUp;
  SetPeaks(o.peak_theta_rad, &row);
  row.nan = IsNonFinite(o.status) || HistoryHasNonFinite(run.history) ||
            !std::all_of(o.peak_theta_rad.begin(), o.peak_theta_rad.end(), Finite);
  CountEvents(run.history, &row);
  std::string flags;
  for (const std::string& f : o.violations) flags += (flags.empty() ? "" : ";") + f;
  row.violations = flags.empty() ? "none" : flags;
  // The reference's run carries its dense solution: its own energies, and nothing to agree with.
  if (const CheckedReference* own = ReferenceResultOf(run.extension.get())) {
    DenseImpactEnergies(c, own->used(), &row);
    return row;
  }
  SampledImpactEnergies(c, run.history, &row);
  const EngineRun ref = RunEngine(TheReference().name(), c.scene, motion, options);
  SetAgreement(CompareWithReference(c.scene, ReferenceResultOf(ref.extension.get())->used(), run),
               &row);
  return row;
}

void SetSettings(const StressCase& c, const std::string& engine, StressRow* row) {
  // Only an engine with a settings table has settings to show (the reference's are the scene's
  // [model] table).
  const Engine* e = FindEngine(engine);
  if (e == nullptr || e->settings_schema().settings.empty()) return;
  row->has_settings = true;
  try {
    row->dt_s = ResolveEngineSettings(c.scene, e->settings_schema()).Number("time_step");
  } catch (const std::exception&) {
    row->dt_s = 0.0;  // the run reports the bad setting
  }
  if (c.setting) {
    for (const auto& [key, value] : c.setting->settings) {
      if (key == "time_step") continue;
      std::string text = SettingText(value);
      std::erase(text, '"');
      row->settings += (row->settings.empty() ? "" : ";") + key + "=" + text;
    }
  }
}

}  // namespace

StressRow RunStressCaseHere(const StressCase& c, const std::string& engine) {
  StressRow row;
  row.case_name = c.name;
  row.engine = engine;
  SetSettings(c, engine, &row);
  if (c.self_test == StressSelfTest::kCrash) {
    // No core file for a deliberate crash, and the default action (a sanitizer's handler
    // would turn the signal into an exit status).
    const rlimit none{0, 0};
    ::setrlimit(RLIMIT_CORE, &none);
    std::fflush(nullptr);
    std::signal(SIGSEGV, SIG_DFL);
    std::raise(SIGSEGV);
  }
  if (c.self_test == StressSelfTest::kHang) {
    while (true) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  try {
    return RunCase(c, engine, row);
  } catch (const std::exception& e) {
    row.finished = false;
    row.status = "error";
    row.detail = e.what();
    return row;
  }
}

namespace {

// The row of a child that ended without printing one (crash, wall limit, error exit).
StressRow ChildRow(const StressCase& c, const std::string& engine, const ProcessResult& p) {
  StressRow row;
  row.case_name = c.name;
  row.engine = engine;
  SetSettings(c, engine, &row);
  row.wall_s = p.wall_s;
  if (!p.started) {
    row.status = "error";
    row.detail = "cannot start the child: " + p.start_error;
    return row;
  }
  if (p.timed_out) {
    row.status = "wall_limit";
    row.detail =
        "killed after the case's wall-clock limit of " + Format("%g", c.wall_limit_s) + " s";
    return row;
  }
  if (p.signal != 0) {
    row.status = "crash (signal " + std::to_string(p.signal) + ")";
    row.detail = std::string("the child died of ") + strsignal(p.signal);
    return row;
  }
  // The last non-empty line of stdout is the row.
  std::string line;
  const size_t end = p.out.find_last_not_of("\n\r ");
  if (end != std::string::npos) {
    const size_t nl = p.out.find_last_of('\n', end);
    const size_t begin = nl == std::string::npos ? 0 : nl + 1;
    line = p.out.substr(begin, end + 1 - begin);
  }
  if (p.exit_code == 0 && !line.empty()) {
    try {
      StressRow r = StressRowFromJson(nlohmann::json::parse(line));
      if (r.case_name == c.name && r.engine == engine) return r;
    } catch (const std::exception&) {
    }
  }
  row.status = "error (exit " + std::to_string(p.exit_code) + ")";
  std::string err = p.err;
  while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
  const size_t nl = err.find_last_of('\n');
  row.detail =
      "no row from the child" +
      (err.empty() ? std::string() : ": " + err.substr(nl == std::string::npos ? 0 : nl + 1));
  return row;
}

}  // namespace

std::vector<StressRow> RunStress(const std::vector<StressCase>& cases,
                                 const StressRunOptions& options, const StressProgress& progress) {
  if (options.jobs < 0) throw SceneError("--jobs: expected 1 or more");
  const std::filesystem::path exe =
      options.executable.empty() ? SelfExecutable() : options.executable;
  struct Task {
    const StressCase* c;
    std::string engine;
  };
  std::vector<Task> tasks;
  for (const StressCase& c : cases) {
    for (const std::string& e : c.engines) tasks.push_back({&c, e});
  }
  std::vector<StressRow> rows(tasks.size());
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::mutex mu;
  int done = 0;
  auto worker = [&] {
    while (true) {
      const size_t k = next++;
      if (k >= tasks.size()) return;
      const Task& t = tasks[k];
      ProcessOptions po;
      po.timeout_s = t.c->wall_limit_s;
      const ProcessResult p =
          RunProcess({exe.string(), "stress", "--run-case", t.c->name, "--engine", t.engine}, po);
      rows[k] = ChildRow(*t.c, t.engine, p);
      std::lock_guard<std::mutex> lock(mu);
      ++done;
      if (progress) progress(done, static_cast<int>(tasks.size()), rows[k]);
    }
  };
  std::vector<std::thread> pool;
  const int n = std::min<int>(jobs, static_cast<int>(std::max<size_t>(1, tasks.size())));
  for (int i = 0; i < n; ++i) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  return rows;
}

}  // namespace rockbench
