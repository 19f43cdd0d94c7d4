#include "compare/agreement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "compare/angle_error.h"
#include "run/tolerance.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

// The interface of an impact event (0: block 1 on the ground; k: block k + 1 on block k), -1
// for any other event.
int ImpactInterface(const Event& e) {
  return ::rockbench::ImpactInterface(e.kind);
}

bool IsImpact(const Event& e) {
  return ImpactInterface(e) >= 0;
}

// Landing rate of an impact: the rate of the block that lands, relative to its support.
double LandingRate(const Event& e) {
  const BlockValues& w = e.omega_before_radps;
  const int k = ImpactInterface(e);
  if (k <= 0 || w.size() < 2) return std::abs(w[0]);
  const size_t i = std::min(static_cast<size_t>(k), w.size() - 1);
  return std::abs(w[i] - w[i - 1]);
}

std::vector<const Event*> Impacts(const History& h, double min_rate, int* all) {
  std::vector<const Event*> out;
  *all = 0;
  for (const Event& e : h.events) {
    if (!IsImpact(e)) continue;
    ++*all;
    if (LandingRate(e) >= min_rate) out.push_back(&e);
  }
  return out;
}

// Peak |theta_i| and its time, measured by the run itself (at every step for the engines).
void EnginePeak(const EngineRun& run, int block, double* peak, double* t) {
  const RunOutcome& o = run.outcome;
  const bool has = block >= 1 && block <= o.blocks();
  *peak = has ? o.peak_theta_rad[block - 1] : 0.0;
  *t = has ? o.peak_theta_t_s[block - 1] : 0.0;
}

// Mode family for the final-state check.
std::string Family(const Configuration& m, bool overturned, bool left_support = false) {
  if (left_support) return "left_support";
  if (overturned) return "overturned";
  return m.at_rest() ? "rest" : "rocking";
}

ImpactAgreement MatchImpacts(const History& ref, const History& eng, double until_s,
                             double min_rate) {
  ImpactAgreement a;
  std::vector<const Event*> r = Impacts(ref, min_rate, &a.reference_impacts_all);
  std::vector<const Event*> e = Impacts(eng, min_rate, &a.engine_impacts_all);
  // Only impacts inside the compared window count.
  auto in_window = [until_s](const Event* x) { return x->t_s <= until_s + 1e-12; };
  r.erase(std::remove_if(r.begin(), r.end(), [&](const Event* x) { return !in_window(x); }),
          r.end());
  e.erase(std::remove_if(e.begin(), e.end(), [&](const Event* x) { return !in_window(x); }),
          e.end());
  a.reference_impacts = static_cast<int>(r.size());
  a.engine_impacts = static_cast<int>(e.size());
  // Impacts slower than twice the minimum rate are marginal: one run may see one where the
  // other's is just below the minimum, so an unmatched marginal impact is skipped rather than
  // ending the sequence.
  auto marginal = [min_rate](const Event* x) { return LandingRate(*x) < 2.0 * min_rate; };
  size_t i = 0, j = 0;
  char buf[160];
  while (i < r.size() && j < e.size()) {
    const double tr = r[i]->t_s, te = e[j]->t_s;
    double gap = 0.5;
    if (i > 0) gap = std::min(gap, tr - r[i - 1]->t_s);
    if (i + 1 < r.size()) gap = std::min(gap, r[i + 1]->t_s - tr);
    const double window = std::clamp(0.5 * gap, 2e-3, 0.25);
    if (r[i]->kind == e[j]->kind && std::abs(te - tr) <= window) {
      a.time_errors_s.push_back(te - tr);
      a.max_abs_time_error_s = std::max(a.max_abs_time_error_s, std::abs(te - tr));
      ++i;
      ++j;
      continue;
    }
    // The earlier of the two is the missing (reference) or extra (engine) impact.
    if (te < tr) {
      if (marginal(e[j])) {
        ++j;
        ++a.skipped_marginal;
        continue;
      }
      std::snprintf(buf, sizeof buf, "extra %s at %.6f s", e[j]->kind.c_str(), te);
    } else {
      if (marginal(r[i])) {
        ++i;
        ++a.skipped_marginal;
        continue;
      }
      std::snprintf(buf, sizeof buf, "missing %s at %.6f s", r[i]->kind.c_str(), tr);
    }
    a.first_mismatch = buf;
    break;
  }
  a.matched = static_cast<int>(a.time_errors_s.size());
  if (a.first_mismatch.empty()) {
    // Left over at the end: marginal ones do not count.
    while (i < r.size() && marginal(r[i])) ++i;
    while (j < e.size() && marginal(e[j])) ++j;
    if (i < r.size()) {
      std::snprintf(buf, sizeof buf, "missing %s at %.6f s", r[i]->kind.c_str(), r[i]->t_s);
      a.first_mismatch = buf;
    } else if (j < e.size()) {
      std::snprintf(buf, sizeof buf, "extra %s at %.6f s", e[j]->kind.c_str(), e[j]->t_s);
      a.first_mismatch = buf;
    }
  }
  return a;
}

nlohmann::json AngleJson(const AngleAgreement& a) {
  return {
      {"max_abs_error_rad", a.max_abs_error_rad},
      {"rms_error_rad", a.rms_error_rad},
      {"peak_rel_error", a.peak_rel_error},
      {"peak_time_error_s", a.peak_time_error_s},
      {"horizon_s", RoundTime_s(a.horizon_s)},
      {"within_tolerance", a.within_tolerance},
      {"tolerance_rad", a.tolerance_rad},
      {"tolerance_min_rad", a.tolerance_min_rad},
      {"tolerance_at_horizon_rad",
       a.within_tolerance ? nlohmann::json(nullptr) : nlohmann::json(a.tolerance_at_horizon_rad)},
      {"max_error_ratio", a.max_error_ratio},
      {"max_error_ratio_t_s", RoundTime_s(a.max_error_ratio_t_s)},
      {"max_error_ratio_predictable", a.max_error_ratio_predictable},
      {"max_abs_error_horizon_rad", a.max_abs_error_horizon_rad},
      {"rms_error_horizon_rad", a.rms_error_horizon_rad},
      {"peak_reference_rad", a.peak_reference_rad},
      {"peak_reference_t_s", a.peak_reference_t_s},
      {"peak_engine_rad", a.peak_engine_rad},
      {"peak_engine_t_s", a.peak_engine_t_s},
      {"max_abs_error_predictable_rad", a.max_abs_error_predictable_rad},
      {"rms_error_predictable_rad", a.rms_error_predictable_rad},
      {"max_abs_error_beyond_rad", a.max_abs_error_beyond_rad},
      {"rms_error_beyond_rad", a.rms_error_beyond_rad},
      {"samples_beyond", a.samples_beyond},
      {"predictability_horizon_s", std::isfinite(a.predictability_horizon_s)
                                       ? nlohmann::json(a.predictability_horizon_s)
                                       : nlohmann::json(nullptr)},
      {"judged", a.judged},
      {"floor_rad", a.floor_rad},
      {"peak_abs_error_rad", a.peak_engine_rad - a.peak_reference_rad},
      {"peak_tolerance_rad", a.peak_tolerance_rad},
      {"peak_within_tolerance", a.peak_within_tolerance},
      {"impacts_reference", a.impacts_reference},
      {"impacts_engine", a.impacts_engine}};
}

nlohmann::json SlipJson(const SlipAgreement& a) {
  return {{"max_abs_error_m", a.max_abs_error_m},
          {"rms_error_m", a.rms_error_m},
          {"final_reference_m", a.final_reference_m},
          {"final_engine_m", a.final_engine_m},
          {"tolerance_m", a.tolerance_m},
          {"floor_m", a.floor_m},
          {"peak_reference_m", a.peak_reference_m},
          {"peak_reference_t_s", a.peak_reference_t_s},
          {"peak_engine_m", a.peak_engine_m},
          {"max_abs_error_predictable_m", a.max_abs_error_predictable_m},
          {"max_error_ratio_predictable", a.max_error_ratio_predictable},
          {"within_tolerance", a.within_tolerance},
          {"horizon_s", RoundTime_s(a.horizon_s)},
          {"time_slack_s", a.time_slack_s},
          {"max_abs_error_slack_m", a.max_abs_error_slack_m}};
}

// Impacts of interface `k` (block k + 1 on its support) faster than `min_rate` up to until_s.
int InterfaceImpacts(const History& h, int k, double until_s, double min_rate) {
  int n = 0;
  for (const Event& e : h.events) {
    if (e.t_s > until_s + 1e-12) break;
    if (ImpactInterface(e) == k && LandingRate(e) >= min_rate) ++n;
  }
  return n;
}

}  // namespace

bool PeakAgrees(double peak_reference_rad, double peak_engine_rad, double floor_rad,
                double* tolerance_rad) {
  const double tol = std::max(kPeakToleranceRel * std::abs(peak_reference_rad),
                              kPeakToleranceFloorFraction * floor_rad);
  if (tolerance_rad) *tolerance_rad = tol;
  return std::abs(peak_engine_rad - peak_reference_rad) <= tol;
}

double SlipTolerance_m(const Scene& scene, int block, double peak_reference_m) {
  const BlockDef& d = scene.blocks.at(static_cast<size_t>(block - 1));
  const double alpha = std::atan(d.width_m / d.height_m);
  return std::max(0.1 * std::abs(peak_reference_m), 0.01 * alpha * d.width_m);
}

void CopyEngineRunStatus(const EngineRun& run, EngineAgreement* a) {
  a->engine = run.engine;
  a->wall_s = run.wall_s;
  a->status = run.outcome.status;
  // The monitor's measures behind the flags, passed through to comparison.json.
  if (run.summary.is_object() && run.summary.contains("violations")) {
    a->violations = run.summary["violations"];
  }
  if (run.summary.is_object()) {
    a->status_detail = run.summary.value("status_detail", std::string());
    if (const auto nf = run.summary.find("non_finite"); nf != run.summary.end()) {
      a->non_finite_what = nf->value("quantity", std::string("a quantity")) + " is " +
                           nf->value("value", std::string("not finite"));
      a->non_finite_t_s = nf->value("t_s", 0.0);
    }
  }
  a->flags = run.outcome.violations;
  a->flag_onsets_t_s = run.outcome.violation_onsets_t_s;
  a->flag_onsets_t_s.resize(a->flags.size(), run.outcome.end_t_s);
  a->significant_flags = run.outcome.significant_violations;
  a->significant_onsets_t_s = run.outcome.significant_onsets_t_s;
  a->significant_onsets_t_s.resize(a->significant_flags.size(), run.outcome.end_t_s);
}

void SampledPeak(const History& h, const StateQuantityReader& angle, int block, double until_s,
                 double* peak, double* t) {
  *peak = 0.0;
  *t = 0.0;
  for (const Sample& x : h.samples) {
    if (x.t_s > until_s + 1e-12) break;
    const double v = std::abs(angle(x, block + 1));
    if (v > *peak) {
      *peak = v;
      *t = x.t_s;
    }
  }
}

int CountComparedImpacts(const History& history, double min_rate_radps) {
  int all = 0;
  return static_cast<int>(Impacts(history, min_rate_radps, &all).size());
}

namespace {

// The compared angle's stem of body `block` (1-based): its kind's first quantity judged as an
// angle ("theta" for the planar block).
std::string ComparedAngleStem(const Scene& scene, int block) {
  const BodyKind* kind = FindBodyKind(scene.blocks.at(static_cast<size_t>(block - 1)).shape);
  if (kind) {
    for (const StateQuantity& q : kind->state) {
      if (q.compared_angle) return q.stem;
    }
  }
  return "theta";
}

// The engine's and the reference's statuses, flags and how each run ended, copied for the
// verdict and comparison.json.
void CopyRunStatuses(const reference::Result& ref, const EngineRun& run, EngineAgreement* a) {
  CopyEngineRunStatus(run, a);
  const reference::Summary& rs = ref.summary;
  a->reference_status = rs.status;
  a->reference_status_detail = rs.status_detail;
  a->reference_end_s = ref.trajectory.end_s();
  a->reference_undetermined_s = rs.undetermined_from_s;
  a->reference_undetermined_detail = rs.undetermined_detail;
  if (IsNonFinite(rs.status)) {
    a->reference_non_finite_what = rs.non_finite_quantity + " is " + rs.non_finite_value;
    a->reference_non_finite_t_s = rs.non_finite_t_s;
  }
}

// The end of the common grid: the engine's sample times, up to the end of the shorter
// meaningful run. A reference that stopped at rest stays valid afterwards (At clamps to its
// end); one that ended non_finite has nothing after its last finite state.
double ComparedUntil_s(const reference::Result& ref, const EngineRun& run) {
  const reference::Summary& rs = ref.summary;
  double until = run.history.samples.empty() ? 0.0 : run.history.samples.back().t_s;
  // The reference ends where a block overturns or leaves its support (it has no model of what
  // follows), where its assumptions end, or at its last finite state.
  if (rs.status == RunStatus::kOverturned || rs.status == RunStatus::kLeftSupport ||
      rs.status == RunStatus::kAssumptionViolated || IsNonFinite(rs.status)) {
    until = std::min(until, ref.trajectory.end_s());
  }
  // Past an impact the model leaves undecided, the reference's motion is its rule's choice.
  if (rs.undetermined_from_s) until = std::min(until, *rs.undetermined_from_s);
  return until;
}

// Body b's (0-based) peaks over the compared window, their errors and its impacts. Peaks are
// compared over the compared window: where the reference's model stopped, or stopped deciding,
// before a run's end, the peaks after that instant are not the model's.
void ComparePeaks(const reference::Result& ref, const EngineRun& run, int b, double until,
                  double min_rate, AngleAgreement* g) {
  const reference::Summary& rs = ref.summary;
  g->peak_reference_rad = rs.peak_theta_rad[b];
  g->peak_reference_t_s = rs.peak_theta_t_s[b];
  EnginePeak(run, b + 1, &g->peak_engine_rad, &g->peak_engine_t_s);
  if (g->peak_engine_t_s > until) {
    const StateQuantityReader angle(run.history, g->quantity);
    SampledPeak(run.history, angle, b, until, &g->peak_engine_rad, &g->peak_engine_t_s);
  }
  if (g->peak_reference_t_s > until) {
    const StateQuantityReader angle(ref.history, g->quantity);
    SampledPeak(ref.history, angle, b, until, &g->peak_reference_rad, &g->peak_reference_t_s);
  }
  const double peak_ref = g->peak_reference_rad;
  g->peak_rel_error = peak_ref > 0.0 ? (g->peak_engine_rad - peak_ref) / peak_ref : 0.0;
  g->peak_time_error_s = g->peak_engine_t_s - g->peak_reference_t_s;
  g->peak_within_tolerance =
      PeakAgrees(peak_ref, g->peak_engine_rad, g->floor_rad, &g->peak_tolerance_rad);
  g->impacts_reference = InterfaceImpacts(ref.history, b, until, min_rate);
  g->impacts_engine = InterfaceImpacts(run.history, b, until, min_rate);
}

// Every body's compared angle on the common grid up to `until`, with its tolerance: the
// scene's [compare] tolerance, else the local tolerance (run/tolerance.h).
std::vector<AngleAgreement> CompareAngles(const Scene& scene, const reference::Result& ref,
                                          const EngineRun& run, double until,
                                          const CompareOptions& options, int* samples_compared) {
  const int nb = scene.block_count();
  const reference::Summary& rs = ref.summary;
  std::vector<AngleAgreement> ang(nb);
  std::vector<ToleranceProfile> profile(nb);
  for (int b = 0; b < nb; ++b) {
    ang[b].quantity = ComparedAngleStem(scene, b + 1);
    ang[b].tolerance_rad = AngleTolerance_rad(scene, b + 1, rs.peak_theta_rad[b]);
    ang[b].horizon_s = until;
    ang[b].predictability_horizon_s = options.predictability_horizon_s[b];
    profile[b] = LocalTolerance(scene, b + 1, ref.history);
    ang[b].tolerance_min_rad = profile[b].Min();
    // Below kJudgedPeakOverFloor floors of motion the pointwise tolerance is more than a fifth
    // of the motion: the peak judges the block instead.
    ang[b].floor_rad = profile[b].fixed_rad ? *profile[b].fixed_rad : profile[b].floor_rad;
    ang[b].judged = !(ang[b].floor_rad * kJudgedPeakOverFloor > rs.peak_theta_rad[b]);
  }
  std::vector<AngleErrorSums> sums;
  std::vector<StateQuantityReader> run_angle, ref_angle;
  for (int b = 0; b < nb; ++b) {
    sums.emplace_back(options.predictability_horizon_s[b]);
    run_angle.emplace_back(run.history, ang[b].quantity);
    ref_angle.emplace_back(ref.history, ang[b].quantity);
  }
  int n = 0;
  for (const Sample& s : run.history.samples) {
    if (s.t_s > until + 1e-12) break;
    const Sample r = ref.trajectory.At(s.t_s);
    ++n;
    for (int b = 0; b < nb; ++b) {
      const double e = std::abs(run_angle[b](s, b + 1) - ref_angle[b](r, b + 1));
      sums[b].Add(s.t_s, e, profile[b].At(s.t_s), &ang[b]);
    }
  }
  *samples_compared = n;
  for (int b = 0; b < nb; ++b) {
    AngleAgreement& g = ang[b];
    sums[b].Finish(&g);
    ComparePeaks(ref, run, b, until, options.min_impact_rate_radps, &g);
  }
  return ang;
}

// Whether a sample carries slip and lift of `nb` bodies.
bool HasSlip(const Sample& x, int nb) {
  return x.u_m.size() >= static_cast<size_t>(nb) && x.z_m.size() >= static_cast<size_t>(nb);
}

// The reference's peak |u_k| and |z_k| over its whole run, and the tolerances they set.
void SlipPeaks(const Scene& scene, const History& reference, std::vector<BodyAgreement>* bodies) {
  const int nb = static_cast<int>(bodies->size());
  for (const Sample& r : reference.samples) {
    if (!HasSlip(r, nb)) break;
    for (int b = 0; b < nb; ++b) {
      const double values[2] = {r.u_m[b], r.z_m[b]};
      SlipAgreement* gs[2] = {&*(*bodies)[b].slip, &*(*bodies)[b].lift};
      for (int q = 0; q < 2; ++q) {
        if (std::abs(values[q]) > gs[q]->peak_reference_m) {
          gs[q]->peak_reference_m = std::abs(values[q]);
          gs[q]->peak_reference_t_s = r.t_s;
        }
      }
    }
  }
  for (int b = 0; b < nb; ++b) {
    for (SlipAgreement* g : {&*(*bodies)[b].slip, &*(*bodies)[b].lift}) {
      g->tolerance_m = SlipTolerance_m(scene, b + 1, g->peak_reference_m);
      g->floor_m = SlipTolerance_m(scene, b + 1, 0.0);
    }
  }
}

// The range [lo, hi] of the reference's u (q = 0) and z (q = 1) of every body within `slack`
// of t: its samples there (the output grid and every event) and the dense output at both ends.
struct SlipRange {
  std::vector<double> lo[2], hi[2];
};

SlipRange ReferenceSlipRange(const reference::Result& ref, const Sample& r, double t_s,
                             double slack, int nb) {
  SlipRange range;
  range.lo[0].assign(r.u_m.begin(), r.u_m.begin() + nb);
  range.lo[1].assign(r.z_m.begin(), r.z_m.begin() + nb);
  range.hi[0] = range.lo[0];
  range.hi[1] = range.lo[1];
  auto widen = [&](const Sample& x) {
    if (!HasSlip(x, nb)) return;
    for (int b = 0; b < nb; ++b) {
      range.lo[0][b] = std::min(range.lo[0][b], x.u_m[b]);
      range.hi[0][b] = std::max(range.hi[0][b], x.u_m[b]);
      range.lo[1][b] = std::min(range.lo[1][b], x.z_m[b]);
      range.hi[1][b] = std::max(range.hi[1][b], x.z_m[b]);
    }
  };
  widen(ref.trajectory.At(std::max(0.0, t_s - slack)));
  widen(ref.trajectory.At(t_s + slack));
  const auto& rh = ref.history.samples;
  for (auto it = std::lower_bound(rh.begin(), rh.end(), t_s - slack,
                                  [](const Sample&x, double t) { return x.t_s < t; });
       it != rh.end() && it->t_s <= t_s + slack; ++it) {
    widen(*it);
  }
  return range;
}

// Accounts one sample's slip (or lift) `engine` against the reference's `reference` and its
// range [lo, hi] within the time slack to `g`; adds the squared error to *sum2.
void AddSlipError(double t_s, double engine, double reference, double lo, double hi, double slack,
                  SlipAgreement* g, double* sum2) {
  const double e0 = std::abs(engine - reference);
  *sum2 += e0 * e0;
  g->max_abs_error_m = std::max(g->max_abs_error_m, e0);
  // The error that decides: outside the reference's range within the time slack.
  const double e = std::max({0.0, lo - engine, engine - hi});
  g->time_slack_s = slack;
  g->max_abs_error_slack_m = std::max(g->max_abs_error_slack_m, e);
  g->peak_engine_m = std::max(g->peak_engine_m, std::abs(engine));
  g->final_engine_m = engine;
  g->final_reference_m = reference;
  if (t_s <= g->predictability_horizon_s) {
    g->max_abs_error_predictable_m = std::max(g->max_abs_error_predictable_m, e);
    g->max_error_ratio_predictable = std::max(g->max_error_ratio_predictable, e / g->tolerance_m);
  }
  if (g->within_tolerance && e > g->tolerance_m) {
    g->within_tolerance = false;
    g->horizon_s = t_s;
  }
}

// Slip and lift of every body, where both histories carry them: on the slip's own scale,
// before the body's predictability horizon as the angles.
void CompareSlipAndLift(const Scene& scene, const reference::Result& ref, const EngineRun& run,
                        double until, const CompareOptions& options,
                        std::vector<BodyAgreement>* bodies) {
  const int nb = static_cast<int>(bodies->size());
  for (int b = 0; b < nb; ++b) {
    BodyAgreement& body = (*bodies)[b];
    body.slip = SlipAgreement{};
    body.lift = SlipAgreement{};
    body.lift->quantity = "z";
    for (SlipAgreement* g : {&*body.slip, &*body.lift}) {
      g->horizon_s = until;
      g->predictability_horizon_s = options.predictability_horizon_s[b];
    }
  }
  SlipPeaks(scene, ref.history, bodies);
  std::vector<double> sum2[2] = {std::vector<double>(nb, 0.0), std::vector<double>(nb, 0.0)};
  int ns = 0;
  for (const Sample& s : run.history.samples) {
    if (s.t_s > until + 1e-12) break;
    if (s.u_m.size() < static_cast<size_t>(nb)) break;
    const Sample r = ref.trajectory.At(s.t_s);
    if (r.u_m.size() < static_cast<size_t>(nb)) break;
    ++ns;
    // Two output intervals: a slip episode that an impact starts inherits the impact's timing,
    // and on rinaldi_with_vertical Bullet's block 2 slips 10-20 ms before the reference's at
    // 3.69 s with the same size (docs/verdicts.md, section 5).
    const double slack = 2.0 * scene.run.output_interval_s;
    const SlipRange range = ReferenceSlipRange(ref, r, s.t_s, slack, nb);
    for (int b = 0; b < nb; ++b) {
      const double engine[2] = {s.u_m[b], s.z_m[b]}, reference[2] = {r.u_m[b], r.z_m[b]};
      SlipAgreement* gs[2] = {&*(*bodies)[b].slip, &*(*bodies)[b].lift};
      for (int q = 0; q < 2; ++q) {
        AddSlipError(s.t_s, engine[q], reference[q], range.lo[q][b], range.hi[q][b], slack, gs[q],
                     &sum2[q][b]);
      }
    }
  }
  for (int b = 0; b < nb; ++b) {
    (*bodies)[b].slip->rms_error_m = ns > 0 ? std::sqrt(sum2[0][b] / ns) : 0.0;
    (*bodies)[b].lift->rms_error_m = ns > 0 ? std::sqrt(sum2[1][b] / ns) : 0.0;
  }
}

// Overturning and leaving the support, compared up to the instant the model stops deciding
// the motion (after it the reference's outcome is one admissible branch's): an overturn or a
// block leaving its support later than that, in either run, is not compared.
void CompareOutcomes(const reference::Summary& rs, const EngineRun& run, EngineAgreement* a) {
  const double t_decided = rs.undetermined_from_s.value_or(std::numeric_limits<double>::infinity());
  const auto decided = [&](double t) { return !(t > t_decided + 1e-12); };

  // Overturning.
  if (rs.overturn_block && decided(rs.overturn_t_s))
    a->overturn_block_reference = rs.overturn_block;
  if (run.outcome.overturned() && decided(run.outcome.overturn_t_s)) {
    a->overturn_block_engine = run.outcome.overturned_block;
    if (a->overturn_block_reference) {
      a->overturn_time_error_s = run.outcome.overturn_t_s - rs.overturn_t_s;
    }
  }
  a->overturn_agree = a->overturn_block_reference == a->overturn_block_engine;

  // Leaving the support (a block slid off the block below): an outcome of its own. The
  // engine's block comes from its outcome, or from its summary's "left_support" object where a
  // helper's protocol carried the status but not the block.
  if (rs.left_support_block && decided(rs.left_support_t_s)) {
    a->left_support_block_reference = rs.left_support_block;
  }
  int engine_off = run.outcome.left_support_block;
  double engine_off_t = run.outcome.left_support_t_s;
  if (engine_off == 0 && run.summary.is_object()) {
    if (const auto it = run.summary.find("left_support");
        it != run.summary.end() && it->is_object()) {
      engine_off = it->value("block", 0);
      engine_off_t = it->value("t_s", std::numeric_limits<double>::quiet_NaN());
    }
  }
  if (engine_off != 0 && decided(engine_off_t)) {
    a->left_support_block_engine = engine_off;
    if (a->left_support_block_reference && std::isfinite(engine_off_t)) {
      a->left_support_time_error_s = engine_off_t - rs.left_support_t_s;
    }
  }
  a->left_support_agree = a->left_support_block_reference == a->left_support_block_engine;
}

// Final state at the end of the common grid: the same family, and every body's angle within
// its tolerance.
void CompareFinalState(const reference::Result& ref, const EngineRun& run, double until,
                       EngineAgreement* a) {
  if (run.history.samples.empty()) return;
  const reference::Summary& rs = ref.summary;
  const Sample* last = &run.history.samples.front();
  for (const Sample& s : run.history.samples) {
    if (s.t_s <= until + 1e-12) last = &s;
  }
  const Sample r = ref.trajectory.At(last->t_s);
  a->final_mode_reference =
      Family(r.mode, rs.overturn_block.has_value(), rs.left_support_block.has_value());
  a->final_mode_engine = Family(last->mode, a->overturn_block_engine.has_value(),
                                a->left_support_block_engine.has_value());
  a->final_agree = a->final_mode_reference == a->final_mode_engine;
  for (int b = 0; b < a->blocks(); ++b) {
    BodyAgreement& body = a->bodies[b];
    const std::string& q = body.angle.quantity;
    body.final_angle_error_rad = StateQuantityReader(run.history, q)(*last, b + 1) -
                                 StateQuantityReader(ref.history, q)(r, b + 1);
    a->final_agree =
        a->final_agree && std::abs(body.final_angle_error_rad) <= body.angle.tolerance_rad;
  }
}

}  // namespace

EngineAgreement CompareWithReference(const Scene& scene, const reference::Result& ref,
                                     const EngineRun& run, const CompareOptions& options) {
  EngineAgreement a;
  CopyRunStatuses(ref, run, &a);
  const double until = ComparedUntil_s(ref, run);
  a.compared_until_s = until;
  for (AngleAgreement& g : CompareAngles(scene, ref, run, until, options, &a.samples_compared)) {
    a.bodies.push_back(BodyAgreement{std::move(g), 0.0, std::nullopt, std::nullopt, {}});
  }
  if (ref.history.slip_and_lift && run.history.slip_and_lift) {
    CompareSlipAndLift(scene, ref, run, until, options, &a.bodies);
  }
  a.impacts = MatchImpacts(ref.history, run.history, until, options.min_impact_rate_radps);
  CompareOutcomes(ref.summary, run, &a);
  CompareFinalState(ref, run, until, &a);
  return a;
}

std::vector<const AngleAgreement*> EngineAgreement::compared_angles() const {
  std::vector<const AngleAgreement*> out;
  for (const BodyAgreement& body : bodies) {
    out.push_back(&body.angle);
    for (const AngleAgreement& g : body.more_angles) out.push_back(&g);
  }
  return out;
}

nlohmann::json AgreementJson(const EngineAgreement& a) {
  nlohmann::json j;
  j["wall_s"] = a.wall_s;
  j["status"] = StatusText(a.status);
  if (IsNonFinite(a.status)) j["status_detail"] = a.status_detail;
  j["compared_until_s"] = RoundTime_s(a.compared_until_s);
  j["samples_compared"] = a.samples_compared;
  for (int b = 1; b <= a.blocks(); ++b) {
    const BodyAgreement& body = a.body(b);
    j[BodyColumn(body.angle.quantity, b)] = AngleJson(body.angle);
    for (const AngleAgreement& g : body.more_angles) j[g.name] = AngleJson(g);
    for (const std::optional<SlipAgreement>* g : {&body.slip, &body.lift}) {
      if (*g) j[BodyColumn((*g)->quantity, b)] = SlipJson(**g);
    }
  }
  j["impacts_matched"] = a.impacts.matched;
  j["impacts_reference"] = a.impacts.reference_impacts;
  j["impacts_engine"] = a.impacts.engine_impacts;
  j["impacts_reference_all"] = a.impacts.reference_impacts_all;
  j["impacts_engine_all"] = a.impacts.engine_impacts_all;
  j["impacts_skipped_marginal"] = a.impacts.skipped_marginal;
  j["impact_time_errors_s"] = a.impacts.time_errors_s;
  j["max_abs_impact_time_error_s"] = a.impacts.max_abs_time_error_s;
  j["first_impact_mismatch"] = a.impacts.first_mismatch.empty()
                                   ? nlohmann::json(nullptr)
                                   : nlohmann::json(a.impacts.first_mismatch);
  nlohmann::json ov;
  ov["agree"] = a.overturn_agree;
  ov["reference_block"] =
      a.overturn_block_reference ? nlohmann::json(*a.overturn_block_reference) : nullptr;
  ov["engine_block"] = a.overturn_block_engine ? nlohmann::json(*a.overturn_block_engine) : nullptr;
  ov["time_error_s"] = a.overturn_time_error_s ? nlohmann::json(*a.overturn_time_error_s) : nullptr;
  // A cylinder's fall direction (planar blocks fall in their plane: no key).
  if (a.overturn_azimuth_reference_rad || a.overturn_azimuth_engine_rad) {
    const auto opt = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    ov["reference_azimuth_rad"] = opt(a.overturn_azimuth_reference_rad);
    ov["engine_azimuth_rad"] = opt(a.overturn_azimuth_engine_rad);
    ov["azimuth_error_rad"] =
        a.overturn_azimuth_reference_rad && a.overturn_azimuth_engine_rad
            ? nlohmann::json(std::remainder(
                  *a.overturn_azimuth_engine_rad - *a.overturn_azimuth_reference_rad, 2.0 * M_PI))
            : nlohmann::json(nullptr);
  }
  j["overturn"] = ov;
  nlohmann::json off;
  off["agree"] = a.left_support_agree;
  off["reference_block"] =
      a.left_support_block_reference ? nlohmann::json(*a.left_support_block_reference) : nullptr;
  off["engine_block"] =
      a.left_support_block_engine ? nlohmann::json(*a.left_support_block_engine) : nullptr;
  off["time_error_s"] =
      a.left_support_time_error_s ? nlohmann::json(*a.left_support_time_error_s) : nullptr;
  j["left_support"] = off;
  j["final"] = {{"agree", a.final_agree},
                {"reference", a.final_mode_reference},
                {"engine", a.final_mode_engine}};
  for (int b = 1; b <= a.blocks(); ++b) {
    j["final"][BodyColumn(a.angle(b).quantity, b) + "_error_rad"] = a.body(b).final_angle_error_rad;
    for (const AngleAgreement& g : a.body(b).more_angles) {
      j["final"][g.name + "_error_rad"] = g.final_error_rad;
    }
  }
  j["violations"] = a.violations;
  if (!a.verdict_kind.empty()) {
    j["verdict"] = a.verdict;
    j["verdict_kind"] = a.verdict_kind;
    j["agrees"] = a.verdict_agrees;
    j["verdict_decided_by"] = a.verdict_decided_by;
    if (!a.seeds.is_null()) j["verdict_seeds"] = a.seeds;
  }
  if (!a.statistics.is_null()) j["statistics"] = a.statistics;
  return j;
}

nlohmann::json ComparisonJson(const Scene& scene, const reference::Result& ref,
                              double reference_wall_s, const std::vector<EngineAgreement>& engines,
                              const CompareOptions& options) {
  const bool two = scene.block_count() == 2;
  nlohmann::json j;
  j["scene"] = {{"path", scene.path.string()}, {"title", scene.title}, {"two_blocks", two}};
  // N >= 3 blocks: how many (one and two blocks say it by two_blocks alone, as they always did).
  if (scene.block_count() >= 3) j["scene"]["blocks"] = scene.block_count();
  const reference::Summary& rs = ref.summary;
  j["reference"] = {{"status", StatusText(rs.status)},
                    {"wall_s", reference_wall_s},
                    {"impacts", rs.impacts()},
                    {"end_s", ref.trajectory.end_s()}};
  for (int k = 0; k < rs.blocks(); ++k) {
    const std::string theta = BodyColumn("peak_theta", k + 1);
    j["reference"][theta + "_rad"] = rs.peak_theta_rad[k];
    j["reference"][theta + "_t_s"] = rs.peak_theta_t_s[k];
  }
  j["tolerance"] = scene.compare.tolerance_rad
                       ? nlohmann::json{{"rule", "scene"}, {"rad", *scene.compare.tolerance_rad}}
                       : nlohmann::json{{"rule", ToleranceRuleText()}};
  for (int k = 0; k < rs.blocks(); ++k) {
    j["tolerance"][BodyColumn(ComparedAngleStem(scene, k + 1), k + 1) + "_rad"] =
        AngleTolerance_rad(scene, k + 1, rs.peak_theta_rad[k]);
  }
  j["impact_min_rate_radps"] = options.min_impact_rate_radps;
  j["engines"] = nlohmann::json::object();
  for (const EngineAgreement& a : engines) j["engines"][a.engine] = AgreementJson(a);
  return j;
}

std::string ComparisonCsv(const std::vector<EngineAgreement>& engines) {
  std::string out =
      "engine,block,max_abs_error_rad,rms_error_rad,horizon_s,within_tolerance,tolerance_rad,"
      "max_abs_error_horizon_rad,rms_error_horizon_rad,peak_reference_rad,peak_engine_rad,"
      "peak_rel_error,peak_time_error_s,impacts_reference,impacts_engine,impacts_matched,"
      "max_abs_impact_time_error_s,overturn_agree,final_agree,status,wall_s,"
      "predictability_horizon_s,max_abs_error_predictable_rad,max_abs_error_beyond_rad,"
      "verdict_kind,judged,max_abs_error_u_m,tolerance_u_m,quantity\n";
  char line[1280];
  for (const EngineAgreement& a : engines) {
    // One row per compared angle: each body's first, then its further ones (a cylinder's
    // tilt_y after tilt_x), the quantity named in the last column.
    std::vector<std::pair<int, const AngleAgreement*>> rows;
    for (int b = 1; b <= a.blocks(); ++b) {
      rows.emplace_back(b, &a.angle(b));
      for (const AngleAgreement& g : a.body(b).more_angles) rows.emplace_back(b, &g);
    }
    for (const auto& [b, gp] : rows) {
      const AngleAgreement& g = *gp;
      const std::string quantity = g.name.empty() ? BodyColumn(g.quantity, b) : g.name;
      const std::optional<SlipAgreement>& slip = a.body(b).slip;
      std::snprintf(line, sizeof line,
                    "%s,%d,%.9e,%.9e,%.9g,%d,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%d,%d,%d,%.9e,%d,"
                    "%d,%s,%.6g,%s,%.9e,%.9e,%s,%d,%s,%s,%s\n",
                    a.engine.c_str(), b, g.max_abs_error_rad, g.rms_error_rad, g.horizon_s,
                    g.within_tolerance ? 1 : 0, g.tolerance_rad, g.max_abs_error_horizon_rad,
                    g.rms_error_horizon_rad, g.peak_reference_rad, g.peak_engine_rad,
                    g.peak_rel_error, g.peak_time_error_s, a.impacts.reference_impacts,
                    a.impacts.engine_impacts, a.impacts.matched, a.impacts.max_abs_time_error_s,
                    a.overturn_agree ? 1 : 0, a.final_agree ? 1 : 0, StatusText(a.status), a.wall_s,
                    std::isfinite(g.predictability_horizon_s)
                        ? std::to_string(g.predictability_horizon_s).c_str()
                        : "",
                    g.max_abs_error_predictable_rad, g.max_abs_error_beyond_rad,
                    a.verdict_kind.c_str(), g.judged ? 1 : 0,
                    slip ? Format("%.9e", slip->max_abs_error_m).c_str() : "",
                    slip ? Format("%.9e", slip->tolerance_m).c_str() : "", quantity.c_str());
      out += line;
    }
  }
  return out;
}

}  // namespace rockbench
