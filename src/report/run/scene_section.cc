#include "report/run/scene_section.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "reference/catalogue.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"
#include "run/engine_registry.h"
#include "scene/body_kind.h"
#include "scene/rigid_block.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

using nlohmann::json;

std::string BlockDescription(const BlockDef& b, int k) {
  // Block k's friction on its support (k = 0: the ground): the scene's key, or none (infinite:
  // the block cannot slide, the thesis's assumption).
  const std::string support = k == 0 ? "the ground" : "block " + std::to_string(k);
  const std::string friction = std::isfinite(b.friction)
                                   ? "friction " + Num(b.friction) + " on " + support
                                   : "no sliding on " + support + " (friction infinite)";
  return Num(b.width_m) + " m wide, " + Num(b.height_m) + " m high, " + Num(b.depth_m) +
         " m deep, " + Num(b.mass_kg, 6) + " kg, " + friction;
}

// PGA, PGV and PGD of each component: PGV and PGD by trapezoidal integration over the simulated
// time T (no baseline correction). One table row per component.
std::vector<std::vector<std::string>> PeakMotionRows(const GroundMotion& motion, double T) {
  // Integration grid: 1 ms, or the record's interval when finer.
  double step = 1e-3;
  for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
    if (*c && (*c)->dt_s() > 0.0) step = std::min(step, (*c)->dt_s());
  }
  const long n = std::max(1L, static_cast<long>(std::ceil(T / step)));
  std::vector<std::vector<std::string>> rows;
  for (int comp = 0; comp < 2; ++comp) {
    const auto& c = comp == 0 ? motion.horizontal() : motion.vertical();
    if (!c) continue;
    double v = 0.0, d = 0.0, pgv = 0.0, pgv_t = 0.0, pgd = 0.0, pgd_t = 0.0;
    double a_prev = c->accel_mps2(0.0);
    for (long k = 1; k <= n; ++k) {
      const double t = std::min(T, k * step);
      const double dt = t - std::min(T, (k - 1) * step);
      const double a = c->accel_mps2(t);
      const double v_new = v + 0.5 * dt * (a_prev + a);
      d += 0.5 * dt * (v + v_new);
      v = v_new;
      a_prev = a;
      if (std::abs(v) > pgv) pgv = std::abs(v), pgv_t = t;
      if (std::abs(d) > pgd) pgd = std::abs(d), pgd_t = t;
    }
    const MotionInfo& i = c->info();
    rows.push_back({comp == 0 ? "horizontal" : "vertical", i.source, i.format,
                    Num(i.peak_g, 4) + " g at " + Fixed(i.peak_t_s, 3) + " s",
                    Num(pgv, 4) + " m/s at " + Fixed(pgv_t, 3) + " s",
                    Num(pgd, 4) + " m at " + Fixed(pgd_t, 3) + " s",
                    i.npts > 0 ? std::to_string(i.npts) + " at " + Num(i.dt_s) + " s" : "analytic",
                    std::to_string(i.padded_samples)});
  }
  return rows;
}

// Plot times: record samples, analytic kinks and jumps (both sides), a fine grid where a
// component is analytic.
std::set<double> PlotTimes(const GroundMotion& motion, double T) {
  std::set<double> times = {0.0, T};
  AddMotionPlotTimes(motion, T, {&motion.horizontal(), &motion.vertical()}, times);
  for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
    if (*c && (*c)->samples_mps2().empty()) {
      for (int k = 0; k <= 2000; ++k) times.insert(T * k / 2000.0);
    }
  }
  return times;
}

// The base acceleration against time (g), both components.
void PlanarBaseMotionFigure(const GroundMotion& motion, double T, Figures& fig) {
  const double g = kStandardGravity_mps2;  // the plot is in g, as the records are
  const std::set<double> times = PlotTimes(motion, T);
  std::string dat = motion.has_vertical() ? "# t_s xg_g yg_g\n" : "# t_s xg_g\n";
  for (double t : times) {
    AppendDat(dat, t);
    dat += ' ';
    AppendDat(dat, motion.xg_mps2(t) / g);
    if (motion.has_vertical()) {
      dat += ' ';
      AppendDat(dat, motion.yg_mps2(t) / g);
    }
    dat += '\n';
  }
  GnuplotFigure f = BaseMotionFigure(dat, T);
  std::string plot = "plot 'base_motion.dat' using 1:2 with lines lw 1.2 lc rgb '#1f4e9a' title " +
                     Quote("horizontal x_g'' (positive to the right)");
  if (motion.has_vertical()) {
    plot += ", '' using 1:3 with lines lw 1.2 lc rgb '#c04000' title " +
            Quote("vertical y_g'' (positive up)");
  }
  f.script += plot + "\n";
  std::string caption = "Base acceleration against time (g).";
  if (motion.horizontal()) {
    caption += " Horizontal PGA " + Num(motion.horizontal()->info().peak_g) + " g at " +
               Fixed(motion.horizontal()->info().peak_t_s, 3) + " s.";
  }
  if (motion.vertical()) {
    caption += " Vertical peak " + Num(motion.vertical()->info().peak_g) + " g at " +
               Fixed(motion.vertical()->info().peak_t_s, 3) + " s.";
  }
  fig.Add(f, caption);
}

// Base motion: table rows and figure.
void BaseMotionSection(const RunData& run, const GroundMotion& motion, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Base motion", 3);
  const Scene& scene = run.scene;
  const double T = scene.run.duration_s;
  if (motion.empty()) {
    page.Paragraph("No base motion: the blocks rock freely from their initial state.");
    return;
  }
  const std::vector<std::vector<std::string>> rows = PeakMotionRows(motion, T);
  page.Table({"component", "source", "format", "peak acceleration (PGA)", "peak velocity (PGV)",
              "peak displacement (PGD)", "samples", "padded zeros"},
             rows);
  page.Paragraph(
      "PGA as read (after units and scale); PGV and PGD by trapezoidal integration "
      "of the acceleration over the simulated " +
      Num(T) + " s from rest, without baseline correction.");

  PlanarBaseMotionFigure(motion, T, fig);
}

}  // namespace

void SceneFileHeading(const RunData& run, Page& page) {
  page.Heading("Scene");
  std::string where = "Scene file " + run.scene.path.string();
  if (!run.overrides.empty()) {
    where += ", with";
    for (const std::string& o : run.overrides) where += " --set " + o;
  }
  page.Paragraph(where + ".");
}

std::vector<std::string> RunSettingsRow(const Scene& scene) {
  return {"run",
          "duration " + Num(scene.run.duration_s) + " s, output every " +
              Num(scene.run.output_interval_s) + " s",
          "gravity " + Num(scene.run.gravity_mps2) + " m/s^2"};
}

void EngineSettingsTable(const RunData& run, const std::string& reference, Page& page) {
  page.Heading("Engine settings", 3);
  std::vector<std::vector<std::string>> settings;
  settings.push_back({"reference", reference});
  // Each engine's settings as its summary.json states them (ours and the values they set).
  for (const EngineData& e : run.engines) {
    if (IsReference(e.name)) continue;
    const json* set = Find(e.summary, "settings");
    if (set == nullptr || !set->is_object()) continue;
    std::string text;
    for (const auto& [key, value] : set->items()) {
      text += (text.empty() ? "" : "; ") + key + " " +
              (value.is_string() ? value.get<std::string>()
                                 : (value.is_number() ? Num(value.get<double>()) : value.dump()));
    }
    settings.push_back({e.name, text});
  }
  page.Table({"engine", "settings"}, settings);
}

GnuplotFigure BaseMotionFigure(const std::string& dat, double T) {
  GnuplotFigure f;
  f.name = "base_motion";
  f.height_px = 420;
  f.data_files = {{"base_motion.dat", dat}};
  f.script = CommonAxes(T) + "set ylabel 'base acceleration (g)'\n";
  return f;
}

void AddMotionPlotTimes(const GroundMotion& motion, double T,
                        std::initializer_list<const std::optional<MotionComponent>*> components,
                        std::set<double>& times) {
  for (const auto* c : components) {
    if (!*c) continue;
    const auto& samples = (*c)->samples_mps2();
    for (size_t k = 0; k < samples.size(); ++k) {
      const double t = (*c)->t0_s() + static_cast<double>(k) * (*c)->dt_s();
      if (t >= 0.0 && t <= T) times.insert(t);
    }
  }
  for (double t = motion.next_breakpoint_after(-1e-9); t <= T;
       t = motion.next_breakpoint_after(t)) {
    if (t - 1e-9 > 0.0) times.insert(t - 1e-9);
    times.insert(t);
  }
}

void SceneSection(const RunData& run, const GroundMotion& motion, Figures& fig) {
  Page& page = *fig.page;
  const Scene& s = run.scene;
  SceneFileHeading(run, page);
  std::vector<std::vector<std::string>> rows;
  const int nb = s.block_count();
  if (nb <= 2) {
    const BlockDef& b1 = s.blocks.at(0);
    rows.push_back({"block 1 (lower)", BlockDescription(b1, 0),
                    "H/B = " + Num(b1.height_m / b1.width_m) + ", slenderness " +
                        Num(MakeBlockProps(b1.width_m, b1.height_m, b1.mass_kg).theta_c) + " rad"});
    const bool two = nb == 2;
    if (two) {
      const BlockDef& b2 = s.blocks[1];
      rows.push_back({"block 2 (upper)", BlockDescription(b2, 1),
                      "H/B = " + Num(b2.height_m / b2.width_m) + ", slenderness " +
                          Num(MakeBlockProps(b2.width_m, b2.height_m, b2.mass_kg).theta_c) +
                          " rad"});
      rows.push_back({"stack", "mass " + Num(b1.mass_kg + b2.mass_kg, 6) + " kg",
                      "slenderness of the stack " + Num(reference::CriticalAngle_rad(s)) + " rad"});
    }
    rows.push_back({"initial state",
                    "theta1 = " + Num(s.initial.theta_rad[0]) +
                        " rad, omega1 = " + Num(s.initial.omega_radps[0]) + " rad/s" +
                        (two ? ", theta2 = " + Num(s.initial.theta_rad[1]) +
                                   " rad, omega2 = " + Num(s.initial.omega_radps[1]) + " rad/s"
                             : ""),
                    "theta > 0: tilted to the right"});
  } else {
    // N >= 3 blocks: one row per block, bottom first, then the stack and the initial state of
    // every block (one row per block: readable at 6 to 8 blocks).
    double mass_kg = 0.0, moment_kgm = 0.0, base_m = 0.0;
    for (int k = 0; k < nb; ++k) {
      const BlockDef& b = s.blocks[k];
      const BlockProps p = MakeBlockProps(b.width_m, b.height_m, b.mass_kg);
      const std::string name = "block " + std::to_string(k + 1) +
                               (k == 0        ? " (bottom)"
                                : k == nb - 1 ? " (top)"
                                              : "");
      rows.push_back(
          {name, BlockDescription(b, k),
           "H/B = " + Num(b.height_m / b.width_m) + ", slenderness " + Num(p.theta_c) + " rad"});
      mass_kg += b.mass_kg;
      moment_kgm += b.mass_kg * (base_m + 0.5 * b.height_m);
      base_m += b.height_m;
    }
    const double h_stack = moment_kgm / mass_kg;
    rows.push_back({"stack", "mass " + Num(mass_kg, 6) + " kg, " + std::to_string(nb) + " blocks",
                    "slenderness of the stack " +
                        Num(std::atan2(0.5 * s.blocks[0].width_m, h_stack)) + " rad"});
    for (int k = 0; k < nb; ++k) {
      rows.push_back({"initial state, block " + std::to_string(k + 1),
                      BodyColumn("theta", k + 1) + " = " + Num(s.initial.theta_rad[k]) + " rad, " +
                          BodyColumn("omega", k + 1) + " = " + Num(s.initial.omega_radps[k]) +
                          " rad/s",
                      k == 0 ? "theta > 0: tilted to the right" : ""});
    }
  }
  rows.push_back(RunSettingsRow(s));
  page.Table({"part", "value", "note"}, rows);
  BaseMotionSection(run, motion, fig);

  const ModelConfig& m = s.model;
  EngineSettingsTable(
      run,
      std::string(IntegratorName(m.integrator)) +
          (m.integrator == Integrator::kRk4 ? ", step " + Num(m.step_s) + " s"
                                            : ", rtol " + Num(m.rtol) + ", atol " + Num(m.atol)) +
          "; events " + (m.events == EventScheme::kLocated ? "located" : "thesis") +
          "; equations " + (m.equations == Equations::kNonlinear ? "nonlinear" : "linearized") +
          "; transitions " + (m.check_transitions ? "checked" : "not checked") + "; rest rate " +
          Num(m.rest_rate_rel) + " sqrt(g/R)" +
          (OptString(run.summary, "convergence.used", run.summary_path) == "witness"
               ? " (not converged: the run used its witness, see Verdict)"
               : ""),
      page);
}

}  // namespace rockbench::report
