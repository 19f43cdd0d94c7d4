#include "compare/perturbation_members.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "compare/agreement.h"
#include "compare/cylinder_compare.h"
#include "reference/stack_model.h"
#include "run/parallel.h"
#include "run/summary.h"
#include "run/tolerance.h"
#include "run/wall_clock.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

// SplitMix64 (Steele, Lea & Flood 2014): a counter-based generator, so a draw depends only on
// (seed, member, slot) and never on the order in which members run.
uint64_t SplitMix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in [-1, 1): 53 random bits.
double Uniform(uint64_t seed, uint64_t member, uint64_t slot) {
  const uint64_t x = SplitMix64(seed ^ SplitMix64(member ^ SplitMix64(slot)));
  return 2.0 * (static_cast<double>(x >> 11) * 0x1.0p-53) - 1.0;
}

// Slots: amplitude of each component (horizontal, vertical, then transverse), initial state,
// a cylinder's initial state, then each record sample (component 0 horizontal, 1 vertical, 2
// transverse). The draws of a planar scene are those it always had.
constexpr uint64_t kSlotAmplitude = 1, kSlotInitial = 8, kSlotSamples = 1ull << 32;
constexpr uint64_t kSlotTransverse = kSlotAmplitude + 2, kSlotCylinderInitial = 1ull << 20;

// The slot of body k's (1-based) initial angle factor (`rate`: of its rate). Bodies 1 and 2 take
// kSlotInitial .. + 3 in the order theta1, theta2, omega1, omega2, body k >= 3 the pair
// kSlotInitial + 4 + 2 (k - 3) (angle), + 1 (rate): the layout in which the draws were first
// made, kept so that every member keeps its inputs.
uint64_t InitialSlot(int body, bool rate) {
  const auto k = static_cast<uint64_t>(body);
  if (body <= 2) return kSlotInitial + (k - 1) + (rate ? 2 : 0);
  return kSlotInitial + 4 + 2 * (k - 3) + (rate ? 1 : 0);
}

MotionComponent PerturbedComponent(const MotionComponent& c, double factor, double precision,
                                   uint64_t seed, uint64_t member, uint64_t component,
                                   double* max_move_mps2) {
  *max_move_mps2 = 0.0;
  const std::vector<double>& res = c.sample_resolution_mps2();
  if (precision > 0.0 && !c.samples_mps2().empty() && res.size() == c.samples_mps2().size()) {
    std::vector<double> a = c.samples_mps2();
    for (size_t k = 0; k < a.size(); ++k) {
      const double move =
          Uniform(seed, member, kSlotSamples * (component + 1) + k) * precision * 0.5 * res[k];
      a[k] += move;
      *max_move_mps2 = std::max(*max_move_mps2, std::abs(move));
    }
    return c.WithSamples(std::move(a)).Scaled(factor);
  }
  return c.Scaled(factor);
}

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::vector<double> OutputGrid_s(const Scene& scene) {
  const double dt = scene.run.output_interval_s;
  const auto n = static_cast<size_t>(std::floor(scene.run.duration_s / dt + 1e-9)) + 1;
  std::vector<double> t_s(n);
  for (size_t k = 0; k < n; ++k) t_s[k] = RoundTime_s(static_cast<double>(k) * dt);
  return t_s;
}

MemberInput PerturbedInput(const Scene& scene, const GroundMotion& motion, int member) {
  const CompareConfig& cfg = scene.compare;
  MemberInput in;
  in.scene = scene;
  MemberPerturbation& p = in.perturbation;
  p.member = member;
  const uint64_t m = static_cast<uint64_t>(member);
  // Each component: its amplitude factor from its slot, its samples from its component index.
  struct Component {
    const std::optional<MotionComponent>& nominal;
    void (GroundMotion::*set)(MotionComponent);
    uint64_t slot, index;
    double *factor, *max_move_mps2;
  };
  const Component components[] = {
      {motion.horizontal(), &GroundMotion::set_horizontal, kSlotAmplitude, 0, &p.horizontal_factor,
       &p.horizontal_max_sample_move_mps2},
      {motion.vertical(), &GroundMotion::set_vertical, kSlotAmplitude + 1, 1, &p.vertical_factor,
       &p.vertical_max_sample_move_mps2},
      {motion.transverse(), &GroundMotion::set_transverse, kSlotTransverse, 2, &p.transverse_factor,
       &p.transverse_max_sample_move_mps2}};
  for (const Component& c : components) {
    if (!c.nominal) continue;
    *c.factor = 1.0 + Uniform(cfg.seed, m, c.slot) * cfg.amplitude_rel;
    (in.motion.*c.set)(PerturbedComponent(*c.nominal, *c.factor, cfg.sample_precision, cfg.seed, m,
                                          c.index, c.max_move_mps2));
  }
  if (scene.three_dimensional()) {
    // A cylinder: its tilt and its rates; a start upright at rest stays so (a factor of zero).
    const auto factor = [&](uint64_t k) {
      return 1.0 + Uniform(cfg.seed, m, kSlotCylinderInitial + k) * cfg.initial_rel;
    };
    p.tilt_factor = factor(0);
    p.tilt_rate_factor = factor(1);
    p.azimuth_rate_factor = factor(2);
    p.spin_rate_factor = factor(3);
    InitialState& c = in.scene.initial;
    c.tilt_rad[0] *= p.tilt_factor;
    c.tilt_rate_radps[0] *= p.tilt_rate_factor;
    c.azimuth_rate_radps[0] *= p.azimuth_rate_factor;
    c.spin_rate_radps[0] *= p.spin_rate_factor;
    return in;
  }
  // Block 1's angle and rate, and every other block's relative to the block below: a closed
  // contact (block 1 flat, or block k flat on block k - 1: a relative value of 0) stays closed,
  // so a member starts in the nominal mode.
  InitialState& s = in.scene.initial;
  const int nb = scene.block_count();
  for (int k = 1; k <= nb; ++k) {
    p.theta_factor.push_back(1.0 + Uniform(cfg.seed, m, InitialSlot(k, false)) * cfg.initial_rel);
    p.omega_factor.push_back(1.0 + Uniform(cfg.seed, m, InitialSlot(k, true)) * cfg.initial_rel);
  }
  std::vector<double> rel_theta(nb, 0.0), rel_omega(nb, 0.0);
  for (int k = 1; k < nb; ++k) {
    rel_theta[k] = s.theta_rad[k] - s.theta_rad[k - 1];
    rel_omega[k] = s.omega_radps[k] - s.omega_radps[k - 1];
  }
  s.theta_rad[0] *= p.theta_factor[0];
  s.omega_radps[0] *= p.omega_factor[0];
  for (int k = 1; k < nb; ++k) {
    s.theta_rad[k] = s.theta_rad[k - 1] + rel_theta[k] * p.theta_factor[k];
    s.omega_radps[k] = s.omega_radps[k - 1] + rel_omega[k] * p.omega_factor[k];
  }
  return in;
}

double SettledAfter_s(const Scene& scene, const GroundMotion& motion, double safety) {
  const double end_s = motion.end_s();
  if (!(end_s > 0.0)) return 0.0;
  if (!std::isfinite(end_s)) return end_s;
  // The rest reactions by the model's contact rule (the thesis's for one or two blocks, the
  // pivot chain's for N >= 3).
  const reference::StackModel model(scene);
  // Whether safety times the base acceleration at t opens a face of the stack at rest.
  auto opens = [&](double t) {
    const double xg = safety * motion.xg_mps2(t);
    const double yg = motion.yg_mps2(t);
    const double yg_worst = yg - (safety - 1.0) * std::abs(yg);
    return !(model.RestFaceMargin(xg, yg_worst) > 0.0);
  };
  auto analytic = [](const std::optional<MotionComponent>& c) {
    return c.has_value() && c->samples_mps2().empty();
  };
  const bool scan = analytic(motion.horizontal()) || analytic(motion.vertical());
  // Records: every sample time (and the window ends); analytic motions: also every 1e-3 s. A
  // face that opens at t may open until the next point: that point is the bound.
  double last_s = 0.0;
  for (double t = 0.0; t < end_s;) {
    double next = motion.next_breakpoint_after(t);
    if (scan) next = std::min(next, t + 1e-3);
    next = std::min(next, end_s);
    if (opens(t)) last_s = next;
    if (!(next > t)) break;
    t = next;
  }
  if (opens(end_s)) last_s = end_s;
  return last_s;
}

namespace {

// Where a run's RMS integral ends: its overturn, or its last sample.
double RmsEnd_s(const MemberOutcome& o, const History& h) {
  return o.overturned_block != 0 ? o.overturn_t_s : h.samples.empty() ? 0.0 : h.samples.back().t_s;
}

// The root mean square of value(sample) over the scene's duration: trapezoids on the history's
// samples (the engines' output grid, the reference's grid and event times) up to t_end.
template <typename Value>
double RmsOver(const History& h, double t_end, double duration_s, Value value) {
  double integral = 0.0;
  for (size_t k = 1; k < h.samples.size(); ++k) {
    const Sample& a = h.samples[k - 1];
    const Sample& c = h.samples[k];
    if (a.t_s >= t_end) break;
    const double va = value(a);
    const double vc = value(c);
    integral += 0.5 * (va * va + vc * vc) * (std::min(c.t_s, t_end) - a.t_s);
  }
  return duration_s > 0.0 ? std::sqrt(integral / duration_s) : 0.0;
}

// A cylinder's outcome: its tilt's peak (the run's own, at every step for the engines), residual
// and RMS; an overturn's time and fall azimuth.
MemberOutcome CylinderOutcomeOf(const EngineRun& run, const Scene& scene) {
  MemberOutcome o;
  const RunOutcome& s = run.outcome;
  o.status = s.status;
  if (run.summary.is_object()) o.detail = run.summary.value("status_detail", std::string());
  o.wall_s = run.wall_s;
  if (s.blocks() >= 1) {
    o.peak_rad[0] = s.peak_theta_rad[0];
    o.peak_t_s[0] = s.peak_theta_t_s[0];
  }
  const StateQuantityReader tilt(run.history, "tilt");
  if (!run.history.samples.empty()) o.residual_rad[0] = tilt(run.history.samples.back(), 1);
  // The time of the largest tilt, to the resolution its value is compared at (the statistics'
  // margin, a tenth of the tolerance at the peak): the first sample within it. A wobble without
  // losses returns to its peak tilt again and again, and which return rounding makes the largest
  // is no outcome.
  const double resolution_rad = 0.1 * AngleTolerance_rad(scene, 1, o.peak_rad[0]);
  for (const Sample& x : run.history.samples) {
    if (tilt(x, 1) >= o.peak_rad[0] - resolution_rad) {
      o.peak_t_s[0] = std::min(o.peak_t_s[0], x.t_s);
      break;
    }
  }
  if (s.overturned()) {
    o.overturned_block = 1;
    o.overturn_t_s = s.overturn_t_s;
    o.peak_rad[0] = o.residual_rad[0] = scene.model.overturn_rad;
    o.peak_t_s[0] = o.overturn_t_s;
    o.overturn_azimuth_rad = FallAzimuthOf(run);
  }
  o.rms_rad[0] = RmsOver(run.history, RmsEnd_s(o, run.history), scene.run.duration_s,
                         [&](const Sample& x) { return tilt(x, 1); });
  return o;
}

}  // namespace

MemberOutcome OutcomeOf(const EngineRun& run, const Scene& scene, double min_impact_rate_radps) {
  if (run.history.shape == kCylinderShape) return CylinderOutcomeOf(run, scene);
  // The blocks both the scene and the run have (a run of another stack compares block 1).
  const int nb = scene.block_count() == run.outcome.blocks() ? scene.block_count() : 1;
  MemberOutcome o;
  const RunOutcome& s = run.outcome;
  o.status = s.status;
  if (run.summary.is_object()) o.detail = run.summary.value("status_detail", std::string());
  o.wall_s = run.wall_s;
  if (s.overturned()) {
    o.overturned_block = s.overturned_block;
    o.overturn_t_s = s.overturn_t_s;
  }
  for (int b = 0; b < std::min(nb, s.blocks()); ++b) {
    o.peak_rad[b] = s.peak_theta_rad[b];
    o.peak_t_s[b] = s.peak_theta_t_s[b];
  }
  if (!run.history.samples.empty()) {
    const Sample& last = run.history.samples.back();
    for (int b = 0; b < std::min(nb, last.blocks()); ++b) o.residual_rad[b] = last.theta_rad[b];
  }
  // An overturned block's peak and residual are the overturn angle, whatever sample an engine
  // stopped on after crossing it (Bullet's last step ends past the crossing).
  if (o.overturned_block >= 1 && o.overturned_block <= kMaxBlocks) {
    const int b = o.overturned_block - 1;
    const double sign = o.residual_rad[b] < 0.0 ? -1.0 : 1.0;
    o.peak_rad[b] = scene.model.overturn_rad;
    o.peak_t_s[b] = o.overturn_t_s;
    o.residual_rad[b] = sign * scene.model.overturn_rad;
  }
  // RMS angles, up to an overturn.
  const double t_end = RmsEnd_s(o, run.history);
  for (int b = 0; b < nb; ++b) {
    o.rms_rad[b] = RmsOver(run.history, t_end, scene.run.duration_s,
                           [b](const Sample& x) { return x.theta_rad[b]; });
  }
  o.impacts = CountComparedImpacts(run.history, min_impact_rate_radps);
  return o;
}

namespace {

// A run on the grid `t_s`, one vector per block. Beyond the end of a run stopped by a violated
// assumption, or ended at its last finite state, there is nothing to compare (NaN); beyond an
// overturn, the overturned block stays at its overturn angle (a lasting outcome that other
// members may not share) and the other blocks' angles are undefined (NaN: the model ends
// there). Past the first impact the model leaves undecided (summary "undetermined"), a run's
// motion is its rule's choice, not the model's: nothing there to compare either (NaN).
std::vector<std::vector<double>> OnGrid(const reference::Result& r, const std::vector<double>& t_s,
                                        int nb) {
  const bool stopped =
      r.summary.status == RunStatus::kAssumptionViolated || IsNonFinite(r.summary.status);
  const int overturned = r.summary.overturn_block.value_or(0);
  const double end = r.trajectory.end_s();
  const double decided_until = r.summary.undetermined_from_s.value_or(INFINITY);
  std::vector<std::vector<double>> th(static_cast<size_t>(nb),
                                      std::vector<double>(t_s.size(), std::nan("")));
  for (size_t k = 0; k < t_s.size(); ++k) {
    const bool after_end = t_s[k] > end;
    if (stopped && after_end) break;
    if (t_s[k] > decided_until) break;
    const Sample s = r.trajectory.At(t_s[k]);
    for (int b = 0; b < nb; ++b) {
      if (!after_end || overturned == b + 1) th[b][k] = s.theta_rad[b];
    }
  }
  return th;
}

// Where a run's model ends without an outcome: its stop (a violated assumption, a state no
// longer finite) or its first undecided impact; infinity when it decides the whole run.
double ModelEnd_s(const reference::Result& r) {
  double end = r.summary.undetermined_from_s.value_or(INFINITY);
  if (r.summary.status == RunStatus::kAssumptionViolated || IsNonFinite(r.summary.status)) {
    end = std::min(end, r.trajectory.end_s());
  }
  return end;
}

// Block b's band (lo, hi, spread about the nominal run) over the members' grids, its largest
// spread and its horizon: the first grid time where the spread exceeds the tolerance, a
// member's model ends while the nominal run's goes on, or the nominal run's model ends.
void MeasureSpread(int b, const std::vector<double>& nominal, double nominal_model_end_s,
                   const std::vector<std::vector<std::vector<double>>>& grids,
                   const std::vector<double>& member_model_end_s, ReferencePerturbationMembers* e) {
  const size_t n_grid = e->t_s.size();
  e->lo_rad[b] = nominal;
  e->hi_rad[b] = nominal;
  e->spread_rad[b].assign(n_grid, 0.0);
  for (size_t k = 0; k < n_grid; ++k) {
    const double nom = nominal[k];
    if (e->t_s[k] > nominal_model_end_s) {
      // The nominal run's model ends here (it stopped, or its motion is undecided): nothing
      // is predictable from here on, and the horizon is here at the latest.
      if (!e->horizon_s[b]) e->horizon_s[b] = e->t_s[k];
      continue;
    }
    if (std::isnan(nom)) continue;  // past the nominal run's overturn
    // A member whose model ended here while the nominal run's goes on (it stopped, or its
    // motion is undecided) is a spread beyond any tolerance: the inputs' uncertainty reaches
    // a different end.
    bool lost = false;
    for (size_t i = 0; i < grids.size(); ++i) {
      const double v = grids[i][b][k];
      if (e->t_s[k] > member_model_end_s[i]) lost = true;
      if (std::isnan(v)) continue;
      e->lo_rad[b][k] = std::min(e->lo_rad[b][k], v);
      e->hi_rad[b][k] = std::max(e->hi_rad[b][k], v);
      e->spread_rad[b][k] = std::max(e->spread_rad[b][k], std::abs(v - nom));
    }
    e->max_spread_rad[b] = std::max(e->max_spread_rad[b], e->spread_rad[b][k]);
    if (!e->horizon_s[b] && (lost || e->spread_rad[b][k] > e->tolerance_rad[b])) {
      e->horizon_s[b] = e->t_s[k];
    }
  }
}

}  // namespace

ReferencePerturbationMembers RunReferencePerturbationMembers(
    const Scene& nominal_scene, const GroundMotion& motion, const reference::Result& nominal,
    int members, std::span<const double> tolerance_rad, int threads, double min_impact_rate_radps) {
  const auto start = std::chrono::steady_clock::now();
  const int nb = nominal_scene.block_count();
  const auto nbs = static_cast<size_t>(nb);
  if (tolerance_rad.size() < nbs) {
    throw std::invalid_argument(
        "RunReferencePerturbationMembers: " + std::to_string(tolerance_rad.size()) +
        " tolerances for " + std::to_string(nb) + " blocks");
  }
  ReferencePerturbationMembers e;
  e.members = members;
  e.blocks = nb;
  e.tolerance_rad.assign(tolerance_rad.begin(), tolerance_rad.begin() + nb);
  e.horizon_s.assign(nbs, std::nullopt);
  e.max_spread_rad.assign(nbs, 0.0);
  e.lo_rad.resize(nbs);
  e.hi_rad.resize(nbs);
  e.spread_rad.resize(nbs);
  e.local_tolerance_rad.resize(nbs);
  e.t_s = OutputGrid_s(nominal_scene);
  const size_t n_grid = e.t_s.size();
  const std::vector<std::vector<double>> nominal_grid = OnGrid(nominal, e.t_s, nb);
  const double nominal_model_end_s = ModelEnd_s(nominal);
  std::vector<double> member_model_end_s(static_cast<size_t>(members), INFINITY);

  e.perturbations.resize(members);
  e.outcomes.resize(members);
  // grids[i][b]: member i's block b on the grid.
  std::vector<std::vector<std::vector<double>>> grids(members);
  ProgressLine progress("reference ensemble");
  ParallelFor(
      members, threads,
      [&](int i) {
        const MemberInput in = PerturbedInput(nominal_scene, motion, i);
        const auto t0 = std::chrono::steady_clock::now();
        reference::Result r = reference::Simulate(in.scene, in.motion);
        member_model_end_s[i] = ModelEnd_s(r);
        EngineRun run;
        run.engine = "reference";
        run.wall_s = SecondsSince(t0);
        run.summary = ReferenceSummaryJson(in.scene, r, run.wall_s);
        run.outcome = ReferenceOutcome(r);
        grids[i] = OnGrid(r, e.t_s, nb);
        run.history = std::move(r.history);
        e.perturbations[i] = in.perturbation;
        e.outcomes[i] = OutcomeOf(run, in.scene, min_impact_rate_radps);
        e.outcomes[i].member = i;
      },
      [&](int done, int total) { progress.Update(done, total); });

  for (int b = 0; b < nb; ++b) {
    // The local tolerance, for the band file (the report draws it); the horizon is judged on
    // the scale of the whole run (docs/verdicts.md, "The error scale").
    const ToleranceProfile profile = LocalTolerance(nominal_scene, b + 1, nominal.history);
    e.local_tolerance_rad[b].resize(n_grid);
    for (size_t k = 0; k < n_grid; ++k) e.local_tolerance_rad[b][k] = profile.At(e.t_s[k]);
    MeasureSpread(b, nominal_grid[b], nominal_model_end_s, grids, member_model_end_s, &e);
  }
  e.wall_s = SecondsSince(start);
  return e;
}

std::vector<MemberOutcome> RunEnginePerturbationMembers(const std::string& name, const Scene& scene,
                                                        const GroundMotion& motion, int members,
                                                        int threads, double min_impact_rate_radps) {
  std::vector<MemberOutcome> out(members);
  ProgressLine progress(name + " ensemble");
  ParallelFor(
      members, threads,
      [&](int i) {
        const MemberInput in = PerturbedInput(scene, motion, i);
        SimulateOptions options;
        options.check_convergence = false;
        // (A cylinder's runs go to the end: its onset from rest is another criterion.)
        if (!in.scene.three_dimensional()) {
          options.stop_at_rest_after_s = SettledAfter_s(in.scene, in.motion);
        }
        const EngineRun run = RunEngine(name, in.scene, in.motion, options);
        out[i] = OutcomeOf(run, in.scene, min_impact_rate_radps);
        out[i].member = i;
      },
      [&](int done, int total) { progress.Update(done, total); });
  return out;
}

nlohmann::json PredictabilityJson(const Scene& scene, const ReferencePerturbationMembers& e) {
  const int nb = std::min(scene.block_count(), static_cast<int>(e.horizon_s.size()));
  const CompareConfig& c = scene.compare;
  nlohmann::json j;
  j["members"] = e.members;
  j["perturbation"] = {
      {"amplitude_rel", c.amplitude_rel},
      {"sample_precision", c.sample_precision},
      {"initial_rel", c.initial_rel},
      {"seed", c.seed},
      {"rule",
       "each component's amplitude x (1 + u amplitude_rel), each record sample + u "
       "sample_precision (half a unit of its last printed digit), each nonzero initial value x "
       "(1 + u initial_rel); u uniform in [-1, 1], independent"}};
  if (e.stem == "tilt") {
    j["perturbation"]["rule"] =
        "each component's amplitude (horizontal, transverse, vertical) x (1 + u amplitude_rel), "
        "each record sample + u sample_precision (half a unit of its last printed digit), the "
        "cylinder's initial tilt and its tilt, azimuth and spin rates x (1 + u initial_rel); u "
        "uniform in [-1, 1], independent; the spread is |member - nominal| of the tilt vector "
        "(tilt_x, tilt_y)";
  }
  auto opt = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  j["horizon_s"] = nlohmann::json::object();
  j["spread_rad"] = nlohmann::json::object();
  j["tolerance_rad"] = nlohmann::json::object();
  for (int b = 0; b < nb; ++b) {
    const std::string th = BodyColumn(e.stem, b + 1);
    j["horizon_s"][th] = opt(e.horizon_s[b]);
    j["spread_rad"][th] = e.max_spread_rad[b];
    j["tolerance_rad"][th] = e.tolerance_rad[b];
  }
  nlohmann::json statuses = nlohmann::json::object();
  for (const MemberOutcome& o : e.outcomes) {
    const char* text = StatusText(o.status);
    statuses[text] = statuses.value(text, 0) + 1;
  }
  j["statuses"] = statuses;
  j["wall_s"] = e.wall_s;
  return j;
}

std::string PerturbationBandCsv(const ReferencePerturbationMembers& e) {
  const int nb = std::min(e.blocks, static_cast<int>(e.lo_rad.size()));
  std::string out = "t";
  for (int b = 1; b <= nb; ++b) {
    const std::string th = BodyColumn(e.stem, b);
    for (const char* col : {"_lo", "_hi", "_spread", "_tol"}) out.append(",").append(th + col);
  }
  out += "\n";
  for (size_t k = 0; k < e.t_s.size(); ++k) {
    // The band ends with the nominal run (a block's angle is undefined after it).
    bool ended = false;
    for (int b = 0; b < nb; ++b) ended = ended || std::isnan(e.lo_rad[b][k]);
    if (ended) break;
    out += Num(e.t_s[k]);
    for (int b = 0; b < nb; ++b) {
      for (double v :
           {e.lo_rad[b][k], e.hi_rad[b][k], e.spread_rad[b][k], e.local_tolerance_rad[b][k]}) {
        out.append(",").append(Num(v));
      }
    }
    out += "\n";
  }
  return out;
}

std::string OutcomesCsv(const std::vector<MemberOutcome>& outcomes,
                        const std::vector<MemberPerturbation>& perturbations, int blocks) {
  const int nb = std::clamp(blocks, 1, kMaxBlocks);
  std::string out =
      "member,horizontal_factor,vertical_factor,initial_factor_theta1,status,overturned_block,"
      "overturn_t_s,peak_theta1_rad,peak_theta1_t_s,residual_theta1_rad,";
  for (int b = 2; b <= nb; ++b) {
    const std::string th = BodyColumn("theta", b);
    out.append("peak_").append(th).append("_rad,peak_").append(th).append("_t_s,residual_");
    out.append(th).append("_rad,");
  }
  for (int b = 1; b <= nb; ++b) out.append("rms_").append(BodyColumn("theta", b)).append("_rad,");
  out += "impacts\n";
  for (const MemberOutcome& o : outcomes) {
    const MemberPerturbation p = o.member >= 0 && o.member < static_cast<int>(perturbations.size())
                                     ? perturbations[o.member]
                                     : MemberPerturbation{};
    // Appended piece by piece (GCC 12 warns, wrongly, on long chains of string +).
    out.append(std::to_string(o.member));
    const double theta1_factor = p.theta_factor.empty() ? 1.0 : p.theta_factor[0];
    for (double v : {p.horizontal_factor, p.vertical_factor, theta1_factor}) {
      out.append(",").append(Num(v));
    }
    out.append(",").append(StatusText(o.status)).append(",");
    if (o.overturned_block) out.append(std::to_string(o.overturned_block));
    out.append(",");
    if (o.overturned_block) out.append(Num(o.overturn_t_s));
    for (int b = 0; b < nb; ++b) {
      out.append(",").append(Num(o.peak_rad[b]));
      out.append(",").append(Num(o.peak_t_s[b]));
      out.append(",").append(Num(o.residual_rad[b]));
    }
    for (int b = 0; b < nb; ++b) out.append(",").append(Num(o.rms_rad[b]));
    out.append(",").append(std::to_string(o.impacts)).append("\n");
  }
  return out;
}

std::string CylinderOutcomesCsv(const std::vector<MemberOutcome>& outcomes,
                                const std::vector<MemberPerturbation>& perturbations) {
  std::string out =
      "member,horizontal_factor,transverse_factor,vertical_factor,initial_factor_tilt1,status,"
      "overturned,overturn_t_s,overturn_azimuth_rad,peak_tilt1_rad,peak_tilt1_t_s,"
      "residual_tilt1_rad,rms_tilt1_rad\n";
  for (const MemberOutcome& o : outcomes) {
    const MemberPerturbation p = o.member >= 0 && o.member < static_cast<int>(perturbations.size())
                                     ? perturbations[o.member]
                                     : MemberPerturbation{};
    out.append(std::to_string(o.member));
    for (double v : {p.horizontal_factor, p.transverse_factor, p.vertical_factor, p.tilt_factor}) {
      out.append(",").append(Num(v));
    }
    out.append(",").append(StatusText(o.status));
    out.append(o.overturned_block ? ",yes," : ",no,");
    if (o.overturned_block) out.append(Num(o.overturn_t_s));
    out.append(",");
    if (o.overturn_azimuth_rad) out.append(Num(*o.overturn_azimuth_rad));
    for (double v : {o.peak_rad[0], o.peak_t_s[0], o.residual_rad[0], o.rms_rad[0]}) {
      out.append(",").append(Num(v));
    }
    out.append("\n");
  }
  return out;
}

}  // namespace rockbench
