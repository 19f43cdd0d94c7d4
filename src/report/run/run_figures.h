#pragma once
/// What the figures of a run page share: data-file numbers, the axis span test, gnuplot
/// quoting, vertical marks (overturning, predictability horizon), the common time axis, the
/// reference ensemble's band data, and the page's figure list (Figures).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "report/common/gnuplot.h"
#include "report/common/page.h"
#include "report/run/run_readers.h"

namespace rockbench::report {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// The reference ensemble: band fill and horizon lines (blue, apart from the engines' colours).
inline constexpr const char* kBandColour = "#c6dbef";
inline constexpr const char* kHorizonColour = "#2166ac";

/// Appends a data-file number: enough digits to redraw exactly, "NaN" for a gap gnuplot
/// understands.
void AppendDat(std::string& out, double v);

/// The positive finite values of a figure, to choose a log axis.
struct Span {
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0.0;
  void Add(double v) {
    if (v > 0.0 && std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  /// Positive values spanning more than two decades get a log axis.
  bool Decades() const { return hi > 0.0 && lo < hi * 1e-2; }
};

/// A gnuplot string literal (GnuplotQuote).
std::string Quote(const std::string& s);

/// Vertical line at time t across the plot (arrow) with a label, both in front of filled areas.
/// The label sits right of the line, or left of it in the last 40% of the axis (t_end_s); a
/// `boxed` label is on a white box, readable over curves.
std::string VerticalMark(double t, double t_end_s, const std::string& colour,
                         const std::string& label, double label_y_graph = 0.95, bool boxed = false);

/// The line of run `i` of run.engines (`e`) in a plot of every run: " with lines lw 2.2 lc rgb
/// '<colour>' title '<label>'" for the reference (i = 0), thinner and dashed (lw 1.4, dt 2) for
/// the engines.
std::string RunLineStyle(size_t i, const EngineData& e);

/// Grid, time axis from 0 to t_end_s and key of every time plot.
std::string CommonAxes(double t_end_s);

/// Overturn marks of every run for the angle figures.
std::string OverturnMarks(const RunData& run);

/// Vertical line at block `block`'s predictability horizon; none when the block is predictable
/// for the whole run, no ensemble was run or the horizon is past the axis.
std::string HorizonMark(const RunData& run, int block, double label_y_graph);
/// Whether any block has a predictability horizon mark.
bool AnyHorizonMark(const RunData& run);

/// "t v1 v2 ..." rows of ensemble_band.csv's `columns` (each at least `floor`) up to the axis
/// end, and one row past it so the drawing reaches the border.
std::string BandDat(const RunData& run, const std::string& header,
                    const std::vector<const std::vector<double>*>& columns, double floor);
/// "reference ensemble (N members)".
std::string BandTitle(const RunData& run);

/// The title of block `block`'s panel in a stack of `blocks`: "block 1 (lower)", "block 2
/// (upper)" for two blocks; "block 1 (bottom)", "block 2", ..., "block N (top)" for N >= 3.
std::string BlockTitle(int block, int blocks);
/// The height of a figure of one panel per block: 420 px for one, 720 for two, 240 px a panel
/// beyond (N = 8: 1920 px).
int PanelsHeight_px(int blocks);

/// The page and its figures folder: Add renders a figure and puts it on the page.
struct Figures {
  std::filesystem::path page_dir;
  std::filesystem::path dir;  ///< page_dir / "figures"
  Page* page = nullptr;
  int count = 0;
  void Add(const GnuplotFigure& f, const std::string& caption);
};

}  // namespace rockbench::report
