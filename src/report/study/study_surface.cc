// The two-parameter fragility of a motion-suite study: overturning against PGA and PGV/PGA
// (Purvance, Anooshehpoor & Brune 2008), one median contour per run and group.
#include <cmath>
#include <map>

#include "report/common/gnuplot.h"
#include "report/common/number_text.h"
#include "report/study/study_sections.h"
#include "run/engine_registry.h"
#include "study/fragility_surface.h"

namespace rockbench::report {

void FragilitySurfaceSection(const EnsembleData& d, const std::filesystem::path& fig_dir,
                             Page& page, std::vector<std::string>& findings) {
  page.Heading("Fragility over PGA and PGV/PGA");
  page.Paragraph(
      "The form Purvance, Anooshehpoor & Brune (2008) use for rocking: P(overturn) = "
      "Phi((ln PGA - m0 - m1 ln(r / 0.1 s)) / beta) with r = PGV/PGA, fitted by maximum "
      "likelihood to the same members as the curves above. Lines: the median contour (P = "
      "0.5) of each run, PGA_50(r) = exp(m0) (r / 0.1 s)^m1; points: the reference's members, "
      "filled where they overturned. Each engine's median over the reference's, at the "
      "smallest, middle and largest PGV/PGA of the study, comes with a 95% paired bootstrap "
      "interval (the same members drawn for both runs, both surfaces refitted).");
  // Group label -> run -> points; and group label -> member -> run -> point (for pairing).
  const std::vector<int> motion = MotionAxisColumns(d);
  std::map<std::string, std::map<std::string, std::vector<stats::SurfacePoint>>> groups;
  std::map<std::string, PointsByMember<stats::SurfacePoint>> members;
  std::vector<std::string> order;
  double r_lo = INFINITY, r_hi = 0.0;
  for (const EnsembleRecord& r : d.records) {
    if (!r.usable() || !r.pga_g || !r.pgv_mps || !(*r.pga_g > 0.0) || !(*r.pgv_mps > 0.0)) {
      continue;
    }
    const std::string g = GroupLabel(d, r, motion);
    if (!groups.count(g)) order.push_back(g);
    const double ratio = *r.pgv_mps / (*r.pga_g * 9.80665);
    r_lo = std::min(r_lo, ratio), r_hi = std::max(r_hi, ratio);
    groups[g][r.engine].push_back({*r.pga_g, ratio, r.overturned_block != 0});
    members[g][r.member][r.engine] = groups[g][r.engine].back();
  }
  std::vector<std::vector<std::string>> table;
  int index = 0;
  for (const std::string& g : order) {
    GnuplotFigure fig;
    fig.name = "fragility_surface_" + std::to_string(index++);
    std::string plots;
    std::string over, stood;
    for (const auto& q : groups[g]["reference"]) {
      (q.failed ? over : stood) += Num(q.ratio_s, 10) + " " + Num(q.pga, 10) + "\n";
    }
    fig.data_files.push_back({fig.name + "_overturned.dat", over.empty() ? "nan nan\n" : over});
    fig.data_files.push_back({fig.name + "_stood.dat", stood.empty() ? "nan nan\n" : stood});
    plots = GnuplotQuote(fig.name + "_overturned.dat") +
            " using 1:2 with points pt 7 lc rgb \"#555555\" title \"reference: overturned\", " +
            GnuplotQuote(fig.name + "_stood.dat") +
            " using 1:2 with points pt 6 lc rgb \"#555555\" title \"reference: stood\"";
    std::map<std::string, stats::FragilitySurface> fits;
    int colour = 1;
    for (const std::string& e : d.engines) {
      const auto it = groups[g].find(e);
      if (it == groups[g].end()) continue;
      const stats::FragilitySurface s = stats::FitFragilitySurface(it->second, 0.1);
      fits[e] = s;
      table.push_back({g.empty() ? "all" : g, e, std::to_string(s.n), std::to_string(s.failures),
                       s.available ? Num(std::exp(s.m0), 3) + " g" : s.reason,
                       s.available ? Num(s.m1, 3) : "", s.available ? Num(s.beta, 3) : ""});
      if (!s.available) continue;
      std::string line;
      for (int k = 0; k <= 50; ++k) {
        const double r = r_lo * std::pow(r_hi / r_lo, k / 50.0);
        line += Num(r, 10) + " " + Num(s.PgaAt(0.5, r), 10) + "\n";
      }
      fig.data_files.push_back({fig.name + "_" + e + ".dat", line});
      plots += ", " + GnuplotQuote(fig.name + "_" + e + ".dat") + " using 1:2 with lines lw 2 lc " +
               std::to_string(colour++) + " title " + GnuplotQuote(e + ": median contour");
    }
    fig.script =
        "set logscale xy\nset xlabel \"PGV/PGA (s)\"\nset ylabel \"PGA (g)\"\nset key left top\n"
        "set xrange [" +
        Num(r_lo / 1.3, 4) + ":" + Num(r_hi * 1.3, 4) + "]\nplot " + plots + "\n";
    RenderGnuplot(fig_dir, fig);
    page.Figure(
        std::filesystem::path("figures") / (fig.name + ".svg"),
        "Median overturning contour over PGA and PGV/PGA" + (g.empty() ? std::string() : ": " + g));
    const auto ref = fits.find("reference");
    if (ref == fits.end() || !ref->second.available) continue;
    const double at[] = {r_lo, std::sqrt(r_lo * r_hi), r_hi};
    for (const auto& [e, s] : fits) {
      if (IsReference(e) || !s.available) continue;
      const auto [a, b] = PairedWithReference(members[g], e);
      const stats::SurfaceMedianRatio ratio = stats::PairedSurfaceRatio(a, b, at, 400);
      std::string text = e + (g.empty() ? std::string() : " (" + g + ")") +
                         ": its median overturning PGA over the reference's, on the " +
                         std::to_string(a.size()) + " members both runs have, across the " +
                         "study's PGV/PGA: ";
      if (!ratio.available) {
        text += "no paired fit (" + ratio.reason + ").";
        findings.push_back(text);
        continue;
      }
      bool differs = false;
      for (size_t k = 0; k < 3; ++k) {
        text += (k ? ", " : "") + Num(ratio.estimate[k], 3) + " [" + Num(ratio.lo[k], 3) + ", " +
                Num(ratio.hi[k], 3) + "] at " + Num(at[k], 2) + " s";
        differs = differs || ratio.lo[k] > 1.0 || ratio.hi[k] < 1.0;
      }
      std::string drawn =
          " (95% paired bootstrap, " + std::to_string(ratio.resamples) + " resamples";
      if (ratio.degenerate > 0) {
        drawn += ", " + std::to_string(ratio.degenerate) + " without a fit on both sides left out";
      }
      text += drawn + (differs ? "): an interval excludes 1, the engine's surface differs from "
                                 "the reference's there."
                               : "): every interval contains 1, no difference is detected with "
                                 "these members.");
      findings.push_back(text);
    }
  }
  page.Table({"group", "run", "members", "overturned", "median PGA at PGV/PGA = 0.1 s",
              "m1 (slope in ln PGV/PGA)", "beta"},
             table);
}

}  // namespace rockbench::report
