#include "report/run/friction_section.h"

#include <algorithm>
#include <cmath>

#include "reference/observables.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"

namespace rockbench::report {

using nlohmann::json;

// |T|/N along the reference's samples, left out where the normal force nearly vanishes.
FrictionFacts ComputeFriction(const RunData& run, const reference::Geometry& geo,
                              const GroundMotion& motion, const RunReportOptions& options) {
  const bool two = run.scene.block_count() == 2;
  const EngineData& ref = run.engines.front();
  const double W = geo.M * geo.g;
  const double n_min = options.friction_min_normal_fraction * W;
  FrictionFacts facts;
  auto& rows = facts.rows;
  Span& span = facts.span;
  for (const Sample& s : ref.history.samples) {
    const reference::ContactDemand c =
        reference::ContactReactions(geo, ModeOfConfiguration(s.mode).value_or(Mode::kRest),
                                    reference::StateOf(s, geo.two_blocks), motion.xg_mps2(s.t_s),
                                    motion.yg_mps2(s.t_s), run.scene.model.equations);
    const reference::Reactions& d = c.reactions;
    if (d.N_ground < facts.min_N_ground)
      facts.min_N_ground = d.N_ground, facts.min_N_ground_t = s.t_s;
    double mg = kNaN, mi = kNaN;
    if (d.N_ground >= n_min) {
      mg = c.mu_ground;
      facts.max_ground = std::max(facts.max_ground, mg);
      span.Add(mg);
    } else {
      ++facts.left_out;
    }
    if (two) {
      if (d.N_interface < facts.min_N_interface) {
        facts.min_N_interface = d.N_interface, facts.min_N_interface_t = s.t_s;
      }
      if (d.N_interface >= n_min) {
        mi = c.mu_interface;
        facts.max_interface = std::max(facts.max_interface, mi);
        span.Add(mi);
      } else {
        ++facts.left_out;
      }
    }
    rows.push_back({s.t_s, mg, mi});
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

void FrictionWarnings(const RunData& run, const reference::Geometry& geo,
                      const FrictionFacts& facts, std::vector<std::string>& warnings) {
  // Friction: the largest |T|/N where the contact carries at least the option's share of the
  // weight (near N = 0, as at an uplift, the ratio grows without bound and says nothing).
  const auto engine_mu = EngineFriction(run);
  for (const char* contact : {"ground", "interface"}) {
    if (!engine_mu) break;
    if (std::string(contact) == "interface" && run.scene.block_count() != 2) continue;
    const double need = std::string(contact) == "ground" ? facts.max_ground : facts.max_interface;
    if (need > engine_mu->first) {
      warnings.push_back(
          std::string("Sliding would occur at the ") + contact +
          (std::string(contact) == "ground" ? " (block 1 on the ground)"
                                            : " (block 2 on block 1)") +
          ": the rigid-block model needs a friction coefficient of " + Num(need, 3) +
          ", more than " + engine_mu->second + "'s " + Num(engine_mu->first, 3) +
          " (between two bodies, its summary's settings.friction_combined). The model assumes "
          "the blocks never slide.");
    }
  }
  // Tension: a normal force below zero by more than the located event's round-off (1e-6 of the
  // weight; at an uplift the run stops where N crosses zero, and that sample is N = 0 to 1e-9).
  const double tension_n = -1e-6 * geo.M * geo.g;
  if (facts.min_N_ground < tension_n ||
      (run.scene.block_count() == 2 && facts.min_N_interface < tension_n)) {
    const bool ground = facts.min_N_ground < tension_n;
    warnings.push_back(std::string("Tension: the reference's normal force at the ") +
                       (ground ? "ground" : "interface") + " is negative (" +
                       Num(ground ? facts.min_N_ground : facts.min_N_interface, 4) + " N at t = " +
                       Fixed(ground ? facts.min_N_ground_t : facts.min_N_interface_t, 4) +
                       " s): the contact would have to pull, so the block would lift off there.");
  }
}

void FrictionSection(const RunData& run, const FrictionFacts& facts,
                     const RunReportOptions& options, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Friction needed");
  const bool two = run.scene.block_count() == 2;
  Span span = facts.span;
  const auto& rows = facts.rows;
  const auto engine_mu = EngineFriction(run);
  if (engine_mu) span.Add(engine_mu->first);
  const bool log = span.Decades();
  const double floor_mu = span.hi * 1e-6;
  std::string dat = two ? "# t_s mu_ground mu_interface (NaN: normal force below the limit)\n"
                        : "# t_s mu_ground (NaN: normal force below the limit)\n";
  for (const auto& r : rows) {
    AppendDat(dat, r[0]);
    for (int k = 1; k <= (two ? 2 : 1); ++k) {
      dat += ' ';
      AppendDat(dat, log && r[k] < floor_mu ? kNaN : r[k]);
    }
    dat += '\n';
  }
  GnuplotFigure f;
  f.name = "friction";
  f.height_px = 480;
  f.data_files = {{"friction.dat", dat}};
  f.script = CommonAxes(run.t_end_s) + "set ylabel 'friction coefficient needed |T|/N'\n" +
             (log ? "set logscale y\nset format y '10^{%L}'\n" : "set yrange [0:*]\n");
  f.script +=
      "plot 'friction.dat' using 1:2 with lines lw 1.6 lc rgb '#1f4e9a' title "
      "'ground (block 1 on the ground)'";
  if (two) {
    f.script +=
        ", '' using 1:3 with lines lw 1.6 lc rgb '#d95f02' title "
        "'interface (block 2 on block 1)'";
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
  const double sum_g = OptNumber(run.summary, "friction_required.ground", run.summary_path);
  const double sum_i = OptNumber(run.summary, "friction_required.interface", run.summary_path);
  std::vector<std::vector<std::string>> table;
  table.push_back({"ground", Num(sum_g), Num(facts.max_ground),
                   Num(facts.min_N_ground, 6) + " N at " + Fixed(facts.min_N_ground_t, 3) + " s",
                   engine_mu_text});
  if (two) {
    table.push_back(
        {"interface", Num(sum_i), Num(facts.max_interface),
         Num(facts.min_N_interface, 6) + " N at " + Fixed(facts.min_N_interface_t, 3) + " s",
         engine_mu_text});
  }
  page.Table({"contact", "largest |T|/N (reference run, every step, N -> 0 included)",
              "largest |T|/N (samples plotted)", "smallest normal force", "engine friction"},
             table);
}

}  // namespace rockbench::report
