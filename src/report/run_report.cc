#include "report/run_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>

#include "reference/kinematics.h"
#include "reference/modes.h"
#include "renders/animation.h"
#include "renders/geometry.h"
#include "renders/gl_context.h"
#include "renders/renderer.h"
#include "report/gnuplot.h"
#include "report/json_keys.h"
#include "report/number_text.h"
#include "report/page.h"
#include "report/predictability.h"
#include "report/verdict_section.h"
#include "scene/ground_motion.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Line colours of the engines after the reference (black): distinct in hue and in greyscale.
constexpr const char* kEngineColours[] = {"#d95f02", "#1b9e77", "#7570b3", "#e7298a", "#66a61e"};

// Data-file numbers: enough digits to redraw exactly, "NaN" for a gap gnuplot understands.
void AppendDat(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "NaN";
    return;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  out += buf;
}

// ---- The run folder ----

struct EngineData {
  std::string name;
  History history;
  std::vector<Event> events;
  json summary;  // the engine's part of summary.json (the reference: the whole summary)
  std::string colour;
  std::string label;  // legend text
};

struct RunData {
  fs::path dir;
  fs::path summary_path, comparison_path;
  json summary;
  std::optional<json> comparison;
  Scene scene;
  std::vector<std::string> overrides;
  std::vector<EngineData> engines;  // the reference first
  double t_end_s = 0.0;             // the latest sample of any history
  // The reference ensemble (comparison.json "predictability"; reference/ensemble_band.csv):
  // nullopt when none was run.
  std::optional<Predictability> predictability;
  std::optional<EnsembleBand> band;
};

// The reference ensemble of a compare folder, when it has one.
void ReadReferenceEnsemble(RunData& run) {
  if (run.comparison) {
    run.predictability =
        ReadPredictability(*run.comparison, run.comparison_path, run.scene.two_blocks());
  }
  const fs::path csv = run.dir / "reference" / "ensemble_band.csv";
  run.band = ReadEnsembleBand(csv);
  if (run.band && run.band->two_blocks != run.scene.two_blocks()) {
    throw std::runtime_error(csv.string() + ": has " +
                             (run.band->two_blocks ? "two blocks" : "one block") +
                             " but the scene " + run.scene.path.string() + " has " +
                             (run.scene.two_blocks() ? "two" : "one"));
  }
}

RunData ReadRunFolder(const fs::path& run_dir) {
  RunData run;
  run.dir = run_dir;
  if (!fs::is_directory(run_dir)) {
    throw std::runtime_error(run_dir.string() +
                             ": not a folder (expected a run folder written by " +
                             "`rockbench run` or `rockbench compare`)");
  }
  run.summary_path = run_dir / "summary.json";
  if (!fs::exists(run.summary_path)) {
    throw std::runtime_error(run.summary_path.string() +
                             ": not found (a run folder from `rockbench run` or `rockbench "
                             "compare` has one)");
  }
  run.summary = ReadJson(run.summary_path);
  if (!run.summary.is_object()) {
    throw std::runtime_error(run.summary_path.string() + ": expected a JSON object");
  }
  const std::string scene_path = OptString(run.summary, "scene.path", run.summary_path);
  if (scene_path.empty()) {
    throw std::runtime_error(run.summary_path.string() +
                             ": key 'scene.path' is missing (the scene file the run used)");
  }
  if (const json* o = Find(run.summary, "scene.overrides"); o != nullptr && !o->is_null()) {
    if (!o->is_array()) {
      throw std::runtime_error(run.summary_path.string() +
                               ": key 'scene.overrides' must be a list of \"key=value\" strings");
    }
    for (const json& v : *o) {
      if (!v.is_string()) {
        throw std::runtime_error(run.summary_path.string() +
                                 ": key 'scene.overrides' must be a list of strings, found " +
                                 v.dump());
      }
      run.overrides.push_back(v.get<std::string>());
    }
  }
  if (!fs::exists(scene_path)) {
    throw std::runtime_error("the scene file " + scene_path + " (scene.path in " +
                             run.summary_path.string() +
                             ") is gone: the report reloads it for the geometry, base motion "
                             "and friction");
  }
  run.scene = LoadScene(scene_path, run.overrides);

  run.comparison_path = run_dir / "comparison.json";
  if (fs::exists(run.comparison_path)) run.comparison = ReadJson(run.comparison_path);
  ReadReferenceEnsemble(run);

  // Engines: the reference, then those in summary.json's "engines" (sorted by name).
  std::vector<std::string> names;
  if (!fs::exists(run_dir / "reference" / "history.csv")) {
    throw std::runtime_error(
        (run_dir / "reference" / "history.csv").string() +
        ": not found; a report compares with the reference model, so the run "
        "folder needs it (`rockbench run SCENE` or `rockbench compare SCENE`)");
  }
  names.push_back("reference");
  if (const json* e = Find(run.summary, "engines"); e != nullptr && !e->is_null()) {
    if (!e->is_object()) {
      throw std::runtime_error(run.summary_path.string() + ": key 'engines' must be an object");
    }
    for (auto it = e->begin(); it != e->end(); ++it) {
      if (it.key() != "reference") names.push_back(it.key());
    }
  }
  int colour = 0;
  for (const std::string& name : names) {
    EngineData d;
    d.name = name;
    d.history = ReadHistoryCsv(run_dir / name / "history.csv");
    d.events = ReadEventsCsv(run_dir / name / "events.csv");
    if (d.history.samples.empty()) {
      throw std::runtime_error((run_dir / name / "history.csv").string() + ": has no samples");
    }
    if (d.history.two_blocks != run.scene.two_blocks()) {
      throw std::runtime_error((run_dir / name / "history.csv").string() + ": has " +
                               (d.history.two_blocks ? "two blocks" : "one block") +
                               " but the scene " + scene_path + " has " +
                               (run.scene.two_blocks() ? "two" : "one"));
    }
    if (name == "reference") {
      d.summary = run.summary;
      d.colour = "#000000";
      d.label = "reference model";
    } else {
      d.summary = run.summary["engines"][name];
      d.colour = kEngineColours[colour++ % std::size(kEngineColours)];
      d.label = name;
    }
    run.t_end_s = std::max(run.t_end_s, d.history.samples.back().t_s);
    run.engines.push_back(std::move(d));
  }
  return run;
}

// ---- Numbers for the figures ----

struct Span {
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0.0;
  void Add(double v) {
    if (v > 0.0 && std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  // Positive values spanning more than two decades get a log axis.
  bool Decades() const { return hi > 0.0 && lo < hi * 1e-2; }
};

std::string Quote(const std::string& s) {
  return GnuplotQuote(s);
}

// Vertical line at time t across the plot (arrow) with a label, both in front of filled areas.
// The label sits right of the line, or left of it in the last 40% of the axis (t_end_s); a
// `boxed` label is on a white box, readable over curves.
std::string VerticalMark(double t, double t_end_s, const std::string& colour,
                         const std::string& label, double label_y_graph = 0.95,
                         bool boxed = false) {
  const bool left = t > 0.6 * t_end_s;
  std::string s = "set arrow from " + Num(t, 9) + ", graph 0 to " + Num(t, 9) +
                  ", graph 1 nohead front dt 2 lw 1.5 lc rgb " + Quote(colour) + "\n";
  if (!label.empty()) {
    if (boxed) s += "set style textbox opaque noborder\n";
    s += "set label " + Quote(label) + " at " + Num(t, 9) + ", graph " + Num(label_y_graph) +
         (left ? " offset -0.5,0 right" : " offset 0.5,0 left") + (boxed ? " boxed" : "") +
         " front font ',10' tc rgb " + Quote(colour) + "\n";
  }
  return s;
}

std::string CommonAxes(double t_end_s) {
  return "set grid lc rgb '#dddddd'\nset xlabel 'time t (s)'\nset xrange [0:" + Num(t_end_s, 9) +
         "]\nset key top right box opaque\n";
}

// Overturn marks of every run for the angle figures.
std::string OverturnMarks(const RunData& run) {
  std::string s;
  double label_y = 0.08;  // bottom of the panel: the key is at the top right
  for (const EngineData& e : run.engines) {
    const json* o = Find(e.summary, "overturn");
    if (o == nullptr || !o->is_object()) continue;
    const double t = OptNumber(*o, "t_s", run.summary_path);
    const double block = OptNumber(*o, "block", run.summary_path);
    if (std::isnan(t)) continue;
    s += VerticalMark(t, run.t_end_s, e.colour,
                      "block " + (std::isnan(block) ? std::string("?") : Num(block)) +
                          " overturns (" + e.name + ")",
                      label_y);
    label_y += 0.08;
  }
  return s;
}

}  // namespace

// ---- Public physics helpers ----

Mode ModeFromAngles(const Sample& s, bool two_blocks) {
  using reference::Contact;
  const auto side = [](double angle, double rate) {
    if (angle > 0.0 || (angle == 0.0 && rate > 0.0)) return Contact::kRight;
    if (angle < 0.0 || (angle == 0.0 && rate < 0.0)) return Contact::kLeft;
    return Contact::kFace;
  };
  reference::Contacts c;
  c.ground = side(s.theta1_rad, s.omega1_radps);
  c.interface = two_blocks ? side(s.theta2_rad - s.theta1_rad, s.omega2_radps - s.omega1_radps)
                           : Contact::kFace;
  return reference::ModeOf(c, two_blocks);
}

namespace {
reference::State ToState(const Sample& s, bool two_blocks) {
  reference::State st;
  st.theta1 = s.theta1_rad;
  st.omega1 = s.omega1_radps;
  st.theta2 = two_blocks ? s.theta2_rad : s.theta1_rad;
  st.omega2 = two_blocks ? s.omega2_radps : s.omega1_radps;
  return st;
}
}  // namespace

double StateEnergy_j(const reference::Geometry& geo, const Sample& s) {
  return reference::Energy(geo, ModeFromAngles(s, geo.two_blocks), ToState(s, geo.two_blocks));
}

double EnergyAboveRest_j(const reference::Geometry& geo, const Sample& s) {
  return StateEnergy_j(geo, s) - reference::Energy(geo, Mode::kRest, reference::State{});
}

FrictionDemand RequiredFriction(const reference::Geometry& geo, Mode mode, const Sample& s,
                                double xg_mps2, double yg_mps2, Equations equations) {
  const reference::State st = ToState(s, geo.two_blocks);
  const auto acc = reference::ModeAccelerations(geo, mode, st, xg_mps2, yg_mps2, equations);
  const reference::Reactions r = reference::ComputeReactions(geo, mode, st, acc, xg_mps2, yg_mps2);
  FrictionDemand d;
  d.N_ground_n = r.N_ground;
  d.T_ground_n = r.T_ground;
  d.mu_ground = r.N_ground > 0.0 ? std::abs(r.T_ground) / r.N_ground : 0.0;
  if (geo.two_blocks) {
    d.N_interface_n = r.N_interface;
    d.T_interface_n = r.T_interface;
    d.mu_interface = r.N_interface > 0.0 ? std::abs(r.T_interface) / r.N_interface : 0.0;
  }
  return d;
}

HistoryInterpolator::HistoryInterpolator(const History& history, const std::vector<Event>& events) {
  // Pre-event rates by event time: the first event at a time holds the rates before them all.
  std::map<double, const Event*> first_event;
  for (const Event& e : events) first_event.emplace(e.t_s, &e);
  for (const Sample& s : history.samples) {
    const double th2 = history.two_blocks ? s.theta2_rad : s.theta1_rad;
    const double w2 = history.two_blocks ? s.omega2_radps : s.omega1_radps;
    if (!nodes_.empty() && s.t_s <= nodes_.back().t) {
      // Several samples at one instant (a cascade of events): keep the last state after it.
      Node& n = nodes_.back();
      n.theta[0] = s.theta1_rad;
      n.theta[1] = th2;
      n.rate_right[0] = s.omega1_radps;
      n.rate_right[1] = w2;
      continue;
    }
    Node n;
    n.t = s.t_s;
    n.theta[0] = s.theta1_rad;
    n.theta[1] = th2;
    n.rate_right[0] = n.rate_left[0] = s.omega1_radps;
    n.rate_right[1] = n.rate_left[1] = w2;
    if (const auto it = first_event.find(s.t_s); it != first_event.end()) {
      n.rate_left[0] = it->second->omega1_before;
      n.rate_left[1] = history.two_blocks ? it->second->omega2_before : it->second->omega1_before;
    }
    nodes_.push_back(n);
  }
  if (nodes_.empty()) throw std::invalid_argument("HistoryInterpolator: empty history");
}

std::array<double, 2> HistoryInterpolator::Angles(double t) const {
  if (t <= nodes_.front().t) return {nodes_.front().theta[0], nodes_.front().theta[1]};
  if (t >= nodes_.back().t) return {nodes_.back().theta[0], nodes_.back().theta[1]};
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t,
                                   [](double v, const Node& n) { return v < n.t; });
  const Node& b = *it;
  const Node& a = *(it - 1);
  const double h = b.t - a.t;
  const double s = (t - a.t) / h;
  const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
  const double h10 = s * (1.0 - s) * (1.0 - s);
  const double h01 = s * s * (3.0 - 2.0 * s);
  const double h11 = s * s * (s - 1.0);
  std::array<double, 2> out{};
  for (int k = 0; k < 2; ++k) {
    out[k] =
        h00 * a.theta[k] + h10 * h * a.rate_right[k] + h01 * b.theta[k] + h11 * h * b.rate_left[k];
  }
  return out;
}

double HistoryInterpolator::end_s() const {
  return nodes_.back().t;
}

// ---- The page ----

namespace {

struct Figures {
  fs::path page_dir;
  fs::path dir;  // page_dir / "figures"
  Page* page = nullptr;
  int count = 0;
  void Add(const GnuplotFigure& f, const std::string& caption) {
    RenderGnuplot(dir, f);
    page->Figure(fs::path("figures") / (f.name + ".svg"), caption);
    ++count;
  }
};

std::string BlockDescription(const BlockDef& b) {
  return Num(b.width_m) + " m wide, " + Num(b.height_m) + " m high, " + Num(b.depth_m) +
         " m deep, " + Num(b.mass_kg, 6) + " kg";
}

// Base motion: figure, table rows. PGV and PGD by trapezoidal integration over the simulated
// time (no baseline correction).
void BaseMotionSection(const RunData& run, const GroundMotion& motion, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Base motion", 3);
  const Scene& scene = run.scene;
  const double T = scene.run.duration_s;
  if (motion.empty()) {
    page.Paragraph("No base motion: the blocks rock freely from their initial state.");
    return;
  }
  const double g = kStandardGravity_mps2;  // the plot is in g, as the records are
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
  page.Table({"component", "source", "format", "peak acceleration (PGA)", "peak velocity (PGV)",
              "peak displacement (PGD)", "samples", "padded zeros"},
             rows);
  page.Paragraph(
      "PGA as read (after units and scale); PGV and PGD by trapezoidal integration "
      "of the acceleration over the simulated " +
      Num(T) + " s from rest, without baseline correction.");

  // Plot times: record samples, analytic kinks and jumps (both sides), a fine grid.
  std::set<double> times = {0.0, T};
  for (const auto* c : {&motion.horizontal(), &motion.vertical()}) {
    if (!*c) continue;
    const auto& samples = (*c)->samples_mps2();
    for (size_t k = 0; k < samples.size(); ++k) {
      const double t = (*c)->t0_s() + static_cast<double>(k) * (*c)->dt_s();
      if (t >= 0.0 && t <= T) times.insert(t);
    }
    if (samples.empty()) {
      for (int k = 0; k <= 2000; ++k) times.insert(T * k / 2000.0);
    }
  }
  for (double t = motion.next_breakpoint_after(-1e-9); t <= T;
       t = motion.next_breakpoint_after(t)) {
    if (t - 1e-9 > 0.0) times.insert(t - 1e-9);
    times.insert(t);
  }
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
  GnuplotFigure f;
  f.name = "base_motion";
  f.height_px = 420;
  f.data_files = {{"base_motion.dat", dat}};
  f.script = CommonAxes(T) + "set ylabel 'base acceleration (g)'\n";
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

void SceneSection(const RunData& run, const GroundMotion& motion, Figures& fig) {
  Page& page = *fig.page;
  const Scene& s = run.scene;
  const reference::Geometry geo = reference::MakeGeometry(s);
  page.Heading("Scene");
  std::string where = "Scene file " + s.path.string();
  if (!run.overrides.empty()) {
    where += ", with";
    for (const std::string& o : run.overrides) where += " --set " + o;
  }
  page.Paragraph(where + ".");
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"block 1 (lower)", BlockDescription(s.block1),
                  "H/B = " + Num(s.block1.height_m / s.block1.width_m) + ", slenderness " +
                      Num(geo.block1.theta_c) + " rad"});
  if (s.block2) {
    rows.push_back({"block 2 (upper)", BlockDescription(*s.block2),
                    "H/B = " + Num(s.block2->height_m / s.block2->width_m) + ", slenderness " +
                        Num(geo.block2.theta_c) + " rad"});
    rows.push_back({"stack", "mass " + Num(geo.M, 6) + " kg",
                    "slenderness of the stack " + Num(geo.theta_c) + " rad"});
  }
  rows.push_back({"initial state",
                  "theta1 = " + Num(s.initial.theta1_rad) +
                      " rad, omega1 = " + Num(s.initial.omega1_radps) + " rad/s" +
                      (s.block2 ? ", theta2 = " + Num(s.initial.theta2_rad) +
                                      " rad, omega2 = " + Num(s.initial.omega2_radps) + " rad/s"
                                : ""),
                  "theta > 0: tilted to the right"});
  rows.push_back({"run",
                  "duration " + Num(s.run.duration_s) + " s, output every " +
                      Num(s.run.output_interval_s) + " s",
                  "gravity " + Num(s.run.gravity_mps2) + " m/s^2"});
  page.Table({"part", "value", "note"}, rows);
  BaseMotionSection(run, motion, fig);

  page.Heading("Engine settings", 3);
  const ModelConfig& m = s.model;
  std::vector<std::vector<std::string>> settings;
  settings.push_back(
      {"reference", std::string(m.integrator == Integrator::kDopri5
                                    ? "dopri5, rtol " + Num(m.rtol) + ", atol " + Num(m.atol)
                                    : "rk4, step " + Num(m.step_s) + " s") +
                        "; events " + (m.events == EventScheme::kLocated ? "located" : "thesis") +
                        "; equations " +
                        (m.equations == Equations::kNonlinear ? "nonlinear" : "linearized") +
                        "; transitions " + (m.check_transitions ? "checked" : "not checked") +
                        "; rest rate " + Num(m.rest_rate_rel) + " sqrt(g/R)" +
                        (OptString(run.summary, "convergence.used", run.summary_path) == "witness"
                             ? " (not converged: the run used its witness, see Verdict)"
                             : "")});
  // Each engine's settings as its summary.json states them (ours and the values they set).
  for (const EngineData& e : run.engines) {
    if (e.name == "reference") continue;
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

// The reference ensemble: band fill and horizon lines (blue, apart from the engines' colours).
constexpr const char* kBandColour = "#c6dbef";
constexpr const char* kHorizonColour = "#2166ac";

// Vertical line at block `block`'s predictability horizon; none when the block is predictable
// for the whole run, no ensemble was run or the horizon is past the axis.
std::string HorizonMark(const RunData& run, int block, double label_y_graph) {
  if (!run.predictability) return "";
  const std::optional<double>& h = run.predictability->horizon_s[block - 1];
  if (!h || *h > run.t_end_s) return "";
  return VerticalMark(*h, run.t_end_s, kHorizonColour,
                      "predictability horizon " + Num(*h, 6) + " s", label_y_graph, true);
}

bool AnyHorizonMark(const RunData& run) {
  return !HorizonMark(run, 1, 0.5).empty() ||
         (run.scene.two_blocks() && !HorizonMark(run, 2, 0.5).empty());
}

// "t v1 v2 ..." rows of ensemble_band.csv's `columns` (each at least `floor`) up to the axis end,
// and one row past it so the drawing reaches the border.
std::string BandDat(const RunData& run, const std::string& header,
                    const std::vector<const std::vector<double>*>& columns, double floor) {
  std::string dat = header;
  const EnsembleBand& band = *run.band;
  for (size_t k = 0; k < band.t_s.size(); ++k) {
    AppendDat(dat, band.t_s[k]);
    for (const std::vector<double>* c : columns) {
      dat += ' ';
      AppendDat(dat, std::max((*c)[k], floor));
    }
    dat += '\n';
    if (band.t_s[k] >= run.t_end_s) break;
  }
  return dat;
}

std::string BandTitle(const RunData& run) {
  return run.predictability
             ? "reference ensemble (" + std::to_string(run.predictability->members) + " members)"
             : std::string("reference ensemble");
}

std::string AnglesCaption(const RunData& run) {
  std::string caption =
      "Block angles against time (rad; positive: tilted to the right), the reference model and "
      "every engine on shared axes";
  if (!OverturnMarks(run).empty()) caption += "; dashed vertical lines: overturning";
  if (run.band) {
    caption += "; shaded: the band " + BandTitle(run) +
               " and the nominal reference span (reference/ensemble_band.csv)";
  } else {
    caption += "; no reference ensemble was run, so there is no band";
  }
  if (AnyHorizonMark(run)) {
    caption += "; dashed blue vertical line: the block's predictability horizon";
  }
  return caption + ".";
}

// theta1 and theta2 against time, every run on shared axes, the reference ensemble's band behind.
void AnglesFigure(const RunData& run, Figures& fig) {
  const bool two = run.scene.two_blocks();
  GnuplotFigure f;
  f.name = "angles";
  f.height_px = two ? 720 : 420;
  for (const EngineData& e : run.engines) {
    std::string dat = two ? "# t_s theta1_rad theta2_rad\n" : "# t_s theta1_rad\n";
    for (const Sample& s : e.history.samples) {
      AppendDat(dat, s.t_s);
      dat += ' ';
      AppendDat(dat, s.theta1_rad);
      if (two) {
        dat += ' ';
        AppendDat(dat, s.theta2_rad);
      }
      dat += '\n';
    }
    f.data_files.push_back({"angles." + e.name + ".dat", dat});
  }
  if (run.band) {
    const EnsembleBand& b = *run.band;
    f.data_files.push_back(
        {"angles.band.dat",
         two ? BandDat(run, "# t_s theta1_lo_rad theta1_hi_rad theta2_lo_rad theta2_hi_rad\n",
                       {&b.lo_rad[0], &b.hi_rad[0], &b.lo_rad[1], &b.hi_rad[1]}, -kInf)
             : BandDat(run, "# t_s theta1_lo_rad theta1_hi_rad\n", {&b.lo_rad[0], &b.hi_rad[0]},
                       -kInf)});
  }
  const auto panel = [&](int block) {
    std::string s = "unset arrow\nunset label\n" + OverturnMarks(run) +
                    HorizonMark(run, block, 0.62) + "set ylabel " +
                    Quote("θ_" + std::to_string(block) + " (rad)") + "\n";
    s += "set title " + Quote(block == 1 ? "block 1 (lower)" : "block 2 (upper)") + "\n";
    std::string plot = "plot ";
    if (run.band) {
      plot += Quote("angles.band.dat") + " using 1:" + std::to_string(2 * block) + ":" +
              std::to_string(2 * block + 1) + " with filledcurves fc rgb " + Quote(kBandColour) +
              " fs solid 1.0 noborder title " + Quote(BandTitle(run)) + ", ";
    }
    for (size_t i = 0; i < run.engines.size(); ++i) {
      const EngineData& e = run.engines[i];
      if (i > 0) plot += ", ";
      plot += Quote("angles." + e.name + ".dat") + " using 1:" + std::to_string(1 + block) +
              " with lines lw " + (i == 0 ? "2.2" : "1.4") + (i == 0 ? "" : " dt 2") + " lc rgb " +
              Quote(e.colour) + " title " + Quote(e.label);
    }
    return s + plot + "\n";
  };
  f.script = CommonAxes(run.t_end_s);
  if (two) {
    f.script += "set multiplot layout 2,1\n" + panel(1) + panel(2) + "unset multiplot\n";
  } else {
    f.script += panel(1);
  }
  fig.Add(f, AnglesCaption(run));
}

struct EngineErrors {
  std::vector<double> t, e1, e2;
  double max1 = 0.0, max2 = 0.0;
};

EngineErrors AngleErrors(const RunData& run, const EngineData& e, const HistoryInterpolator& ref) {
  EngineErrors out;
  double until = ref.end_s();
  if (run.comparison) {
    const double c =
        OptNumber(*run.comparison, "engines." + e.name + ".compared_until_s", run.comparison_path);
    if (!std::isnan(c)) until = std::min(until, c);
  }
  for (const Sample& s : e.history.samples) {
    if (s.t_s > until + 1e-12) break;
    const auto a = ref.Angles(s.t_s);
    out.t.push_back(s.t_s);
    out.e1.push_back(std::abs(s.theta1_rad - a[0]));
    out.e2.push_back(run.scene.two_blocks() ? std::abs(s.theta2_rad - a[1]) : 0.0);
    out.max1 = std::max(out.max1, out.e1.back());
    out.max2 = std::max(out.max2, out.e2.back());
  }
  return out;
}

void MetricsTable(const RunData& run, Page& page) {
  const json& c = *run.comparison;
  const fs::path& file = run.comparison_path;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::vector<std::string>> impacts;
  for (const EngineData& e : run.engines) {
    if (e.name == "reference") continue;
    const std::string k = "engines." + e.name;
    if (Find(c, k) == nullptr) continue;
    for (int b = 1; b <= (run.scene.two_blocks() ? 2 : 1); ++b) {
      const std::string kb = k + ".theta" + std::to_string(b);
      const bool within = OptBool(c, kb + ".within_tolerance", file);
      rows.push_back({e.name, "theta" + std::to_string(b),
                      Num(NeedNumber(c, kb + ".max_abs_error_rad", file), 3),
                      Num(NeedNumber(c, kb + ".rms_error_rad", file), 3),
                      Num(OptNumber(c, kb + ".tolerance_rad", file), 3),
                      within ? "whole run (" + Num(NeedNumber(c, kb + ".horizon_s", file)) + " s)"
                             : Num(NeedNumber(c, kb + ".horizon_s", file), 5) + " s",
                      Num(100.0 * NeedNumber(c, kb + ".peak_rel_error", file), 3) + " %",
                      Num(1e3 * NeedNumber(c, kb + ".peak_time_error_s", file), 3) + " ms"});
    }
    const double matched = NeedNumber(c, k + ".impacts_matched", file);
    const double nref = OptNumber(c, k + ".impacts_reference", file);
    const double neng = OptNumber(c, k + ".impacts_engine", file);
    const std::string mismatch = Find(c, k + ".first_impact_mismatch") != nullptr &&
                                         Find(c, k + ".first_impact_mismatch")->is_string()
                                     ? Find(c, k + ".first_impact_mismatch")->get<std::string>()
                                     : "";
    impacts.push_back({e.name, Num(matched) + " of " + Num(nref) + " (engine: " + Num(neng) + ")",
                       Num(1e3 * OptNumber(c, k + ".max_abs_impact_time_error_s", file), 3) + " ms",
                       mismatch.empty() ? "none" : mismatch,
                       OptBool(c, k + ".overturn.agree", file) ? "agrees" : "DIFFERS",
                       OptBool(c, k + ".final.agree", file) ? "agrees" : "DIFFERS",
                       Num(NeedNumber(c, k + ".wall_s", file), 3) + " s"});
  }
  page.Table({"engine", "angle", "max error (rad)", "RMS error (rad)", "tolerance (rad)",
              "agreement horizon", "peak error", "peak time error"},
             rows);
  page.Table({"engine", "impacts matched", "max impact time error", "first mismatch", "overturning",
              "final state", "wall time"},
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
// spread, the comparison tolerance, the engines' agreement horizons and the predictability
// horizon.
std::string ErrorPanel(const RunData& run, int block) {
  std::string s =
      "set ylabel " +
      Quote("|θ_" + std::to_string(block) + " - θ_" + std::to_string(block) + "^{ref}| (rad)") +
      "\nset title " + Quote(block == 1 ? "block 1 (lower)" : "block 2 (upper)") +
      "\nunset arrow\nunset label\n" + HorizonMark(run, block, 0.97);
  std::string plot = "plot ";
  double tol = run.predictability ? run.predictability->tolerance_rad[block - 1] : kNaN;
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
  if (!std::isnan(tol)) {
    plot += ", " + Num(tol, 9) + " with lines dt 2 lw 1.5 lc rgb '#b00000' title " +
            Quote("comparison tolerance " + Num(tol, 3) + " rad");
  }
  return s + plot + "\n";
}

std::string ErrorCaption(const RunData& run, const RunReportOptions& options) {
  std::string caption =
      "Angle error |theta_engine - theta_reference| against time (rad, log scale), at the "
      "engine's sample times, the reference interpolated between its samples with its rates "
      "(cubic Hermite, pre-impact rates before each impact). Dashed red: the comparison "
      "tolerance; dashed vertical lines in an engine's colour: its agreement horizon (none when "
      "it stays within the tolerance).";
  if (run.band) {
    caption +=
        " Dotted blue: the reference ensemble's spread, the largest |member - nominal| at each "
        "time (reference/ensemble_band.csv).";
  }
  if (AnyHorizonMark(run)) {
    caption +=
        " Dashed blue vertical line: the predictability horizon, where that spread first "
        "exceeds the tolerance; beyond it two correct runs differ by more than the tolerance.";
  } else if (run.predictability) {
    caption += " The reference is predictable for the whole run: no predictability horizon.";
  }
  return caption + " Errors below " + Num(options.error_floor_rad) + " rad are drawn at " +
         Num(options.error_floor_rad) + " rad.";
}

void ErrorFigure(const RunData& run, const RunReportOptions& options, Figures& fig) {
  const EngineData& ref = run.engines.front();
  const HistoryInterpolator interp(ref.history, ref.events);
  const bool two = run.scene.two_blocks();
  GnuplotFigure f;
  f.name = "angle_error";
  f.height_px = two ? 720 : 420;
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    const EngineErrors err = AngleErrors(run, e, interp);
    std::string dat = two ? "# t_s err_theta1_rad err_theta2_rad\n" : "# t_s err_theta1_rad\n";
    for (size_t k = 0; k < err.t.size(); ++k) {
      AppendDat(dat, err.t[k]);
      dat += ' ';
      AppendDat(dat, std::max(err.e1[k], options.error_floor_rad));
      if (two) {
        dat += ' ';
        AppendDat(dat, std::max(err.e2[k], options.error_floor_rad));
      }
      dat += '\n';
    }
    f.data_files.push_back({"angle_error." + e.name + ".dat", dat});
  }
  if (run.band) {
    const EnsembleBand& b = *run.band;
    f.data_files.push_back(
        {"angle_error.ensemble_spread.dat",
         two ? BandDat(run, "# t_s theta1_spread_rad theta2_spread_rad\n",
                       {&b.spread_rad[0], &b.spread_rad[1]}, options.error_floor_rad)
             : BandDat(run, "# t_s theta1_spread_rad\n", {&b.spread_rad[0]},
                       options.error_floor_rad)});
  }
  f.script = CommonAxes(run.t_end_s) +
             "set logscale y\nset format y '10^{%L}'\nset key bottom right box opaque\n";
  if (two) {
    f.script += "set multiplot layout 2,1\n" + ErrorPanel(run, 1) + ErrorPanel(run, 2) +
                "unset multiplot\n";
  } else {
    f.script += ErrorPanel(run, 1);
  }
  fig.Add(f, ErrorCaption(run, options));
}

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

int EventCode(const std::string& kind) {
  if (kind == "ground_impact") return 1;
  if (kind == "interface_impact") return 2;
  if (kind == "transition" || kind == "initiation") return 3;
  if (kind == "overturn" || kind == "assumption_violated") return 4;
  return 0;  // rest and anything else: not drawn
}

void ImpactsSection(const RunData& run, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Impacts and mode changes");
  std::vector<std::vector<std::string>> rows;
  std::string dat =
      "# t_s row code (1 ground impact, 2 interface impact, 3 transition or "
      "initiation, 4 overturn or assumption violated)\n";
  std::set<int> codes;
  std::string ytics;
  for (size_t i = 0; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    int n[5] = {0, 0, 0, 0, 0};
    dat += "# " + e.name + "\n";
    for (const Event& ev : e.events) {
      const int code = EventCode(ev.kind);
      ++n[code];
      if (code == 0) continue;
      codes.insert(code);
      AppendDat(dat, ev.t_s);
      dat += ' ' + std::to_string(i) + ' ' + std::to_string(code) + '\n';
    }
    ytics += (i ? ", " : "") + Quote(e.name) + " " + std::to_string(i);
    rows.push_back({e.name, std::to_string(n[1]), std::to_string(n[2]), std::to_string(n[3]),
                    std::to_string(n[4])});
  }
  page.Table({"run", "ground impacts", "interface impacts", "transitions and initiations",
              "overturn or violation"},
             rows);
  if (codes.empty()) {
    page.Paragraph("No impact, transition or overturning in any run: no timeline.");
    return;
  }
  GnuplotFigure f;
  f.name = "impacts";
  f.height_px = 200 + 60 * static_cast<int>(run.engines.size());
  f.data_files = {{"impacts.dat", dat}};
  f.script = CommonAxes(run.t_end_s) + "set ytics (" + ytics + ")\nset yrange [" +
             Num(static_cast<double>(run.engines.size()) - 0.4) +
             ":-0.6]\nset key outside top center horizontal\nset grid noytics\n";
  static const char* kStyle[] = {"", "pt 7 ps 1.1 lc rgb '#1f4e9a'", "pt 5 ps 0.9 lc rgb '#d95f02'",
                                 "pt 2 ps 1.2 lc rgb '#444444'", "pt 9 ps 1.8 lc rgb '#b00000'"};
  static const char* kTitle[] = {
      "", "ground impact (block 1 lands)", "interface impact (block 2 lands on block 1)",
      "transition or initiation (no impact)", "overturn or assumption violated"};
  std::string plot = "plot ";
  bool first = true;
  for (int code : codes) {
    if (!first) plot += ", ";
    first = false;
    // Rows are slightly offset by kind so coincident markers stay visible.
    const double dy = code == 2 ? 0.15 : (code == 3 ? -0.15 : 0.0);
    plot += "'impacts.dat' using 1:($3==" + std::to_string(code) + " ? $2+" + Num(dy) +
            " : 1/0) with points " + kStyle[code] + " title " + Quote(kTitle[code]);
  }
  f.script += plot + "\n";
  fig.Add(f,
          "Impact timeline: one row per run, a marker per event (ground and interface "
          "impacts, mode changes without impact, overturning). Times from each run's "
          "events.csv.");
}

void EnergySection(const RunData& run, const reference::Geometry& geo, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Energy");
  GnuplotFigure f;
  f.name = "energy";
  f.height_px = 480;
  Span span;
  std::vector<std::vector<double>> values(run.engines.size());
  for (size_t i = 0; i < run.engines.size(); ++i) {
    for (const Sample& s : run.engines[i].history.samples) {
      values[i].push_back(EnergyAboveRest_j(geo, s));
      span.Add(values[i].back());
    }
  }
  // On a log axis, values a billion times below the largest (rest) are gaps.
  const bool log = span.Decades();
  const double floor_j = span.hi * 1e-9;
  for (size_t i = 0; i < run.engines.size(); ++i) {
    std::string dat = "# t_s energy_above_rest_j\n";
    const auto& samples = run.engines[i].history.samples;
    for (size_t k = 0; k < samples.size(); ++k) {
      AppendDat(dat, samples[k].t_s);
      dat += ' ';
      AppendDat(dat, log && values[i][k] < floor_j ? kNaN : values[i][k]);
      dat += '\n';
    }
    f.data_files.push_back({"energy." + run.engines[i].name + ".dat", dat});
  }
  f.script = CommonAxes(run.t_end_s) + "set ylabel 'energy above rest (J)'\n" +
             (log ? "set logscale y\nset format y '10^{%L}'\n" : "");
  std::string plot = "plot ";
  for (size_t i = 0; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    if (i > 0) plot += ", ";
    plot += Quote("energy." + e.name + ".dat") + " using 1:2 with lines lw " +
            (i == 0 ? "2.2" : "1.4") + (i == 0 ? "" : " dt 2") + " lc rgb " + Quote(e.colour) +
            " title " + Quote(e.label);
  }
  f.script += plot + "\n";
  fig.Add(
      f, std::string("Energy against time: kinetic energy in the base frame plus potential "
                     "energy above the rest position (J)") +
             (log ? ", log scale (values below 1e-9 of the largest, such as rest, are gaps)" : "") +
             ". Every run's energy, engines included, is evaluated from its angles and rates "
             "with the rigid-block model (reference/kinematics.h), not read from the engine.");
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < run.engines.size(); ++i) {
    rows.push_back({run.engines[i].name, Num(values[i].front(), 6) + " J",
                    Num(values[i].back(), 6) + " J",
                    Num(*std::max_element(values[i].begin(), values[i].end()), 6) + " J"});
  }
  page.Table({"run", "initial", "final", "largest"}, rows);
}

struct FrictionFacts {
  double max_ground = 0.0, max_interface = 0.0;  // over the plotted samples
  double min_N_ground = std::numeric_limits<double>::infinity();
  double min_N_interface = std::numeric_limits<double>::infinity();
  double min_N_ground_t = 0.0, min_N_interface_t = 0.0;
  int left_out = 0;
  std::vector<std::array<double, 3>> rows;  // t, mu ground, mu interface (NaN: left out)
  Span span;                                // of the values kept
};

// |T|/N along the reference's samples, left out where the normal force nearly vanishes.
FrictionFacts ComputeFriction(const RunData& run, const reference::Geometry& geo,
                              const GroundMotion& motion, const RunReportOptions& options) {
  const bool two = run.scene.two_blocks();
  const EngineData& ref = run.engines.front();
  const double W = geo.M * geo.g;
  const double n_min = options.friction_min_normal_fraction * W;
  FrictionFacts facts;
  auto& rows = facts.rows;
  Span& span = facts.span;
  for (const Sample& s : ref.history.samples) {
    const FrictionDemand d = RequiredFriction(geo, s.mode, s, motion.xg_mps2(s.t_s),
                                              motion.yg_mps2(s.t_s), run.scene.model.equations);
    if (d.N_ground_n < facts.min_N_ground)
      facts.min_N_ground = d.N_ground_n, facts.min_N_ground_t = s.t_s;
    double mg = kNaN, mi = kNaN;
    if (d.N_ground_n >= n_min) {
      mg = d.mu_ground;
      facts.max_ground = std::max(facts.max_ground, mg);
      span.Add(mg);
    } else {
      ++facts.left_out;
    }
    if (two) {
      if (d.N_interface_n < facts.min_N_interface) {
        facts.min_N_interface = d.N_interface_n, facts.min_N_interface_t = s.t_s;
      }
      if (d.N_interface_n >= n_min) {
        mi = d.mu_interface;
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

void FrictionSection(const RunData& run, const FrictionFacts& facts,
                     const RunReportOptions& options, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Friction needed");
  const bool two = run.scene.two_blocks();
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

// Keyframe times: peaks of every angle, overturning, then the reference's first impacts.
struct Keyframe {
  double t_s = 0.0;
  std::vector<std::string> why;
  std::vector<int> impacts;  // numbers of the reference's impacts at this time
  std::string Caption() const {
    std::string out;
    for (const std::string& w : why) out += (out.empty() ? "" : "; ") + w;
    if (!impacts.empty()) {
      out += out.empty() ? "" : "; ";
      out += impacts.size() == 1 ? "impact " + std::to_string(impacts.front())
                                 : "impacts " + std::to_string(impacts.front()) + " to " +
                                       std::to_string(impacts.back());
      out += " of the reference";
    }
    return out;
  }
};

std::vector<Keyframe> KeyframeTimes(const RunData& run, int max_frames) {
  std::vector<Keyframe> chosen;
  // Times within 5 ms share a frame; `impact` > 0 is the reference's impact number.
  const auto add = [&](double t, const std::string& why, int impact = 0) {
    if (std::isnan(t)) return;
    Keyframe* k = nullptr;
    for (Keyframe& c : chosen) {
      if (std::abs(c.t_s - t) < 5e-3) k = &c;
    }
    if (k == nullptr) {
      if (static_cast<int>(chosen.size()) >= max_frames) return;
      chosen.push_back({t, {}, {}});
      k = &chosen.back();
    }
    if (impact > 0) {
      k->impacts.push_back(impact);
    } else {
      k->why.push_back(why);
    }
  };
  const EngineData& ref = run.engines.front();
  for (int b = 1; b <= (run.scene.two_blocks() ? 2 : 1); ++b) {
    const std::string key = "peaks.theta" + std::to_string(b) + ".t_s";
    add(OptNumber(ref.summary, key, run.summary_path),
        "peak |theta" + std::to_string(b) + "| of the reference");
  }
  for (const EngineData& e : run.engines) {
    add(OptNumber(e.summary, "overturn.t_s", run.summary_path), "overturn (" + e.name + ")");
  }
  int impact = 0;
  for (const Event& ev : ref.events) {
    if (ev.kind != "ground_impact" && ev.kind != "interface_impact") continue;
    ++impact;
    add(ev.t_s, "", impact);
  }
  std::sort(chosen.begin(), chosen.end(),
            [](const Keyframe& a, const Keyframe& b) { return a.t_s < b.t_s; });
  return chosen;
}

void PicturesSection(const RunData& run, const GroundMotion& motion,
                     const RunReportOptions& options, Figures& fig, RunReportResult& result) {
  Page& page = *fig.page;
  if (!options.keyframes && !options.animation) {
    result.left_out.push_back(
        "keyframes and animation: left out on request (--no-keyframes, "
        "--no-animation)");
    return;
  }
  if (!renders::GlAvailable()) {
    result.left_out.push_back("keyframes and animation: " + renders::GlUnavailableReason());
    return;
  }
  std::vector<renders::Track> tracks;
  for (const EngineData& e : run.engines) tracks.push_back({e.name, e.history});
  renders::RenderConfig config;
  config.width_px = options.animation_width_px;
  config.height_px = options.animation_height_px;
  config.title = run.scene.title;
  const renders::BaseDisplacement base = renders::IntegrateBaseDisplacement(motion, run.t_end_s);
  try {
    if (options.keyframes) {
      renders::RenderConfig kc = config;
      kc.width_px = options.keyframe_width_px;
      kc.height_px = options.keyframe_height_px;
      renders::FrameRenderer renderer(run.scene, tracks, base, kc);
      page.Heading("Keyframes");
      page.Paragraph(
          "Frames drawn from the histories (renders/): the reference solid, the "
          "engines outlined on top; the strip chart shows the angles up to that time.");
      int index = 0;
      for (const Keyframe& k : KeyframeTimes(run, options.max_keyframes)) {
        char name[64];
        std::snprintf(name, sizeof name, "keyframe_%02d.png", ++index);
        renders::WritePng(renderer.Render(k.t_s), fig.page_dir / "keyframes" / name);
        page.Figure(fs::path("keyframes") / name,
                    "t = " + Fixed(k.t_s, 4) + " s: " + k.Caption() + ".");
        ++fig.count;
      }
    } else {
      result.left_out.push_back("keyframes: left out on request (--no-keyframes)");
    }
    if (options.animation) {
      renders::FrameRenderer renderer(run.scene, tracks, base, config);
      renders::AnimationConfig anim;
      anim.out_dir = fig.page_dir;
      anim.fps = options.animation_fps;
      anim.mp4 = true;
      anim.name = "animation";
      const renders::AnimationResult r = renders::ExportAnimation(renderer, anim);
      if (!r.problems.empty()) {
        std::string all;
        for (const std::string& p : r.problems) all += (all.empty() ? "" : "; ") + p;
        result.left_out.push_back("animation: " + all);
        // Without ffmpeg the exporter falls back to PNG frames; they are not part of the page.
        std::error_code ec;
        fs::remove_all(fig.page_dir / "frames", ec);
      } else {
        page.Heading("Animation");
        page.Video("animation.mp4", "The whole run at real speed, " + Num(options.animation_fps) +
                                        " frames/s, " + std::to_string(config.width_px) + "x" +
                                        std::to_string(config.height_px) + " (H.264)");
      }
    } else {
      result.left_out.push_back("animation: left out on request (--no-animation)");
    }
  } catch (const renders::RenderError& e) {
    result.left_out.push_back(std::string("keyframes and animation: ") + e.what());
  }
}

std::string EngineWarnings(const EngineData& e, std::vector<std::string>& out) {
  const json* v = Find(e.summary, "violations");
  std::string status = e.summary.value("status", std::string("unknown"));
  if (v == nullptr || !v->is_object()) return status;
  const auto flag = [&](const char* k) {
    return v->contains(k) && (*v)[k].is_boolean() && (*v)[k].get<bool>();
  };
  const auto num = [&](const char* k) {
    return v->contains(k) && (*v)[k].is_number() ? (*v)[k].get<double>() : kNaN;
  };
  const std::string who = "The " + e.name + " run";
  if (flag("sliding")) {
    out.push_back(who + " slid: the blocks slipped " + Num(1e3 * num("slip_ground_m"), 3) +
                  " mm at the ground and " + Num(1e3 * num("slip_interface_m"), 3) +
                  " mm at the interface. The rigid-block model assumes no sliding, so the two "
                  "are not simulating the same system.");
  }
  if (flag("uplift")) {
    std::string where;
    for (const char* c : {"ground", "interface"}) {
      const double n = num((std::string("uplift_") + c + "_episodes").c_str());
      if (!(n > 0)) continue;
      where += std::string(where.empty() ? "" : " and ") + Num(n) + " time(s) at the " + c +
               " (up to " + Num(1e3 * num((std::string("uplift_") + c + "_max_m").c_str()), 3) +
               " mm)";
    }
    out.push_back(who + " lifted off" + (where.empty() ? "" : ": " + where) +
                  ". The model assumes the pivots stay in contact (no bouncing or jumping).");
  }
  if (flag("penetration")) {
    out.push_back(
        who + " let the blocks sink into each other or the ground by up to " +
        Num(1e3 * std::max(num("penetration_ground_max_m"), num("penetration_interface_max_m")),
            3) +
        " mm: its contacts are soft at this time step.");
  }
  if (flag("energy_growth")) {
    out.push_back(who + " gained energy without input: up to " + Num(num("energy_gain_max_j")) +
                  " J (" + Num(100.0 * num("energy_gain_rel"), 3) +
                  " % of the energy needed to tip the stack) at t = " +
                  Num(num("energy_gain_t_s"), 4) + " s.");
  }
  if (flag("blow_up")) {
    out.push_back(who +
                  " blew up (non-finite state, runaway rate or energy) and stopped early; "
                  "its results after that are meaningless.");
  }
  return status;
}

void VerdictSection(const RunData& run, Page& page, RunReportResult& result) {
  VerdictInput in;
  in.comparison = run.comparison ? &*run.comparison : nullptr;
  in.comparison_path = run.comparison_path;
  in.summary = &run.summary;
  in.summary_path = run.summary_path;
  for (size_t i = 1; i < run.engines.size(); ++i) in.engines.push_back(run.engines[i].name);
  in.two_blocks = run.scene.two_blocks();
  in.predictability = run.predictability;
  for (std::string& w : WriteVerdictSection(in, page)) result.warnings.push_back(std::move(w));
}

}  // namespace

RunReportResult WriteRunReport(const fs::path& run_dir, const fs::path& out_dir,
                               const RunReportOptions& options) {
  if (options.animation &&
      (options.animation_width_px % 2 != 0 || options.animation_height_px % 2 != 0)) {
    throw std::invalid_argument("animation size " + std::to_string(options.animation_width_px) +
                                "x" + std::to_string(options.animation_height_px) +
                                ": H.264 needs an even width and height");
  }
  // Everything read from the run folder is input: its failures are the user's to fix.
  const RunData run = [&] {
    try {
      return ReadRunFolder(run_dir);
    } catch (const SceneError&) {
      throw;
    } catch (const ReportInputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw ReportInputError(e.what());
    }
  }();
  const GroundMotion motion = GroundMotion::FromScene(run.scene);
  const reference::Geometry geo = reference::MakeGeometry(run.scene);
  RunReportResult result;
  result.name = fs::absolute(run_dir).lexically_normal().filename().string();
  if (result.name.empty())
    result.name = fs::absolute(run_dir).lexically_normal().parent_path().filename().string();
  result.page_dir = out_dir / result.name;
  const std::string scene_name =
      run.scene.title.empty() ? run.scene.path.stem().string() : run.scene.title;
  result.scene = scene_name;
  result.title = "rockbench report: " + scene_name;
  Page page(result.title);
  Figures fig;
  fig.page_dir = result.page_dir;
  fig.dir = result.page_dir / "figures";
  fig.page = &page;
  fs::create_directories(fig.dir);

  // Outcome in words; the warnings go to the top of the page.
  const EngineData& ref = run.engines.front();
  std::string outcome;
  const std::string status = OptString(run.summary, "status", run.summary_path);
  if (status == "overturned") {
    outcome =
        "The reference model: block " +
        Num(OptNumber(run.summary, "overturn.block", run.summary_path)) +
        " overturned at t = " + Fixed(OptNumber(run.summary, "overturn.t_s", run.summary_path), 4) +
        " s.";
  } else if (status == "at_rest") {
    outcome = "The reference model: the blocks came to rest (run to " +
              Fixed(ref.history.samples.back().t_s, 3) + " s).";
  } else if (status == "assumption_violated") {
    outcome = "The reference model stopped: an assumption was violated.";
    std::string when;
    for (const Event& ev : ref.events) {
      if (ev.kind == "assumption_violated") when = Fixed(ev.t_s, 4);
    }
    result.warnings.push_back("The reference model's assumptions were violated" +
                              (when.empty() ? std::string() : " at t = " + when + " s") + ": " +
                              OptString(run.summary, "status_detail", run.summary_path) +
                              ". The run stopped there; nothing after that time is simulated.");
  } else {
    outcome = "The reference model ran to t = " + Fixed(ref.history.samples.back().t_s, 3) +
              " s (" + status + ").";
  }
  const double inadmissible = OptNumber(run.summary, "impacts.inadmissible", run.summary_path);
  if (inadmissible > 0) {
    result.warnings.push_back(
        Num(inadmissible) +
        " impact(s) of the reference had no admissible outcome (every "
        "candidate needs a pulling impulse or moves a body into another); the thesis's velocity "
        "check chose the outcome (notes in reference/events.csv).");
  }
  const double gain = OptNumber(run.summary, "impacts.energy_gain", run.summary_path);
  if (gain > 0) {
    result.warnings.push_back(Num(gain) + " impact(s) of the reference added energy.");
  }
  // Friction: the largest |T|/N where the contact carries at least the option's share of the
  // weight (near N = 0, as at an uplift, the ratio grows without bound and says nothing).
  const FrictionFacts ff = ComputeFriction(run, geo, motion, options);
  const auto engine_mu = EngineFriction(run);
  for (const char* contact : {"ground", "interface"}) {
    if (!engine_mu) break;
    if (std::string(contact) == "interface" && !run.scene.two_blocks()) continue;
    const double need = std::string(contact) == "ground" ? ff.max_ground : ff.max_interface;
    if (need > engine_mu->first) {
      result.warnings.push_back(
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
  if (ff.min_N_ground < tension_n || (run.scene.two_blocks() && ff.min_N_interface < tension_n)) {
    const bool ground = ff.min_N_ground < tension_n;
    result.warnings.push_back(
        std::string("Tension: the reference's normal force at the ") +
        (ground ? "ground" : "interface") + " is negative (" +
        Num(ground ? ff.min_N_ground : ff.min_N_interface, 4) +
        " N at t = " + Fixed(ground ? ff.min_N_ground_t : ff.min_N_interface_t, 4) +
        " s): the contact would have to pull, so the block would lift off there.");
  }
  std::vector<std::string> engine_status;
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const std::string st = EngineWarnings(run.engines[i], result.warnings);
    std::string line = run.engines[i].name + ": " + st;
    const double ot = OptNumber(run.engines[i].summary, "overturn.t_s", run.summary_path);
    if (!std::isnan(ot)) {
      line += ", block " +
              Num(OptNumber(run.engines[i].summary, "overturn.block", run.summary_path)) +
              " overturned at t = " + Fixed(ot, 4) + " s";
    }
    engine_status.push_back(line);
  }
  if (run.engines.size() > 1) {
    outcome += " Engines compared:";
    for (size_t i = 0; i < engine_status.size(); ++i) {
      outcome += (i ? "; " : " ") + engine_status[i];
    }
    outcome += ".";
  } else {
    outcome += " No engine was compared with it.";
  }
  result.outcome = outcome;

  page.Heading("Outcome");
  page.Paragraph(outcome);
  VerdictSection(run, page, result);
  SceneSection(run, motion, fig);
  page.Heading("Angles");
  AnglesFigure(run, fig);
  AgreementSection(run, options, fig);
  ImpactsSection(run, fig);
  EnergySection(run, geo, fig);
  FrictionSection(run, ff, options, fig);
  PicturesSection(run, motion, options, fig, result);
  if (!result.left_out.empty()) {
    page.Heading("Left out");
    for (const std::string& l : result.left_out) page.Paragraph(l + ".");
  }
  page.Heading("Files");
  page.Paragraph(
      "Each figure is figures/NAME.svg, drawn by gnuplot from figures/NAME.gp and its "
      "figures/NAME.*.dat data: edit the script and run `gnuplot NAME.gp` in "
      "figures/ to restyle it (docs/report.md). Run folder: " +
      fs::absolute(run_dir).lexically_normal().string() + ".");
  for (const std::string& w : result.warnings) page.Warning(w);
  result.figure_count = static_cast<int>(page.figures().size());
  WriteFileAtomic(result.page_dir / "report.md", page.Markdown());
  WriteFileAtomic(result.page_dir / "report.html", page.Html(result.page_dir));
  return result;
}

void WriteReportIndex(const fs::path& out_dir, const std::vector<IndexEntry>& pages) {
  Page html("rockbench reports");
  Page md("rockbench reports");
  std::vector<std::vector<std::string>> rows;
  for (const IndexEntry& p : pages) {
    rows.push_back({p.name, p.title, p.outcome, std::to_string(p.warning_count)});
  }
  for (Page* page : {&html, &md}) {
    page->Table({"run", "scene", "outcome", "validity warnings"}, rows);
    page->Heading("Reports");
  }
  for (const IndexEntry& p : pages) {
    html.Link(fs::path(p.name) / "report.html", p.name + ": " + p.title);
    md.Link(fs::path(p.name) / "report.md", p.name + ": " + p.title);
  }
  WriteFileAtomic(out_dir / "index.md", md.Markdown());
  WriteFileAtomic(out_dir / "index.html", html.Html(out_dir));
}

}  // namespace rockbench::report
