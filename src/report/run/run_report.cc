#include "report/run/run_report.h"

#include <stdexcept>

#include "files/atomic_file.h"
#include "motion/ground_motion.h"
#include "reference/stack_model.h"
#include "report/common/page.h"
#include "report/compare/agreement_section.h"
#include "report/run/angles_section.h"
#include "report/run/cylinder_sections.h"
#include "report/run/energy_section.h"
#include "report/run/friction_section.h"
#include "report/run/impacts_section.h"
#include "report/run/outcome_section.h"
#include "report/run/pictures_section.h"
#include "report/run/run_figures.h"
#include "report/run/run_readers.h"
#include "report/run/scene_section.h"

namespace rockbench::report {

namespace fs = std::filesystem;

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

  if (run.scene.three_dimensional()) {
    // A cylinder: its own outcome, scene, tilt and axis-path figures and events; the planar
    // stack's angles, agreement, impacts, energy and friction are not its (docs/report.md).
    result.outcome = CylinderOutcome(run, result.warnings);
    page.Heading("Outcome");
    page.Paragraph(result.outcome);
    VerdictSection(run, page, result);
    CylinderSceneSection(run, motion, fig);
    page.Heading("Tilt and axis path");
    CylinderTiltFigure(run, fig);
    CylinderAxisPathFigure(run, fig);
    CylinderEventsSection(run, fig);
    PicturesSection(run, motion, options, fig, result);
    result.left_out.push_back(
        "the planar stack's sections (theta angles, the angle-error figures, impacts, energy, "
        "friction): a cylinder rocks in 3-D; its tilt, axis path and events are above, and a "
        "compare folder's verdict on tilt_x1 and tilt_y1 is in the Verdict");
  } else {
    const reference::StackModel model(run.scene);
    // Outcome in words; the warnings go to the top of the page.
    std::string outcome = ReferenceOutcome(run, result.warnings);
    const FrictionFacts ff = ComputeFriction(run, model, motion, options);
    FrictionWarnings(run, model, ff, result.warnings);
    outcome += EnginesOutcome(run, result.warnings);
    result.outcome = outcome;

    page.Heading("Outcome");
    page.Paragraph(outcome);
    VerdictSection(run, page, result);
    SceneSection(run, motion, fig);
    page.Heading("Angles");
    AnglesFigure(run, fig);
    AgreementSection(run, options, fig);
    ImpactsSection(run, fig);
    EnergySection(run, model, fig);
    FrictionSection(run, ff, options, fig);
    PicturesSection(run, motion, options, fig, result);
  }
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
