#include "report/sweep/work_precision.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "files/atomic_file.h"
#include "report/common/gnuplot.h"
#include "report/common/page.h"
#include "run/engine_registry.h"
#include "scene/body_kind.h"
#include "scene/history.h"
#include "scene/mode.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;

// A family's colour and style: the reference black and grey; each engine family a colour of
// its own (in family order), each engine a point type and a dash pattern of its own.
struct Style {
  std::string colour;
  int point_type = 7;
  int dash_type = 1;
};

Style FamilyStyle(const SweepRecord& r, size_t family_index, size_t engine_index) {
  Style s;
  if (IsReference(r.engine)) {
    // dopri5 black squares, dop853 black diamonds, RK4 grey triangles.
    s.colour = r.integrator == "rk4" ? "#8c8c8c" : "#000000";
    s.point_type = r.integrator == "dopri5" ? 5 : r.integrator == "dop853" ? 13 : 9;
    return s;
  }
  static const char* kPalette[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e",
                                   "#e6ab02", "#a6761d", "#1f78b4", "#b2df8a", "#fb9a99"};
  static const int kPoints[] = {7, 6, 13, 11, 9};
  s.colour = kPalette[family_index % std::size(kPalette)];
  s.point_type = kPoints[engine_index % std::size(kPoints)];
  s.dash_type = 1 + static_cast<int>(engine_index % 4);
  return s;
}

// Log-axis range [10^floor(log10 lo), 10^ceil(log10 hi)], at least one decade.
std::pair<double, double> DecadeRange(double lo, double hi) {
  double a = std::pow(10.0, std::floor(std::log10(lo)));
  double b = std::pow(10.0, std::ceil(std::log10(hi)));
  if (b <= a) b = a * 10.0;
  return {a, b};
}

// What sweep.json says (all optional: an older sweep folder has only sweep.csv).
struct SweepInfo {
  bool present = false;
  std::string scene_path, scene_title;
  std::vector<std::string> overrides;
  double duration_s = 0.0;
  bool quick = false;
  int repeat = 1, threads = 0;
  double tight_wall_s = 0.0;
  std::string tight_status;
  // The tight reference's peak |theta| of each body (body k at k - 1; sweep.json gives
  // bodies 1 and 2 always, one block's body 2 as 0), rad, and when (-1: not recorded), s.
  std::vector<double> tight_peak_rad, tight_peak_t_s;
  int overturn_block = 0;  // 1..N; 0: none
  double overturn_t_s = 0.0;
  // The simulated span a run covers: runs stop when a block overturns (the reference's
  // overturn time stands for every run's), else the scene's duration. The real-time mark.
  double span_s() const {
    return overturn_block > 0 && overturn_t_s > 0.0 ? std::min(overturn_t_s, duration_s)
                                                    : duration_s;
  }
  std::string machine;
};

// "peak |theta1| X rad, peak |theta2| Y rad, ..." of the tight reference's bodies; body 2 is
// left out when its peak is 0 (one block).
std::string PeaksText(const SweepInfo& info) {
  std::string out;
  for (size_t k = 0; k < info.tight_peak_rad.size(); ++k) {
    if (k == 1 && !(info.tight_peak_rad[k] > 0.0)) continue;
    out.append(k > 0 ? ", peak |" : "peak |").append(BodyColumn("theta", static_cast<int>(k) + 1));
    out.append("| ").append(Format("%.4g", info.tight_peak_rad[k])).append(" rad");
  }
  return out;
}

SweepInfo ReadSweepInfo(const fs::path& path) {
  SweepInfo info;
  if (!fs::exists(path)) return info;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ReadTextFile(path));
    info.scene_path = j.at("scene").at("path").get<std::string>();
    info.scene_title = j.at("scene").value("title", "");
    info.overrides = j.at("scene").value("overrides", std::vector<std::string>{});
    info.duration_s = j.at("simulated_duration_s").get<double>();
    info.quick = j.at("options").value("quick", false);
    info.repeat = j.at("options").value("repeat", 1);
    info.threads = j.at("options").value("threads", 0);
    const nlohmann::json& t = j.at("tight_reference");
    info.tight_wall_s = t.value("wall_s", 0.0);
    info.tight_status = t.value("status", "");
    // Bodies 1 and 2 always (0 and not recorded when absent), then 3, 4, ... as present.
    for (int b = 1; b <= kMaxBlocks && (b <= 2 || t.contains(BodyColumn("peak_theta", b) + "_rad"));
         ++b) {
      const std::string th = BodyColumn("peak_theta", b);
      info.tight_peak_rad.push_back(t.value(th + "_rad", 0.0));
      info.tight_peak_t_s.push_back(t.value(th + "_t_s", -1.0));
    }
    if (t.contains("overturn_block") && t.at("overturn_block").is_number_integer()) {
      info.overturn_block = t.at("overturn_block").get<int>();
      info.overturn_t_s = t.value("overturn_t_s", 0.0);
    }
    info.machine = j.value("machine", "");
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": not a sweep.json as `rockbench sweep` writes it (" +
                             e.what() + ")");
  }
  if (!(info.duration_s > 0.0) || !std::isfinite(info.duration_s)) {
    throw std::runtime_error(path.string() +
                             ": simulated_duration_s: expected a positive number of seconds");
  }
  info.present = true;
  return info;
}

// One figure: a value per usable row against wall time, one curve per family.
struct FigureSpec {
  std::string name;
  std::string ylabel;
  double (*value)(const SweepRecord&);
  std::optional<double> hline;  // a horizontal mark (the 1% line)
  std::string hline_label;
};

GnuplotFigure BuildFigure(const std::vector<SweepRecord>& rows, const FigureSpec& spec,
                          double duration_s, const std::string& real_time_label,
                          std::vector<std::string>* not_drawn) {
  const auto families = SweepFamilies(rows);
  std::string data = "# " + spec.name + ": wall_s, value, label (the family's varying setting)\n";
  std::string plot = "plot ";
  double xlo = HUGE_VAL, xhi = 0.0, ylo = HUGE_VAL, yhi = 0.0;
  int block = 0;
  for (const auto& [family, indices] : families) {
    std::string text;
    for (size_t i : indices) {
      const SweepRecord& r = rows[i];
      const double y = spec.value(r);
      if (!(y > 0.0) || !(r.wall_s > 0.0)) {
        if (not_drawn) not_drawn->push_back(SweepSettingDescription(r));
        continue;
      }
      text += Format("%.6g", r.wall_s) + " " + Format("%.6g", y) + " " +
              GnuplotDataString(SweepSettingLabel(r)) + "\n";
      xlo = std::min(xlo, r.wall_s);
      xhi = std::max(xhi, r.wall_s);
      ylo = std::min(ylo, y);
      yhi = std::max(yhi, y);
    }
    if (text.empty()) continue;
    // The family as a comment: one line, its control characters shown as \xHH.
    const std::string comment = GnuplotDataString(family);
    data += (block > 0 ? "\n\n" : "") + std::string("# ") + comment.substr(1, comment.size() - 2) +
            "\n" + text;
    const SweepRecord& head = rows[indices.front()];
    const std::vector<std::string> engines = SweepEngines(rows);
    const size_t engine_index = static_cast<size_t>(
        std::find(engines.begin(), engines.end(), head.engine) - engines.begin());
    const Style st = FamilyStyle(head, static_cast<size_t>(block), engine_index);
    const std::string idx = " index " + std::to_string(block);
    // A family's title as written ("ODE world_step"): no enhanced-text subscripts.
    plot += std::string(block > 0 ? ", \\\n     " : "") + "'" + spec.name + ".dat'" + idx +
            " using 1:2 with linespoints lw 1.5 pt " + std::to_string(st.point_type) +
            " ps 0.8 dt " + std::to_string(st.dash_type) + " lc rgb '" + st.colour + "' title " +
            GnuplotQuote(family) + " noenhanced, \\\n     '" + spec.name + ".dat'" + idx +
            " using 1:2:3 with labels font ',7' offset char 0.4,0.55 left tc rgb '" + st.colour +
            "' notitle";
    ++block;
  }
  std::string script =
      "set logscale xy\n"
      "set format x '10^{%L}'\n"
      "set format y '10^{%L}'\n"
      "set xlabel 'wall time of the run (s)'\n"
      "set ylabel " +
      GnuplotQuote(spec.ylabel) +
      "\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set key outside right top box font ',10' spacing 1.1\n"
      "set title 'points labelled: engine time step (s), dopri5 and dop853 rtol, RK4 step (s)' "
      "font ',10'\n";
  if (block == 0) {
    // Nothing usable: an empty frame that says so.
    script += "set xrange [1e-3:1]\nset yrange [1e-3:1]\n";
    script += "set label 'no usable runs' at graph 0.5, graph 0.5 center\n";
    script += "plot NaN notitle\n";
    return GnuplotFigure{spec.name, script, {{spec.name + ".dat", data}}, 1100, 620};
  }
  if (duration_s > 0.0) {
    xlo = std::min(xlo, duration_s);
    xhi = std::max(xhi, duration_s);
  }
  if (spec.hline) {
    ylo = std::min(ylo, *spec.hline);
    yhi = std::max(yhi, *spec.hline);
  }
  const auto [x0, x1] = DecadeRange(xlo, xhi);
  const auto [y0, y1] = DecadeRange(ylo, yhi);
  script += "set xrange [" + Format("%.6g", x0) + ":" + Format("%.6g", x1) + "]\n";
  script += "set yrange [" + Format("%.6g", y0) + ":" + Format("%.6g", y1) + "]\n";
  if (duration_s > 0.0) {
    // Left of this line a run is faster than the motion it simulates.
    const std::string d = Format("%.6g", duration_s);
    script += "set arrow 1 from " + d + ", graph 0 to " + d +
              ", graph 1 nohead dt 3 lw 1.5 lc rgb '#444444'\n";
    script += "set label 1 " + GnuplotQuote(real_time_label) + " at " + d +
              ", graph 0.04 right offset char -0.5,0 font ',9' tc rgb '#444444'\n";
  }
  if (spec.hline) {
    const std::string h = Format("%.6g", *spec.hline);
    script += "set arrow 2 from graph 0, first " + h + " to graph 1, first " + h +
              " nohead dt 4 lw 1.5 lc rgb '#b00000'\n";
    script += "set label 2 " + GnuplotQuote(spec.hline_label) + " at graph 0.01, first " + h +
              " left offset char 0,0.6 font ',9' tc rgb '#b00000'\n";
  }
  script += plot + "\n";
  return GnuplotFigure{spec.name, script, {{spec.name + ".dat", data}}, 1100, 620};
}

// Warnings at the top: failed runs, no sweep.json, no engine. Returns the failed rows.
std::vector<size_t> WarningsSection(const std::vector<SweepRecord>& rows, const SweepInfo& info,
                                    Page& page) {
  std::vector<size_t> failed;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].failure.empty()) failed.push_back(i);
  }
  if (!failed.empty()) {
    page.Warning(std::to_string(failed.size()) + " of " + std::to_string(rows.size()) +
                 " runs failed or gave non-finite results; they are listed under \"Failed runs\" "
                 "and not plotted.");
  }
  if (!info.present) {
    page.Warning(
        "No sweep.json beside sweep.csv (a sweep from an older rockbench): the "
        "simulated duration is unknown, so real time is not marked.");
  }
  if (SweepEngines(rows).empty()) {
    page.Warning(
        "The sweep has no engine runs (built without engines?): there is nothing to "
        "compare the reference with.");
  }

  return failed;
}

// What was swept, on which scene and machine.
void SweepSection(const fs::path& sweep_dir, const std::vector<SweepRecord>& rows,
                  const SweepInfo& info, Page& page) {
  page.Heading("The sweep");
  std::string about = "Sweep folder: " + sweep_dir.string() + ", " + std::to_string(rows.size()) +
                      " runs, each compared with a tight reference (dopri5, rtol 1e-12, atol "
                      "1e-14) on the engine's sample times.";
  if (info.present) {
    about += " Scene: " + info.scene_path;
    for (const std::string& o : info.overrides) about += " --set " + o;
    about +=
        "; simulated duration " + Format("%g", info.duration_s) +
        " s. Grid: " + (info.quick ? "quick" : "full") + "; wall time of a run: the minimum of " +
        std::to_string(info.repeat) + " repetition" + (info.repeat == 1 ? "" : "s") + ", with " +
        (info.threads == 0
             ? std::string("one worker thread per core")
             : std::to_string(info.threads) + " worker thread" + (info.threads == 1 ? "" : "s")) +
        " (runs sharing cores read slower than alone). Machine: " + info.machine +
        ". The tight reference took " + Format("%.3g", info.tight_wall_s) + " s (status " +
        info.tight_status + ", " + PeaksText(info) +
        (info.overturn_block > 0
             ? ", block " + std::to_string(info.overturn_block) + " overturns at " +
                   Format("%.4g", info.overturn_t_s) + " s, where every run that overturns stops"
             : std::string()) +
        ").";
  }
  page.Paragraph(about);
}

// Each engine's cheapest setting for 1% peak-angle agreement, and for the stricter history
// criterion when the scene's peaks cannot tell runs apart.
void StatementSection(const std::vector<SweepRecord>& rows, const SweepInfo& info, Page& page) {
  page.Heading("Cheapest setting for 1% peak-angle agreement");
  for (const std::string& engine : SweepEngines(rows)) {
    const CheapestSetting cheapest = FindCheapestSetting(rows, 0.01, engine);
    page.Paragraph(cheapest.statement);
    if (info.present && cheapest.engine_row) {
      const SweepRecord& b = rows[*cheapest.engine_row];
      page.Paragraph("That " + engine + " run simulates " + Format("%.3g", info.span_s()) +
                     " s in " + Format("%.3g", b.wall_s) + " s: " +
                     Format("%.3g", info.span_s() / b.wall_s) + " times faster than real time.");
    }
  }
  // When the peak criterion cannot tell runs apart, say so, and give a stricter one.
  if (info.present) {
    std::vector<std::string> caveats;
    // Bodies 1 and 2 (the caveats as the report has always given them).
    const std::vector<double>& peak = info.tight_peak_rad;
    const std::vector<double>& peak_t = info.tight_peak_t_s;
    for (int b = 0; b < 2; ++b) {
      const std::string theta = BodyColumn("theta", b + 1);
      if (info.overturn_block == b + 1) {
        caveats.push_back("block " + std::to_string(b + 1) + " overturns, so " + theta +
                          "'s peak is the overturn angle, which every run that overturns "
                          "reaches: the criterion checks little more than the outcome for " +
                          theta);
      } else if (peak[b] > 0.0 && peak_t[b] == 0.0) {
        caveats.push_back(theta +
                          "'s peak is its release angle (t = 0 s), where every run "
                          "starts: the criterion says nothing about " +
                          theta);
      }
    }
    if (!caveats.empty()) {
      std::string text = "On this scene ";
      for (size_t i = 0; i < caveats.size(); ++i) text += (i ? "; and " : "") + caveats[i];
      page.Paragraph(text + ". A stricter criterion, on the whole history:");
    } else {
      page.Paragraph("A stricter criterion, on the whole history:");
    }
    for (const std::string& engine : SweepEngines(rows)) {
      page.Paragraph(
          FindCheapestSetting(rows, HistoryAgreement(0.01, info.tight_peak_rad), engine).statement);
    }
  }
  page.Paragraph(
      "Wall times are measured: they vary from run to run and with the load of the "
      "machine, so a choice between two settings of close wall times can go either "
      "way when the sweep is repeated (sweep --repeat N takes the minimum of N).");
}

// The engines ranked by the cost of the cheapest setting that reaches each accuracy level, with
// each engine's fitted order of convergence.
void RankingSection(const std::vector<SweepRecord>& rows, const SweepInfo& info, Page& page) {
  if (!info.present) return;
  const std::vector<double> fractions = {0.1, 0.01, 0.001};
  std::vector<AgreementCriterion> levels;
  for (double f : fractions) {
    levels.push_back(HistoryAgreement(f, info.tight_peak_rad));
  }
  const std::vector<EngineAtLevels> ranked = RankAtEqualAccuracy(rows, levels, 1);
  if (ranked.empty()) return;
  page.Heading("Engines at equal accuracy");
  std::vector<std::vector<std::string>> table;
  for (const EngineAtLevels& e : ranked) {
    std::vector<std::string> cells = {e.engine};
    for (size_t k = 0; k < levels.size(); ++k) {
      if (!e.cheapest[k]) {
        cells.push_back("not reached");
        continue;
      }
      const SweepRecord& r = rows[*e.cheapest[k]];
      std::string cell = "#";
      cell += std::to_string(e.rank[k]);
      cell += ": ";
      cell += Format("%.3g", r.wall_s);
      cell += " s (";
      cell += SweepSettingDescription(r);
      cell += ")";
      cells.push_back(std::move(cell));
    }
    cells.push_back(e.most_accurate ? Format("%.2e", MaxAngleError(rows[*e.most_accurate])) : "");
    std::string order;
    if (e.order) {
      order = Format("%.2f", e.order->order);
      order += " (";
      order += e.order->family;
      order += ", ";
      order += Format("%.3g", e.order->coarsest);
      order += " to ";
      order += Format("%.3g", e.order->finest);
      order += ", ";
      order += std::to_string(e.order->points);
      order += " points)";
    }
    cells.push_back(std::move(order));
    table.push_back(std::move(cells));
  }
  page.Table({"engine", "within 10% of the peaks", "within 1%", "within 0.1%",
              "smallest max angle error (rad)", "fitted order in dt"},
             table);
  page.Paragraph(
      "An accuracy level: the max |angle error| over the whole run within 10%, 1% or 0.1% of the "
      "reference's peak |theta_i| for each block, with the same overturning. Each cell is the "
      "engine's cheapest setting reaching the level, ranked by wall time among the engines that "
      "reach it (#1 the cheapest); rows in rank order at 1%. The fitted order is the "
      "least-squares slope of log(max angle error) against log(time step) over the family of "
      "the engine's most accurate run; it mixes regimes when the error stops falling (a floor set "
      "by the contact model or, on a chaotic scene, by the predictability horizon), so read it "
      "with the figure and the order column of the table of all runs.");
}

// The blocks of the sweep's stack: 2 for one or two blocks (their columns are the same), N
// for a row with N >= 3 bodies.
int SweepBlocks(const std::vector<SweepRecord>& rows) {
  int blocks = 2;
  for (const SweepRecord& r : rows) blocks = std::max(blocks, r.column_blocks());
  return blocks;
}

// The two figures against wall time, and the rows a log axis cannot draw.
void FiguresSection(const std::vector<SweepRecord>& rows, const SweepInfo& info,
                    const fs::path& fig_dir, Page& page) {
  // The angles whose largest error the figures draw: "θ_1, θ_2", or every block's.
  const int blocks = SweepBlocks(rows);
  const std::string angles =
      blocks >= 3 ? std::string("θ_1 to θ_") + std::to_string(blocks) : std::string("θ_1, θ_2");
  std::vector<std::string> not_drawn_error, not_drawn_peak;
  FigureSpec error_spec;
  error_spec.name = "work_precision";
  error_spec.ylabel = "max |angle error| over the run, max of " + angles + " (rad)";
  error_spec.value = &MaxAngleError;
  const double duration = info.present ? info.span_s() : 0.0;
  std::string real_time_label = "real time (" + Format("%.3g", duration) + " s simulated";
  if (info.span_s() < info.duration_s) {
    real_time_label += ": block " + std::to_string(info.overturn_block) + " overturns";
  }
  real_time_label += ")";
  RenderGnuplot(fig_dir,
                BuildFigure(rows, error_spec, duration, real_time_label, &not_drawn_error));
  FigureSpec peak_spec;
  peak_spec.name = "peak_error";
  peak_spec.ylabel = "|peak angle relative error|, max of " + angles;
  peak_spec.value = &MaxPeakRelError;
  peak_spec.hline = 0.01;
  peak_spec.hline_label = "1% peak-angle agreement";
  RenderGnuplot(fig_dir, BuildFigure(rows, peak_spec, duration, real_time_label, &not_drawn_peak));
  page.Heading("Error against run time");
  page.Figure(
      "figures/work_precision.svg",
      "Max angle error against wall time, log-log, one curve per engine and setting "
      "family; points labelled with their time step (engines, RK4; s) or rtol (dopri5, dop853)." +
          std::string(duration > 0.0 ? " Left of the dotted line a run is faster than "
                                       "real time."
                                     : ""));
  if (!not_drawn_error.empty()) {
    std::string s =
        "Not drawn (zero error, e.g. the tight reference's own setting; no place "
        "on a log axis): ";
    for (size_t i = 0; i < not_drawn_error.size(); ++i) {
      s += (i ? "; " : "") + not_drawn_error[i];
    }
    page.Paragraph(s + ".");
  }
  page.Figure("figures/peak_error.svg",
              "|Peak relative error| (" +
                  (blocks >= 3 ? std::string("the largest of theta1's to theta") +
                                     std::to_string(blocks) + "'s"
                               : std::string("the larger of theta1's and theta2's")) +
                  ") against wall time; the red line is the 1% criterion.");
  if (!not_drawn_peak.empty()) {
    std::string s = "Not drawn (zero peak error): ";
    for (size_t i = 0; i < not_drawn_peak.size(); ++i) s += (i ? "; " : "") + not_drawn_peak[i];
    page.Paragraph(s + ".");
  }
}

// A body's error as the table of all runs shows it, "%.2e"; empty when the row lacks the body.
std::string BodyCell(const SweepRecord& r, int body, double SweepBodyErrors::*error) {
  if (body > static_cast<int>(r.bodies.size())) return "";
  return Format("%.2e", r.bodies[static_cast<size_t>(body - 1)].*error);
}

// The largest |error| of bodies 3..N of a row, "%.2e (θk)"; empty for one or two bodies.
std::string LargestFromThirdBody(const SweepRecord& r, double SweepBodyErrors::*error) {
  if (r.bodies.size() < 3) return "";
  size_t w = 2;
  for (size_t k = 3; k < r.bodies.size(); ++k) {
    if (std::fabs(r.bodies[k].*error) > std::fabs(r.bodies[w].*error)) w = k;
  }
  return Format("%.2e", r.bodies[w].*error) + " (θ" + std::to_string(w + 1) + ")";
}

// Every usable run by family, with the observed order of convergence.
void RunsSection(const std::vector<SweepRecord>& rows, double duration, Page& page) {
  // N >= 3 blocks: blocks 3..N in two more columns, the largest of them each (one row per
  // run stays readable at 6 to 8 blocks).
  const int blocks = SweepBlocks(rows);
  const bool many = blocks >= 3;
  page.Heading("All runs by family");
  page.Paragraph(
      std::string("Max angle error: the max over the run of |theta_engine - theta_reference|, ") +
      (many ? "per block (blocks 3 to " + std::to_string(blocks) +
                  ": the largest of them, and which)"
            : "the larger of theta1's and theta2's") +
      ". Order: the observed order of convergence "
      "from the previous (coarser) setting of the family, log(e_coarse/e_fine) / "
      "log(s_coarse/s_fine). Real-time factor: simulated time / wall time (the simulated "
      "time ends where the reference overturns, if it does).");
  std::vector<std::vector<std::string>> table;
  for (const auto& [family, indices] : SweepFamilies(rows)) {
    for (size_t k = 0; k < indices.size(); ++k) {
      const SweepRecord& r = rows[indices[k]];
      std::optional<double> order;
      if (k > 0) order = ObservedOrder(rows[indices[k - 1]], r);
      std::vector<std::string> cells = {family,
                                        SweepSettingLabel(r),
                                        Format("%.3g", r.wall_s),
                                        duration > 0.0 ? Format("%.3g", duration / r.wall_s) : "",
                                        BodyCell(r, 1, &SweepBodyErrors::max_abs_error_rad),
                                        BodyCell(r, 2, &SweepBodyErrors::max_abs_error_rad)};
      if (many) cells.push_back(LargestFromThirdBody(r, &SweepBodyErrors::max_abs_error_rad));
      cells.push_back(BodyCell(r, 1, &SweepBodyErrors::peak_rel_error));
      cells.push_back(BodyCell(r, 2, &SweepBodyErrors::peak_rel_error));
      if (many) cells.push_back(LargestFromThirdBody(r, &SweepBodyErrors::peak_rel_error));
      for (std::string c :
           {std::to_string(r.impacts_matched) + "/" + std::to_string(r.impacts_reference),
            std::string(r.overturn_agree ? "yes" : "no"),
            std::string(ReachesPeakAgreement(r, 0.01) ? "yes" : "no"),
            order ? Format("%.2f", *order) : std::string(), r.status}) {
        cells.push_back(std::move(c));
      }
      table.push_back(std::move(cells));
    }
  }
  std::vector<std::string> header = {"family",      "setting",          "wall (s)",
                                     "x real time", "max err θ1 (rad)", "max err θ2 (rad)"};
  const std::string range = blocks == 3 ? std::string("θ3") : "θ3-θ" + std::to_string(blocks);
  if (many) header.push_back("max err " + range + " (largest, rad)");
  header.push_back("peak rel err θ1");
  header.push_back("peak rel err θ2");
  if (many) header.push_back("peak rel err " + range + " (largest)");
  for (const char* h : {"impacts matched", "same overturn", "1% peak", "order", "status"}) {
    header.push_back(h);
  }
  page.Table(header, table);
}

// The failed rows with their sweep.csv line.
void FailedSection(const std::vector<SweepRecord>& rows, const std::vector<size_t>& failed,
                   Page& page) {
  if (failed.empty()) return;
  page.Heading("Failed runs");
  std::vector<std::vector<std::string>> ft;
  for (size_t i : failed) {
    ft.push_back({std::to_string(rows[i].line), SweepFamily(rows[i]), SweepSettingLabel(rows[i]),
                  rows[i].failure});
  }
  page.Table({"sweep.csv line", "family", "setting", "why"}, ft);
}

}  // namespace

std::string SweepReportName(const fs::path& sweep_dir) {
  // As `rockbench report` names run folders: the last component of the absolute path.
  const fs::path p = fs::absolute(sweep_dir).lexically_normal();
  const std::string name =
      p.filename().empty() ? p.parent_path().filename().string() : p.filename().string();
  return name.empty() ? "sweep" : name;
}

std::filesystem::path WriteSweepReport(const fs::path& sweep_dir, const fs::path& out_dir) {
  const fs::path csv = sweep_dir / "sweep.csv";
  const std::vector<SweepRecord> rows = ParseSweepCsv(ReadTextFile(csv), csv);
  const SweepInfo info = ReadSweepInfo(sweep_dir / "sweep.json");
  const std::string name = SweepReportName(sweep_dir);
  const fs::path page_dir = out_dir / name;
  const fs::path fig_dir = page_dir / "figures";
  fs::create_directories(fig_dir);

  std::string title = "Work-precision: ";
  title += info.present && !info.scene_title.empty() ? info.scene_title : name;
  Page page(title);
  const std::vector<size_t> failed = WarningsSection(rows, info, page);
  SweepSection(sweep_dir, rows, info, page);
  StatementSection(rows, info, page);
  RankingSection(rows, info, page);
  FiguresSection(rows, info, fig_dir, page);
  RunsSection(rows, info.present ? info.span_s() : 0.0, page);
  FailedSection(rows, failed, page);
  page.Paragraph(
      "Each figure's gnuplot script (.gp) and data (.dat) are kept beside its SVG in "
      "figures/: edit the script and run `gnuplot NAME.gp` there to restyle it.");

  WriteFileAtomic(page_dir / "report.html", page.Html(page_dir));
  WriteFileAtomic(page_dir / "report.md", page.Markdown());
  return page_dir;
}

}  // namespace rockbench::report
