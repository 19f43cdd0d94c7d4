// The ensemble report: assembles the study's sections (ensemble_sections.h) into one page.
#include "report/study/study_report.h"

#include <map>

#include "report/common/number_text.h"
#include "report/common/page.h"
#include "report/study/study_csv.h"
#include "report/study/study_sections.h"
#include "scene/history.h"

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
  if (HasSpectrumAxes(d)) SpectraSection(d, fig_dir, body, findings);
  if (HasMotionSuite(d)) {
    FragilitySection(d, fig_dir, body, findings);
    FragilitySurfaceSection(d, fig_dir, body, findings);
  }
  if (d.Axis("base.horizontal.pga_g") >= 0 || HasMotionSuite(d)) ScatterSection(d, fig_dir, body);
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
