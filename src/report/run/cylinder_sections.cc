#include "report/run/cylinder_sections.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>

#include "report/common/json_keys.h"
#include "report/common/number_text.h"
#include "report/run/outcome_section.h"
#include "report/run/scene_section.h"
#include "run/engine_registry.h"
#include "scene/body_kind.h"
#include "scene/cylinder_state.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

using nlohmann::json;

// A quantity of body 1 of a run's history, every sample.
std::vector<double> Column(const EngineData& e, const char* stem) {
  const StateQuantityReader q(e.history, stem);
  std::vector<double> v;
  v.reserve(e.history.samples.size());
  for (const Sample& s : e.history.samples) v.push_back(q(s, 1));
  return v;
}

// The data file of a run's history: the header line, then a row a sample: its time and each
// of `columns` (one value a sample).
std::string HistoryDat(const EngineData& e, const std::string& header,
                       std::initializer_list<const std::vector<double>*> columns) {
  std::string dat = header + "\n";
  for (size_t k = 0; k < e.history.samples.size(); ++k) {
    AppendDat(dat, e.history.samples[k].t_s);
    for (const std::vector<double>* c : columns) {
      dat += ' ';
      AppendDat(dat, (*c)[k]);
    }
    dat += '\n';
  }
  return dat;
}

// A run's overturn (summary.json "overturn"): its time and azimuth, NaN when it did not.
struct Overturn {
  double t_s = kNaN;
  double azimuth_rad = kNaN;
};
Overturn OverturnOf(const RunData& run, const EngineData& e) {
  Overturn o;
  const json* j = Find(e.summary, "overturn");
  if (j == nullptr || !j->is_object()) return o;
  o.t_s = OptNumber(*j, "t_s", run.summary_path);
  o.azimuth_rad = OptNumber(*j, "azimuth_rad", run.summary_path);
  return o;
}

// "overturned at t = 1.1207 s toward azimuth 2.195 rad".
std::string OverturnText(const Overturn& o) {
  std::string s = "overturned at t = " + Fixed(o.t_s, 4) + " s";
  if (!std::isnan(o.azimuth_rad)) s += " toward azimuth " + Num(o.azimuth_rad, 4) + " rad";
  return s;
}

// "0.06646 rad at 2.655 s" from summary.json's peaks.tilt1; empty without it.
std::string PeakText(const RunData& run, const EngineData& e) {
  const double peak = OptNumber(e.summary, "peaks.tilt1.abs_rad", run.summary_path);
  const double t = OptNumber(e.summary, "peaks.tilt1.t_s", run.summary_path);
  if (std::isnan(peak)) return "";
  return Num(peak, 4) + " rad" + (std::isnan(t) ? "" : " at " + Fixed(t, 3) + " s");
}

// The monitor's measures of an engine's cylinder, in words.
std::string MonitorText(const EngineData& e) {
  const json* m = Find(e.summary, "monitor");
  if (m == nullptr || !m->is_object()) return "";
  std::string out;
  const auto mm = [&](const char* key, const char* words) {
    if (!m->contains(key) || !(*m)[key].is_number()) return;
    out += (out.empty() ? "" : ", ") + std::string(words) + " " +
           Num(1e3 * (*m)[key].get<double>(), 3) + " mm";
  };
  mm("slip_m", "rim slip");
  mm("max_uplift_m", "uplift");
  mm("max_penetration_m", "penetration");
  return out;
}

// The three components' rows: source, format and PGA as read.
std::vector<std::vector<std::string>> ComponentRows(const GroundMotion& motion) {
  std::vector<std::vector<std::string>> rows;
  const std::pair<const std::optional<MotionComponent>*, const char*> parts[] = {
      {&motion.horizontal(), "horizontal (+x)"},
      {&motion.transverse(), "transverse (+y)"},
      {&motion.vertical(), "vertical (+z)"}};
  for (const auto& [c, name] : parts) {
    if (!*c) continue;
    const MotionInfo& i = (*c)->info();
    rows.push_back(
        {name, i.source, i.format, Num(i.peak_g, 4) + " g at " + Fixed(i.peak_t_s, 3) + " s",
         i.npts > 0 ? std::to_string(i.npts) + " at " + Num(i.dt_s) + " s" : "analytic"});
  }
  return rows;
}

// The three accelerations against time (g): record samples, breakpoints (both sides) and a fine
// grid.
void CylinderBaseFigure(const GroundMotion& motion, double T, Figures& fig) {
  const double g = kStandardGravity_mps2;
  std::set<double> times = {0.0, T};
  for (int k = 0; k <= 4000; ++k) times.insert(T * k / 4000.0);
  AddMotionPlotTimes(motion, T, {&motion.horizontal(), &motion.transverse(), &motion.vertical()},
                     times);
  std::string dat = "# t_s xg_g yg_transverse_g zg_vertical_g\n";
  for (double t : times) {
    AppendDat(dat, t);
    for (double a : {motion.xg_mps2(t), motion.transverse_mps2(t), motion.yg_mps2(t)}) {
      dat += ' ';
      AppendDat(dat, a / g);
    }
    dat += '\n';
  }
  GnuplotFigure f = BaseMotionFigure(dat, T);
  std::string plot = "plot ";
  std::string sep;
  if (motion.horizontal()) {
    plot += "'base_motion.dat' using 1:2 with lines lw 1.2 lc rgb '#1f4e9a' title " +
            Quote("horizontal along +x");
    sep = ", ";
  }
  if (motion.transverse()) {
    plot += sep + "'base_motion.dat' using 1:3 with lines lw 1.2 lc rgb '#1b9e77' title " +
            Quote("transverse along +y");
    sep = ", ";
  }
  if (motion.vertical()) {
    plot += sep + "'base_motion.dat' using 1:4 with lines lw 1.2 lc rgb '#c04000' title " +
            Quote("vertical (+z up)");
  }
  f.script += plot + "\n";
  fig.Add(f, "Base acceleration against time (g): each component the scene gives.");
}

}  // namespace

std::string CylinderOutcome(const RunData& run, std::vector<std::string>& warnings) {
  const EngineData& ref = run.engines.front();
  const std::string status = OptString(run.summary, "status", run.summary_path);
  std::string outcome;
  const Overturn o = OverturnOf(run, ref);
  if (status == "overturned" && !std::isnan(o.t_s)) {
    outcome = "The reference model: the cylinder " + OverturnText(o) + ".";
  } else if (status == "at_rest") {
    outcome = "The reference model: the cylinder came to rest (run to " +
              Fixed(ref.history.samples.back().t_s, 3) + " s).";
  } else if (status == "assumption_violated") {
    outcome = AssumptionViolatedOutcome(run, warnings);
  } else if (status == "non_finite") {
    outcome = "The reference model FAILED: its solution stopped being finite.";
    warnings.push_back("The reference model's solution is not finite: " +
                       OptString(run.summary, "status_detail", run.summary_path) + ".");
  } else {
    outcome = "The reference model ran to t = " + Fixed(ref.history.samples.back().t_s, 3) +
              " s (" + status + ").";
  }
  const std::string peak = PeakText(run, ref);
  if (!peak.empty()) outcome += " Peak tilt " + peak + ".";
  const double landings = OptNumber(run.summary, "impacts.ground", run.summary_path);
  if (!std::isnan(landings)) outcome += " Landings of its face: " + Num(landings) + ".";
  if (run.engines.size() == 1) return outcome + " No engine was run with it.";
  outcome += " Engines:";
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    std::string line = e.name + ": " + e.summary.value("status", std::string("unknown"));
    const std::string p = PeakText(run, e);
    if (!p.empty()) line += ", peak tilt " + p;
    const Overturn eo = OverturnOf(run, e);
    if (!std::isnan(eo.t_s)) line += ", " + OverturnText(eo);
    outcome += (i == 1 ? " " : "; ") + line;
    // The monitor's significant flags: what the engine did that the reference's cylinder
    // cannot (slide on a rim without a friction coefficient, lift off, sink in).
    const json* flags = Find(e.summary, "significant_violations");
    if (flags != nullptr && flags->is_array() && !flags->empty()) {
      std::string names;
      for (const json& f : *flags) {
        names += (names.empty() ? "" : ", ") + (f.is_string() ? f.get<std::string>() : f.dump());
      }
      const std::string measures = MonitorText(e);
      warnings.push_back("The " + e.name + " run was flagged: " + names +
                         (measures.empty() ? std::string() : " (" + measures + ")") +
                         (std::isfinite(run.scene.blocks.front().friction)
                              ? std::string(".")
                              : ". The scene gives no friction coefficient: the reference's "
                                "cylinder rolls on its rim without slipping."));
    }
  }
  return outcome + ".";
}

void CylinderSceneSection(const RunData& run, const GroundMotion& motion, Figures& fig) {
  Page& page = *fig.page;
  const Scene& s = run.scene;
  SceneFileHeading(run, page);
  const BlockDef& b = s.blocks.front();
  const double critical = std::atan2(b.diameter_m, b.height_m);
  const std::string friction = std::isfinite(b.friction) ? "rim friction " + Num(b.friction)
                                                         : "no slip on the rim (friction infinite)";
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"cylinder",
                  "diameter " + Num(b.diameter_m) + " m, height " + Num(b.height_m) + " m, " +
                      Num(b.mass_kg, 6) + " kg, " + friction,
                  "D/H = " + Num(b.diameter_m / b.height_m) +
                      ", critical angle atan(D/H) = " + Num(critical) + " rad"});
  const InitialState& i = s.initial;
  rows.push_back({"initial state",
                  "tilt " + Num(i.tilt_rad[0]) + " rad toward azimuth " + Num(i.azimuth_rad[0]) +
                      " rad; rates: tilt " + Num(i.tilt_rate_radps[0]) + ", azimuth " +
                      Num(i.azimuth_rate_radps[0]) + ", spin " + Num(i.spin_rate_radps[0]) +
                      " rad/s",
                  "azimuth: the direction the top leans toward, from +x toward +y"});
  rows.push_back({"landing", "clearance " + Num(s.model.landing_clearance_rel) + " of the diameter",
                  "a pass near upright lands its face below tilt asin(" +
                      Num(s.model.landing_clearance_rel) + ") (docs/three-d.md)"});
  rows.push_back(RunSettingsRow(s));
  page.Table({"part", "value", "note"}, rows);

  page.Heading("Base motion", 3);
  if (motion.empty()) {
    page.Paragraph("No base motion: the cylinder moves freely from its initial state.");
  } else {
    page.Table({"component", "source", "format", "peak acceleration (PGA)", "samples"},
               ComponentRows(motion));
    CylinderBaseFigure(motion, s.run.duration_s, fig);
  }

  const ModelConfig& m = s.model;
  EngineSettingsTable(run,
                      std::string(IntegratorName(m.integrator)) + ", rtol " + Num(m.rtol) +
                          ", atol " + Num(m.atol) + "; rest rate " + Num(m.rest_rate_rel) +
                          " sqrt(g/R)",
                      page);
}

void CylinderTiltFigure(const RunData& run, Figures& fig) {
  GnuplotFigure f;
  f.name = "tilt";
  f.height_px = 420;
  std::string marks;
  double label_y = 0.08;
  for (const EngineData& e : run.engines) {
    const std::vector<double> tilt = Column(e, "tilt");
    f.data_files.push_back({"tilt." + e.name + ".dat", HistoryDat(e, "# t_s tilt1_rad", {&tilt})});
    const Overturn o = OverturnOf(run, e);
    if (!std::isnan(o.t_s)) {
      marks += VerticalMark(o.t_s, run.t_end_s, e.colour, "overturns (" + e.name + ")", label_y);
      label_y += 0.08;
    }
  }
  std::string plot = "plot ";
  for (size_t i = 0; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    plot += std::string(i > 0 ? ", " : "") + Quote("tilt." + e.name + ".dat") + " using 1:2" +
            RunLineStyle(i, e);
  }
  f.script = CommonAxes(run.t_end_s) + marks + "set ylabel " + Quote("tilt (rad)") + "\n" +
             "set yrange [0:*]\n" + plot + "\n";
  fig.Add(f, std::string("The tilt of the cylinder's axis from vertical against time (rad), the "
                         "reference model and every engine on shared axes") +
                 (marks.empty() ? "" : "; dashed vertical lines: overturning") + ".");
}

void CylinderAxisPathFigure(const RunData& run, Figures& fig) {
  GnuplotFigure f;
  f.name = "axis_path";
  f.width_px = 720;
  f.height_px = 720;
  double peak = 0.0;
  std::string points = "# tilt_x1_rad tilt_y1_rad run\n";
  std::string overturns = "# tilt_x1_rad tilt_y1_rad label\n";
  bool any_overturn = false;
  for (const EngineData& e : run.engines) {
    const std::vector<double> tx = Column(e, "tilt_x"), ty = Column(e, "tilt_y");
    for (size_t k = 0; k < tx.size(); ++k) {
      if (std::isfinite(tx[k]) && std::isfinite(ty[k]))
        peak = std::max(peak, std::hypot(tx[k], ty[k]));
    }
    f.data_files.push_back({"axis_path." + e.name + ".dat",
                            HistoryDat(e, "# t_s tilt_x1_rad tilt_y1_rad", {&tx, &ty})});
    // The overturn: where the path is at its time (the last sample at or before it).
    const Overturn o = OverturnOf(run, e);
    if (!std::isnan(o.t_s) && !tx.empty()) {
      size_t k = 0;
      while (k + 1 < tx.size() && e.history.samples[k + 1].t_s <= o.t_s) ++k;
      AppendDat(overturns, tx[k]);
      overturns += ' ';
      AppendDat(overturns, ty[k]);
      overturns += ' ' +
                   GnuplotDataString(IsReference(e.name)
                                         ? "reference overturns, t = " + Fixed(o.t_s, 3) +
                                               " s, azimuth " + Num(o.azimuth_rad, 4) + " rad"
                                         : "") +
                   '\n';
      any_overturn = true;
    }
  }
  // Symmetric, equal axes about upright, a little beyond the largest tilt.
  const double range = std::max(peak, 1e-6) * 1.1;
  const double critical =
      std::atan2(run.scene.blocks.front().diameter_m, run.scene.blocks.front().height_m);
  std::string s = "set grid lc rgb '#dddddd'\nset size ratio -1\n";
  s += "set xrange [" + Num(-range, 6) + ":" + Num(range, 6) + "]\nset yrange [" + Num(-range, 6) +
       ":" + Num(range, 6) + "]\n";
  s += "set xlabel " + Quote("tilt_x = tilt cos(azimuth) (rad), toward +x") + "\n";
  s += "set ylabel " + Quote("tilt_y = tilt sin(azimuth) (rad), toward +y") + "\n";
  s += "set key top right box opaque\n";
  s += "set arrow from " + Num(-range, 6) + ",0 to " + Num(range, 6) +
       ",0 nohead lc rgb '#999999' back\nset arrow from 0," + Num(-range, 6) + " to 0," +
       Num(range, 6) + " nohead lc rgb '#999999' back\n";
  if (critical < range) {
    s += "set object 1 circle at 0,0 size " + Num(critical, 9) +
         " fs empty border lc rgb '#888888' dt 2 back\n";
    s += "set label " + Quote("critical angle atan(D/H)") + " at " + Num(critical * 0.7071, 6) +
         "," + Num(critical * 0.7071, 6) + " offset 0.5,0.5 font ',9' tc rgb '#666666'\n";
  }
  std::string plot = "plot ";
  for (size_t i = 0; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    const std::string file = Quote("axis_path." + e.name + ".dat");
    plot += std::string(i > 0 ? ", " : "") + file + " using 2:3" + RunLineStyle(i, e);
    // The path's end.
    plot += ", " + file + " every ::" + std::to_string(e.history.samples.size() - 1) +
            " using 2:3 with points pt 7 ps 1.2 lc rgb " + Quote(e.colour) + " notitle";
  }
  if (any_overturn) {
    f.data_files.push_back({"axis_path.overturns.dat", overturns});
    plot +=
        ", 'axis_path.overturns.dat' using 1:2 with points pt 6 ps 2.5 lw 2 lc rgb "
        "'#b2182b' title 'overturn', '' using 1:2:3 with labels offset 1,-1 left font ',9' "
        "tc rgb '#b2182b' notitle";
  }
  f.script = s + plot + "\n";
  std::string caption =
      "The axis's path seen from above: the tilt vector tilt_y against tilt_x (rad, equal axes; "
      "its direction is the azimuth the top leans toward, its length the tilt), the reference "
      "model and every engine; a dot marks where each path ends";
  if (critical < range) caption += "; dashed circle: the critical angle atan(D/H)";
  if (any_overturn) caption += "; open circles: overturning, the reference's labelled";
  fig.Add(f, caption + ".");
}

void CylinderEventsSection(const RunData& run, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Events");
  // Each kind's words, in this order; any other kind goes last under its own name.
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"initiation", "onsets from rest"},
      {"ground_impact", "landings of the face"},
      {"rest", "rests"},
      {"overturn", "overturns"},
      {"assumption_violated", "assumptions violated"}};
  std::vector<std::vector<std::string>> rows;
  for (const EngineData& e : run.engines) {
    std::map<std::string, int> count;
    for (const Event& ev : e.events) ++count[ev.kind];
    std::string text;
    for (const auto& [kind, words] : kinds) {
      const auto it = count.find(kind);
      if (it == count.end()) continue;
      text += (text.empty() ? "" : ", ") + std::to_string(it->second) + " " + words;
      count.erase(it);
    }
    for (const auto& [kind, n] : count) {
      text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
    }
    std::string first;
    if (!e.events.empty()) {
      first = e.events.front().kind + " at t = " + Fixed(e.events.front().t_s, 4) + " s";
    }
    rows.push_back({e.name, text.empty() ? "none" : text, first});
  }
  page.Table({"run", "events (events.csv)", "first"}, rows);
  const double passes = OptNumber(run.summary, "landing.passes_near_upright", run.summary_path);
  if (!std::isnan(passes)) {
    page.Paragraph(
        "The reference's passes near upright that turned above the landing tilt "
        "(rolling round the rim without landing): " +
        Num(passes) + ".");
  }
}

}  // namespace rockbench::report
