#include "compare/cylinder_compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "compare/angle_error.h"
#include "run/parallel.h"
#include "run/tolerance.h"
#include "run/wall_clock.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

using reference::cylinder::CylinderResult;
using reference::cylinder::CylinderSummary;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Whether the reference's solution ends without an outcome there: a violated assumption
// (lift-off, slip) or a state no longer finite.
bool ModelStops(const CylinderSummary& s) {
  return s.status == RunStatus::kAssumptionViolated || IsNonFinite(s.status);
}

// The statuses, flags and ends of both runs, as CompareWithReference copies them.
void CopyRunStatuses(const CylinderResult& ref, const EngineRun& run, EngineAgreement* a) {
  CopyEngineRunStatus(run, a);
  const CylinderSummary& rs = ref.summary;
  a->reference_status = rs.status;
  a->reference_status_detail = rs.status_detail;
  a->reference_end_s = rs.end_s;
  if (IsNonFinite(rs.status)) {
    a->reference_non_finite_what = rs.status_detail;
    a->reference_non_finite_t_s = rs.end_s;
  }
}

// The reference's tilt vector on the grid t_s: NaN past the end of a solution whose model
// stopped; the last state held past an overturn or a rest.
void OnGrid(const CylinderResult& r, const std::vector<double>& t_s, std::vector<double>* x,
            std::vector<double>* y) {
  const bool stopped = ModelStops(r.summary);
  x->assign(t_s.size(), std::nan(""));
  y->assign(t_s.size(), std::nan(""));
  for (size_t k = 0; k < t_s.size(); ++k) {
    if (stopped && t_s[k] > r.summary.end_s) break;
    const TiltVector v = TiltVectorAt(r.history, t_s[k]);
    (*x)[k] = v.x_rad;
    (*y)[k] = v.y_rad;
  }
}

double ModelEnd_s(const CylinderResult& r) {
  return ModelStops(r.summary) ? r.summary.end_s : kInf;
}

// A member's outcome, from its solution (MemberOutcome of the engines' OutcomeOf).
MemberOutcome MemberOutcomeOf(const Scene& scene, CylinderResult&& r, double wall_s) {
  EngineRun run;
  run.engine = "reference";
  run.wall_s = wall_s;
  run.history = std::move(r.history);
  run.outcome = RunOutcome(1);
  run.outcome.status = r.summary.status;
  run.outcome.end_t_s = r.summary.end_s;
  run.outcome.peak_theta_rad[0] = r.summary.peak_tilt_rad;
  run.outcome.peak_theta_t_s[0] = r.summary.peak_tilt_t_s;
  run.summary = nlohmann::json::object();
  if (!r.summary.status_detail.empty()) run.summary["status_detail"] = r.summary.status_detail;
  if (r.summary.overturn_t_s) {
    run.outcome.overturned_block = 1;
    run.outcome.overturn_t_s = *r.summary.overturn_t_s;
    run.summary["overturn"] = {{"t_s", *r.summary.overturn_t_s},
                               {"azimuth_rad", r.summary.overturn_azimuth_rad}};
  }
  return OutcomeOf(run, scene, 0.0);
}

}  // namespace

std::optional<double> FallAzimuthOf(const EngineRun& run) {
  if (!run.summary.is_object()) return std::nullopt;
  const auto ov = run.summary.find("overturn");
  if (ov == run.summary.end() || !ov->is_object() || !ov->contains("azimuth_rad")) {
    return std::nullopt;
  }
  return (*ov)["azimuth_rad"].get<double>();
}

TiltVector TiltVectorAt(const History& history, double t_s) {
  const std::vector<Sample>& s = history.samples;
  if (s.empty()) return {};
  const StateQuantityReader tx(history, "tilt_x"), ty(history, "tilt_y");
  // The first sample at or after t (the last of several at one time: an event's row).
  auto it = std::lower_bound(s.begin(), s.end(), t_s,
                             [](const Sample& a, double t) { return a.t_s < t; });
  if (it == s.end()) return {tx(s.back(), 1), ty(s.back(), 1)};
  if (it == s.begin() || it->t_s == t_s) return {tx(*it, 1), ty(*it, 1)};
  const Sample& b = *it;
  const Sample& a = *(it - 1);
  const double w = (t_s - a.t_s) / (b.t_s - a.t_s);
  return {tx(a, 1) + w * (tx(b, 1) - tx(a, 1)), ty(a, 1) + w * (ty(b, 1) - ty(a, 1))};
}

EngineAgreement CompareCylinderWithReference(const Scene& scene, const CylinderResult& ref,
                                             const EngineRun& run, const CompareOptions& options) {
  EngineAgreement a;
  CopyRunStatuses(ref, run, &a);
  const CylinderSummary& rs = ref.summary;
  // The common window: the engine's samples, to the end of the reference where it stopped
  // (an overturn: it has no model of what follows; a violated assumption; a failure).
  double until = run.history.samples.empty() ? 0.0 : run.history.samples.back().t_s;
  if (rs.overturn_t_s || ModelStops(rs)) until = std::min(until, rs.end_s);
  a.compared_until_s = until;

  // Both components on the tilt's local tolerance; judged point by point when the reference's
  // peak tilt is at least kJudgedPeakOverFloor floors.
  const ToleranceProfile profile = LocalTolerance(scene, 1, ref.history);
  const double floor_rad = profile.fixed_rad ? *profile.fixed_rad : profile.floor_rad;
  AngleAgreement gx, gy;
  gx.quantity = "tilt_x";
  gy.quantity = "tilt_y";
  gy.name = BodyColumn("tilt_y", 1);
  for (AngleAgreement* g : {&gx, &gy}) {
    g->tolerance_rad = AngleTolerance_rad(scene, 1, rs.peak_tilt_rad);
    g->tolerance_min_rad = profile.Min();
    g->horizon_s = until;
    g->predictability_horizon_s = options.predictability_horizon_s[0];
    g->floor_rad = floor_rad;
    g->judged = !(floor_rad * kJudgedPeakOverFloor > rs.peak_tilt_rad);
  }
  AngleErrorSums sx(options.predictability_horizon_s[0]), sy(options.predictability_horizon_s[0]);
  const StateQuantityReader etx(run.history, "tilt_x"), ety(run.history, "tilt_y");
  int n = 0;
  const Sample* last = nullptr;
  TiltVector last_ref;
  for (const Sample& s : run.history.samples) {
    if (s.t_s > until + 1e-12) break;
    const TiltVector r = TiltVectorAt(ref.history, s.t_s);
    const double tol = profile.At(s.t_s);
    sx.Add(s.t_s, std::abs(etx(s, 1) - r.x_rad), tol, &gx);
    sy.Add(s.t_s, std::abs(ety(s, 1) - r.y_rad), tol, &gy);
    last = &s;
    last_ref = r;
    ++n;
  }
  a.samples_compared = n;
  sx.Finish(&gx);
  sy.Finish(&gy);
  // Peaks of each component over the compared window.
  const StateQuantityReader rtx(ref.history, "tilt_x"), rty(ref.history, "tilt_y");
  SampledPeak(ref.history, rtx, 0, until, &gx.peak_reference_rad, &gx.peak_reference_t_s);
  SampledPeak(ref.history, rty, 0, until, &gy.peak_reference_rad, &gy.peak_reference_t_s);
  SampledPeak(run.history, etx, 0, until, &gx.peak_engine_rad, &gx.peak_engine_t_s);
  SampledPeak(run.history, ety, 0, until, &gy.peak_engine_rad, &gy.peak_engine_t_s);
  for (AngleAgreement* g : {&gx, &gy}) {
    g->peak_rel_error = g->peak_reference_rad > 0.0
                            ? (g->peak_engine_rad - g->peak_reference_rad) / g->peak_reference_rad
                            : 0.0;
    g->peak_time_error_s = g->peak_engine_t_s - g->peak_reference_t_s;
    g->peak_within_tolerance =
        PeakAgrees(g->peak_reference_rad, g->peak_engine_rad, g->floor_rad, &g->peak_tolerance_rad);
  }

  // Overturning, and the direction of the fall.
  if (rs.overturn_t_s) {
    a.overturn_block_reference = 1;
    a.overturn_azimuth_reference_rad = rs.overturn_azimuth_rad;
  }
  if (run.outcome.overturned()) {
    a.overturn_block_engine = 1;
    a.overturn_azimuth_engine_rad = FallAzimuthOf(run);
    if (rs.overturn_t_s) a.overturn_time_error_s = run.outcome.overturn_t_s - *rs.overturn_t_s;
  }
  a.overturn_agree = a.overturn_block_reference == a.overturn_block_engine;

  // The final state at the end of the common window: the same family (rest on the face,
  // rocking on the rim, overturned) and both components within the tolerance at the peak.
  if (last != nullptr) {
    const auto family = [](const Sample& s, bool overturned) {
      if (overturned) return std::string("overturned");
      return s.mode.at_rest() ? std::string("rest") : std::string("rocking");
    };
    const auto ref_last =
        std::upper_bound(ref.history.samples.begin(), ref.history.samples.end(), last->t_s + 1e-12,
                         [](double t, const Sample& x) { return t < x.t_s; });
    const Sample& ref_sample =
        ref_last == ref.history.samples.begin() ? ref.history.samples.front() : *(ref_last - 1);
    a.final_mode_reference = family(ref_sample, a.overturn_block_reference.has_value());
    a.final_mode_engine = family(*last, a.overturn_block_engine.has_value());
    gy.final_error_rad = ety(*last, 1) - last_ref.y_rad;
    const double final_x = etx(*last, 1) - last_ref.x_rad;
    a.final_agree = a.final_mode_reference == a.final_mode_engine &&
                    std::abs(final_x) <= gx.tolerance_rad &&
                    std::abs(gy.final_error_rad) <= gy.tolerance_rad;
    a.bodies.push_back(BodyAgreement{std::move(gx), final_x, std::nullopt, std::nullopt, {}});
  } else {
    a.bodies.push_back(BodyAgreement{std::move(gx), 0.0, std::nullopt, std::nullopt, {}});
  }
  a.bodies[0].more_angles.push_back(std::move(gy));
  return a;
}

ReferencePerturbationMembers RunCylinderPerturbationMembers(const Scene& nominal_scene,
                                                            const GroundMotion& motion,
                                                            const CylinderResult& nominal,
                                                            int members, double tolerance_rad,
                                                            int threads) {
  const auto start = std::chrono::steady_clock::now();
  ReferencePerturbationMembers e;
  e.members = members;
  e.blocks = 1;
  e.stem = "tilt";
  e.tolerance_rad = {tolerance_rad};
  e.horizon_s.assign(1, std::nullopt);
  e.max_spread_rad.assign(1, 0.0);
  e.lo_rad.resize(1);
  e.hi_rad.resize(1);
  e.spread_rad.resize(1);
  e.local_tolerance_rad.resize(1);
  e.t_s = OutputGrid_s(nominal_scene);
  const size_t n_grid = e.t_s.size();
  std::vector<double> nx, ny;
  OnGrid(nominal, e.t_s, &nx, &ny);

  e.perturbations.resize(members);
  e.outcomes.resize(members);
  std::vector<std::vector<double>> gx(members), gy(members);
  std::vector<double> member_end_s(members, kInf);
  ProgressLine progress("reference ensemble");
  ParallelFor(
      members, threads,
      [&](int i) {
        const MemberInput in = PerturbedInput(nominal_scene, motion, i);
        const auto t0 = std::chrono::steady_clock::now();
        CylinderResult r = reference::cylinder::SimulateCylinder(in.scene, in.motion);
        const double wall_s = SecondsSince(t0);
        OnGrid(r, e.t_s, &gx[i], &gy[i]);
        member_end_s[i] = ModelEnd_s(r);
        e.perturbations[i] = in.perturbation;
        e.outcomes[i] = MemberOutcomeOf(in.scene, std::move(r), wall_s);
        e.outcomes[i].member = i;
      },
      [&](int done, int total) { progress.Update(done, total); });

  // The band of the tilt, the spread of the tilt vector, and the horizon.
  const ToleranceProfile profile = LocalTolerance(nominal_scene, 1, nominal.history);
  const double nominal_end_s = ModelEnd_s(nominal);
  std::vector<double>& lo = e.lo_rad[0];
  std::vector<double>& hi = e.hi_rad[0];
  std::vector<double>& spread = e.spread_rad[0];
  e.local_tolerance_rad[0].resize(n_grid);
  lo.assign(n_grid, std::nan(""));
  hi.assign(n_grid, std::nan(""));
  spread.assign(n_grid, 0.0);
  for (size_t k = 0; k < n_grid; ++k) {
    e.local_tolerance_rad[0][k] = profile.At(e.t_s[k]);
    if (e.t_s[k] > nominal_end_s) {
      if (!e.horizon_s[0]) e.horizon_s[0] = e.t_s[k];
      continue;
    }
    if (std::isnan(nx[k])) continue;
    lo[k] = hi[k] = std::hypot(nx[k], ny[k]);
    bool lost = false;
    for (int i = 0; i < members; ++i) {
      if (e.t_s[k] > member_end_s[i]) lost = true;
      if (std::isnan(gx[i][k])) continue;
      lo[k] = std::min(lo[k], std::hypot(gx[i][k], gy[i][k]));
      hi[k] = std::max(hi[k], std::hypot(gx[i][k], gy[i][k]));
      spread[k] = std::max(spread[k], std::hypot(gx[i][k] - nx[k], gy[i][k] - ny[k]));
    }
    e.max_spread_rad[0] = std::max(e.max_spread_rad[0], spread[k]);
    if (!e.horizon_s[0] && (lost || spread[k] > tolerance_rad)) e.horizon_s[0] = e.t_s[k];
  }
  e.wall_s = SecondsSince(start);
  return e;
}

nlohmann::json CylinderComparisonJson(const Scene& scene, const CylinderResult& ref,
                                      double reference_wall_s,
                                      const std::vector<EngineAgreement>& engines) {
  const CylinderSummary& rs = ref.summary;
  nlohmann::json j;
  j["scene"] = {{"path", scene.path.string()},
                {"title", scene.title},
                {"two_blocks", false},
                {"shape", std::string(kCylinderShape)}};
  j["reference"] = {{"status", StatusText(rs.status)},
                    {"wall_s", reference_wall_s},
                    {"landings", rs.landings},
                    {"end_s", rs.end_s},
                    {"peak_tilt1_rad", rs.peak_tilt_rad},
                    {"peak_tilt1_t_s", rs.peak_tilt_t_s}};
  j["reference"]["overturn"] =
      rs.overturn_t_s
          ? nlohmann::json{{"t_s", *rs.overturn_t_s}, {"azimuth_rad", rs.overturn_azimuth_rad}}
          : nlohmann::json(nullptr);
  const double tol = AngleTolerance_rad(scene, 1, rs.peak_tilt_rad);
  j["tolerance"] =
      scene.compare.tolerance_rad
          ? nlohmann::json{{"rule", "scene"}, {"rad", *scene.compare.tolerance_rad}}
          : nlohmann::json{{"rule", ToleranceRuleText() +
                                        "; for the cylinder, on its tilt (the length of the "
                                        "tilt vector) with B = D"}};
  j["tolerance"]["tilt_x1_rad"] = tol;
  j["tolerance"]["tilt_y1_rad"] = tol;
  // The cylinder's impacts are not matched (its landings are counted in each summary).
  j["impact_min_rate_radps"] = nullptr;
  j["engines"] = nlohmann::json::object();
  for (const EngineAgreement& a : engines) j["engines"][a.engine] = AgreementJson(a);
  return j;
}

}  // namespace rockbench
