// Fragility curves over PGA for motion-suite studies (reference and each engine, per group of
// the geometry axes), the paired bootstrap of the difference of medians, and the peak-angle
// scatter.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "renders/renderer.h"
#include "report/common/gnuplot.h"
#include "report/common/number_text.h"
#include "report/study/study_sections.h"
#include "run/engine_registry.h"
#include "statistics/statistics.h"
#include "study/fragility.h"

namespace rockbench::report {
namespace {

// Axes that choose or scale the motion: the rest are the geometry (and settings) groups.
const std::vector<std::string>& MotionAxes() {
  static const std::vector<std::string> keys = {
      "base.horizontal.file",    "base.horizontal.seed",      "base.horizontal.pga_g",
      "base.horizontal.pgv_mps", "base.horizontal.scale",     "base.horizontal.amplitude_g",
      "pulse.amplitude_ratio",   "base.horizontal.intensity", "base.transverse.file",
      "base.transverse.scale",   "base.pga_resultant_g"};
  return keys;
}

// Members of one group: member -> (PGA, failed) per engine, usable runs only; and per engine
// each usable run's (PGA, the block that overturned first, 0 for none).
struct GroupData {
  PointsByMember<stats::FragilityPoint> members;
  std::map<std::string, std::vector<std::pair<double, int>>> overturned_block;
};

// The paired bootstrap of median(engine) - median(reference): members drawn with replacement,
// the same draw for both; each resample refitted. Percentile interval at 95%.
struct MedianDifference {
  double estimate = std::nan("");
  double lo = std::nan(""), hi = std::nan("");
  int resamples = 0, degenerate = 0;
};

MedianDifference PairedDifference(const std::vector<stats::FragilityPoint>& ref,
                                  const std::vector<stats::FragilityPoint>& eng, int draws) {
  MedianDifference out;
  const stats::LognormalFragility a = stats::FitLognormalFragility(ref, 0);
  const stats::LognormalFragility b = stats::FitLognormalFragility(eng, 0);
  if (!a.available || !b.available) return out;
  out.estimate = b.median - a.median;
  std::vector<stats::FragilityPoint> ra(ref.size()), rb(eng.size());
  const stats::BootstrapDraws d =
      stats::Bootstrap(ref.size(), draws, 0x656e73656d626c65, 1,
                       [&](std::span<const size_t> members, std::vector<double>& diff) {
                         for (size_t i = 0; i < ref.size(); ++i) {
                           ra[i] = ref[members[i]];
                           rb[i] = eng[members[i]];
                         }
                         const stats::LognormalFragility fa = stats::FitLognormalFragility(ra, 0);
                         const stats::LognormalFragility fb = stats::FitLognormalFragility(rb, 0);
                         if (!fa.available || !fb.available) return false;
                         diff[0] = fb.median - fa.median;
                         return true;
                       });
  out.resamples = d.resamples;
  out.degenerate = d.degenerate;
  if (d.values[0].size() < 20) return out;
  out.lo = stats::LowerOrderPercentile(d.values[0], 0.025);
  out.hi = stats::LowerOrderPercentile(d.values[0], 0.975);
  return out;
}

std::string FitText(const stats::LognormalFragility& f) {
  if (!f.available) return "no fit (" + f.reason + ")";
  return Num(f.median, 3) + " g [" + Num(f.median_lo, 3) + ", " + Num(f.median_hi, 3) + "]";
}

// N >= 3 blocks: the fragility of each block's overturning, per group and run. Block k
// overturns when it and the blocks above it (the sub-stack k..N) fall off block k - 1 (the
// ground for k = 1) before any other block overturns: that member is a failure of block k's
// fit and a survival of every other block's.
void BlockFragilityTable(const EnsembleData& d, const std::vector<std::string>& order,
                         const std::map<std::string, GroupData>& groups, Page& page) {
  std::vector<std::vector<std::string>> table;
  for (const std::string& g : order) {
    for (const std::string& e : d.engines) {
      const auto it = groups.at(g).overturned_block.find(e);
      if (it == groups.at(g).overturned_block.end()) continue;
      for (int b = 1; b <= d.blocks; ++b) {
        std::vector<stats::FragilityPoint> points;
        for (const auto& [pga, block] : it->second) points.push_back({pga, block == b});
        const stats::LognormalFragility fit = stats::FitLognormalFragility(points, 1000);
        table.push_back({g.empty() ? "all" : g, e,
                         std::string("block ") + std::to_string(b) + " (blocks " +
                             std::to_string(b) + "-" + std::to_string(d.blocks) + ")",
                         std::to_string(fit.n), std::to_string(fit.failures), FitText(fit),
                         fit.available ? Num(fit.beta, 3) : ""});
      }
    }
  }
  page.Paragraph(
      "By the block that overturns: the same lognormal fit, per block, of P(block k overturns | "
      "PGA): block k falls off block k - 1 (block 1: off the ground) and takes the blocks above "
      "it (the sub-stack k to " +
      std::to_string(d.blocks) +
      ") before any other block overturns; a member where another block overturned counts as a "
      "survival of block k. Medians with the 95% percentile bootstrap interval of 1000 "
      "resamples.");
  page.Table({"group", "run", "overturning block (sub-stack)", "members", "overturned",
              "median PGA [95%]", "beta"},
             table);
}

// The members grouped by motion (GroupLabel), in the order the groups first appear; the runs
// without an outcome or a PGA counted per engine.
struct Groups {
  std::map<std::string, GroupData> data;
  std::vector<std::string> order;
  std::map<std::string, int> left_out;  // engine -> runs left out
};

Groups GroupMembers(const EnsembleData& d) {
  const std::vector<int> motion = MotionAxisColumns(d);
  Groups groups;
  for (const EnsembleRecord& r : d.records) {
    const std::string g = GroupLabel(d, r, motion);
    if (!groups.data.count(g)) groups.order.push_back(g);
    const std::optional<double> pga = d.Pga_g(r);
    if (!r.usable() || !pga || !(*pga > 0.0)) {
      ++groups.left_out[r.engine];
      continue;
    }
    groups.data[g].members[r.member][r.engine] = {*pga, r.overturned_block != 0};
    groups.data[g].overturned_block[r.engine].push_back({*pga, r.overturned_block});
  }
  return groups;
}

// One run's curves in a group's figure: the fraction of members overturned at each PGA and,
// when fitted, the fit with its band up to 1.1 `max_pga` (g); adds the data files to `fig` and
// the plot clauses to `plots`.
void PlotRun(const std::string& e, const std::vector<stats::FragilityPoint>& points,
             const stats::LognormalFragility& fit, double max_pga, int colour, GnuplotFigure& fig,
             std::string& plots) {
  // Empirical fractions per PGA value (a record scaled to a target PGA measures it back
  // to within rounding: 6 significant digits make one bin).
  std::map<double, std::pair<int, int>> bins;
  for (const auto& p : points) {
    const double key = std::stod(Num(p.im, 6));
    bins[key].first += p.failed;
    bins[key].second += 1;
  }
  std::string pts, curve;
  for (const auto& [x, c] : bins) {
    pts += Num(x, 10) + " " + Num(static_cast<double>(c.first) / c.second, 10) + "\n";
  }
  if (fit.available) {
    for (int k = 1; k <= 200; ++k) {
      const double x = 1.1 * max_pga * k / 200.0;
      const double lo = stats::FragilityAt({true, "", fit.median_hi, fit.beta}, x);
      const double hi = stats::FragilityAt({true, "", fit.median_lo, fit.beta}, x);
      curve += Num(x, 10) + " " + Num(stats::FragilityAt(fit, x), 10) + " " + Num(lo, 10) + " " +
               Num(hi, 10) + "\n";
    }
  }
  const std::string pf = fig.name + "_" + e + "_points.dat";
  fig.data_files.push_back({pf, pts});
  const std::string lc = " lc " + std::to_string(colour);
  plots += (plots.empty() ? "" : ", ") + GnuplotQuote(pf) + " using 1:2 with points pt 7" + lc +
           " title " + GnuplotQuote(e + " (fraction)");
  if (fit.available) {
    const std::string cf = fig.name + "_" + e + "_fit.dat";
    fig.data_files.push_back({cf, curve});
    plots += ", " + GnuplotQuote(cf) + " using 1:3:4 with filledcurves" + lc + " notitle, " +
             GnuplotQuote(cf) + " using 1:2 with lines lw 2" + lc + " title " +
             GnuplotQuote(e + " (lognormal fit)");
  }
}

// Engine `e`'s median PGA of overturning against the reference's on the members of group `g`
// where both have an outcome: the table's cell (the paired bootstrap's difference, or "no
// paired fit"), and a finding in words.
std::string PairedMedianCell(const std::string& g, const std::string& e,
                             const PointsByMember<stats::FragilityPoint>& members,
                             std::vector<std::string>& findings) {
  const auto [a, b] = PairedWithReference(members, e);
  const MedianDifference md = PairedDifference(a, b, 400);
  if (std::isnan(md.lo)) return "no paired fit";
  int same = 0;
  for (size_t i = 0; i < a.size(); ++i) same += a[i].failed == b[i].failed;
  const bool differs = md.lo > 0.0 || md.hi < 0.0;
  std::string f = e + (g.empty() ? std::string() : " (" + g + ")") + ", on the " +
                  std::to_string(a.size()) + " members where both runs have an " +
                  "outcome (the same outcome on " + std::to_string(same) +
                  "): median PGA of overturning " + FitText(stats::FitLognormalFragility(b, 1000)) +
                  " against the reference's " + FitText(stats::FitLognormalFragility(a, 1000)) +
                  "; the difference, " + Num(md.estimate, 3) + " g [" + Num(md.lo, 3) + ", " +
                  Num(md.hi, 3) + "], ";
  if (same == static_cast<int>(a.size())) {
    f += "is zero: the two curves are the same.";
  } else if (differs) {
    f += "excludes zero: the engine's fragility curve differs from the reference's.";
  } else {
    f += "contains zero: no difference is detected with these members.";
  }
  findings.push_back(f);
  return Num(md.estimate, 3) + " g [" + Num(md.lo, 3) + ", " + Num(md.hi, 3) + "]";
}

}  // namespace

std::vector<int> MotionAxisColumns(const EnsembleData& d) {
  std::vector<int> cols;
  for (const std::string& k : MotionAxes()) {
    if (d.Axis(k) >= 0) cols.push_back(d.Axis(k));
  }
  return cols;
}

bool HasMotionSuite(const EnsembleData& d) {
  return d.Axis("base.horizontal.file") >= 0 || d.Axis("base.horizontal.seed") >= 0;
}

void FragilitySection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page,
                      std::vector<std::string>& findings) {
  page.Heading("Fragility curves");
  if (d.cylinder) {
    page.Paragraph(
        "The body is a cylinder rocking, rolling and wobbling in 3-D (docs/three-d.md): "
        "overturned = its tilt reached the overturn angle (model.overturn_angle), toward any "
        "azimuth. The intensity measure is the peak of the horizontal resultant, max over t of "
        "sqrt(a_x(t)^2 + a_y(t)^2) in g (members.csv's pga_resultant_g): \"PGA\" below is "
        "that resultant PGA.");
  }
  page.Paragraph(
      "P(overturn | PGA), the lognormal form Phi(ln(PGA / median) / beta) fitted by maximum "
      "likelihood (Baker 2015) to the members whose run has an outcome (runs where the "
      "reference's model stopped, and runs without a result, are left out of both fits: they "
      "are counted in the table). Medians with the 95% percentile bootstrap interval of 1000 "
      "resamples; the difference of an engine's median from the reference's with the interval "
      "of a paired bootstrap (the same members drawn for both, 400 resamples). Points: the "
      "fraction of members overturned at each PGA of the study; lines: the fits; band: the "
      "fit's curve at the two ends of its median's interval.");
  Groups groups = GroupMembers(d);
  std::vector<std::vector<std::string>> table;
  int index = 0;
  for (const std::string& g : groups.order) {
    GnuplotFigure fig;
    fig.name = "fragility_" + std::to_string(index++);
    const std::string script = "set xlabel \"" + d.PgaName() +
                               " (g)\"\nset ylabel \"P(overturn)\"\nset yrange [-0.02:1.02]\n"
                               "set key left top\nset style fill transparent solid 0.15 noborder\n";
    std::string plots;
    bool reference_plotted = false;
    std::map<std::string, std::vector<stats::FragilityPoint>> by_engine;
    for (const auto& [m, runs] : groups.data[g].members) {
      for (const auto& [e, p] : runs) by_engine[e].push_back(p);
    }
    double max_pga = 0.0;
    for (const auto& [e, pts] : by_engine) {
      for (const auto& p : pts) max_pga = std::max(max_pga, p.im);
    }
    int colour = 1;
    for (const std::string& e : d.engines) {
      const auto it = by_engine.find(e);
      if (it == by_engine.end()) continue;
      const stats::LognormalFragility fit = stats::FitLognormalFragility(it->second, 1000);
      PlotRun(e, it->second, fit, max_pga, colour++, fig, plots);
      // The reference's row, then each engine's against it (once the reference has points).
      if (IsReference(e)) reference_plotted = !it->second.empty();
      const std::string paired = !IsReference(e) && reference_plotted
                                     ? PairedMedianCell(g, e, groups.data[g].members, findings)
                                     : "";
      table.push_back({g.empty() ? "all" : g, e, std::to_string(fit.n),
                       std::to_string(fit.failures), FitText(fit),
                       fit.available ? Num(fit.beta, 3) : "", paired});
    }
    fig.script = script + "plot " + plots + "\n";
    RenderGnuplot(fig_dir, fig);
    page.Figure(std::filesystem::path("figures") / (fig.name + ".svg"),
                "Fragility over " + d.PgaName() + (g.empty() ? std::string() : ": " + g));
  }
  page.Table({"group", "run", "members", "overturned", "median PGA [95%]", "beta",
              "median - reference's [95%, paired]"},
             table);
  if (d.blocks >= 3) BlockFragilityTable(d, groups.order, groups.data, page);
  std::string out;
  for (const auto& [e, n] : groups.left_out) {
    out += (out.empty() ? "" : "; ") + e + " " + std::to_string(n);
  }
  if (!out.empty()) {
    page.Paragraph(
        "Runs left out of the fits (no outcome, or the reference's model stopped): " + out + ".");
  }
}

namespace {

// Draws a figure of peak angles (log y, `ylabel`) against PGA from its `plots` and puts it on
// the page with its caption.
void DrawScatter(GnuplotFigure& fig, const std::string& plots, const std::string& ylabel,
                 const std::string& caption, const std::filesystem::path& fig_dir, Page& page,
                 const std::string& xlabel = "PGA") {
  fig.script = "set logscale y\nset xlabel \"" + xlabel + " (g)\"\nset ylabel \"";
  fig.script += ylabel + "\"\nset key left top\nplot " + plots + "\n";
  RenderGnuplot(fig_dir, fig);
  page.Figure(std::filesystem::path("figures") / (fig.name + ".svg"), caption);
}

// A colour of the renders' palette as gnuplot reads it: "#284882".
std::string HexColour(renders::Rgb c) {
  char out[8];
  std::snprintf(out, sizeof out, "#%02x%02x%02x", static_cast<unsigned>(c.r),
                static_cast<unsigned>(c.g), static_cast<unsigned>(c.b));
  return out;
}

// N >= 3 blocks: a figure per run, one series per block (its peak |theta_k| against the PGA),
// in the colours the renders give the blocks' traces.
void BlocksScatter(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page) {
  const renders::Palette palette;
  bool any = false;
  for (const std::string& e : d.engines) {
    GnuplotFigure fig;
    fig.name = "peak_theta_vs_pga_" + e;
    std::string plots;
    for (int b = 1; b <= d.blocks; ++b) {
      std::string data;
      for (const EnsembleRecord& r : d.records) {
        if (r.engine != e || !r.usable() || !r.pga_g) continue;
        if (static_cast<int>(r.peak_theta_rad.size()) < b || !(r.peak_theta_rad[b - 1] > 0.0)) {
          continue;
        }
        data += Num(*r.pga_g, 10) + " " + Num(r.peak_theta_rad[b - 1], 10) + "\n";
      }
      if (data.empty()) continue;
      const std::string f = fig.name + "_block" + std::to_string(b) + ".dat";
      fig.data_files.push_back({f, data});
      plots += (plots.empty() ? "" : ", ") + GnuplotQuote(f) +
               " using 1:2 with points pt 7 lc rgb " +
               GnuplotQuote(HexColour(palette.chart_theta(b - 1))) + " title " +
               GnuplotQuote(std::string("block ") + std::to_string(b));
    }
    if (plots.empty()) continue;
    any = true;
    DrawScatter(fig, plots, "peak |theta_k| (rad)",
                e + ": the peak |theta_k| of every block (block 1 the bottom, block " +
                    std::to_string(d.blocks) +
                    " the top) in each run that rocked against the PGA of its motion (an "
                    "overturned block at its overturn angle); blocks at rest are left out of the "
                    "log axis.",
                fig_dir, page);
  }
  if (!any) page.Paragraph("No run rocked: nothing to draw.");
}

}  // namespace

void ScatterSection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page) {
  page.Heading(d.cylinder ? "Peak tilt against resultant PGA" : "Peak angle against PGA");
  if (d.blocks >= 3) {
    BlocksScatter(d, fig_dir, page);
    return;
  }
  GnuplotFigure fig;
  fig.name = "peak_theta1_vs_pga";
  std::string plots;
  int colour = 1;
  for (const std::string& e : d.engines) {
    std::string data;
    for (const EnsembleRecord& r : d.records) {
      const std::optional<double> pga = d.Pga_g(r);
      if (r.engine != e || !r.usable() || !pga || !(r.peak_theta1_rad > 0.0)) continue;
      data += Num(*pga, 10) + " " + Num(r.peak_theta1_rad, 10) + "\n";
    }
    if (data.empty()) continue;
    const std::string f = fig.name + "_" + e + ".dat";
    fig.data_files.push_back({f, data});
    plots += (plots.empty() ? "" : ", ") + GnuplotQuote(f) + " using 1:2 with points pt " +
             std::to_string(colour == 1 ? 7 : 6) + " lc " + std::to_string(colour) + " title " +
             GnuplotQuote(e);
    ++colour;
  }
  if (plots.empty()) {
    page.Paragraph("No run rocked: nothing to draw.");
    return;
  }
  if (d.cylinder) {
    DrawScatter(fig, plots, "peak tilt (rad)",
                "Peak tilt of the cylinder in every run that rocked against the resultant PGA of "
                "its motion (an overturned cylinder at its overturn angle); runs at rest are left "
                "out of the log axis.",
                fig_dir, page, d.PgaName());
    return;
  }
  DrawScatter(fig, plots, "peak |theta1| (rad)",
              "Peak |theta1| of every run that rocked against the PGA of its motion (an "
              "overturned block at its overturn angle); runs at rest are left out of the log "
              "axis.",
              fig_dir, page);
}

}  // namespace rockbench::report
