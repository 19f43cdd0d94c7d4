#include "report/compare/agreement_section.h"

#include <algorithm>
#include <cmath>

#include "report/common/interpolation.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"
#include "run/engine_registry.h"
#include "run/tolerance.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Per sample time, every block's |error| (block b + 1 at b).
struct EngineErrors {
  std::vector<double> t;
  std::vector<std::vector<double>> e;
};

EngineErrors AngleErrors(const RunData& run, const EngineData& e, const HistoryInterpolator& ref) {
  EngineErrors out;
  double until = ref.end_s();
  if (run.comparison) {
    const double c =
        OptNumber(*run.comparison, "engines." + e.name + ".compared_until_s", run.comparison_path);
    if (!std::isnan(c)) until = std::min(until, c);
  }
  const int nb = run.scene.block_count();
  out.e.resize(nb);
  for (const Sample& s : e.history.samples) {
    if (s.t_s > until + 1e-12) break;
    const auto a = ref.Angles(s.t_s);
    out.t.push_back(s.t_s);
    for (int b = 0; b < nb; ++b) out.e[b].push_back(std::abs(s.theta_rad[b] - a[b]));
  }
  return out;
}

void MetricsTable(const RunData& run, Page& page) {
  const json& c = *run.comparison;
  const fs::path& file = run.comparison_path;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::vector<std::string>> impacts, slips;
  for (const EngineData& e : run.engines) {
    if (IsReference(e.name)) continue;
    const std::string k = "engines." + e.name;
    if (Find(c, k) == nullptr) continue;
    for (int b = 1; b <= run.scene.block_count(); ++b) {
      const std::string kb = k + "." + BodyColumn("theta", b);
      const bool within = OptBool(c, kb + ".within_tolerance", file);
      // A block below the floor (judged false): no relative peak error (its reference peak may
      // be zero), the absolute one and the peak judgement instead.
      const json* judged = Find(c, kb + ".judged");
      const bool is_judged = judged == nullptr || !judged->is_boolean() || judged->get<bool>();
      const std::string peak_error =
          is_judged ? Num(100.0 * NeedNumber(c, kb + ".peak_rel_error", file), 3) + " %"
                    : "not judged (below the floor): " +
                          Num(OptNumber(c, kb + ".peak_abs_error_rad", file), 3) + " rad, " +
                          (OptBool(c, kb + ".peak_within_tolerance", file) ? "within" : "BEYOND") +
                          " the peak tolerance " +
                          Num(OptNumber(c, kb + ".peak_tolerance_rad", file), 3) + " rad";
      rows.push_back({e.name, "theta" + std::to_string(b),
                      Num(NeedNumber(c, kb + ".max_abs_error_rad", file), 3),
                      Num(NeedNumber(c, kb + ".rms_error_rad", file), 3),
                      Num(OptNumber(c, kb + ".tolerance_rad", file), 3),
                      within ? "whole run (" + Num(NeedNumber(c, kb + ".horizon_s", file)) + " s)"
                             : Num(NeedNumber(c, kb + ".horizon_s", file), 5) + " s",
                      peak_error,
                      Num(1e3 * NeedNumber(c, kb + ".peak_time_error_s", file), 3) + " ms"});
    }
    const double matched = NeedNumber(c, k + ".impacts_matched", file);
    const double nref = OptNumber(c, k + ".impacts_reference", file);
    const double neng = OptNumber(c, k + ".impacts_engine", file);
    const std::string mismatch = Find(c, k + ".first_impact_mismatch") != nullptr &&
                                         Find(c, k + ".first_impact_mismatch")->is_string()
                                     ? Find(c, k + ".first_impact_mismatch")->get<std::string>()
                                     : "";
    const double rate = OptNumber(c, "impact_min_rate_radps", file);
    const double nref_all = OptNumber(c, k + ".impacts_reference_all", file);
    const double neng_all = OptNumber(c, k + ".impacts_engine_all", file);
    // The threshold on the same line as the counts it selects.
    std::string matched_text = Num(matched) + " of " + Num(nref) + " (engine: " + Num(neng) + ")";
    if (!std::isnan(rate)) matched_text += " faster than " + Num(rate) + " rad/s";
    if (!std::isnan(nref_all) && !std::isnan(neng_all)) {
      matched_text +=
          "; all impacts: " + Num(nref_all) + " reference, " + Num(neng_all) + " engine";
    }
    // Slip and lift (u1.., z1..), where the histories carry them.
    for (int b = 1; b <= run.scene.block_count(); ++b) {
      for (const char* q : {"u", "z"}) {
        const std::string kq = k + "." + BodyColumn(q, b);
        if (Find(c, kq) == nullptr) continue;
        slips.push_back({e.name, BodyColumn(q, b) + (q[0] == 'u' ? " (slip)" : " (lift)"),
                         Num(NeedNumber(c, kq + ".max_abs_error_m", file), 3),
                         Num(NeedNumber(c, kq + ".tolerance_m", file), 3),
                         Num(OptNumber(c, kq + ".peak_reference_m", file), 4),
                         Num(OptNumber(c, kq + ".final_reference_m", file), 4),
                         Num(OptNumber(c, kq + ".final_engine_m", file), 4),
                         OptBool(c, kq + ".within_tolerance", file)
                             ? "whole run"
                             : Num(OptNumber(c, kq + ".horizon_s", file), 5) + " s"});
      }
    }
    std::string off = "none";
    if (const json* o = Find(c, k + ".left_support");
        o != nullptr && o->is_object() &&
        (!o->value("reference_block", json()).is_null() ||
         !o->value("engine_block", json()).is_null())) {
      off = OptBool(c, k + ".left_support.agree", file) ? "agrees" : "DIFFERS";
    }
    impacts.push_back({e.name, matched_text,
                       Num(1e3 * OptNumber(c, k + ".max_abs_impact_time_error_s", file), 3) + " ms",
                       mismatch.empty() ? "none" : mismatch,
                       OptBool(c, k + ".overturn.agree", file) ? "agrees" : "DIFFERS", off,
                       OptBool(c, k + ".final.agree", file) ? "agrees" : "DIFFERS",
                       Num(NeedNumber(c, k + ".wall_s", file), 3) + " s"});
  }
  page.Table({"engine", "angle", "max error (rad)", "RMS error (rad)", "tolerance (rad)",
              "agreement horizon", "peak error", "peak time error"},
             rows);
  if (!slips.empty()) {
    page.Table({"engine", "quantity", "max error (m)", "tolerance (m)", "reference peak (m)",
                "reference final (m)", "engine final (m)", "within the tolerance until"},
               slips);
    page.Paragraph(
        "Slip u of a block on its support and lift z of its lowest base corner above it "
        "(docs/sliding.md), compared at the engine's sample times; tolerance 10% of the "
        "reference's peak, never below 1% of the block's critical angle times its width. An "
        "error beyond it where the reference is predictable decides DIFFERS.");
  }
  page.Table({"engine", "impacts matched", "max impact time error", "first mismatch", "overturning",
              "left its support", "final state", "wall time"},
             impacts);
  page.Paragraph("From comparison.json (reference wall time " +
                 Num(OptNumber(c, "reference.wall_s", file), 3) +
                 " s). Errors are taken at the engine's sample times against the reference's "
                 "dense output; the agreement horizon is the first time the error exceeds the "
                 "tolerance. Impacts slower than " +
                 Num(OptNumber(c, "impact_min_rate_radps", file)) +
                 " rad/s are not compared. Wall times are those of the run, not of the report.");
}

// The error figure's panel of block `block`: errors of every engine, the reference ensemble's
// spread, the local tolerance the pointwise check applies, the whole-run tolerance the
// predictability horizon uses, the engines' agreement horizons and the predictability horizon.
std::string ErrorPanel(const RunData& run, int block) {
  std::string s =
      "set ylabel " +
      Quote("|θ_" + std::to_string(block) + " - θ_" + std::to_string(block) + "^{ref}| (rad)") +
      "\nset title " + Quote(BlockTitle(block, run.scene.block_count())) +
      "\nunset arrow\nunset label\n" + HorizonMark(run, block, 0.97);
  std::string plot = "plot ";
  double tol =
      run.predictability && block <= static_cast<int>(run.predictability->tolerance_rad.size())
          ? run.predictability->tolerance_rad[block - 1]
          : kNaN;
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    const std::string key = "engines." + e.name + ".theta" + std::to_string(block);
    if (run.comparison && Find(*run.comparison, key) != nullptr) {
      tol = OptNumber(*run.comparison, key + ".tolerance_rad", run.comparison_path);
      if (!OptBool(*run.comparison, key + ".within_tolerance", run.comparison_path)) {
        const double h = OptNumber(*run.comparison, key + ".horizon_s", run.comparison_path);
        s += VerticalMark(h, run.t_end_s, e.colour,
                          "agreement horizon (" + e.name + ") " + Num(h, 4) + " s",
                          0.9 - 0.07 * static_cast<double>(i - 1));
      }
    }
    if (i > 1) plot += ", ";
    plot += Quote("angle_error." + e.name + ".dat") + " using 1:" + std::to_string(1 + block) +
            " with lines lw 1.4 lc rgb " + Quote(e.colour) + " title " + Quote(e.label);
  }
  if (run.band) {
    plot += ", " + Quote("angle_error.ensemble_spread.dat") +
            " using 1:" + std::to_string(1 + block) + " with lines lw 1.2 lc rgb " +
            Quote(kHorizonColour) + " dt 3 title " + Quote("spread of the " + BandTitle(run));
  }
  // The local tolerance on the output grid.
  plot += ", " + Quote("angle_error.tolerance.dat") + " using 1:" + std::to_string(1 + block) +
          " with lines dt 2 lw 1.5 lc rgb '#b00000' title " + Quote("local tolerance");
  // The whole run's scale: what the predictability horizon compares the members' spread with.
  if (run.band && !std::isnan(tol)) {
    plot += ", " + Num(tol, 9) + " with lines dt 3 lw 1 lc rgb '#b00000' title " +
            Quote("whole-run tolerance " + Num(tol, 3) + " rad (predictability horizon)");
  }
  return s + plot + "\n";
}

std::string ErrorCaption(const RunData& run, const RunReportOptions& options) {
  std::string caption =
      "Angle error |theta_engine - theta_reference| against time (rad, log scale), at the "
      "engine's sample times, the reference interpolated between its samples with its rates "
      "(cubic Hermite, pre-impact rates before each impact). Dashed red: the local tolerance, " +
      ToleranceRuleText() +
      " (the scene's [compare] tolerance, a constant, when it sets one); an error above it where "
      "the reference is predictable decides DIFFERS. Dashed vertical lines in an engine's "
      "colour: its agreement horizon, the first time its error exceeds the local tolerance (none "
      "when it stays within).";
  if (run.band) {
    caption +=
        " Dotted blue: the reference ensemble's spread, the largest |member - nominal| at each "
        "time (reference/ensemble_band.csv); dotted red: the whole run's tolerance (the rule at "
        "the reference's peak), which the predictability horizon compares that spread with.";
  }
  if (AnyHorizonMark(run)) {
    caption +=
        " Dashed blue vertical line: the predictability horizon, where that spread first "
        "exceeds the whole-run tolerance; beyond it two correct runs differ by more than it.";
  } else if (run.predictability) {
    caption += " The reference is predictable for the whole run: no predictability horizon.";
  }
  return caption + " Errors below " + Num(options.error_floor_rad) + " rad are drawn at " +
         Num(options.error_floor_rad) + " rad.";
}

void ErrorFigure(const RunData& run, const RunReportOptions& options, Figures& fig) {
  const EngineData& ref = run.engines.front();
  const HistoryInterpolator interp(ref.history, ref.events);
  const int nb = run.scene.block_count();
  // "# t_s <stem>theta1<tail> ... <stem>thetaN<tail>\n"
  const auto header = [nb](const char* stem, const char* tail) {
    std::string h = "# t_s";
    for (int b = 1; b <= nb; ++b)
      h.append(" ").append(stem).append(BodyColumn("theta", b)).append(tail);
    return h + "\n";
  };
  GnuplotFigure f;
  f.name = "angle_error";
  f.height_px = PanelsHeight_px(nb);
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    const EngineErrors err = AngleErrors(run, e, interp);
    std::string dat = header("err_", "_rad");
    for (size_t k = 0; k < err.t.size(); ++k) {
      AppendDat(dat, err.t[k]);
      for (int b = 0; b < nb; ++b) {
        dat += ' ';
        AppendDat(dat, std::max(err.e[b][k], options.error_floor_rad));
      }
      dat += '\n';
    }
    f.data_files.push_back({"angle_error." + e.name + ".dat", dat});
  }
  if (run.band) {
    const EnsembleBand& b = *run.band;
    std::vector<const std::vector<double>*> columns;
    for (int k = 0; k < nb; ++k) columns.push_back(&b.spread_rad[k]);
    f.data_files.push_back(
        {"angle_error.ensemble_spread.dat",
         BandDat(run, header("", "_spread_rad"), columns, options.error_floor_rad)});
  }
  // The local tolerance of each block from the reference's history, as compare computed it.
  {
    std::vector<ToleranceProfile> p;
    for (int b = 1; b <= nb; ++b) p.push_back(LocalTolerance(run.scene, b, ref.history));
    std::string dat = header("tol_", "_rad");
    // On the profile's grid; a constant ([compare] tolerance) at the two ends of the run.
    std::vector<double> times = {0.0, run.t_end_s};
    if (p[0].tol_rad.size() >= 2) {
      times.resize(p[0].tol_rad.size());
      for (size_t k = 0; k < times.size(); ++k) times[k] = static_cast<double>(k) * p[0].grid_dt_s;
    }
    for (const double t : times) {
      AppendDat(dat, t);
      for (int b = 0; b < nb; ++b) {
        dat += ' ';
        AppendDat(dat, p[b].At(t));
      }
      dat += '\n';
    }
    f.data_files.push_back({"angle_error.tolerance.dat", dat});
  }
  f.script = CommonAxes(run.t_end_s) +
             "set logscale y\nset format y '10^{%L}'\nset key bottom right box opaque\n";
  if (nb >= 2) {
    f.script += "set multiplot layout " + std::to_string(nb) + ",1\n";
    for (int b = 1; b <= nb; ++b) f.script += ErrorPanel(run, b);
    f.script += "unset multiplot\n";
  } else {
    f.script += ErrorPanel(run, 1);
  }
  fig.Add(f, ErrorCaption(run, options));
}

}  // namespace

void AgreementSection(const RunData& run, const RunReportOptions& options, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Agreement with the reference");
  if (run.engines.size() < 2) {
    page.Paragraph(
        "No engine was compared with the reference model in this run folder (a "
        "`rockbench run` folder): there is no error figure or metrics table. "
        "`rockbench compare SCENE --out DIR` runs the engines and compares them.");
    return;
  }
  if (run.comparison) {
    MetricsTable(run, page);
  } else {
    page.Paragraph(
        "This run folder has no comparison.json (engines run with `rockbench run`): "
        "the metrics table and the agreement horizons are left out; the error figure "
        "below is computed from the histories.");
  }
  ErrorFigure(run, options, fig);
}

}  // namespace rockbench::report
