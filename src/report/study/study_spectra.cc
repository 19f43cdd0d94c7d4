// Overturning spectra of pulse studies: one map per group of the other axes, one panel per
// run (reference and engines), engine cells that disagree with the reference marked.
#include <algorithm>
#include <map>
#include <set>

#include "report/common/gnuplot.h"
#include "report/common/number_text.h"
#include "report/study/study_sections.h"
#include "run/engine_registry.h"

namespace rockbench::report {
namespace {

struct SpectrumAxes {
  int x = -1, y = -1;  // frequency and amplitude axis columns
  std::string x_label, y_label;
};

SpectrumAxes FindAxes(const EnsembleData& d) {
  SpectrumAxes a;
  if (d.Axis("pulse.frequency_ratio") >= 0 && d.Axis("pulse.amplitude_ratio") >= 0) {
    a.x = d.Axis("pulse.frequency_ratio");
    a.y = d.Axis("pulse.amplitude_ratio");
    a.x_label = "omega_p / p";
    a.y_label = "a_p / (g tan alpha_1)";
  } else if (d.Axis("base.horizontal.frequency_hz") >= 0 &&
             d.Axis("base.horizontal.amplitude_g") >= 0) {
    a.x = d.Axis("base.horizontal.frequency_hz");
    a.y = d.Axis("base.horizontal.amplitude_g");
    a.x_label = "pulse frequency (Hz)";
    a.y_label = "pulse amplitude (g)";
  }
  return a;
}

// RGB as an integer (gnuplot's "lc rgb variable" reads it from the data). Blocks 3 and up
// (kUpperBlock) have a colour each, from `kUpperColours` by block.
constexpr long kUpperColours[] = {0x38761d, 0x93c47d, 0x8e7cc3, 0xc27ba0, 0xe69138, 0x76a5af};
constexpr const char* kUpperColourNames[] = {"dark green", "light green", "purple",
                                             "pink",       "orange",      "teal"};

long ClassColour(OverturnClass c, int block) {
  switch (c) {
    case OverturnClass::kUpperBlock:
      return kUpperColours[static_cast<size_t>(std::max(block - 3, 0)) % std::size(kUpperColours)];
    case OverturnClass::kNone:
      return 0xd9d9d9;
    case OverturnClass::kBlock1:
      return 0x1f4e79;
    case OverturnClass::kBlock2:
      return 0x6fa8dc;
    case OverturnClass::kStopped:
      return 0xf1c232;
    case OverturnClass::kFailed:
      return 0xc00000;
  }
  return 0x000000;
}

// Per group: member -> class per engine (reference first).
struct Cell {
  double x = 0.0, y = 0.0;
  std::map<std::string, OverturnClass> by_engine;
  std::map<std::string, int> block;  ///< the overturned block (0: none)
  std::map<std::string, int> impacts;
};

bool Overturned(OverturnClass c) {
  return c == OverturnClass::kBlock1 || c == OverturnClass::kBlock2 ||
         c == OverturnClass::kUpperBlock;
}

// The reference's two overturning modes: overturning without an impact and after one or more,
// and frequencies at which a safe amplitude lies above an overturning one.
std::string ReferenceModes(const std::vector<Cell>& cells, const std::string& group) {
  int without = 0, after = 0;
  std::map<double, std::vector<std::pair<double, OverturnClass>>> columns;
  for (const Cell& c : cells) {
    const auto it = c.by_engine.find("reference");
    if (it == c.by_engine.end()) continue;
    if (Overturned(it->second)) {
      (c.impacts.at("reference") == 0 ? without : after)++;
    }
    columns[c.x].push_back({c.y, it->second});
  }
  int safe_above = 0;
  for (auto& [x, col] : columns) {
    std::sort(col.begin(), col.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    bool overturned_below = false;
    for (const auto& [y, cls] : col) {
      const bool over = Overturned(cls);
      if (over) overturned_below = true;
      if (overturned_below && cls == OverturnClass::kNone) {
        ++safe_above;
        break;
      }
    }
  }
  std::string s =
      "Reference" + (group.empty() ? std::string() : " (" + group + ")") + ": " +
      std::to_string(without) + (without == 1 ? " member overturns" : " members overturn") +
      " without an impact and " + std::to_string(after) + " after one or more impacts; at " +
      std::to_string(safe_above) + " of " + std::to_string(columns.size()) +
      " frequencies a larger pulse leaves the block standing where a smaller one "
      "overturned it (the safe region between the two overturning modes).";
  return s;
}

}  // namespace

OverturnClass ClassOf(const EnsembleRecord& r) {
  if (!r.has_result || r.status == "blow_up" || r.status == "non_finite") {
    return OverturnClass::kFailed;
  }
  if (r.status == "assumption_violated") return OverturnClass::kStopped;
  if (r.overturned_block == 1) return OverturnClass::kBlock1;
  if (r.overturned_block == 2) return OverturnClass::kBlock2;
  if (r.overturned_block >= 3) return OverturnClass::kUpperBlock;
  return OverturnClass::kNone;
}

std::string ClassName(OverturnClass c) {
  switch (c) {
    case OverturnClass::kNone:
      return "none";
    case OverturnClass::kBlock1:
      return "block 1 (the stack)";
    case OverturnClass::kBlock2:
      return "block 2";
    case OverturnClass::kUpperBlock:
      return "block 3 or above";
    case OverturnClass::kStopped:
      return "model stopped";
    case OverturnClass::kFailed:
      return "no result";
  }
  return "";
}

bool HasSpectrumAxes(const EnsembleData& d) {
  return FindAxes(d).x >= 0;
}

std::string GroupLabel(const EnsembleData& d, const EnsembleRecord& r,
                       const std::vector<int>& except) {
  std::string label;
  for (size_t k = 0; k < d.axes.size(); ++k) {
    if (std::find(except.begin(), except.end(), static_cast<int>(k)) != except.end()) continue;
    label += (label.empty() ? "" : ", ") + d.axes[k] + "=" + r.axis_values[k];
  }
  return label;
}

void SpectraSection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page,
                    std::vector<std::string>& findings) {
  const SpectrumAxes ax = FindAxes(d);
  page.Heading("Overturning spectra");
  std::string upper;
  if (d.blocks >= 3) {
    // N >= 3 blocks: a colour for each block from the third up.
    upper = " Blocks 3 and up (each fell off the block below):";
    for (int b = 3; b <= d.blocks; ++b) {
      upper += std::string(b == 3 ? " " : ", ") + "block " + std::to_string(b) + " " +
               kUpperColourNames[static_cast<size_t>(b - 3) % std::size(kUpperColourNames)];
    }
    upper +=
        "; a member where a different block overturns in the engine's run than in the "
        "reference's differs.";
  }
  page.Paragraph(
      "Each map shows how every member ended, over the pulse's frequency and amplitude (" +
      ax.x_label + " against " + ax.y_label +
      "), one panel per run. Grey: no block overturned; dark blue: block 1 (and with it the "
      "stack); light blue: block 2 fell off block 1; yellow: the reference's model stopped "
      "(the block was thrown off its pivot or would slide: outside the rocking model's "
      "assumptions); red: no result. A red cross on an engine's panel marks a member whose "
      "outcome differs from the reference's where the reference's model holds." +
      upper);
  // Group the members by the other axes.
  std::map<std::string, std::map<long long, Cell>> groups;
  std::vector<std::string> order;
  for (const EnsembleRecord& r : d.records) {
    const std::string g = GroupLabel(d, r, {ax.x, ax.y});
    if (!groups.count(g)) order.push_back(g);
    Cell& c = groups[g][r.member];
    c.x = std::stod(r.axis_values[ax.x]);
    c.y = std::stod(r.axis_values[ax.y]);
    c.by_engine[r.engine] = ClassOf(r);
    c.block[r.engine] = r.overturned_block;
    c.impacts[r.engine] = r.impacts;
  }
  std::vector<std::vector<std::string>> table;
  int index = 0;
  for (const std::string& g : order) {
    std::vector<Cell> cells;
    for (auto& [m, c] : groups[g]) cells.push_back(c);
    GnuplotFigure fig;
    fig.name = "spectrum_" + std::to_string(index++);
    const int panels = static_cast<int>(d.engines.size());
    fig.width_px = std::max(480, 420 * panels);
    fig.height_px = 460;
    double x0 = cells.front().x, x1 = x0, y0 = cells.front().y, y1 = y0;
    for (const Cell& c : cells) {
      x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
      y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
    }
    const double dx = x1 > x0 ? 0.04 * (x1 - x0) : 0.5;
    std::string script = "set multiplot layout 1," + std::to_string(panels) + "\n";
    script += "set xrange [" + Num(x0 - dx, 6) + ":" + Num(x1 + dx, 6) + "]\nset yrange [" +
              Num(y0 / 1.1, 6) + ":" + Num(y1 * 1.1, 6) + "]\n";
    script += "set xlabel " + GnuplotQuote(ax.x_label) + "\nset ylabel " +
              GnuplotQuote(ax.y_label) + "\nset key off\nset logscale y\n";
    for (const std::string& e : d.engines) {
      std::string data, crosses;
      int agree = 0, disagree = 0, stopped = 0;
      for (const Cell& c : cells) {
        const auto it = c.by_engine.find(e);
        if (it == c.by_engine.end()) continue;
        data += Num(c.x, 10) + " " + Num(c.y, 10) + " " +
                std::to_string(ClassColour(it->second, c.block.at(e))) + "\n";
        const auto ref = c.by_engine.find("reference");
        if (IsReference(e) || ref == c.by_engine.end()) continue;
        if (ref->second == OverturnClass::kStopped || ref->second == OverturnClass::kFailed) {
          ++stopped;
          continue;
        }
        // The same class, and for blocks 3 and up the same block.
        if (it->second == ref->second && c.block.at(e) == c.block.at("reference")) {
          ++agree;
        } else {
          ++disagree;
          crosses += Num(c.x, 10) + " " + Num(c.y, 10) + "\n";
        }
      }
      const std::string file = fig.name + "_" + e + ".dat";
      const std::string cross_file = fig.name + "_" + e + "_differs.dat";
      fig.data_files.push_back({file, data});
      fig.data_files.push_back({cross_file, crosses.empty() ? "nan nan\n" : crosses});
      script += "set title " + GnuplotQuote(e) + "\n";
      script += "plot " + GnuplotQuote(file) +
                " using 1:2:3 with points pt 5 ps 1.0 lc rgb variable, " +
                GnuplotQuote(cross_file) + " using 1:2 with points pt 2 ps 1.3 lw 2 lc rgb " +
                "\"#d62728\"\n";
      if (!IsReference(e)) {
        table.push_back({g.empty() ? "all" : g, e, std::to_string(agree), std::to_string(disagree),
                         std::to_string(stopped)});
        findings.push_back(e + (g.empty() ? std::string() : " (" + g + ")") + ": the same " +
                           "outcome as the reference on " + std::to_string(agree) + " of " +
                           std::to_string(agree + disagree) +
                           " members where the reference's model holds (" +
                           std::to_string(disagree) + " differ).");
      }
    }
    script += "unset multiplot\n";
    fig.script = script;
    RenderGnuplot(fig_dir, fig);
    page.Figure(std::filesystem::path("figures") / (fig.name + ".svg"),
                "Overturning map" + (g.empty() ? std::string() : ": " + g));
    findings.push_back(ReferenceModes(cells, g));
  }
  if (!table.empty()) {
    page.Table({"group", "engine", "same outcome", "different outcome", "reference model stopped"},
               table);
  }
}

}  // namespace rockbench::report
