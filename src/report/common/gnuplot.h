#pragma once
/// Figures through gnuplot (Debian's gnuplot-nox): a figure is a gnuplot script plus the data
/// files it plots. Both are kept beside the SVG so a user can restyle a figure and re-run
/// `gnuplot NAME.gp` in that folder.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace rockbench::report {

/// One figure: the script's plotting part and its data files.
struct GnuplotFigure {
  /// File stem: the figure is written as NAME.svg from NAME.gp.
  std::string name;
  /// Gnuplot commands after the preamble (terminal and output are set by RenderGnuplot); data
  /// files are referred to by their bare file names (the script runs in the figure folder).
  std::string script;
  /// (file name, text) of each data file, written before gnuplot runs.
  std::vector<std::pair<std::string, std::string>> data_files;
  int width_px = 960;  ///< SVG size
  int height_px = 540;
};

/// The gnuplot program: $ROCKBENCH_GNUPLOT if set, else "gnuplot" on PATH.
std::string GnuplotProgram();

/// True when the gnuplot program runs (`gnuplot --version` exits 0).
bool GnuplotAvailable();

/// Writes DIR/<data files>, DIR/NAME.gp (with a preamble: SVG terminal, font, output
/// NAME.svg.tmp) and runs gnuplot in DIR; renames NAME.svg.tmp to NAME.svg only when gnuplot
/// succeeded and wrote a non-empty file. Returns the SVG path. Throws std::runtime_error with
/// gnuplot's own message (and the script's path) when it fails or is missing.
std::filesystem::path RenderGnuplot(const std::filesystem::path& dir, const GnuplotFigure& figure);

/// Quotes text for a gnuplot string literal that nothing in it can escape from or run: double
/// quotes with \ and " escaped, ` and @ as octal escapes (\140, \100: the script line holds no
/// backquote to substitute and no macro), control characters (a line break ends a command) as the
/// text \xHH. Every text from a file (engine, family and axis names, titles) reaches a script
/// through it. The enhanced-text markup of labels ("theta_1^{ref}") still applies.
std::string GnuplotQuote(const std::string& text);

/// A string field of a data file (labels plotted `with labels`): double quotes, each " in the
/// text shown as ', control characters as the text \xHH (a line break would start a data row).
std::string GnuplotDataString(const std::string& text);

}  // namespace rockbench::report
