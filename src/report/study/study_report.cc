// The ensemble report: assembles the study's sections (ensemble_sections.h) into one page.
#include "report/study/study_report.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "files/atomic_file.h"
#include "report/common/number_text.h"
#include "report/common/page.h"
#include "report/study/study_csv.h"
#include "report/study/study_sections.h"
#include "scene/history.h"
#include "statistics/statistics.h"

namespace rockbench::report {
namespace {

// Runs per engine and status.
void StudySection(const EnsembleData& d, Page& page) {
  page.Heading("The study");
  std::string axes;
  for (const std::string& a : d.axes) axes += (axes.empty() ? "" : ", ") + a;
  page.Paragraph(std::to_string(d.members) + " members over the axes " +
                 (axes.empty() ? std::string("(none)") : axes) + ", each run by " +
                 std::to_string(d.engines.size()) + " runs; " + Num(d.wall_s, 3) +
                 " s of wall time on " + std::to_string(d.ranks) + " rank(s) of " +
                 std::to_string(d.jobs) + " worker(s), of which " + Num(d.serial_s, 3) +
                 " s serial (reading the study and the journal, merging the rows).");
  std::map<std::string, std::map<std::string, int>> counts;
  std::map<std::string, double> wall;
  for (const EnsembleRecord& r : d.records) {
    counts[r.engine][r.status]++;
    wall[r.engine] += r.wall_s;
  }
  std::vector<std::vector<std::string>> rows;
  for (const std::string& e : d.engines) {
    std::string statuses;
    int n = 0;
    for (const auto& [s, c] : counts[e]) {
      statuses += (statuses.empty() ? "" : ", ") + s + " " + std::to_string(c);
      n += c;
    }
    rows.push_back(
        {e, std::to_string(n), statuses, n > 0 ? Num(wall[e] / n * 1e3, 3) + " ms" : ""});
  }
  page.Table({"run", "runs", "statuses", "mean wall time per run"}, rows);
}

// A cylinder study: per engine, on the members where both it and the reference have an outcome,
// how often the overturn agrees, and where both overturned, by how much its time and its
// azimuth (the direction of the fall) differ from the reference's.
void CylinderSection(const EnsembleData& d, Page& page, std::vector<std::string>& findings) {
  if (!d.cylinder) return;
  page.Heading("Cylinder: overturns against the reference");
  page.Paragraph(
      "The body is a cylinder rocking, rolling and wobbling in 3-D (docs/three-d.md); overturned "
      "= its tilt reached the overturn angle (model.overturn_angle), toward the azimuth given "
      "(from +x toward +y). Per engine, on the members where both it and the reference have an "
      "outcome: the members with the same outcome, and where both overturned the median and "
      "largest difference of the overturn's time and of its azimuth (wrapped to [0, pi]).");
  std::map<long long, const EnsembleRecord*> reference;
  for (const EnsembleRecord& r : d.records) {
    if (r.engine == "reference" && r.usable()) reference[r.member] = &r;
  }
  std::vector<std::vector<std::string>> rows;
  for (const std::string& e : d.engines) {
    if (e == "reference") continue;
    int both = 0, same = 0;
    std::vector<double> dt, dphi;
    for (const EnsembleRecord& r : d.records) {
      if (r.engine != e || !r.usable()) continue;
      const auto it = reference.find(r.member);
      if (it == reference.end()) continue;
      const EnsembleRecord& ref = *it->second;
      ++both;
      same += (r.overturned_block != 0) == (ref.overturned_block != 0);
      if (r.overturned_block != 0 && ref.overturned_block != 0) {
        dt.push_back(std::abs(r.overturn_t_s - ref.overturn_t_s));
        if (r.overturn_azimuth_rad && ref.overturn_azimuth_rad) {
          const double a = std::remainder(*r.overturn_azimuth_rad - *ref.overturn_azimuth_rad,
                                          2.0 * 3.14159265358979323846);
          dphi.push_back(std::abs(a));
        }
      }
    }
    const auto median = [](const std::vector<double>& v) {
      return v.empty() ? std::string() : Num(stats::Median(v), 3);
    };
    const auto largest = [](const std::vector<double>& v) {
      return v.empty() ? std::string() : Num(*std::max_element(v.begin(), v.end()), 3);
    };
    rows.push_back({e, std::to_string(both), std::to_string(same), std::to_string(dt.size()),
                    median(dt), largest(dt), median(dphi), largest(dphi)});
    if (both > 0) {
      findings.push_back(e + " (cylinder): the reference's outcome (overturned or not) on " +
                         std::to_string(same) + " of " + std::to_string(both) + " members" +
                         (dt.empty() ? std::string(".")
                                     : "; where both overturned (" + std::to_string(dt.size()) +
                                           "), the overturn's time differs by " + median(dt) +
                                           " s (median; at most " + largest(dt) +
                                           " s) and its azimuth by " + median(dphi) +
                                           " rad (median; at most " + largest(dphi) + " rad)."));
    }
  }
  page.Table({"run", "members (both with an outcome)", "same outcome", "both overturned",
              "median |dt| (s)", "largest |dt| (s)", "median |d azimuth| (rad)",
              "largest |d azimuth| (rad)"},
             rows);
}

}  // namespace

void BlocksSection(const EnsembleData& d, Page& page, std::vector<std::string>& findings) {
  if (d.blocks < 3) return;
  page.Heading("By block");
  page.Paragraph(
      "A stack of " + std::to_string(d.blocks) +
      " blocks: per run and block, the members in which that block overturned first (block 1 "
      "takes the stack with it; block k > 1 fell off block k - 1) and the peak |theta_k| over "
      "the members with a usable outcome (the median, and the largest; an overturned block's "
      "peak is its overturn angle).");
  std::vector<std::vector<std::string>> rows;
  for (const std::string& e : d.engines) {
    std::vector<int> overturned(static_cast<size_t>(d.blocks) + 1, 0);
    std::vector<std::vector<double>> peaks(static_cast<size_t>(d.blocks));
    int usable = 0;
    for (const EnsembleRecord& r : d.records) {
      if (r.engine != e || !r.usable()) continue;
      ++usable;
      if (r.overturned_block >= 1 && r.overturned_block <= d.blocks) {
        ++overturned[r.overturned_block];
      }
      for (int b = 0; b < d.blocks && b < static_cast<int>(r.peak_theta_rad.size()); ++b) {
        peaks[b].push_back(r.peak_theta_rad[b]);
      }
    }
    int most = 0;
    for (int b = 1; b <= d.blocks; ++b) {
      if (overturned[b] > overturned[most]) most = b;
      const std::vector<double>& p = peaks[b - 1];
      rows.push_back({e, "block " + std::to_string(b),
                      std::to_string(overturned[b]) + " of " + std::to_string(usable),
                      p.empty() ? "" : Num(stats::Median(p), 4) + " rad",
                      p.empty() ? "" : Num(*std::max_element(p.begin(), p.end()), 4) + " rad"});
    }
    if (most > 0) {
      findings.push_back(e + ": block " + std::to_string(most) + " overturns first most often (" +
                         std::to_string(overturned[most]) + " of " + std::to_string(usable) +
                         " members with an outcome).");
    }
  }
  page.Table({"run", "block", "overturned first", "median peak |theta|", "largest peak |theta|"},
             rows);
}

namespace {

std::string FolderName(const std::filesystem::path& dir) {
  const std::filesystem::path p = dir.lexically_normal();
  std::string name = (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
  return name.empty() ? "ensemble" : name;
}

}  // namespace

std::filesystem::path WriteEnsembleReport(const std::filesystem::path& ensemble_dir,
                                          const std::filesystem::path& out_dir) {
  const EnsembleData d = ReadEnsemble(ensemble_dir);
  const std::filesystem::path page_dir = out_dir / FolderName(ensemble_dir);
  const std::filesystem::path fig_dir = page_dir / "figures";
  std::filesystem::create_directories(fig_dir);
  Page page("Ensemble: " + (d.title.empty() ? FolderName(ensemble_dir) : d.title));
  std::vector<std::string> findings;
  // The sections first (they collect the findings), the findings above them.
  Page body("");
  StudySection(d, body);
  BlocksSection(d, body, findings);
  if (HasSpectrumAxes(d)) SpectraSection(d, fig_dir, body, findings);
  if (HasMotionSuite(d)) {
    FragilitySection(d, fig_dir, body, findings);
    // The two-parameter surface pairs PGA with PGV / PGA of one component: not drawn over a
    // cylinder's resultant PGA.
    if (!d.cylinder) FragilitySurfaceSection(d, fig_dir, body, findings);
  }
  CylinderSection(d, body, findings);
  if (d.Axis("base.horizontal.pga_g") >= 0 || d.Axis("base.pga_resultant_g") >= 0 ||
      HasMotionSuite(d)) {
    ScatterSection(d, fig_dir, body);
  }
  page.Heading("In plain words");
  if (findings.empty()) {
    page.Paragraph(
        "This study has neither pulse-spectrum axes nor a motion suite: its rows are "
        "in members.csv, summarised below.");
  }
  for (const std::string& f : findings) page.Paragraph(f);
  page.Append(body);
  page.Paragraph(
      "Each figure's gnuplot script (.gp) and data (.dat) are kept beside its SVG in figures/.");
  WriteFileAtomic(page_dir / "report.html", page.Html(page_dir));
  WriteFileAtomic(page_dir / "report.md", page.Markdown());
  return page_dir;
}

}  // namespace rockbench::report
