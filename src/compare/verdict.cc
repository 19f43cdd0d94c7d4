#include "compare/verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

// Fewer valid members than this on either side: no statistical comparison.
constexpr int kMinMembers = 5;

// A p-value in words: "p = 0.41", "p = 3e-05", "p < 1e-300".
std::string PText(double p) {
  if (std::isnan(p)) return "p undefined";
  if (p == 0.0) return "p < 1e-300";
  return p >= 0.001 ? Format("p = %.2g", p) : Format("p = %.1e", p);
}

nlohmann::json TestJson(const stats::TestResult& t) {
  auto num = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  return {{"test", t.test},     {"statistic", num(t.statistic)}, {"p_value", num(t.p_value)},
          {"method", t.method}, {"n_reference", t.n_a},          {"n_engine", t.n_b}};
}

nlohmann::json SpreadJson(const std::vector<double>& v) {
  if (v.empty()) return nullptr;
  return {{"median", stats::Median(v)},
          {"q05", stats::Quantile(v, 0.05)},
          {"q95", stats::Quantile(v, 0.95)},
          {"n", v.size()}};
}

std::string Value(double v, const std::string& unit) {
  if (unit.empty()) return Format("%.3g", v);
  return Format("%.3g", v) + " " + unit;
}

}  // namespace

namespace {

// The members each side's tests use: the reference's valid members, and the engine's members
// whose reference run is valid and that did not fail; counts what is left out in `s`.
struct ValidMembers {
  std::vector<const MemberOutcome*> reference, engine;
};

ValidMembers SelectValidMembers(const std::vector<MemberOutcome>& reference,
                                const std::vector<MemberOutcome>& engine,
                                StatisticalComparison& s) {
  ValidMembers m;
  // Members whose reference run stopped on a violated assumption have no reference outcome;
  // the engine's run on the same inputs is left out with them.
  for (const MemberOutcome& o : reference) {
    if (o.valid()) {
      m.reference.push_back(&o);
    } else {
      ++s.excluded;
      if (IsNonFinite(o.status)) ++s.excluded_non_finite;
    }
  }
  for (const MemberOutcome& o : engine) {
    // A failed engine member is the engine's failure, whatever the reference did there.
    if (IsNonFinite(o.status) && s.engine_non_finite++ == 0) {
      s.engine_non_finite_detail = "member " + std::to_string(o.member) + ": " + o.detail;
    }
  }
  for (const MemberOutcome& o : engine) {
    const bool ref_valid = o.member >= 0 && o.member < static_cast<int>(reference.size()) &&
                           reference[o.member].valid();
    if (ref_valid && !IsNonFinite(o.status)) m.engine.push_back(&o);
  }
  s.reference_members = static_cast<int>(m.reference.size());
  s.engine_members = static_cast<int>(m.engine.size());
  return m;
}

// One quantity of every member: `value` of the members `include` keeps, on both sides, with
// its two-sample tests.
template <typename Value, typename Include>
QuantityComparison CompareQuantity(const ValidMembers& m, std::string key, std::string label,
                                   std::string unit, double margin, Value value, Include include) {
  QuantityComparison q;
  q.key = std::move(key);
  q.label = std::move(label);
  q.unit = std::move(unit);
  q.margin = margin;
  for (const MemberOutcome* o : m.reference) {
    if (include(*o)) q.reference.push_back(value(*o));
  }
  for (const MemberOutcome* o : m.engine) {
    if (include(*o)) q.engine.push_back(value(*o));
  }
  q.ks = stats::KolmogorovSmirnovSlackTest(q.reference, q.engine, margin);
  q.ad = stats::AndersonDarlingTest(q.reference, q.engine);
  return q;
}

// The compared quantities, in the table's order: every body's peak, its time, RMS, then the
// impacts (outside the family), then every body's residual.
std::vector<QuantityComparison> CompareQuantities(const ValidMembers& m,
                                                  std::span<const double> tolerance_rad, int blocks,
                                                  double time_margin_s, std::string_view stem) {
  std::vector<QuantityComparison> out;
  const auto always = [](const MemberOutcome&) { return true; };
  for (int b = 0; b < blocks; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    out.push_back(CompareQuantity(
        m, "peak_" + th + "_rad", "peak |" + th + "|", "rad", 0.1 * tolerance_rad[b],
        [b](const MemberOutcome& o) { return o.peak_rad[b]; }, always));
  }
  for (int b = 0; b < blocks; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    const double tol = tolerance_rad[b];
    // The time of the largest excursion means something only for a block that moved.
    out.push_back(CompareQuantity(
        m, "peak_" + th + "_t_s", "time of the largest |" + th + "|", "s", time_margin_s,
        [b](const MemberOutcome& o) { return o.peak_t_s[b]; },
        [b, tol](const MemberOutcome& o) { return o.peak_rad[b] > tol; }));
  }
  for (int b = 0; b < blocks; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    out.push_back(CompareQuantity(
        m, "rms_" + th + "_rad", "RMS " + th, "rad", 0.1 * tolerance_rad[b],
        [b](const MemberOutcome& o) { return o.rms_rad[b]; }, always));
  }
  out.push_back(CompareQuantity(
      m, "impacts", "impacts", "", 0.0,
      [](const MemberOutcome& o) { return static_cast<double>(o.impacts); }, always));
  out.back().in_family = false;
  for (int b = 0; b < blocks; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    out.push_back(CompareQuantity(
        m, "residual_" + th + "_rad", "residual " + th, "rad", 0.1 * tolerance_rad[b],
        [b](const MemberOutcome& o) { return o.residual_rad[b]; }, always));
  }
  // A cylinder's fall direction, over the members that overturned (kMinMembers on each side at
  // least): the azimuth relative to the circular mean of the reference's falls, within
  // (-pi, pi]. Its margin, 0.01 rad, is the KS margin of the angles (a tenth of the tolerance)
  // turned into an azimuth at the tilt where the tolerance is largest: 0.1 x (0.1 alpha) / alpha.
  double sx = 0.0, sy = 0.0;
  int ref_falls = 0, eng_falls = 0;
  for (const MemberOutcome* o : m.reference) {
    if (o->overturn_azimuth_rad) {
      sx += std::cos(*o->overturn_azimuth_rad);
      sy += std::sin(*o->overturn_azimuth_rad);
      ++ref_falls;
    }
  }
  for (const MemberOutcome* o : m.engine) eng_falls += o->overturn_azimuth_rad ? 1 : 0;
  if (ref_falls >= kMinMembers && eng_falls >= kMinMembers) {
    const double mean = std::atan2(sy, sx);
    out.push_back(CompareQuantity(
        m, "fall_azimuth1_rad", "fall azimuth (from the reference's mean direction)", "rad", 0.01,
        [mean](const MemberOutcome& o) {
          return std::remainder(*o.overturn_azimuth_rad - mean, 2.0 * M_PI);
        },
        [](const MemberOutcome& o) { return o.overturn_azimuth_rad.has_value(); }));
  }
  return out;
}

// Which block overturned (none, block 1 .. block N) in each ensemble, and the exact test of
// the two rows of counts.
void CompareOverturning(const ValidMembers& m, StatisticalComparison& s) {
  // Categories: none, block 1 .. block N (one or two blocks: none, block 1, block 2).
  const int categories = std::max(s.blocks, 2) + 1;
  for (const MemberOutcome* o : m.reference) {
    ++s.overturn_reference[std::clamp(o->overturned_block, 0, categories - 1)];
  }
  for (const MemberOutcome* o : m.engine) {
    ++s.overturn_engine[std::clamp(o->overturned_block, 0, categories - 1)];
  }
  // Categories that occur in neither ensemble are dropped (a column of zeros has no table).
  std::vector<int> row_r, row_e;
  for (int c = 0; c < categories; ++c) {
    if (s.overturn_reference[c] + s.overturn_engine[c] == 0) continue;
    row_r.push_back(s.overturn_reference[c]);
    row_e.push_back(s.overturn_engine[c]);
  }
  if (row_r.size() >= 2) {
    s.overturn = stats::FisherExactTest(row_r, row_e);
  } else {
    s.overturn.test = "Fisher-Freeman-Halton exact";
    s.overturn.statistic = 1.0;
    s.overturn.p_value = 1.0;
    s.overturn.n_a = s.reference_members;
    s.overturn.n_b = s.engine_members;
    s.overturn.method = "exact (one outcome in both ensembles)";
  }
}

// One family: every defined KS p-value and the overturning test, Holm-adjusted; the rejected
// keys and the verdict.
void JudgeFamily(StatisticalComparison& s) {
  std::vector<double> p;
  for (const QuantityComparison& q : s.quantities) {
    if (q.in_family) p.push_back(q.ks.p_value);
  }
  p.push_back(s.overturn.p_value);
  const std::vector<double> holm = stats::HolmAdjust(p);
  size_t next = 0;
  for (QuantityComparison& q : s.quantities) {
    if (!q.in_family) {
      q.p_holm = std::nan("");
      continue;
    }
    q.p_holm = holm[next++];
    if (!std::isnan(q.p_holm) && q.p_holm <= s.alpha) s.rejected.push_back(q.key);
  }
  s.overturn_p_holm = holm.back();
  if (!std::isnan(s.overturn_p_holm) && s.overturn_p_holm <= s.alpha) {
    s.rejected.push_back("overturn");
  }
  s.consistent = s.rejected.empty();
}

}  // namespace

StatisticalComparison ComparePerturbationMembers(const std::vector<MemberOutcome>& reference,
                                                 const std::vector<MemberOutcome>& engine,
                                                 std::span<const double> tolerance_rad,
                                                 double time_margin_s, double alpha,
                                                 std::string_view stem) {
  StatisticalComparison s;
  s.alpha = alpha;
  s.blocks = std::clamp(static_cast<int>(tolerance_rad.size()), 1, kMaxBlocks);
  const ValidMembers members = SelectValidMembers(reference, engine, s);
  if (s.reference_members < kMinMembers || s.engine_members < kMinMembers) {
    s.unavailable_reason = "too few members with a valid reference run (" +
                           std::to_string(s.reference_members) + " reference, " +
                           std::to_string(s.engine_members) + " engine; at least " +
                           std::to_string(kMinMembers) + " each)";
    return s;
  }
  s.available = true;
  s.quantities = CompareQuantities(members, tolerance_rad, s.blocks, time_margin_s, stem);
  CompareOverturning(members, s);
  JudgeFamily(s);
  return s;
}

namespace {

// The name of body b + 1's compared angle: "theta1", "theta2", ...
std::string Name(int b, const AngleAgreement& g) {
  return g.name.empty() ? BodyColumn(g.quantity, b + 1) : g.name;
}

// A flag in words: what the engine did.
std::string FlagWords(const std::string& flag) {
  if (flag == "sliding") return "slid";
  if (flag == "uplift") return "lifted off its support";
  if (flag == "penetration") return "penetrated its support";
  if (flag == "energy_growth") return "gained energy without base input";
  if (flag == "blow_up") return "blew up";
  return flag;
}

// "slid from 1.23 s, lifted off its support from 1.50 s", for the flags whose onset is in
// [from_s, to_s).
// `significant`: the flags at the verdict's scale, else the monitor's.
std::string FlagsText(const EngineAgreement& a, double from_s, double to_s,
                      const std::vector<std::string>& only, bool significant) {
  const std::vector<std::string>& flags = significant ? a.significant_flags : a.flags;
  const std::vector<double>& onsets = significant ? a.significant_onsets_t_s : a.flag_onsets_t_s;
  std::string out;
  for (size_t k = 0; k < flags.size() && k < onsets.size(); ++k) {
    if (!only.empty() && std::find(only.begin(), only.end(), flags[k]) == only.end()) continue;
    const double t = onsets[k];
    if (t < from_s || t >= to_s) continue;
    out += (out.empty() ? "" : ", ") + FlagWords(flags[k]) + " (" + flags[k] + " flag) from " +
           Format("%.2f", t) + " s";
  }
  return out;
}

// Why a block is not judged point by point alone, in words.
std::string NotJudgedText(int b, const AngleAgreement& g) {
  return Name(b, g) + " is not judged point by point alone (the reference's peak, " +
         Format("%.3g", g.peak_reference_rad) + " rad, is below " +
         Format("%g", kJudgedPeakOverFloor) + " x the tolerance floor " +
         Format("%.3g", g.floor_rad) +
         " rad: the floor exceeds a fifth of its motion, so a block at rest would pass), so its "
         "peak is judged too";
}

// How a block not judged point by point fares on its peak, in words.
std::string PeakText(const AngleAgreement& g) {
  return "its peak " + Format("%.3g", g.peak_engine_rad) + " rad against the reference's " +
         Format("%.3g", g.peak_reference_rad) + " rad is " +
         (g.peak_within_tolerance ? "within" : "beyond") + " the peak tolerance " +
         Format("%.3g", g.peak_tolerance_rad) +
         " rad (impacts faster than the minimum rate: " + std::to_string(g.impacts_engine) +
         " against " + std::to_string(g.impacts_reference) + ")";
}

// "u2 (slip of block 2 on block 1)", "z1 (lift of block 1 off the ground)": body b + 1's.
std::string SlipName(const SlipAgreement& g, int b) {
  const bool lift = g.quantity == "z";
  const std::string support = b == 0 ? std::string("the ground") : "block " + std::to_string(b);
  return BodyColumn(g.quantity, b + 1) + " (" + (lift ? "lift" : "slip") + " of block " +
         std::to_string(b + 1) + (lift ? " off " : " on ") + support + ")";
}

// What a run did with its blocks: "block 2 leaves its support at 0.863 s", "block 1
// overturns", "no block overturns or leaves its support".
std::string EndText(const std::optional<int>& overturned, const std::optional<int>& left,
                    std::optional<double> left_t_s = std::nullopt) {
  std::string out;
  if (left) {
    out = "block " + std::to_string(*left) + " leaves its support" +
          (left_t_s ? " at " + Format("%.3f", *left_t_s) + " s" : std::string());
  }
  if (overturned) {
    out += (out.empty() ? "" : ", ") + std::string("block ") + std::to_string(*overturned) +
           " overturns";
  }
  return out.empty() ? "no block overturns or leaves its support" : out;
}

// The first block below the floor whose peak is beyond its peak tolerance, in words; empty:
// none.
std::string PeakDecides(const std::vector<const AngleAgreement*>& ang) {
  for (int b = 0; b < static_cast<int>(ang.size()); ++b) {
    const AngleAgreement& g = *ang[b];
    if (g.judged || g.peak_within_tolerance) continue;
    return Name(b, g) + " peak " + Format("%.3g", g.peak_engine_rad) + " rad against " +
           Format("%.3g", g.peak_reference_rad) + " rad, beyond its peak tolerance " +
           Format("%.3g", g.peak_tolerance_rad) + " rad (the block is below the floor)";
  }
  return "";
}

// The block with the largest error ratio, in words: before the horizons (`predictable`), or
// over the whole comparison.
std::string RatioText(const std::vector<const AngleAgreement*>& ang, bool predictable) {
  const int nb = static_cast<int>(ang.size());
  auto ratio = [predictable](const AngleAgreement* g) {
    return predictable ? g->max_error_ratio_predictable : g->max_error_ratio;
  };
  int w = 0;
  for (int b = 1; b < nb; ++b) {
    if (ratio(ang[b]) > ratio(ang[w])) w = b;
  }
  return Name(w, *ang[w]) + " error at most " + Format("%.3g", ratio(ang[w])) +
         " x the local tolerance" +
         (predictable ? " where the reference is predictable" : std::string());
}

}  // namespace

std::string VerdictLabel(const std::string& kind) {
  if (kind == "agrees" || kind == "agrees_to_horizon" || kind == "pointwise_only") return "AGREES";
  if (kind == "outside_model") return "OUTSIDE MODEL";
  if (kind == "reference_failed") return "NO VERDICT";
  if (kind == "marginal") return "MARGINAL";
  return "DIFFERS";
}

namespace {

// Where the reference's model holds: to its end when it stopped on a violated assumption, or to
// its first impact that the model leaves undecided (no admissible outcome or several),
// whichever comes first.
struct ModelEnd {
  bool ends = false;
  double at_s = std::numeric_limits<double>::infinity();
  std::string why;
};

ModelEnd ModelEndOf(const EngineAgreement& a) {
  const bool stopped = a.reference_status == RunStatus::kAssumptionViolated;
  const bool undetermined =
      a.reference_undetermined_s && (!stopped || *a.reference_undetermined_s < a.reference_end_s);
  ModelEnd m;
  m.ends = stopped || undetermined;
  if (undetermined) m.at_s = *a.reference_undetermined_s;
  if (!undetermined && stopped) m.at_s = a.reference_end_s;
  m.why = undetermined ? a.reference_undetermined_detail
                       : (a.reference_status_detail.empty() ? std::string("assumption violated")
                                                            : a.reference_status_detail);
  return m;
}

Verdict Decided(std::string kind, bool agrees, std::string text, std::string decided_by) {
  Verdict v;
  v.kind = std::move(kind);
  v.agrees = agrees;
  v.text = std::move(text);
  v.decided_by = std::move(decided_by);
  return v;
}

// A run that is not finite failed: never an agreement. The engine's failure is its own,
// whatever the reference did; a reference that failed leaves nothing to compare with.
std::optional<Verdict> FailedRunVerdict(const EngineAgreement& a,
                                        const std::optional<Horizons>& predictability,
                                        const std::optional<StatisticalComparison>& statistics) {
  if (IsNonFinite(a.status)) {
    const std::string by =
        "non_finite at t = " + Format("%.6g", a.non_finite_t_s) + " s" +
        (a.non_finite_what.empty() ? std::string() : " (" + a.non_finite_what + ")");
    return Decided("violates_model", false,
                   "the engine's run failed: " + (a.status_detail.empty() ? by : a.status_detail) +
                       "; a run that is not finite is never an agreement",
                   by);
  }
  if (IsNonFinite(a.reference_status)) {
    const std::string by =
        "reference non_finite at t = " + Format("%.6g", a.reference_non_finite_t_s) + " s" +
        (a.reference_non_finite_what.empty() ? std::string()
                                             : " (" + a.reference_non_finite_what + ")");
    return Decided("reference_failed", false,
                   "no verdict: the reference's solution failed (" +
                       (a.reference_status_detail.empty() ? by : a.reference_status_detail) +
                       "), so there is nothing to compare the engine with",
                   by);
  }
  if (predictability && predictability->non_finite_members > 0) {
    return Decided("reference_failed", false,
                   "no verdict: " + std::to_string(predictability->non_finite_members) +
                       " of the reference ensemble's members failed (" +
                       predictability->non_finite_detail +
                       "), so the reference's predictability is unknown",
                   "reference ensemble: " + std::to_string(predictability->non_finite_members) +
                       " members non_finite");
  }
  if (statistics && statistics->engine_non_finite > 0) {
    return Decided("violates_model", false,
                   "the engine's run failed on " + std::to_string(statistics->engine_non_finite) +
                       " of its ensemble's members (" + statistics->engine_non_finite_detail +
                       "); a run that is not finite is never an agreement",
                   "non_finite in " + std::to_string(statistics->engine_non_finite) +
                       " of its ensemble's members");
  }
  return std::nullopt;
}

// 0. The engine's own integrity: a blow-up or energy gained without input decides, whatever
//    the angles; sliding, uplift and penetration decide where the reference's model holds.
//    With a finite friction the reference's model slides and lifts off (its unilateral model,
//    docs/sliding.md): there only penetration is forbidden, and the angles judge the rest.
std::optional<Verdict> IntegrityVerdict(const Scene& scene, const EngineAgreement& a,
                                        const ModelEnd& model) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::string failure = FlagsText(a, -inf, inf, {"blow_up", "energy_growth"}, true);
  const std::vector<std::string> excluded =
      scene.has_finite_friction() ? std::vector<std::string>{"penetration"}
                                  : std::vector<std::string>{"sliding", "uplift", "penetration"};
  const std::string forbidden = FlagsText(a, -inf, model.at_s, excluded, true);
  if (failure.empty() && forbidden.empty() && a.status != RunStatus::kBlowUp) return std::nullopt;
  std::string what = failure;
  if (!forbidden.empty()) {
    what +=
        (what.empty() ? "" : "; ") + forbidden +
        (model.ends ? ", before the reference's model ends at " + Format("%.2f", model.at_s) + " s"
         : scene.has_finite_friction()
             ? ", while the reference's model (rigid contact) holds throughout"
             : ", while the reference's model (no sliding, no uplift, rigid "
               "contact) holds throughout");
  }
  if (what.empty()) what = "the run ended in a blow-up";
  return Decided("violates_model", false, "the engine does what the model forbids: " + what,
                 what.substr(0, what.find(';')));
}

// The slip and lift agreements of the bodies that carry them, with the body's 0-based index.
std::vector<std::pair<int, const SlipAgreement*>> Slips(const EngineAgreement& a) {
  std::vector<std::pair<int, const SlipAgreement*>> out;
  for (int b = 0; b < a.blocks(); ++b) {
    for (const std::optional<SlipAgreement>* g : {&a.bodies[b].slip, &a.bodies[b].lift}) {
      if (*g) out.emplace_back(b, &**g);
    }
  }
  return out;
}

// No ensemble was run: the pointwise comparison over the whole run decides.
Verdict PointwiseVerdict(const EngineAgreement& a, const std::vector<const AngleAgreement*>& ang,
                         const ModelEnd& model) {
  const int nb = static_cast<int>(ang.size());
  bool all_within = true;
  std::string out;
  std::string unjudged;
  for (int b = 0; b < nb; ++b) {
    if (!ang[b]->judged) {
      const std::string words = NotJudgedText(b, *ang[b]) + ": " + PeakText(*ang[b]);
      if (ang[b]->peak_within_tolerance) {
        unjudged += "; " + words;
      } else {
        all_within = false;
        out += (out.empty() ? "" : "; ") + words;
      }
    }
    if (ang[b]->within_tolerance) continue;
    all_within = false;
    out += (out.empty() ? "" : "; ") + Name(b, *ang[b]) + " leaves the local tolerance (" +
           Format("%.3g", ang[b]->tolerance_at_horizon_rad) + " rad there) at " +
           Format("%.3f", ang[b]->horizon_s) + " s";
  }
  for (const auto& [b, g] : Slips(a)) {
    if (g->within_tolerance) continue;
    all_within = false;
    out += (out.empty() ? "" : "; ") + SlipName(*g, b) + " leaves its tolerance (" +
           Format("%.3g", g->tolerance_m) + " m) at " + Format("%.3f", g->horizon_s) + " s";
  }
  // Where the reference's model ends, its end is not an outcome to match.
  if ((!a.overturn_agree || !a.left_support_agree) && !model.ends) {
    all_within = false;
    out +=
        (out.empty() ? "" : "; ") + EndText(a.overturn_block_engine, a.left_support_block_engine) +
        " in the engine's run, " +
        EndText(a.overturn_block_reference, a.left_support_block_reference) + " in the reference's";
  }
  // The same rule as with the ensemble: where the reference's model ends, it has nothing to
  // say after that instant; what came before is said.
  if (model.ends) {
    return Decided("outside_model", false,
                   "outside the model: the reference's model ends at " +
                       Format("%.2f", model.at_s) + " s (" + model.why +
                       "); pointwise until then the engine " +
                       (all_within ? "agrees with it" + unjudged : "differs: " + out) +
                       "; no reference ensemble was run",
                   model.why);
  }
  const bool angles_out = std::any_of(ang.begin(), ang.end(),
                                      [](const AngleAgreement* g) { return !g->within_tolerance; });
  const std::string by =
      angles_out || PeakDecides(ang).empty() ? RatioText(ang, false) : PeakDecides(ang);
  if (!all_within) {
    return Decided("pointwise_differs", false,
                   out +
                       "; no reference ensemble was run, so whether the reference is "
                       "itself predictable there is unknown",
                   by);
  }
  return Decided("pointwise_only", true,
                 "agrees pointwise over the whole comparison (" +
                     Format("%.3f", a.compared_until_s) + " s)" + unjudged +
                     "; no reference ensemble was run, so the reference's own "
                     "predictability was not measured",
                 by);
}

// What the comparison before the horizon says: the errors there (`before`: the engine's), what
// agrees, and what decides.
struct BeforeHorizon {
  std::string before, agree_part;
  bool whole_run = true;  ///< no block has a horizon: the reference is predictable throughout
  bool angles_decide = false, peak_decides = false;
  std::string slip_decided;
};

// Whether block b's angle agrees where the reference is predictable (to its horizon `hp`,
// within the output interval `slack_s`).
bool AgreesPredictable(const AngleAgreement& g, const std::optional<double>& hp, double slack_s) {
  return g.within_tolerance || (hp && g.horizon_s >= *hp - slack_s);
}

// 1. Before the horizon: an error there is the engine's. The angles' part.
void AnglesBeforeHorizon(const std::vector<const AngleAgreement*>& ang, const Horizons& horizons,
                         double slack_s, BeforeHorizon* out) {
  bool peak_decided = false;
  for (int b = 0; b < static_cast<int>(ang.size()); ++b) {
    const std::optional<double>& hp = horizons.horizon_s[b];
    const AngleAgreement& g = *ang[b];
    out->whole_run = out->whole_run && !hp;
    const std::string hp_text = hp ? Format("%.2f s", *hp) : "the end of the run";
    // A block below the floor: its peak decides where the reference is predictable throughout
    // (with a horizon, the statistics beyond it judge the peak).
    if (!g.judged) {
      const std::string words = NotJudgedText(b, g) + ": " + PeakText(g);
      if (g.peak_within_tolerance || hp) {
        out->agree_part +=
            (out->agree_part.empty() ? "" : "; ") + words +
            (hp ? " (the reference's own horizon is " + hp_text + ")" : std::string());
      } else {
        out->before += (out->before.empty() ? "" : "; ") + words +
                       ", while the reference is predictable throughout";
        peak_decided = true;
      }
    }
    if (!AgreesPredictable(g, hp, slack_s)) {
      out->angles_decide = true;
      out->before +=
          (out->before.empty() ? "" : "; ") + Name(b, g) + " leaves the local tolerance (" +
          Format("%.3g", g.tolerance_at_horizon_rad) + " rad there) at " +
          Format("%.2f", g.horizon_s) + " s while the reference is predictable until " + hp_text +
          " (max error there " + Format("%.3g", g.max_abs_error_predictable_rad) + " rad, " +
          Format("%.3g", g.max_error_ratio_predictable) + " x the local tolerance)";
    } else {
      out->agree_part += (out->agree_part.empty() ? "" : "; ") + Name(b, g) + " " +
                         (g.within_tolerance ? "within the local tolerance for the whole comparison"
                                             : "until " + Format("%.2f", g.horizon_s) + " s") +
                         (hp ? " (the reference's own horizon is " + hp_text + ")"
                             : " (the reference is predictable throughout)");
    }
  }
  // Whether the angles' pointwise errors decide (else a peak below the floor, or the slip).
  out->peak_decides = peak_decided && !out->angles_decide;
}

// 1. Before the horizon, slip and lift where the reference is predictable: on the slip's own
// scale.
void SlipBeforeHorizon(const EngineAgreement& a, BeforeHorizon* out) {
  std::string slip_before;
  double slip_worst = 0.0;
  for (const auto& [b, g] : Slips(a)) {
    if (g->agrees_predictable()) {
      out->agree_part += (out->agree_part.empty() ? "" : "; ") + SlipName(*g, b) + " within " +
                         Format("%.3g", g->tolerance_m) + " m (max error " +
                         Format("%.3g", g->max_abs_error_predictable_m) + " m)";
      continue;
    }
    slip_before += (slip_before.empty() ? "" : "; ") + SlipName(*g, b) + " leaves its tolerance (" +
                   Format("%.3g", g->tolerance_m) + " m: 10% of the reference's peak " +
                   Format("%.3g", g->peak_reference_m) + " m, at least " +
                   Format("%.3g", g->floor_m) + " m) at " + Format("%.2f", g->horizon_s) +
                   " s where the reference is predictable (max error there " +
                   Format("%.3g", g->max_abs_error_predictable_m) + " m, " +
                   Format("%.3g", g->max_error_ratio_predictable) + " x the tolerance)";
    if (g->max_error_ratio_predictable > slip_worst) {
      slip_worst = g->max_error_ratio_predictable;
      out->slip_decided = BodyColumn(g->quantity, b + 1) + " error at most " +
                          Format("%.3g", g->max_error_ratio_predictable) +
                          " x its tolerance where the reference is predictable";
    }
  }
  if (!slip_before.empty()) out->before += (out->before.empty() ? "" : "; ") + slip_before;
}

// 3. Beyond the horizon: the ensembles' distributions decide. `v` holds the text so far.
Verdict StatisticalVerdict(const StatisticalComparison& s, Verdict v) {
  // The family's smallest Holm-adjusted p-value decides.
  const QuantityComparison* lowest = nullptr;
  for (const QuantityComparison& q : s.quantities) {
    if (q.in_family && !std::isnan(q.p_holm) && (!lowest || q.p_holm < lowest->p_holm)) lowest = &q;
  }
  const bool overturn_lowest = !lowest || s.overturn_p_holm < lowest->p_holm;
  v.decided_by = overturn_lowest ? "overturning, Fisher Holm " + PText(s.overturn_p_holm)
                                 : lowest->label + ", KS Holm " + PText(lowest->p_holm);
  if (s.consistent) {
    v.kind = "agrees";
    v.agrees = true;
    // Name the headline quantity: the peak of the block that moves most.
    const QuantityComparison* head = nullptr;
    for (const QuantityComparison& q : s.quantities) {
      if (q.key.rfind("peak_", 0) == 0 && q.unit == "rad" &&
          (!head || stats::Median(q.reference) > stats::Median(head->reference))) {
        head = &q;
      }
    }
    v.text +=
        "; beyond it, the engine's ensemble (" + std::to_string(s.engine_members) +
        " members) is consistent with the reference's (" + std::to_string(s.reference_members) +
        "): " + (head ? head->label + " KS " + PText(head->ks.p_value) + ", " : std::string()) +
        "no quantity differs at a family-wise 5% level (smallest: " + v.decided_by + ")";
    return v;
  }
  v.kind = "differs_beyond_horizon";
  v.agrees = false;
  std::string diffs;
  for (const QuantityComparison& q : s.quantities) {
    if (std::find(s.rejected.begin(), s.rejected.end(), q.key) == s.rejected.end()) continue;
    diffs += (diffs.empty() ? "" : "; ") + q.label + " (engine median " +
             Value(stats::Median(q.engine), q.unit) + " against " +
             Value(stats::Median(q.reference), q.unit) + ", KS " + PText(q.ks.p_value) + ", Holm " +
             PText(q.p_holm) + ")";
  }
  if (std::find(s.rejected.begin(), s.rejected.end(), "overturn") != s.rejected.end()) {
    int engine_over = 0, reference_over = 0;
    for (int b = 1; b <= kMaxBlocks; ++b) {
      engine_over += s.overturn_engine[b];
      reference_over += s.overturn_reference[b];
    }
    diffs += std::string(diffs.empty() ? "" : "; ") + "overturning (engine " +
             std::to_string(engine_over) + " of " + std::to_string(s.engine_members) + " against " +
             std::to_string(reference_over) + " of " + std::to_string(s.reference_members) +
             ", Fisher " + PText(s.overturn.p_value) + ")";
  }
  v.text += "; beyond it, the engine's ensemble differs from the reference's: " + diffs;
  return v;
}

// 2. Where the reference stops because its assumptions end, it has nothing to say: what the
// engine did from `from_s` on, after what agreed until then.
Verdict OutsideModel(const EngineAgreement& a, const std::string& agree_part,
                     const std::string& why, double from_s, double slack_s) {
  std::string did = FlagsText(a, from_s - slack_s, std::numeric_limits<double>::infinity(),
                              {"sliding", "uplift", "penetration"}, false);
  if (a.overturn_block_engine) {
    did += (did.empty() ? "" : ", ") + std::string("overturned block ") +
           std::to_string(*a.overturn_block_engine);
  }
  if (did.empty()) did = "stayed within the model's assumptions (no flag raised)";
  return Decided("outside_model", false,
                 "outside the model: " + why + "; the engine agrees with it until then (" +
                     agree_part + "); there the engine " + did,
                 why);
}

// Too few reference members remain beyond the horizon because they stop where the model's
// assumptions end: outside the model from the first horizon on.
Verdict TooFewReferenceMembers(const EngineAgreement& a, const std::string& agree_part,
                               const Horizons& horizons, const StatisticalComparison& s, int nb,
                               double slack_s) {
  double first_h = std::numeric_limits<double>::infinity();
  for (int b = 0; b < nb; ++b) {
    if (horizons.horizon_s[b]) first_h = std::min(first_h, *horizons.horizon_s[b]);
  }
  const int violated = s.excluded - s.excluded_non_finite;
  std::string why =
      std::to_string(violated) + " reference members stop where the model's assumptions end";
  if (s.excluded_non_finite > 0) {
    why = std::to_string(s.excluded) + " reference members stop (" + std::to_string(violated) +
          " where the model's assumptions end, " + std::to_string(s.excluded_non_finite) +
          " non_finite)";
  }
  return OutsideModel(a, agree_part,
                      "beyond the horizon (" + Format("%.2f", first_h) + " s) " + why +
                          ", too few remain (" + std::to_string(s.reference_members) + ")",
                      first_h, slack_s);
}

}  // namespace

Verdict MakeVerdict(const Scene& scene, const EngineAgreement& a,
                    const std::optional<Horizons>& predictability,
                    const std::optional<StatisticalComparison>& statistics) {
  const int nb = a.blocks();
  const std::vector<const AngleAgreement*> ang = a.compared_angles();
  const double slack_s = scene.run.output_interval_s;
  const ModelEnd model = ModelEndOf(a);
  if (auto v = FailedRunVerdict(a, predictability, statistics)) return *v;
  if (auto v = IntegrityVerdict(scene, a, model)) return *v;
  if (!predictability) return PointwiseVerdict(a, ang, model);

  // 1. Before the horizon: an error there is the engine's.
  BeforeHorizon bh;
  AnglesBeforeHorizon(ang, *predictability, slack_s, &bh);
  SlipBeforeHorizon(a, &bh);
  if (!bh.before.empty()) {
    return Decided("differs_before_horizon", false, "an engine error: " + bh.before,
                   bh.angles_decide  ? RatioText(ang, true)
                   : bh.peak_decides ? PeakDecides(ang)
                                     : bh.slip_decided);
  }
  // Overturning, or a block leaving its support, where the reference is predictable throughout
  // is the engine's to reproduce.
  if (bh.whole_run && (!a.overturn_agree || !a.left_support_agree) && !model.ends) {
    return Decided(
        "differs_before_horizon", false,
        "an engine error: " + EndText(a.overturn_block_engine, a.left_support_block_engine) +
            " in the engine's run, " +
            EndText(a.overturn_block_reference, a.left_support_block_reference) +
            " in the reference's, which is predictable throughout",
        !a.overturn_agree ? "overturning" : "leaving the support");
  }
  std::string& agree_part = bh.agree_part;
  if (a.left_support_block_reference && a.left_support_agree) {
    agree_part += std::string(agree_part.empty() ? "" : "; ") + "block " +
                  std::to_string(*a.left_support_block_reference) +
                  " leaves its support in both runs" +
                  (a.left_support_time_error_s
                       ? " (the engine's " + Format("%+.3f", *a.left_support_time_error_s) +
                             " s from the reference's)"
                       : std::string());
  }

  // 2. Where the reference stops because its assumptions end, it has nothing to say.
  if (model.ends) {
    return OutsideModel(
        a, agree_part,
        "the reference's model ends at " + Format("%.2f", model.at_s) + " s (" + model.why + ")",
        model.at_s, slack_s);
  }
  if (bh.whole_run) {
    return Decided("agrees", true, "agrees pointwise: " + agree_part, RatioText(ang, true));
  }
  Verdict v;
  v.text = "agrees pointwise where the reference is predictable: " + agree_part;
  // 3. Beyond the horizon: distributions.
  if (statistics && !statistics->available && statistics->excluded > 0 &&
      statistics->reference_members < kMinMembers) {
    return TooFewReferenceMembers(a, agree_part, *predictability, *statistics, nb, slack_s);
  }
  if (!statistics || !statistics->available) {
    v.kind = "agrees_to_horizon";
    v.agrees = true;
    v.text += "; beyond the horizon no statistical comparison was made (" +
              (statistics ? statistics->unavailable_reason
                          : std::string("no engine ensemble: compare.engine_members = 0")) +
              ")";
    v.decided_by = RatioText(ang, true);
    return v;
  }
  return StatisticalVerdict(*statistics, v);
}

double SmallestFamilyP(const StatisticalComparison& s) {
  double p = s.overturn_p_holm;
  for (const QuantityComparison& q : s.quantities) {
    if (q.in_family && !std::isnan(q.p_holm)) p = std::min(p, q.p_holm);
  }
  return p;
}

nlohmann::json StatisticsJson(const StatisticalComparison& s) {
  nlohmann::json j;
  j["available"] = s.available;
  if (s.engine_non_finite > 0) {
    j["engine_non_finite"] = s.engine_non_finite;
    j["engine_non_finite_detail"] = s.engine_non_finite_detail;
  }
  if (!s.available) {
    j["reason"] = s.unavailable_reason;
    return j;
  }
  j["reference_members"] = s.reference_members;
  j["engine_members"] = s.engine_members;
  j["excluded"] = s.excluded;
  if (s.excluded_non_finite > 0) j["excluded_non_finite"] = s.excluded_non_finite;
  j["alpha"] = s.alpha;
  j["family"] = "Holm-Bonferroni over every test below (KS p-values and the overturning test)";
  nlohmann::json tests = nlohmann::json::object();
  for (const QuantityComparison& q : s.quantities) {
    nlohmann::json t = TestJson(q.ks);
    t["p_holm"] = std::isnan(q.p_holm) ? nlohmann::json(nullptr) : nlohmann::json(q.p_holm);
    t["in_family"] = q.in_family;
    t["margin"] = q.margin;
    t["unit"] = q.unit;
    t["reference"] = SpreadJson(q.reference);
    t["engine"] = SpreadJson(q.engine);
    t["anderson_darling"] = TestJson(q.ad);
    tests[q.key] = t;
  }
  nlohmann::json ov = TestJson(s.overturn);
  ov["p_holm"] =
      std::isnan(s.overturn_p_holm) ? nlohmann::json(nullptr) : nlohmann::json(s.overturn_p_holm);
  // none, block1, block2 (one and two blocks alike), then block3 .. blockN.
  ov["reference"] = {{"none", s.overturn_reference[0]}};
  ov["engine"] = {{"none", s.overturn_engine[0]}};
  for (int b = 1; b <= std::max(s.blocks, 2); ++b) {
    ov["reference"][BodyColumn("block", b)] = s.overturn_reference[b];
    ov["engine"][BodyColumn("block", b)] = s.overturn_engine[b];
  }
  tests["overturn"] = ov;
  j["tests"] = tests;
  j["consistent"] = s.consistent;
  j["rejected"] = s.rejected;
  return j;
}

}  // namespace rockbench
