#include "report/common/gnuplot.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "files/atomic_file.h"
#include "scene/history.h"
#include "util/relayed_text.h"
#include "util/subprocess.h"

namespace rockbench::report {

std::string GnuplotProgram() {
  const char* env = std::getenv("ROCKBENCH_GNUPLOT");
  return env != nullptr && *env != '\0' ? env : "gnuplot";
}

bool GnuplotAvailable() {
  ProcessOptions options;
  options.timeout_s = 30.0;
  return RunProcess({GnuplotProgram(), "--version"}, options).ok();
}

std::string GnuplotQuote(const std::string& text) {
  // gnuplot substitutes `command` anywhere in a script line outside single quotes, before it
  // reads the strings; and a ' doubled inside single quotes fails when two follow each other
  // (x_g''). So: double quotes, with backquote and @ as octal escapes (the line holds neither).
  std::string out = "\"";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (c == '`') {
      out += "\\140";
    } else if (c == '@') {
      out += "\\100";
    } else if (u < 0x20 || u == 0x7f) {
      // A line break would end the command: shown as the text \xHH.
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\\\x%02X", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string GnuplotDataString(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"') {
      out += '\'';
    } else if (u < 0x20 || u == 0x7f) {
      AppendHexEscape(out, u);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::filesystem::path RenderGnuplot(const std::filesystem::path& dir, const GnuplotFigure& figure) {
  for (const auto& [name, text] : figure.data_files) WriteFileAtomic(dir / name, text);
  const std::string svg = figure.name + ".svg";
  const std::string tmp = svg + ".tmp";
  // The kept script writes NAME.svg; the run below redirects it to a temporary name first.
  const std::string preamble = "# rockbench figure; re-run with `gnuplot " + figure.name +
                               ".gp` in this folder to restyle it.\n"
                               "set terminal svg size " +
                               std::to_string(figure.width_px) + "," +
                               std::to_string(figure.height_px) +
                               " dynamic enhanced font 'DejaVu Sans,12' background '#ffffff'\n"
                               "if (!exists(\"output_file\")) output_file = " +
                               GnuplotQuote(svg) +
                               "\n"
                               "set output output_file\n"
                               "set encoding utf8\n";
  const std::filesystem::path script = dir / (figure.name + ".gp");
  WriteFileAtomic(script, preamble + figure.script + "\nunset output\n");
  std::error_code ec;
  std::filesystem::remove(dir / tmp, ec);
  ProcessOptions options;
  options.working_dir = dir;
  options.timeout_s = 120.0;
  const ProcessResult r = RunProcess(
      {GnuplotProgram(), "-e", "output_file=" + GnuplotQuote(tmp), script.filename()}, options);
  const auto fail = [&](const std::string& why) {
    std::filesystem::remove(dir / tmp, ec);
    throw std::runtime_error(script.string() + ": gnuplot " + why);
  };
  if (!r.started) fail("could not start (" + r.start_error + "; Debian package gnuplot-nox)");
  if (r.timed_out) fail("did not finish in 120 s");
  if (r.exit_code != 0) fail("failed: " + r.err);
  if (!std::filesystem::exists(dir / tmp) || std::filesystem::file_size(dir / tmp) == 0) {
    fail("wrote no figure: " + r.err);
  }
  std::filesystem::rename(dir / tmp, dir / svg);
  return dir / svg;
}

}  // namespace rockbench::report
