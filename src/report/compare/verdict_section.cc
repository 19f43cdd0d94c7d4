#include "report/compare/verdict_section.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compare/verdict.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"
#include "scene/body_kind.h"
#include "scene/mode.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Theta(int b) {
  return BodyColumn("theta", b + 1);
}

int Blocks(const VerdictInput& in) {
  return in.blocks > 0 ? in.blocks : 1;
}

std::string Rad(double v) {
  return Num(v, 3) + " rad";
}

// "theta1 X rad, theta2 Y rad, ..." from an object {"theta1": x, "theta2": y, ...}, blocks 1..nb.
std::string PerBlock(const json& root, const std::string& key, const fs::path& file, int nb) {
  std::string out;
  for (int b = 0; b < nb; ++b) {
    const double v = OptNumber(root, key + "." + Theta(b), file);
    if (std::isnan(v)) continue;
    out += (out.empty() ? "" : ", ") + Theta(b) + " " + Rad(v);
  }
  return out;
}

// ---- Verdicts ----

std::string KindInWords(const std::string& kind, bool statistics) {
  if (kind == "agrees") {
    return statistics ? "agrees up to the horizon and, beyond it, statistically"
                      : "agrees pointwise over the whole run (the reference is predictable "
                        "throughout)";
  }
  if (kind == "agrees_to_horizon")
    return "agrees up to the horizon; not compared statistically beyond it";
  if (kind == "differs_before_horizon") return "differs where the reference is predictable";
  if (kind == "differs_beyond_horizon")
    return "agrees up to the horizon; its ensemble differs from the reference's beyond it";
  if (kind == "pointwise_only") return "agrees pointwise (no reference ensemble was run)";
  if (kind == "pointwise_differs") return "differs pointwise (no reference ensemble was run)";
  if (kind == "violates_model")
    return "does what the model forbids (a run that is not finite, a blow-up, energy growth, "
           "or sliding, uplift or penetration at the verdict's scale) while the model holds";
  if (kind == "reference_failed")
    return "no verdict: the reference's solution (or a member of its ensemble) is not finite, "
           "so there is nothing to compare with";
  if (kind == "outside_model")
    return "the reference's model ends (a violated assumption) or too few reference members "
           "remain: nothing to compare there";
  if (kind == "marginal") return "the statistical decision changes with the ensemble's seed";
  return kind;
}

// The verdict's word: comparison.json's kind (AGREES, DIFFERS, MARGINAL, OUTSIDE MODEL), or
// agrees / differs for a folder written before the kinds.
std::string Label(const std::string& kind, bool agrees) {
  if (kind.empty()) return agrees ? "AGREES" : "DIFFERS";
  return VerdictLabel(kind);
}

void VerdictTable(const VerdictInput& in, Page& page) {
  const json& c = *in.comparison;
  const fs::path& file = in.comparison_path;
  std::vector<std::vector<std::string>> rows;
  bool old = false;
  for (const std::string& name : in.engines) {
    const std::string k = "engines." + name;
    if (Find(c, k) == nullptr) continue;
    const std::string text = OptString(c, k + ".verdict", file);
    if (text.empty()) {
      old = true;
      rows.push_back({name, "not recorded", "", "", ""});
      continue;
    }
    const std::string kind = OptString(c, k + ".verdict_kind", file);
    rows.push_back({name, Label(kind, OptBool(c, k + ".agrees", file)),
                    KindInWords(kind, Find(c, k + ".statistics") != nullptr &&
                                          !Find(c, k + ".statistics")->is_null()),
                    OptString(c, k + ".verdict_decided_by", file), text + "."});
  }
  if (rows.empty()) {
    page.Paragraph("comparison.json compares no engine with the reference: there is no verdict.");
    return;
  }
  page.Table({"engine", "verdict", "what was found", "decided by", "in words (comparison.json)"},
             rows);
  if (old) {
    page.Paragraph(
        "This comparison.json has no verdict (written by a rockbench before the verdicts): the "
        "agreement table below is all there is.");
  }
}

// ---- Ranking ----

void RankingPart(const VerdictInput& in, Page& page) {
  const std::vector<EngineRank> ranks = RankEngines(*in.comparison, in.engines, in.comparison_path);
  if (ranks.size() < 2) return;
  page.Heading("Ranking", 3);
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < ranks.size(); ++i) {
    const EngineRank& r = ranks[i];
    rows.push_back({std::to_string(i + 1), r.engine, Label(r.kind, r.agrees),
                    r.first_block.empty()
                        ? "whole comparison (" + Fixed(r.compared_until_s, 3) + " s)"
                        : Fixed(r.agreement_horizon_s, 3) + " s (" + r.first_block + ")",
                    Fixed(r.ranked_horizon_s, 3) + " s", Num(r.wall_s, 3) + " s",
                    std::isnan(r.wall_per_simulated_s) ? "" : Num(r.wall_per_simulated_s, 3)});
  }
  page.Table({"rank", "engine", "verdict", "agreement horizon (first block to leave)",
              "ranked horizon", "wall time", "wall s per simulated s"},
             rows);
  page.Paragraph(
      "Ranked by verdict, then by the ranked horizon, then by wall time per simulated second. "
      "An engine's agreement horizon is the first time one of its blocks leaves the comparison "
      "tolerance of the reference; the ranked horizon caps each block's at the reference's "
      "predictability horizon, beyond which two correct runs differ too, so a later departure "
      "ranks nothing. Each engine ran at its own settings (comparison.json engines.<name>): the "
      "cost of equal accuracy is the work-precision report's (`rockbench sweep`).");
}

// ---- Convergence ----

std::string WitnessSettings(const json& w, const fs::path& file) {
  const std::string integrator = OptString(w, "integrator", file);
  std::string s = integrator.empty() ? "settings not recorded" : integrator;
  if (integrator == "dopri5" || integrator == "dop853") {
    s += ", rtol " + Num(OptNumber(w, "rtol", file)) + ", atol " + Num(OptNumber(w, "atol", file));
  } else if (integrator == "rk4") {
    s += ", step " + Num(OptNumber(w, "step_s", file)) + " s";
  }
  const std::string events = OptString(w, "events", file);
  if (!events.empty()) s += ", events " + events;
  return s;
}

// The convergence check in plain words; `warning` is set when the reference is not converged.
std::string ConvergenceText(const json& conv, const fs::path& file, int nb, std::string& warning) {
  const json* w = Find(conv, "witness");
  const std::string witness = w != nullptr ? WitnessSettings(*w, file) : "settings not recorded";
  const double diff = OptNumber(conv, "max_abs_diff_rad", file);
  const std::string per_block = PerBlock(conv, "max_abs_diff_rad_per_block", file, nb);
  const std::string diff_text =
      Rad(diff) + (nb >= 2 && !per_block.empty() ? " (" + per_block + ")" : "");
  const std::string tol = PerBlock(conv, "tolerance_rad", file, nb);
  const std::string tol_text = tol.empty() ? "" : " (" + tol + ")";
  if (OptBool(conv, "converged", file)) {
    return "The reference is converged: its witness (the same model at tighter settings: " +
           witness + ") differs from it by at most " + diff_text +
           ", within the comparison tolerance" + tol_text + ", and ends the run the same way.";
  }
  const double at = OptNumber(conv, "diverges_at_s", file);
  const bool witness_used = OptString(conv, "used", file) == "witness";
  std::string text = "The reference is NOT converged: the default reference ";
  if (!std::isnan(at)) {
    text += "differs from its tighter witness (" + witness + ") by up to " + diff_text +
            " from t = " + Fixed(at, 3) + " s on, more than the comparison tolerance" + tol_text;
  } else {
    text += "and its tighter witness (" + witness +
            ") end the run differently (status or overturned block), although their angles "
            "differ by at most " +
            diff_text;
  }
  text += witness_used ? ", so the comparison used the witness: the reference on this page is "
                         "the witness's solution. Tighten model.rtol and model.atol (dopri5) or "
                         "model.step (rk4) for a converged default."
                       : ", and the comparison used the default reference nevertheless.";
  warning = text;
  return text;
}

std::vector<std::string> ConvergencePart(const VerdictInput& in, Page& page) {
  page.Heading("Convergence of the reference", 3);
  const json* conv = nullptr;
  fs::path file;
  if (in.comparison != nullptr) {
    conv = Find(*in.comparison, "reference.convergence");
    file = in.comparison_path;
  }
  if ((conv == nullptr || conv->is_null()) && in.summary != nullptr) {
    conv = Find(*in.summary, "convergence");
    file = in.summary_path;
  }
  if (conv == nullptr || !conv->is_object()) {
    page.Paragraph(
        "No convergence check was recorded (a folder from a rockbench older than the witness "
        "check): whether the reference is converged is unknown.");
    return {};
  }
  std::string warning;
  page.Paragraph(ConvergenceText(*conv, file, Blocks(in), warning));
  if (warning.empty()) return {};
  return {warning};
}

// ---- Predictability ----

void PredictabilityPart(const VerdictInput& in, Page& page) {
  page.Heading("Predictability horizon", 3);
  if (!in.predictability) {
    page.Paragraph(
        "No reference ensemble was run (a `rockbench compare --quick` folder, or one from a "
        "rockbench older than the ensembles): there is no predictability horizon, no ensemble "
        "band and no statistical comparison. The verdicts rest on the pointwise comparison over "
        "the whole run, and whether the reference is itself predictable there is unknown.");
    return;
  }
  const Predictability& p = *in.predictability;
  std::string perturbation =
      "base-motion amplitude x (1 +- " + Num(p.amplitude_rel) + ") (amplitude_rel " +
      Num(p.amplitude_rel) + "), each record sample moved by up to " + Num(p.sample_precision) +
      " x half a unit of its last printed digit (sample_precision " + Num(p.sample_precision) +
      "), each nonzero initial value x (1 +- " + Num(p.initial_rel) + ") (initial_rel " +
      Num(p.initial_rel) + "), seed " + Num(p.seed, 12);
  std::string statuses;
  for (const auto& [status, n] : p.statuses) {
    statuses += (statuses.empty() ? "" : ", ") + status + " " + std::to_string(n);
  }
  page.Paragraph("A reference ensemble of " + std::to_string(p.members) +
                 " members, the nominal inputs perturbed within what they are known to: " +
                 perturbation + "." + (p.rule.empty() ? "" : " Rule: " + p.rule + ".") +
                 (statuses.empty() ? "" : " Members' outcomes: " + statuses + ".") +
                 (std::isnan(p.wall_s) ? "" : " Wall time " + Num(p.wall_s, 3) + " s."));
  std::vector<std::vector<std::string>> rows;
  for (int b = 0; b < std::min(Blocks(in), static_cast<int>(p.horizon_s.size())); ++b) {
    const std::optional<double>& h = p.horizon_s[b];
    rows.push_back(
        {Theta(b), h ? Num(*h, 6) + " s" : "none", Rad(p.tolerance_rad[b]), Rad(p.spread_rad[b]),
         h ? "predictable until " + Num(*h, 6) +
                 " s; beyond it one run's error ranks nothing, the ensembles are compared instead"
           : "predictable for the whole run: every member stays within the tolerance of the "
             "nominal run to the end"});
  }
  page.Table({"angle", "predictability horizon", "comparison tolerance",
              "largest spread |member - nominal|", "meaning"},
             rows);
  page.Paragraph(
      "A block's predictability horizon is the first time any member leaves the nominal run "
      "by more than the comparison tolerance; \"none\" (null in comparison.json) means the "
      "reference is predictable for the whole run. Before the horizon an engine's error is the "
      "engine's; beyond it the problem's own sensitivity is part of it. The angle figure shades "
      "the band the members span; dashed blue lines mark the horizons on the angle and error "
      "figures.");
}

// ---- Statistics ----

// The block of a per-block quantity's key ("peak_theta3_rad" -> 3; `prefix` "peak_theta",
// `suffix` "_rad"), 0 when the key is not of that form.
int KeyBlock(const std::string& key, const std::string& prefix, const std::string& suffix) {
  if (key.size() <= prefix.size() + suffix.size() || key.compare(0, prefix.size(), prefix) != 0 ||
      key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return 0;
  }
  const std::string digits = key.substr(prefix.size(), key.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 2 ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return 0;
  }
  return std::stoi(digits);
}

// Display order of the tested quantities: the peaks of every block, the times of the peaks,
// the impacts, the residual angles, the overturning; others (the RMS angles) follow in
// comparison.json's order.
int QuantityRank(const std::string& key) {
  constexpr int kGroup = kMaxBlocks + 1;
  if (const int b = KeyBlock(key, "peak_theta", "_rad")) return 0 * kGroup + b;
  if (const int b = KeyBlock(key, "peak_theta", "_t_s")) return 1 * kGroup + b;
  if (key == "impacts") return 2 * kGroup;
  if (const int b = KeyBlock(key, "residual_theta", "_rad")) return 3 * kGroup + b;
  if (key == "overturn") return 4 * kGroup;
  return 5 * kGroup;
}

// "block 1, block 2" (one or two blocks), "block 1, ..., block N".
std::string BlockList(int nb) {
  if (nb <= 2) return "block 1, block 2";
  return nb == 3 ? "block 1, block 2, block 3" : "block 1, ..., block " + std::to_string(nb);
}

std::string QuantityLabel(const std::string& key, int nb) {
  for (int b = 0; b < std::max(nb, 2); ++b) {
    const std::string th = Theta(b);
    if (key == "peak_" + th + "_rad") return "peak |" + th + "|";
    if (key == "peak_" + th + "_t_s") return "time of the largest |" + th + "|";
    if (key == "residual_" + th + "_rad") return "residual " + th + " (end of the run)";
  }
  if (key == "impacts") return "impacts";
  if (key == "overturn") return "overturning (none, " + BlockList(nb) + ")";
  return key;
}

// "median [q05, q95] unit", or the overturning counts.
std::string Spread(const json& t, const std::string& side, const fs::path& file) {
  const json* s = Find(t, side);
  if (s == nullptr || s->is_null()) return "no members";
  if (Find(*s, "median") == nullptr) {
    // none, block 1, block 2 always; block 3 ... as long as the counts have them.
    std::string out = "none " + Num(OptNumber(*s, "none", file));
    for (int b = 1; b <= kMaxBlocks; ++b) {
      const std::string key = BodyColumn("block", b);
      if (b > 2 && Find(*s, key) == nullptr) break;
      out += ", block " + std::to_string(b) + " " + Num(OptNumber(*s, key, file));
    }
    return out;
  }
  const std::string unit = OptString(t, "unit", file);
  return Num(OptNumber(*s, "median", file)) + " [" + Num(OptNumber(*s, "q05", file)) + ", " +
         Num(OptNumber(*s, "q95", file)) + "]" + (unit.empty() ? "" : " " + unit);
}

std::vector<std::vector<std::string>> TestRows(const json& st, const fs::path& file, int nb) {
  const json* tests = Find(st, "tests");
  if (tests == nullptr || !tests->is_object()) return {};
  std::vector<std::string> keys;
  for (auto it = tests->begin(); it != tests->end(); ++it) keys.push_back(it.key());
  std::stable_sort(keys.begin(), keys.end(), [](const std::string& a, const std::string& b) {
    return QuantityRank(a) < QuantityRank(b);
  });
  std::vector<std::string> rejected;
  if (const json* r = Find(st, "rejected"); r != nullptr && r->is_array()) {
    for (const json& k : *r) {
      if (k.is_string()) rejected.push_back(k.get<std::string>());
    }
  }
  std::vector<std::vector<std::string>> rows;
  for (const std::string& key : keys) {
    const json& t = (*tests)[key];
    std::string test = OptString(t, "test", file);
    const double margin = OptNumber(t, "margin", file);
    if (margin > 0) {
      const std::string unit = OptString(t, "unit", file);
      test += " (margin " + Num(margin, 3) + (unit.empty() ? "" : " " + unit) + ")";
    }
    const double ad = OptNumber(t, "anderson_darling.p_value", file);
    const bool flagged = std::find(rejected.begin(), rejected.end(), key) != rejected.end();
    rows.push_back({QuantityLabel(key, nb), Spread(t, "reference", file), Spread(t, "engine", file),
                    test, Num(OptNumber(t, "statistic", file), 3),
                    Num(OptNumber(t, "p_value", file), 3), Num(OptNumber(t, "p_holm", file), 3),
                    std::isnan(ad) ? "" : Num(ad, 3), flagged ? "DIFFERS" : "no"});
  }
  return rows;
}

// Why an engine has no statistical comparison in comparison.json.
std::string NoStatisticsReason(const VerdictInput& in, const std::string& name) {
  const Predictability& p = *in.predictability;
  bool any_horizon = false;
  for (int b = 0; b < std::min(Blocks(in), static_cast<int>(p.horizon_s.size())); ++b) {
    any_horizon = any_horizon || p.horizon_s[b].has_value();
  }
  if (!any_horizon) {
    return "the reference is predictable for the whole run, so the pointwise comparison is the "
           "verdict and no engine ensemble was run";
  }
  const std::string kind =
      OptString(*in.comparison, "engines." + name + ".verdict_kind", in.comparison_path);
  if (kind == "differs_before_horizon") {
    return "the engine already differs where the reference is predictable, so its ensemble "
           "was not run";
  }
  return "no engine ensemble was run (compare.engine_members = 0, or an older rockbench)";
}

// The engine's tests as a table (true), or why there are none (false).
bool EngineStatistics(const VerdictInput& in, const std::string& name, Page& page) {
  const fs::path& file = in.comparison_path;
  const json* st = Find(*in.comparison, "engines." + name + ".statistics");
  if (st == nullptr || st->is_null()) {
    page.Paragraph(name + ": no statistical comparison: " + NoStatisticsReason(in, name) + ".");
    return false;
  }
  if (!OptBool(*st, "available", file)) {
    const std::string reason = OptString(*st, "reason", file);
    page.Paragraph(name + ": no statistical comparison" + (reason.empty() ? "" : ": " + reason) +
                   ".");
    return false;
  }
  const double alpha = OptNumber(*st, "alpha", file);
  const double excluded = OptNumber(*st, "excluded", file);
  const bool consistent = OptBool(*st, "consistent", file);
  page.Paragraph(name + ": its ensemble of " + Num(OptNumber(*st, "engine_members", file)) +
                 " members (the inputs of the first reference members) against the reference's " +
                 Num(OptNumber(*st, "reference_members", file)) +
                 (excluded > 0 ? " (" + Num(excluded) +
                                     " left out: their reference run broke the model's "
                                     "assumptions)"
                               : "") +
                 ". Family: " + OptString(*st, "family", file) + ", at alpha = " + Num(alpha) +
                 "; a quantity is flagged when its Holm-adjusted p is at or below alpha. Result: " +
                 (consistent ? "consistent, no quantity differs." : "the ensembles differ."));
  page.Table(
      {"quantity", "reference median [5%, 95%]", "engine median [5%, 95%]", "test (the verdict's)",
       "statistic", "p", "Holm-adjusted p", "Anderson-Darling p (no margin)", "flagged"},
      TestRows(*st, file, Blocks(in)));
  return true;
}

void StatisticsPart(const VerdictInput& in, Page& page) {
  if (!in.predictability || in.comparison == nullptr || in.engines.empty()) return;
  page.Heading("Statistical comparison beyond the horizon", 3);
  bool any_table = false;
  for (const std::string& name : in.engines) {
    if (Find(*in.comparison, "engines." + name) == nullptr) continue;
    any_table = EngineStatistics(in, name, page) || any_table;
  }
  if (!any_table) return;
  page.Paragraph(
      "Beyond the horizon two correct runs differ by more than the tolerance, so the engine's "
      "ensemble (the same perturbed inputs) is compared with the reference's on what a user "
      "cares about. Medians with the 5% and 95% quantiles; overturning as counts of members. "
      "The margin is the resolution below which values do not differ (the Kolmogorov-Smirnov "
      "test's slack); Anderson-Darling, without a margin, is shown beside it and does not "
      "decide.");
}

// ---- Errors split at the horizon ----

void SplitErrorsPart(const VerdictInput& in, Page& page) {
  // Without an ensemble there is no horizon to split at.
  if (in.comparison == nullptr || in.engines.empty() || !in.predictability) return;
  const json& c = *in.comparison;
  const fs::path& file = in.comparison_path;
  std::vector<std::vector<std::string>> rows;
  for (const std::string& name : in.engines) {
    for (int b = 0; b < Blocks(in); ++b) {
      const std::string k = "engines." + name + "." + Theta(b);
      if (Find(c, k + ".max_abs_error_predictable_rad") == nullptr) continue;
      const double h = OptNumber(c, k + ".predictability_horizon_s", file);
      const double beyond = OptNumber(c, k + ".samples_beyond", file);
      const bool none_beyond = !(beyond > 0);
      rows.push_back(
          {name, Theta(b), std::isnan(h) ? "none (predictable throughout)" : Num(h, 6) + " s",
           Rad(OptNumber(c, k + ".max_abs_error_predictable_rad", file)),
           Rad(OptNumber(c, k + ".rms_error_predictable_rad", file)),
           none_beyond ? "no sample" : Rad(OptNumber(c, k + ".max_abs_error_beyond_rad", file)),
           none_beyond ? "no sample" : Rad(OptNumber(c, k + ".rms_error_beyond_rad", file)),
           Num(beyond), Rad(OptNumber(c, k + ".tolerance_rad", file))});
    }
  }
  if (rows.empty()) return;
  page.Heading("Errors before and beyond the horizon", 3);
  page.Table({"engine", "angle", "predictability horizon", "max error, predictable",
              "RMS error, predictable", "max error, beyond", "RMS error, beyond", "samples beyond",
              "tolerance"},
             rows);
  page.Paragraph(
      "|theta_engine - theta_reference| over the compared run, split at the reference's "
      "predictability horizon: before it an error is the engine's; beyond it two correct runs "
      "may differ by the ensemble's spread.");
}

}  // namespace

std::vector<EngineRank> RankEngines(const json& comparison, const std::vector<std::string>& engines,
                                    const fs::path& file) {
  std::vector<EngineRank> ranks;
  for (const std::string& name : engines) {
    const std::string k = "engines." + name;
    if (Find(comparison, k) == nullptr) continue;
    EngineRank r;
    r.engine = name;
    r.compared_until_s = OptNumber(comparison, k + ".compared_until_s", file);
    r.wall_s = OptNumber(comparison, k + ".wall_s", file);
    r.wall_per_simulated_s = r.compared_until_s > 0.0 ? r.wall_s / r.compared_until_s : NAN;
    r.agreement_horizon_s = r.compared_until_s;
    r.ranked_horizon_s = r.compared_until_s;
    bool all_within = true;
    // Every block comparison.json has: theta1, theta2, ..., thetaN.
    for (int b = 0; b < kMaxBlocks; ++b) {
      const std::string kb = k + "." + Theta(b);
      if (Find(comparison, kb) == nullptr) continue;
      const bool within = OptBool(comparison, kb + ".within_tolerance", file);
      const double h = within ? r.compared_until_s : OptNumber(comparison, kb + ".horizon_s", file);
      all_within = all_within && within;
      if (!within && (r.first_block.empty() || h < r.agreement_horizon_s)) {
        r.agreement_horizon_s = h;
        r.first_block = Theta(b);
      }
      const double hp = OptNumber(comparison, kb + ".predictability_horizon_s", file);
      r.ranked_horizon_s = std::min(r.ranked_horizon_s, std::isnan(hp) ? h : std::min(h, hp));
    }
    r.agrees = Find(comparison, k + ".agrees") != nullptr ? OptBool(comparison, k + ".agrees", file)
                                                          : all_within;
    r.kind = OptString(comparison, k + ".verdict_kind", file);
    ranks.push_back(std::move(r));
  }
  std::stable_sort(ranks.begin(), ranks.end(), [](const EngineRank& a, const EngineRank& b) {
    if (a.agrees != b.agrees) return a.agrees;
    // NaN (not recorded) ranks last.
    const double ha = std::isnan(a.ranked_horizon_s) ? -INFINITY : a.ranked_horizon_s;
    const double hb = std::isnan(b.ranked_horizon_s) ? -INFINITY : b.ranked_horizon_s;
    if (ha != hb) return ha > hb;
    const double ca = std::isnan(a.wall_per_simulated_s) ? INFINITY : a.wall_per_simulated_s;
    const double cb = std::isnan(b.wall_per_simulated_s) ? INFINITY : b.wall_per_simulated_s;
    return ca < cb;
  });
  return ranks;
}

std::vector<std::string> WriteVerdictSection(const VerdictInput& in, Page& page) {
  page.Heading("Verdict");
  if (in.comparison == nullptr) {
    page.Paragraph(
        "This run folder has no comparison.json (a `rockbench run` folder): no engine was "
        "compared with the reference, so there is no verdict.");
  } else {
    VerdictTable(in, page);
    RankingPart(in, page);
  }
  std::vector<std::string> warnings = ConvergencePart(in, page);
  if (in.comparison != nullptr) {
    PredictabilityPart(in, page);
    StatisticsPart(in, page);
    SplitErrorsPart(in, page);
  }
  return warnings;
}

}  // namespace rockbench::report
