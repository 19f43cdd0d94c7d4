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
#include <optional>
#include <thread>

#include "compare/agreement.h"
#include "engine/outcome.h"
#include "engines/common/monitor.h"
#include "motion/ground_motion.h"
#include "reference/chain/stack_chain.h"
#include "reference/simulate.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
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

// The state at an impact of one or two blocks: the angles of `at`, the rates `w`.
reference::State ImpactState(const Sample& at, const BlockValues& w) {
  const size_t top = at.theta_rad.size() >= 2 && w.size() >= 2 ? 1 : 0;
  return {at.theta_rad[0], at.theta_rad[top], w[0], w[top]};
}

// Kinetic energy (base frame) of a state moving in configuration `c` (one or two blocks), J:
// sum of m v_G^2 / 2 + I_G w^2 / 2, computed directly (not as total minus potential energy,
// which would cancel digits).
double KineticEnergy(const reference::Geometry& geo, const Configuration& c, reference::State s) {
  const Mode mode = ModeOfConfiguration(c).value_or(Mode::kRest);
  if (!geo.two_blocks) {
    s.theta2 = s.theta1;
    s.omega2 = s.omega1;
  }
  const reference::BodyVelocities v = reference::Velocities(geo, mode, s);
  const double m[2] = {geo.block1.m, geo.block2.m};
  const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
  double ke = 0.0;
  for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
    ke += 0.5 * m[b] * reference::Dot(v.vG[b], v.vG[b]) + 0.5 * IG[b] * v.w[b] * v.w[b];
  }
  return ke;
}

// The kinetic energy (base frame) of the case's stack at an impact, J: KineticEnergy for one
// and two blocks; for N >= 3 blocks the same sum from every block's motion along the pivot
// chain (reference::StackChain::Body), the interface's closed faces taken from the
// configuration.
class ImpactKinetics {
 public:
  explicit ImpactKinetics(const Scene& scene) : blocks_(scene.block_count()) {
    if (blocks_ <= 2) {
      geo_ = reference::MakeGeometry(scene);
      mass_kg_ = geo_.M;
    } else {
      std::vector<reference::BlockSize> sizes;
      for (const BlockDef& b : scene.blocks) {
        sizes.push_back({b.width_m, b.height_m, b.mass_kg});
        mass_kg_ += b.mass_kg;
      }
      chain_.emplace(reference::MakeStackGeometry(sizes, scene.run.gravity_mps2));
    }
    g_mps2_ = scene.run.gravity_mps2;
    b1_m_ = 0.5 * scene.blocks.at(0).width_m;
  }
  /// At the angles of `at`, the rates `w`, in configuration `c`.
  double operator()(const Configuration& c, const Sample& at, const BlockValues& w) {
    if (blocks_ <= 2) return KineticEnergy(geo_, c, ImpactState(at, w));
    const std::vector<double> theta(at.theta_rad.begin(), at.theta_rad.end());
    const std::vector<double> omega(w.begin(), w.end());
    chain_->Place(c, theta.data(), omega.data());
    double ke = 0.0;
    for (int b = 0; b < blocks_; ++b) {
      const BodyMotion m = chain_->Body(b);
      const BlockProps& p = chain_->geometry().blocks[static_cast<size_t>(b)];
      ke += 0.5 * p.m * reference::Dot(m.vG, m.vG) + 0.5 * p.I_G * m.w_radps * m.w_radps;
    }
    return ke;
  }
  /// The potential energy of the whole stack tilted by `tilt_rad` about block 1's corner, to
  /// first order: M g b1 tilt, J.
  double TiltEnergy_j(double tilt_rad) const { return mass_kg_ * g_mps2_ * b1_m_ * tilt_rad; }

 private:
  int blocks_ = 0;
  reference::Geometry geo_;
  std::optional<reference::StackChain> chain_;
  double mass_kg_ = 0.0, g_mps2_ = 0.0, b1_m_ = 0.0;
};

// Peaks of every block into the row: theta1, theta2 (0 for one block) and blocks 3..N.
void SetPeaks(const std::vector<double>& peaks, StressRow* row) {
  row->peak_theta1_rad = !peaks.empty() ? peaks[0] : 0.0;
  row->peak_theta2_rad = peaks.size() >= 2 ? peaks[1] : 0.0;
  row->peak_theta_from3_rad.assign(peaks.begin() + std::min<size_t>(peaks.size(), 2), peaks.end());
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

StressRow RunReference(const StressCase& c, StressRow row) {
  const GroundMotion motion = GroundMotion::FromScene(c.scene);
  const auto start = std::chrono::steady_clock::now();
  const reference::Result r = reference::Simulate(c.scene, motion);
  row.wall_s = SecondsSince(start);
  const reference::Summary& s = r.summary;
  row.status = StatusText(s.status);
  row.detail = s.status_detail;
  // A run that ended non_finite failed (its figures are those of its finite part).
  row.finished = !IsNonFinite(s.status);
  SetPeaks(s.peak_theta_rad, &row);
  row.nan = IsNonFinite(s.status) || HistoryHasNonFinite(r.history) ||
            !std::all_of(s.peak_theta_rad.begin(), s.peak_theta_rad.end(), Finite);
  CountEvents(r.history, &row);
  // Energy across each impact: the configuration does not jump, so E_after - E_before is the
  // change of kinetic energy, computed directly at the impact's angles (the post-event state of
  // the dense solution) with the rates the event records before and after.
  ImpactKinetics kinetic(c.scene);
  for (const Event& e : r.history.events) {
    if (!IsImpact(e)) continue;
    if (s.unilateral_from_s && e.t_s >= *s.unilateral_from_s) {
      // The unilateral model's impacts (sliding and flying blocks: the rates alone do not give
      // the kinetic energy) carry the stack's energy before and after, which only the kinetic
      // part changes: the gain relative to that energy.
      RecordGain((e.energy_after_j - e.energy_before_j) / std::abs(e.energy_before_j), &row);
      continue;
    }
    const Sample at = r.trajectory.At(e.t_s);
    const double ke_before = kinetic(e.mode_before, at, e.omega_before_radps);
    const double ke_after = kinetic(e.mode_after, at, e.omega_after_radps);
    if (!(ke_before > 0.0)) continue;
    RecordGain((ke_after - ke_before) / ke_before, &row);
  }
  if (s.impacts_energy_gain > 0) {
    row.detail += (row.detail.empty() ? "" : "; ") + std::to_string(s.impacts_energy_gain) +
                  " impacts flagged ENERGY GAIN by the model";
  }
  return row;
}

// The engines' monitor resolves tilts above MonitorConfig::angle_enter_rad (1e-5 rad); a block
// tilted by a small angle a holds about M g b1 a of potential energy, so impacts with less
// kinetic energy than M g b1 1e-5 are below what the monitor can see and are left out.
const double kEngineResolvedTilt_rad = MonitorConfig{}.angle_enter_rad;

StressRow RunEngineCase(const StressCase& c, const std::string& engine, StressRow row) {
  const GroundMotion motion = GroundMotion::FromScene(c.scene);
  const EngineRun run = RunEngine(engine, c.scene, motion);
  row.wall_s = run.wall_s;
  const RunOutcome& o = run.outcome;
  row.status = StatusText(o.status);
  row.detail = run.summary.value("status_detail", "");
  row.finished = o.status == RunStatus::kCompleted || o.status == RunStatus::kOverturned ||
                 o.status == RunStatus::kAtRest || o.status == RunStatus::kAssumptionViolated;
  SetPeaks(o.peak_theta_rad, &row);
  row.nan = IsNonFinite(o.status) || HistoryHasNonFinite(run.history);
  CountEvents(run.history, &row);
  std::string flags;
  for (const std::string& f : o.violations) flags += (flags.empty() ? "" : ";") + f;
  row.violations = flags.empty() ? "none" : flags;
  // Energy across each impact: the monitor records E = kinetic (base frame) + potential one
  // step before the crossing step and one step after it; the scale is the kinetic energy
  // before, from the recorded rates at the impact's angles (history interpolated).
  ImpactKinetics kinetic(c.scene);
  const double floor_j = kinetic.TiltEnergy_j(kEngineResolvedTilt_rad);
  for (const Event& e : run.history.events) {
    if (!IsImpact(e)) continue;
    const Sample at = AnglesAt(run.history, e.t_s);
    const double ke_before = kinetic(e.mode_before, at, e.omega_before_radps);
    if (!(ke_before > floor_j)) continue;
    RecordGain((e.energy_after_j - e.energy_before_j) / ke_before, &row);
  }
  // Agreement with the reference on the same scene.
  const reference::Result ref = reference::Simulate(c.scene, motion);
  const EngineAgreement a = CompareWithReference(c.scene, ref, run);
  row.has_agreement = true;
  row.theta1_max_abs_error_rad = a.theta1.max_abs_error_rad;
  row.theta1_peak_rel_error = a.theta1.peak_rel_error;
  if (a.theta2) {
    row.theta2_max_abs_error_rad = a.theta2->max_abs_error_rad;
    row.theta2_peak_rel_error = a.theta2->peak_rel_error;
  }
  for (const AngleAgreement& k : a.theta_from3) {
    row.theta_from3_max_abs_error_rad.push_back(k.max_abs_error_rad);
    row.theta_from3_peak_rel_error.push_back(k.peak_rel_error);
  }
  row.impacts_matched = a.impacts.matched;
  row.reference_impacts = a.impacts.reference_impacts;
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
    if (IsReference(engine)) return RunReference(c, row);
    return RunEngineCase(c, engine, row);
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
