#include "report/run/friction_section.h"

#include <algorithm>
#include <cmath>

#include "engine/outcome.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"

namespace rockbench::report {

using nlohmann::json;

namespace {

// The contact of interface k in words: "ground (block 1 on the ground)", "interface (block 2 on
// block 1)"; N >= 3 blocks: "interface3 (block 3 on block 2)".
std::string ContactText(int k, int blocks) {
  if (k == 0) return "ground (block 1 on the ground)";
  return InterfaceName(k, blocks) + " (block " + std::to_string(k + 1) + " on block " +
         std::to_string(k) + ")";
}

}  // namespace

// |T|/N along the reference's samples, left out where the normal force nearly vanishes.
FrictionFacts ComputeFriction(const RunData& run, const reference::StackModel& model,
                              const GroundMotion& motion, const RunReportOptions& options) {
  const int nc = model.blocks();
  const EngineData& ref = run.engines.front();
  const double n_min = options.friction_min_normal_fraction * model.weight_n();
  FrictionFacts facts;
  facts.max_mu.assign(nc, 0.0);
  facts.min_N.assign(nc, std::numeric_limits<double>::infinity());
  facts.min_N_t.assign(nc, 0.0);
  // The reference's own normal forces are the chain's only up to the hand-over to its
  // unilateral model, whose forces are never negative (complementarity): past it the chain's
  // reaction at a sample is not the reference's, and no tension is read from it.
  const double handed_over_s = OptNumber(run.summary, "unilateral.from_t_s", run.summary_path);
  for (const Sample& s : ref.history.samples) {
    const reference::StackModel::Contacts c =
        model.Reactions(s, motion.xg_mps2(s.t_s), motion.yg_mps2(s.t_s));
    std::vector<double> row = {s.t_s};
    const bool chain = !(s.t_s > handed_over_s);
    for (int k = 0; k < nc; ++k) {
      if (chain && c.normal_n[k] < facts.min_N[k]) {
        facts.min_N[k] = c.normal_n[k], facts.min_N_t[k] = s.t_s;
      }
      double mu = kNaN;
      if (c.normal_n[k] >= n_min) {
        mu = c.mu[k];
        facts.max_mu[k] = std::max(facts.max_mu[k], mu);
        facts.span.Add(mu);
      } else {
        ++facts.left_out;
      }
      row.push_back(mu);
    }
    facts.rows.push_back(std::move(row));
  }
  return facts;
}

// The smallest friction coefficient between the blocks (and the ground) among the run's
// engines, as each states it in summary.json settings.friction_combined, and that engine's
// name; nullopt when no engine of the run states one.
std::optional<std::pair<double, std::string>> EngineFriction(const RunData& run) {
  std::optional<std::pair<double, std::string>> out;
  for (const EngineData& e : run.engines) {
    const json* set = Find(e.summary, "settings");
    // An engine whose friction is unbounded (ODE's inf) states none.
    if (set == nullptr || !set->is_object() || !set->contains("friction_combined") ||
        !(*set)["friction_combined"].is_number()) {
      continue;
    }
    const double mu = (*set)["friction_combined"].get<double>();
    if (!out || mu < out->first) out = std::make_pair(mu, e.name);
  }
  return out;
}

void FrictionWarnings(const RunData& run, const reference::StackModel& model,
                      const FrictionFacts& facts, std::vector<std::string>& warnings) {
  const int nc = static_cast<int>(facts.max_mu.size());
  // Friction: the largest |T|/N where the contact carries at least the option's share of the
  // weight (near N = 0, as at an uplift, the ratio grows without bound and says nothing).
  const auto engine_mu = EngineFriction(run);
  for (int k = 0; k < nc && engine_mu; ++k) {
    // Where the scene gives a finite friction, every engine uses it and the reference slides
    // too (docs/sliding.md): no warning, the comparison judges the slip.
    if (k < run.scene.block_count() && std::isfinite(run.scene.blocks[k].friction)) continue;
    const double need = facts.max_mu[k];
    if (need > engine_mu->first) {
      // One or two blocks: "the ground (block 1 on the ground)", "the interface (block 2 on
      // block 1)".
      warnings.push_back(
          "Sliding would occur at the " + ContactText(k, nc) +
          ": the rigid-block model needs a friction coefficient of " + Num(need, 3) +
          ", more than " + engine_mu->second + "'s " + Num(engine_mu->first, 3) +
          " (between two bodies, its summary's settings.friction_combined). The model assumes "
          "the blocks never slide.");
    }
  }
  // Tension: a normal force below zero by more than the located event's round-off (1e-6 of the
  // weight; at an uplift the run stops where N crosses zero, and that sample is N = 0 to 1e-9).
  // The first contact (from the ground up) that pulls is named.
  const double tension_n = -1e-6 * model.weight_n();
  for (int k = 0; k < nc; ++k) {
    if (!(facts.min_N[k] < tension_n)) continue;
    const std::string where = k == 0 ? "ground" : InterfaceName(k, nc);
    warnings.push_back("Tension: the reference's normal force at the " + where + " is negative (" +
                       Num(facts.min_N[k], 4) + " N at t = " + Fixed(facts.min_N_t[k], 4) +
                       " s): the contact would have to pull, so the block would lift off there.");
    break;
  }
}

void FrictionSection(const RunData& run, const FrictionFacts& facts,
                     const RunReportOptions& options, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Friction needed");
  const int nc = static_cast<int>(facts.max_mu.size());
  Span span = facts.span;
  const auto& rows = facts.rows;
  const auto engine_mu = EngineFriction(run);
  if (engine_mu) span.Add(engine_mu->first);
  const bool log = span.Decades();
  const double floor_mu = span.hi * 1e-6;
  std::string dat = "# t_s mu_ground";
  for (int k = 1; k < nc; ++k) dat.append(" mu_").append(InterfaceName(k, nc));
  dat += " (NaN: normal force below the limit)\n";
  for (const auto& r : rows) {
    AppendDat(dat, r[0]);
    for (int k = 1; k <= nc; ++k) {
      dat += ' ';
      AppendDat(dat, log && r[k] < floor_mu ? kNaN : r[k]);
    }
    dat += '\n';
  }
  // One colour per contact: the ground and the first interface as they always were, then a
  // palette for the interfaces of N >= 3 blocks.
  static const char* kColours[] = {"#1f4e9a", "#d95f02", "#1b9e77", "#7570b3",
                                   "#e7298a", "#66a61e", "#a6761d", "#666666"};
  GnuplotFigure f;
  f.name = "friction";
  f.height_px = 480;
  f.data_files = {{"friction.dat", dat}};
  f.script = CommonAxes(run.t_end_s) + "set ylabel 'friction coefficient needed |T|/N'\n" +
             (log ? "set logscale y\nset format y '10^{%L}'\n" : "set yrange [0:*]\n");
  f.script +=
      "plot 'friction.dat' using 1:2 with lines lw 1.6 lc rgb '#1f4e9a' title "
      "'ground (block 1 on the ground)'";
  for (int k = 1; k < nc; ++k) {
    f.script.append(", '' using 1:").append(std::to_string(k + 2));
    f.script.append(" with lines lw 1.6 lc rgb '").append(kColours[k % std::size(kColours)]);
    f.script.append("' title '").append(ContactText(k, nc)).append("'");
  }
  if (engine_mu) {
    f.script +=
        ", " + Num(engine_mu->first, 9) + " with lines dt 2 lw 1.5 lc rgb '#b00000' title " +
        Quote(engine_mu->second + "'s friction " + Num(engine_mu->first) + " (between two bodies)");
  }
  f.script += "\n";
  fig.Add(f,
          "Friction coefficient the rigid-block model needs, |T|/N, against time, from the "
          "reference's contact reactions at each sample (the accelerations of its mode and "
          "the base acceleration at that time)" +
              std::string(log ? ", log scale" : "") +
              ". Samples where a contact's normal force is below " +
              Num(100.0 * options.friction_min_normal_fraction) +
              "% of the stack's weight are left out (" + std::to_string(facts.left_out) +
              " of them): |T|/N has no meaning as N goes to 0. Dashed red: the smallest "
              "friction coefficient of the run's engines.");
  const std::string engine_mu_text =
      engine_mu ? Num(engine_mu->first) + " (" + engine_mu->second + ")" : std::string("-");
  std::vector<std::vector<std::string>> table;
  for (int k = 0; k < nc; ++k) {
    // summary.json friction_required.ground, .interface (two blocks), .interface2 ... (N >= 3).
    const std::string name = k == 0 ? "ground" : InterfaceName(k, nc);
    const double sum = OptNumber(run.summary, "friction_required." + name, run.summary_path);
    // A finite friction of the scene is every engine's (docs/engines.md, 'Friction from the
    // scene') and the reference's.
    const double mu_scene = run.scene.blocks.at(static_cast<size_t>(k)).friction;
    table.push_back({name, Num(sum), Num(facts.max_mu[k]),
                     std::isfinite(facts.min_N[k])
                         ? Num(facts.min_N[k], 6) + " N at " + Fixed(facts.min_N_t[k], 3) + " s"
                         : std::string("- (no sample before the hand-over)"),
                     std::isfinite(mu_scene) ? Num(mu_scene) + " (the scene's: every engine and "
                                                               "the reference)"
                                             : engine_mu_text});
  }
  page.Table({"contact", "largest |T|/N (reference run, every step, N -> 0 included)",
              "largest |T|/N (samples plotted)",
              "smallest normal force (the rigid chain's samples)", "engine friction"},
             table);
  // With a finite friction the reference slides: what the numbers above are then.
  std::string finite;
  for (int k = 0; k < nc; ++k) {
    const double mu = run.scene.blocks.at(static_cast<size_t>(k)).friction;
    if (!std::isfinite(mu)) continue;
    finite += (finite.empty() ? "" : ", ") +
              (k == 0 ? std::string("ground") : InterfaceName(k, nc)) + " " + Num(mu);
  }
  if (!finite.empty()) {
    const double from = OptNumber(run.summary, "unilateral.from_t_s", run.summary_path);
    page.Paragraph(
        "The scene gives a finite friction coefficient (" + finite +
        "): there the reference itself slips once |T|/N reaches it, and its unilateral model "
        "(docs/sliding.md) follows the slip" +
        (std::isnan(from) ? std::string(" (it never did in this run)")
                          : " from " + Fixed(from, 3) + " s") +
        ". The curves are the no-slip value of each sample's contact configuration, which "
        "exceeds the coefficient while a block slides; the reference run's column covers the "
        "steps of the rigid chain only, before the unilateral model takes over.");
  }
}

}  // namespace rockbench::report
