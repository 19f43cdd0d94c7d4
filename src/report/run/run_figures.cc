#include "report/run/run_figures.h"

#include <cmath>
#include <cstdio>

#include "report/common/json_keys.h"
#include "report/common/number_text.h"

namespace rockbench::report {

namespace fs = std::filesystem;
using nlohmann::json;

void AppendDat(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "NaN";
    return;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  out += buf;
}

std::string Quote(const std::string& s) {
  return GnuplotQuote(s);
}

std::string VerticalMark(double t, double t_end_s, const std::string& colour,
                         const std::string& label, double label_y_graph, bool boxed) {
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

std::string RunLineStyle(size_t i, const EngineData& e) {
  return std::string(" with lines lw ") + (i == 0 ? "2.2" : "1.4") + (i == 0 ? "" : " dt 2") +
         " lc rgb " + Quote(e.colour) + " title " + Quote(e.label);
}

std::string CommonAxes(double t_end_s) {
  return "set grid lc rgb '#dddddd'\nset xlabel 'time t (s)'\nset xrange [0:" + Num(t_end_s, 9) +
         "]\nset key top right box opaque\n";
}

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

std::string HorizonMark(const RunData& run, int block, double label_y_graph) {
  if (!run.predictability || block > static_cast<int>(run.predictability->horizon_s.size())) {
    return "";
  }
  const std::optional<double>& h = run.predictability->horizon_s[block - 1];
  if (!h || *h > run.t_end_s) return "";
  return VerticalMark(*h, run.t_end_s, kHorizonColour,
                      "predictability horizon " + Num(*h, 6) + " s", label_y_graph, true);
}

bool AnyHorizonMark(const RunData& run) {
  for (int b = 1; b <= run.scene.block_count(); ++b) {
    if (!HorizonMark(run, b, 0.5).empty()) return true;
  }
  return false;
}

std::string BlockTitle(int block, int blocks) {
  if (blocks <= 2) return block == 1 ? "block 1 (lower)" : "block 2 (upper)";
  std::string t = "block " + std::to_string(block);
  if (block == 1) t += " (bottom)";
  if (block == blocks) t += " (top)";
  return t;
}

int PanelsHeight_px(int blocks) {
  return blocks <= 1 ? 420 : blocks == 2 ? 720 : 240 * blocks;
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

void Figures::Add(const GnuplotFigure& f, const std::string& caption) {
  RenderGnuplot(dir, f);
  page->Figure(fs::path("figures") / (f.name + ".svg"), caption);
  ++count;
}

}  // namespace rockbench::report
