#include "compare/compare_run.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <new>

#include "compare/cylinder_compare.h"
#include "run/reference_engine.h"
#include "run/reference_witness.h"
#include "run/summary.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

std::string HorizonText(const std::optional<double>& h) {
  if (!h) return "never (predictable for the whole run)";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f s", *h);
  return buf;
}

// The ensemble's horizons, as the verdict reads them and as the comparison splits its errors.
// A cylinder's one horizon (its tilt vector's) holds for both its compared angles.
void TakeHorizons(const ReferencePerturbationMembers& e, int nb, Horizons* h, CompareOptions* o) {
  for (int b = 0; b < nb; ++b) {
    h->horizon_s[b] = e.horizon_s[b];
    if (e.horizon_s[b]) o->predictability_horizon_s[b] = *e.horizon_s[b];
  }
  if (e.stem == "tilt") h->horizon_s[1] = e.horizon_s[0];
  for (const MemberOutcome& m : e.outcomes) {
    if (IsNonFinite(m.status) && h->non_finite_members++ == 0) {
      h->non_finite_detail = "member " + std::to_string(m.member) + ": " + m.detail;
    }
  }
}

// An engine's run against the reference's solution used (a cylinder's or the planar model's).
EngineAgreement CompareWithUsed(const Scene& scene, const CompareRun& out, const EngineRun& run,
                                const CompareOptions& options) {
  if (const CylinderReferenceExtension* c = out.cylinder_reference()) {
    return CompareCylinderWithReference(scene, c->used(), run, options);
  }
  return CompareWithReference(scene, out.reference().used(), run, options);
}

// The reference's perturbation members of `scene` (the model settings of the solution used).
ReferencePerturbationMembers ReferenceMembers(const Scene& scene, const GroundMotion& motion,
                                              const CompareRun& out, int jobs) {
  if (const CylinderReferenceExtension* c = out.cylinder_reference()) {
    return RunCylinderPerturbationMembers(scene, motion, c->used(), scene.compare.members,
                                          out.tolerance_rad.at(0), jobs);
  }
  return RunReferencePerturbationMembers(scene, motion, out.reference().used(),
                                         scene.compare.members, out.tolerance_rad, jobs,
                                         CompareOptions{}.min_impact_rate_radps);
}

// The members' statistics: a cylinder's on its tilt ("tilt" keys, and its fall's azimuth).
StatisticalComparison CompareMembers(const Scene& scene, const CompareRun& out,
                                     const ReferencePerturbationMembers& reference,
                                     const std::vector<MemberOutcome>& engine) {
  return ComparePerturbationMembers(reference.outcomes, engine, out.tolerance_rad,
                                    scene.run.output_interval_s, 0.05, reference.stem);
}

// The statistical decision with the next kVerdictSeeds - 1 seeds.
struct SeedCheck {
  nlohmann::json seeds = nlohmann::json::array();  ///< comparison.json verdict_seeds
  std::string text;  ///< "seed 1: agrees (smallest Holm p 0.03), seed 2: ..."
  bool same = true;  ///< every seed agrees (or differs) as the first
};

// Re-runs the reference's perturbation members (cached per seed in `extra_ensembles`, shared by the
// engines) and engine `name`'s ensemble with seeds scene.compare.seed + 1, + 2, ..., and judges
// each as the first seed's verdict `first` was judged.
SeedCheck RecheckWithSeeds(
    const Scene& scene, const CompareRun& out, const GroundMotion& motion, const std::string& name,
    const EngineRun& run, int engine_members, int jobs, const Verdict& first, double first_p,
    std::vector<std::optional<ReferencePerturbationMembers>>* extra_ensembles) {
  const CompareOptions base;
  SeedCheck c;
  c.seeds.push_back(
      {{"seed", scene.compare.seed}, {"verdict_kind", first.kind}, {"smallest_p_holm", first_p}});
  for (int k = 1; k < kVerdictSeeds; ++k) {
    Scene seeded = scene;
    seeded.compare.seed = scene.compare.seed + static_cast<uint64_t>(k);
    std::optional<ReferencePerturbationMembers>& e = (*extra_ensembles)[k - 1];
    if (!e) {
      Scene seeded_reference = out.reference_scene;
      seeded_reference.compare.seed = seeded.compare.seed;
      e = ReferenceMembers(seeded_reference, motion, out, jobs);
    }
    Horizons h;
    CompareOptions o = base;
    TakeHorizons(*e, scene.block_count(), &h, &o);
    const EngineAgreement ak = CompareWithUsed(seeded, out, run, o);
    const std::vector<MemberOutcome> ok = RunEnginePerturbationMembers(
        name, seeded, motion, engine_members, jobs, base.min_impact_rate_radps);
    const StatisticalComparison sk = CompareMembers(scene, out, *e, ok);
    const Verdict vk = MakeVerdict(seeded, ak, h, sk);
    c.same = c.same && vk.agrees == first.agrees;
    c.seeds.push_back({{"seed", seeded.compare.seed},
                       {"verdict_kind", vk.kind},
                       {"smallest_p_holm", sk.available ? nlohmann::json(SmallestFamilyP(sk))
                                                        : nlohmann::json(nullptr)}});
  }
  char buf[64];
  for (const nlohmann::json& sd : c.seeds) {
    c.text += (c.text.empty() ? "" : ", ") + std::string("seed ") +
              std::to_string(sd["seed"].get<uint64_t>()) + ": " +
              sd["verdict_kind"].get<std::string>();
    if (sd["smallest_p_holm"].is_number()) {
      std::snprintf(buf, sizeof buf, " (smallest Holm p %.2g)",
                    sd["smallest_p_holm"].get<double>());
      c.text += buf;
    }
  }
  return c;
}

// One engine's nominal run, comparison, perturbation members where the horizon asks for them,
// and verdict, appended to `out` (all three lists, or nothing when it throws).
void CompareOneEngine(const Scene& scene, const GroundMotion& motion, const std::string& name,
                      const CompareRunOptions& options, int engine_members, bool horizon_within_run,
                      const std::optional<Horizons>& horizons,
                      const CompareOptions& compare_options,
                      std::vector<std::optional<ReferencePerturbationMembers>>* extra_ensembles,
                      CompareRun* out_ptr) {
  CompareRun& out = *out_ptr;
  const CompareOptions base;
  auto log = [&](const std::string& line) {
    if (options.log) options.log(line);
  };
  EngineRun run = RunEngine(name, scene, motion);
  log(run.one_line);

  EngineAgreement a = CompareWithUsed(scene, out, run, compare_options);
  std::optional<StatisticalComparison> statistics;
  std::vector<MemberOutcome> outcomes;
  Verdict v = MakeVerdict(scene, a, horizons, std::nullopt);
  const bool beyond = horizon_within_run && v.kind != "differs_before_horizon" &&
                      v.kind != "violates_model" && v.kind != "outside_model" &&
                      v.kind != "reference_failed";
  if (beyond) {
    if (engine_members > 0) {
      outcomes = RunEnginePerturbationMembers(name, scene, motion, engine_members, options.jobs,
                                              base.min_impact_rate_radps);
      statistics = CompareMembers(scene, out, *out.perturbation_members, outcomes);
    }
    v = MakeVerdict(scene, a, horizons, statistics);
  }
  // A statistical decision near the level is re-checked with two more seeds: one that
  // changes with the seed is "marginal", not AGREES or DIFFERS at random.
  if (statistics && statistics->available && InMarginalBand(SmallestFamilyP(*statistics))) {
    const SeedCheck c =
        RecheckWithSeeds(scene, out, motion, name, run, engine_members, options.jobs, v,
                         SmallestFamilyP(*statistics), extra_ensembles);
    if (c.same) {
      v.text +=
          "; the same with " + std::to_string(kVerdictSeeds) + " ensemble seeds (" + c.text + ")";
    } else {
      v.kind = "marginal";
      v.agrees = false;
      v.text =
          "marginal: the statistical decision beyond the horizon changes with the "
          "ensemble's seed (" +
          c.text + "); " + v.text;
      v.decided_by = "the seeds disagree: " + c.text;
    }
    a.seeds = c.seeds;
  }
  a.verdict_kind = v.kind;
  a.verdict = v.text;
  a.verdict_agrees = v.agrees;
  a.verdict_decided_by = v.decided_by;
  if (statistics) a.statistics = StatisticsJson(*statistics);
  out.agreements.push_back(std::move(a));
  out.engine_runs.push_back(std::move(run));
  out.engine_outcomes.push_back(std::move(outcomes));
}

// 1. The reference and its witness; comparisons use the witness when the default is not
//    converged.
void RunReference(const Scene& scene, const GroundMotion& motion,
                  const std::function<void(const std::string&)>& log, CompareRun* out) {
  char buf[512];
  out->reference_run = RunEngine(std::string(kReferenceEngine), scene, motion);
  out->reference_scene = scene;
  if (const CylinderReferenceExtension* c = out->cylinder_reference()) {
    // A cylinder: the witness's model when the nominal solution is not converged.
    if (!c->converged()) out->reference_scene.model = WitnessModel(scene.model);
    std::snprintf(buf, sizeof buf, "; witness within %.2g rad of the tilt vector%s",
                  c->max_abs_diff_rad, c->converged() ? ", converged" : "");
    log(CylinderSummaryLine(*c) + buf);
    if (!c->converged()) {
      std::snprintf(buf, sizeof buf,
                    "  WARNING: the reference's nominal solution differs from its witness by "
                    "%.3g rad (tolerance %.3g rad)%s: the witness's solution is compared",
                    c->max_abs_diff_rad, c->tolerance_rad,
                    c->same_status ? "" : " and ends otherwise");
      log(buf);
    }
    return;
  }
  const reference::Result& ref = out->reference().used();
  const ConvergenceCheck& check = *out->reference().check;
  if (&ref != &out->reference().nominal) out->reference_scene.model = check.witness;
  std::snprintf(buf, sizeof buf, "reference: %s, %zu events, %.3g ms; witness within %.2g rad%s",
                StatusText(ref.summary.status), ref.history.events.size(),
                out->reference().nominal_wall_s * 1e3, check.max_abs_diff(),
                check.converged ? ", converged" : "");
  log(buf);
  // Where the model stopped deciding the motion: nothing is compared after it.
  if (ref.summary.undetermined_from_s) {
    std::snprintf(buf, sizeof buf,
                  "  UNDETERMINED from %.4f s: ", *ref.summary.undetermined_from_s);
    log(buf + ref.summary.undetermined_detail +
        "; no engine is compared after it (the reference's history there is one admissible "
        "outcome the rule chose)");
  }
  if (!check.converged) log("  WARNING: " + ConvergenceWarning(check));
}

// 2. The reference's perturbation members: the predictability horizon, taken into `horizons`
// and `compare_options` (none when the scene asks for no members or the reference failed).
void RunPredictability(const Scene& scene, const GroundMotion& motion, int jobs,
                       const std::function<void(const std::string&)>& log, CompareRun* out,
                       std::optional<Horizons>* horizons, CompareOptions* compare_options) {
  const int nb = scene.block_count();
  const CylinderReferenceExtension* cylinder = out->cylinder_reference();
  out->tolerance_rad.resize(nb);
  RunStatus status = RunStatus::kCompleted;
  if (cylinder) {
    // One tolerance for both components: the tilt's at its peak.
    out->tolerance_rad[0] = AngleTolerance_rad(scene, 1, cylinder->used().summary.peak_tilt_rad);
    status = cylinder->used().summary.status;
  } else {
    const reference::Result& ref = out->reference().used();
    for (int b = 0; b < nb; ++b) {
      out->tolerance_rad[b] = AngleTolerance_rad(scene, b + 1, ref.summary.peak_theta_rad[b]);
    }
    status = ref.summary.status;
  }
  // A reference that failed (non_finite) leaves nothing to compare with: no ensemble, and every
  // verdict is reference_failed.
  const bool reference_failed = IsNonFinite(status);
  if (reference_failed) log("  FAILED: " + NonFiniteText(out->reference_run));
  if (scene.compare.members <= 0 || reference_failed) return;
  out->perturbation_members = ReferenceMembers(out->reference_scene, motion, *out, jobs);
  *horizons = Horizons{};
  TakeHorizons(*out->perturbation_members, nb, &**horizons, compare_options);
  char buf[512];
  std::string line = "predictability (" + std::to_string(scene.compare.members) + " members";
  std::snprintf(buf, sizeof buf,
                ", amplitude +-%g, samples +-%g of their printed precision, initial state "
                "+-%g): ",
                scene.compare.amplitude_rel, scene.compare.sample_precision,
                scene.compare.initial_rel);
  line += buf;
  for (int b = 0; b < nb; ++b) {
    line += (b == 0 ? "" : ", ") + BodyColumn(out->perturbation_members->stem, b + 1) +
            (cylinder ? " (tilt vector)" : "") + " horizon " +
            HorizonText(out->perturbation_members->horizon_s[b]);
  }
  std::snprintf(buf, sizeof buf, " (ensemble wall time %.2f s)", out->perturbation_members->wall_s);
  log(line + buf);
}

// 3. Each engine: its nominal run, and its perturbation members when the reference's horizon
// falls inside the run (before it, one run is enough to judge) and the engine agrees up to it.
// An engine that fails is that engine's verdict: the others' comparisons stand.
void CompareEngines(const Scene& scene, const GroundMotion& motion,
                    const std::vector<std::string>& engines, const CompareRunOptions& options,
                    const std::optional<Horizons>& horizons, const CompareOptions& compare_options,
                    CompareRun* out) {
  bool horizon_within_run = false;
  for (int b = 0; b < scene.block_count() && horizons; ++b) {
    horizon_within_run = horizon_within_run || horizons->horizon_s[b].has_value();
  }
  const int engine_members = std::min(scene.compare.engine_members, scene.compare.members);
  // Reference perturbation members of the extra seeds, run once for every engine that needs
  // them.
  std::vector<std::optional<ReferencePerturbationMembers>> extra_ensembles(kVerdictSeeds - 1);
  for (const std::string& name : engines) {
    try {
      CompareOneEngine(scene, motion, name, options, engine_members, horizon_within_run, horizons,
                       compare_options, &extra_ensembles, out);
    } catch (const std::bad_alloc&) {
      out->failed_engines.push_back(
          {name,
           "out of memory (std::bad_alloc): the engine could not reserve the memory it "
           "needed"});
    } catch (const std::exception& e) {
      std::string reason = e.what();
      // "NAME: ..." said once, by the verdict line.
      if (reason.rfind(name + ": ", 0) == 0) reason.erase(0, name.size() + 2);
      for (char& c : reason) {
        if (c == '\n' || c == '\r') c = ' ';
      }
      out->failed_engines.push_back({name, reason});
    }
    if (!out->failed_engines.empty() && out->failed_engines.back().engine == name && options.log) {
      options.log(name + ": FAILED: " + out->failed_engines.back().reason);
    }
  }
}

// Every run that ended non_finite, into out->failures.
void CollectFailures(CompareRun* out) {
  auto members = [&](const std::string& who, const std::vector<MemberOutcome>& outcomes) {
    for (const MemberOutcome& o : outcomes) {
      if (IsNonFinite(o.status)) {
        out->failures.push_back(who + " ensemble member " + std::to_string(o.member) + ": " +
                                o.detail);
      }
    }
  };
  if (const std::string t = NonFiniteText(out->reference_run); !t.empty()) {
    out->failures.push_back(t);
  }
  if (out->perturbation_members) members("reference", out->perturbation_members->outcomes);
  for (size_t k = 0; k < out->engine_runs.size(); ++k) {
    if (const std::string t = NonFiniteText(out->engine_runs[k]); !t.empty()) {
      out->failures.push_back(t);
    }
    members(out->engine_runs[k].engine, out->engine_outcomes[k]);
  }
}

}  // namespace

CompareRun RunCompare(const Scene& scene, const GroundMotion& motion,
                      const std::vector<std::string>& engines, const CompareRunOptions& options) {
  const std::function<void(const std::string&)> log = [&](const std::string& line) {
    if (options.log) options.log(line);
  };
  CompareRun out;
  const CompareOptions base;
  RunReference(scene, motion, log, &out);
  std::optional<Horizons> horizons;
  CompareOptions compare_options = base;
  RunPredictability(scene, motion, options.jobs, log, &out, &horizons, &compare_options);
  CompareEngines(scene, motion, engines, options, horizons, compare_options, &out);
  CollectFailures(&out);

  if (const CylinderReferenceExtension* c = out.cylinder_reference()) {
    out.comparison = CylinderComparisonJson(scene, c->used(), c->nominal_wall_s, out.agreements);
    out.comparison["reference"]["convergence"] =
        out.reference_run.summary.value("convergence", nlohmann::json(nullptr));
  } else {
    const reference::Result& ref = out.reference().used();
    out.comparison =
        ComparisonJson(scene, ref, out.reference().nominal_wall_s, out.agreements, base);
    out.comparison["reference"]["convergence"] = ConvergenceJson(scene, *out.reference().check);
  }
  out.comparison["failed_engines"] = nlohmann::json::array();
  for (const FailedEngine& f : out.failed_engines) {
    out.comparison["failed_engines"].push_back({{"engine", f.engine}, {"reason", f.reason}});
  }
  out.comparison["predictability"] = out.perturbation_members
                                         ? PredictabilityJson(scene, *out.perturbation_members)
                                         : nlohmann::json(nullptr);
  return out;
}

}  // namespace rockbench
