#include "report/run/impacts_section.h"

#include <set>

#include "engine/outcome.h"
#include "report/common/number_text.h"

namespace rockbench::report {
namespace {

int EventCode(const std::string& kind) {
  // Two blocks: "interface_impact"; N >= 3 blocks: "interface2_impact" ... "interfaceN_impact".
  const int interface = ImpactInterface(kind);
  if (interface >= 0) return interface == 0 ? 1 : 2;
  if (kind == "transition" || kind == "initiation") return 3;
  if (kind == "overturn" || kind == "left_support" || kind == "assumption_violated") return 4;
  return 0;  // rest and anything else: not drawn
}

}  // namespace

void ImpactsSection(const RunData& run, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Impacts and mode changes");
  std::vector<std::vector<std::string>> rows;
  std::string dat =
      "# t_s row code (1 ground impact, 2 interface impact, 3 transition or "
      "initiation, 4 overturn, left its support or assumption violated)\n";
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
              "overturn, left its support or violation"},
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
  const bool many = run.scene.block_count() >= 3;
  const char* kTitle[] = {"", "ground impact (block 1 lands)",
                          many ? "interface impact (a block lands on the one below)"
                               : "interface impact (block 2 lands on block 1)",
                          "transition or initiation (no impact)",
                          "overturn, left its support or assumption violated"};
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

}  // namespace rockbench::report
