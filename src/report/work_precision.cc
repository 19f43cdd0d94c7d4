#include "report/work_precision.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "report/gnuplot.h"
#include "report/page.h"
#include "scene/history.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;

// The columns the report reads; sweep.csv may carry more (ignored).
const std::vector<std::string> kColumns = {"engine",
                                           "family",
                                           "setting",
                                           "time_step_s",
                                           "settings",
                                           "integrator",
                                           "rtol",
                                           "atol",
                                           "rk4_step_s",
                                           "status",
                                           "wall_s",
                                           "theta1_max_abs_error_rad",
                                           "theta1_rms_error_rad",
                                           "theta1_horizon_s",
                                           "theta1_peak_rel_error",
                                           "theta1_peak_time_error_s",
                                           "theta2_max_abs_error_rad",
                                           "theta2_rms_error_rad",
                                           "theta2_horizon_s",
                                           "theta2_peak_rel_error",
                                           "theta2_peak_time_error_s",
                                           "impacts_reference",
                                           "impacts_engine",
                                           "impacts_matched",
                                           "max_abs_impact_time_error_s",
                                           "overturn_agree",
                                           "final_agree",
                                           "error"};

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  for (char c : line) {
    if (c == ',') {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  out.push_back(field);
  return out;
}

std::string Fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// Reads one row's fields by column name, with messages naming file, line and column.
class RowReader {
 public:
  RowReader(const fs::path& path, int line, const std::map<std::string, size_t>& index,
            const std::vector<std::string>& fields)
      : path_(path), line_(line), index_(index), fields_(fields) {}

  const std::string& Text(const std::string& column) const { return fields_.at(index_.at(column)); }
  [[noreturn]] void Fail(const std::string& column, const std::string& what) const {
    throw std::runtime_error(path_.string() + ":" + std::to_string(line_) + ": column '" + column +
                             "': " + what);
  }
  // A number (nan and inf parse; the caller decides). Empty is an error.
  double Number(const std::string& column) const {
    const std::string& t = Text(column);
    if (t.empty()) Fail(column, "expected a number, got an empty field");
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) Fail(column, "expected a number, got '" + t + "'");
    return v;
  }
  double Positive(const std::string& column) const {
    const double v = Number(column);
    if (!(v > 0.0) || !std::isfinite(v)) {
      Fail(column, "expected a positive finite number, got '" + Text(column) + "'");
    }
    return v;
  }
  int Integer(const std::string& column, int min_value) const {
    const double v = Number(column);
    if (!std::isfinite(v) || v != std::floor(v) || v < min_value || v > 1e9) {
      Fail(column,
           "expected an integer >= " + std::to_string(min_value) + ", got '" + Text(column) + "'");
    }
    return static_cast<int>(v);
  }
  bool Flag(const std::string& column) const {
    const std::string& t = Text(column);
    if (t != "0" && t != "1") Fail(column, "expected 0 or 1, got '" + t + "'");
    return t == "1";
  }

 private:
  const fs::path& path_;
  int line_;
  const std::map<std::string, size_t>& index_;
  const std::vector<std::string>& fields_;
};

// A family's colour and style: the reference black and grey; each engine family a colour of
// its own (in family order), each engine a point type and a dash pattern of its own.
struct Style {
  std::string colour;
  int point_type = 7;
  int dash_type = 1;
};

Style FamilyStyle(const SweepRecord& r, size_t family_index, size_t engine_index) {
  Style s;
  if (r.engine == "reference") {
    s.colour = r.integrator == "dopri5" ? "#000000" : "#8c8c8c";
    s.point_type = r.integrator == "dopri5" ? 5 : 9;
    return s;
  }
  static const char* kPalette[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e",
                                   "#e6ab02", "#a6761d", "#1f78b4", "#b2df8a", "#fb9a99"};
  static const int kPoints[] = {7, 6, 13, 11, 9};
  s.colour = kPalette[family_index % std::size(kPalette)];
  s.point_type = kPoints[engine_index % std::size(kPoints)];
  s.dash_type = 1 + static_cast<int>(engine_index % 4);
  return s;
}

// Log-axis range [10^floor(log10 lo), 10^ceil(log10 hi)], at least one decade.
std::pair<double, double> DecadeRange(double lo, double hi) {
  double a = std::pow(10.0, std::floor(std::log10(lo)));
  double b = std::pow(10.0, std::ceil(std::log10(hi)));
  if (b <= a) b = a * 10.0;
  return {a, b};
}

// What sweep.json says (all optional: an older sweep folder has only sweep.csv).
struct SweepInfo {
  bool present = false;
  std::string scene_path, scene_title;
  std::vector<std::string> overrides;
  double duration_s = 0.0;
  bool quick = false;
  int repeat = 1, threads = 0;
  double tight_wall_s = 0.0;
  std::string tight_status;
  double tight_peak1 = 0.0, tight_peak2 = 0.0;        // rad
  double tight_peak1_t = -1.0, tight_peak2_t = -1.0;  // s; -1: not recorded
  int overturn_block = 0;                             // 1, 2; 0: none
  double overturn_t_s = 0.0;
  // The simulated span a run covers: runs stop when a block overturns (the reference's
  // overturn time stands for every run's), else the scene's duration. The real-time mark.
  double span_s() const {
    return overturn_block > 0 && overturn_t_s > 0.0 ? std::min(overturn_t_s, duration_s)
                                                    : duration_s;
  }
  std::string machine;
};

SweepInfo ReadSweepInfo(const fs::path& path) {
  SweepInfo info;
  if (!fs::exists(path)) return info;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ReadTextFile(path));
    info.scene_path = j.at("scene").at("path").get<std::string>();
    info.scene_title = j.at("scene").value("title", "");
    info.overrides = j.at("scene").value("overrides", std::vector<std::string>{});
    info.duration_s = j.at("simulated_duration_s").get<double>();
    info.quick = j.at("options").value("quick", false);
    info.repeat = j.at("options").value("repeat", 1);
    info.threads = j.at("options").value("threads", 0);
    const nlohmann::json& t = j.at("tight_reference");
    info.tight_wall_s = t.value("wall_s", 0.0);
    info.tight_status = t.value("status", "");
    info.tight_peak1 = t.value("peak_theta1_rad", 0.0);
    info.tight_peak2 = t.value("peak_theta2_rad", 0.0);
    info.tight_peak1_t = t.value("peak_theta1_t_s", -1.0);
    info.tight_peak2_t = t.value("peak_theta2_t_s", -1.0);
    if (t.contains("overturn_block") && t.at("overturn_block").is_number_integer()) {
      info.overturn_block = t.at("overturn_block").get<int>();
      info.overturn_t_s = t.value("overturn_t_s", 0.0);
    }
    info.machine = j.value("machine", "");
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": not a sweep.json as `rockbench sweep` writes it (" +
                             e.what() + ")");
  }
  if (!(info.duration_s > 0.0) || !std::isfinite(info.duration_s)) {
    throw std::runtime_error(path.string() +
                             ": simulated_duration_s: expected a positive number of seconds");
  }
  info.present = true;
  return info;
}

std::string SettingDescription(const SweepRecord& r) {
  if (r.engine != "reference") return r.family + ", time step " + SweepSettingLabel(r) + " s";
  if (r.integrator == "dopri5") return "reference dopri5, rtol " + SweepSettingLabel(r);
  return "reference RK4, step " + SweepSettingLabel(r) + " s";
}

// One figure: a value per usable row against wall time, one curve per family.
struct FigureSpec {
  std::string name;
  std::string ylabel;
  double (*value)(const SweepRecord&);
  std::optional<double> hline;  // a horizontal mark (the 1% line)
  std::string hline_label;
};

GnuplotFigure BuildFigure(const std::vector<SweepRecord>& rows, const FigureSpec& spec,
                          double duration_s, const std::string& real_time_label,
                          std::vector<std::string>* not_drawn) {
  const auto families = SweepFamilies(rows);
  std::string data = "# " + spec.name + ": wall_s, value, label (the family's varying setting)\n";
  std::string plot = "plot ";
  double xlo = HUGE_VAL, xhi = 0.0, ylo = HUGE_VAL, yhi = 0.0;
  int block = 0;
  for (const auto& [family, indices] : families) {
    std::string text;
    for (size_t i : indices) {
      const SweepRecord& r = rows[i];
      const double y = spec.value(r);
      if (!(y > 0.0) || !(r.wall_s > 0.0)) {
        if (not_drawn) not_drawn->push_back(SettingDescription(r));
        continue;
      }
      text += Fmt("%.6g", r.wall_s) + " " + Fmt("%.6g", y) + " \"" + SweepSettingLabel(r) + "\"\n";
      xlo = std::min(xlo, r.wall_s);
      xhi = std::max(xhi, r.wall_s);
      ylo = std::min(ylo, y);
      yhi = std::max(yhi, y);
    }
    if (text.empty()) continue;
    data += (block > 0 ? "\n\n" : "") + std::string("# ") + family + "\n" + text;
    const SweepRecord& head = rows[indices.front()];
    const std::vector<std::string> engines = SweepEngines(rows);
    const size_t engine_index = static_cast<size_t>(
        std::find(engines.begin(), engines.end(), head.engine) - engines.begin());
    const Style st = FamilyStyle(head, static_cast<size_t>(block), engine_index);
    const std::string idx = " index " + std::to_string(block);
    plot += std::string(block > 0 ? ", \\\n     " : "") + "'" + spec.name + ".dat'" + idx +
            " using 1:2 with linespoints lw 1.5 pt " + std::to_string(st.point_type) +
            " ps 0.8 dt " + std::to_string(st.dash_type) + " lc rgb '" + st.colour + "' title " +
            GnuplotQuote(family) + ", \\\n     '" + spec.name + ".dat'" + idx +
            " using 1:2:3 with labels font ',7' offset char 0.4,0.55 left tc rgb '" + st.colour +
            "' notitle";
    ++block;
  }
  std::string script =
      "set logscale xy\n"
      "set format x '10^{%L}'\n"
      "set format y '10^{%L}'\n"
      "set xlabel 'wall time of the run (s)'\n"
      "set ylabel " +
      GnuplotQuote(spec.ylabel) +
      "\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set key outside right top box font ',10' spacing 1.1\n"
      "set title 'points labelled: engine time step (s), dopri5 rtol, RK4 step (s)' font ',10'\n";
  if (block == 0) {
    // Nothing usable: an empty frame that says so.
    script += "set xrange [1e-3:1]\nset yrange [1e-3:1]\n";
    script += "set label 'no usable runs' at graph 0.5, graph 0.5 center\n";
    script += "plot NaN notitle\n";
    return GnuplotFigure{spec.name, script, {{spec.name + ".dat", data}}, 1100, 620};
  }
  if (duration_s > 0.0) {
    xlo = std::min(xlo, duration_s);
    xhi = std::max(xhi, duration_s);
  }
  if (spec.hline) {
    ylo = std::min(ylo, *spec.hline);
    yhi = std::max(yhi, *spec.hline);
  }
  const auto [x0, x1] = DecadeRange(xlo, xhi);
  const auto [y0, y1] = DecadeRange(ylo, yhi);
  script += "set xrange [" + Fmt("%.6g", x0) + ":" + Fmt("%.6g", x1) + "]\n";
  script += "set yrange [" + Fmt("%.6g", y0) + ":" + Fmt("%.6g", y1) + "]\n";
  if (duration_s > 0.0) {
    // Left of this line a run is faster than the motion it simulates.
    const std::string d = Fmt("%.6g", duration_s);
    script += "set arrow 1 from " + d + ", graph 0 to " + d +
              ", graph 1 nohead dt 3 lw 1.5 lc rgb '#444444'\n";
    script += "set label 1 " + GnuplotQuote(real_time_label) + " at " + d +
              ", graph 0.04 right offset char -0.5,0 font ',9' tc rgb '#444444'\n";
  }
  if (spec.hline) {
    const std::string h = Fmt("%.6g", *spec.hline);
    script += "set arrow 2 from graph 0, first " + h + " to graph 1, first " + h +
              " nohead dt 4 lw 1.5 lc rgb '#b00000'\n";
    script += "set label 2 " + GnuplotQuote(spec.hline_label) + " at graph 0.01, first " + h +
              " left offset char 0,0.6 font ',9' tc rgb '#b00000'\n";
  }
  script += plot + "\n";
  return GnuplotFigure{spec.name, script, {{spec.name + ".dat", data}}, 1100, 620};
}

}  // namespace

std::string SweepReportName(const fs::path& sweep_dir) {
  // As `rockbench report` names run folders: the last component of the absolute path.
  const fs::path p = fs::absolute(sweep_dir).lexically_normal();
  const std::string name =
      p.filename().empty() ? p.parent_path().filename().string() : p.filename().string();
  return name.empty() ? "sweep" : name;
}

std::vector<SweepRecord> ParseSweepCsv(const std::string& text, const fs::path& path) {
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines.push_back(l);
    }
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  const std::string where = path.string() + ":";
  if (lines.empty())
    throw std::runtime_error(where + "1: empty file (expected sweep.csv's header)");
  const std::vector<std::string> header = SplitCsv(lines[0]);
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < header.size(); ++i) index[header[i]] = i;
  for (const std::string& c : kColumns) {
    if (!index.count(c)) {
      throw std::runtime_error(where + "1: header lacks column '" + c +
                               "' (is this a sweep.csv from `rockbench sweep`?)");
    }
  }
  std::vector<SweepRecord> rows;
  for (size_t n = 1; n < lines.size(); ++n) {
    const int line = static_cast<int>(n) + 1;
    const std::vector<std::string> f = SplitCsv(lines[n]);
    if (f.size() != header.size()) {
      throw std::runtime_error(where + std::to_string(line) + ": expected " +
                               std::to_string(header.size()) + " comma-separated fields (as the " +
                               "header), got " + std::to_string(f.size()));
    }
    const RowReader rd(path, line, index, f);
    SweepRecord r;
    r.line = line;
    r.engine = rd.Text("engine");
    if (r.engine.empty()) rd.Fail("engine", "expected an engine name or reference, got ''");
    r.setting = rd.Text("setting");
    if (r.setting.empty()) rd.Fail("setting", "expected the point's label, got ''");
    if (r.engine != "reference") {
      r.family = rd.Text("family");
      r.settings = rd.Text("settings");
      if (r.family.empty()) rd.Fail("family", "expected the engine's settings family, got ''");
      r.time_step_s = rd.Positive("time_step_s");
    } else {
      r.integrator = rd.Text("integrator");
      if (r.integrator == "dopri5") {
        r.rtol = rd.Positive("rtol");
        r.atol = rd.Positive("atol");
      } else if (r.integrator == "rk4") {
        r.rk4_step_s = rd.Positive("rk4_step_s");
      } else {
        rd.Fail("integrator", "expected dopri5 or rk4, got '" + r.integrator + "'");
      }
    }
    r.status = rd.Text("status");
    r.error = rd.Text("error");
    if (!r.error.empty() || r.status == "error") {
      r.failure = r.error.empty() ? "failed (no message)" : r.error;
      rows.push_back(r);
      continue;
    }
    if (r.status.empty()) rd.Fail("status", "expected the run's status, got an empty field");
    struct NumberColumn {
      const char* name;
      double* value;
    };
    const std::vector<NumberColumn> numbers = {
        {"wall_s", &r.wall_s},
        {"theta1_max_abs_error_rad", &r.theta1_max_abs_error_rad},
        {"theta1_rms_error_rad", &r.theta1_rms_error_rad},
        {"theta1_horizon_s", &r.theta1_horizon_s},
        {"theta1_peak_rel_error", &r.theta1_peak_rel_error},
        {"theta1_peak_time_error_s", &r.theta1_peak_time_error_s},
        {"max_abs_impact_time_error_s", &r.max_abs_impact_time_error_s}};
    const std::vector<NumberColumn> theta2 = {
        {"theta2_max_abs_error_rad", &r.theta2_max_abs_error_rad},
        {"theta2_rms_error_rad", &r.theta2_rms_error_rad},
        {"theta2_horizon_s", &r.theta2_horizon_s},
        {"theta2_peak_rel_error", &r.theta2_peak_rel_error},
        {"theta2_peak_time_error_s", &r.theta2_peak_time_error_s}};
    for (const NumberColumn& c : numbers) *c.value = rd.Number(c.name);
    // The theta2 columns: all filled (two blocks) or all empty (one block).
    int filled = 0;
    for (const NumberColumn& c : theta2) filled += rd.Text(c.name).empty() ? 0 : 1;
    if (filled != 0 && filled != static_cast<int>(theta2.size())) {
      for (const NumberColumn& c : theta2) {
        if (rd.Text(c.name).empty()) rd.Fail(c.name, "empty while other theta2 columns are set");
      }
    }
    r.has_theta2 = filled > 0;
    if (r.has_theta2) {
      for (const NumberColumn& c : theta2) *c.value = rd.Number(c.name);
    }
    r.impacts_reference = rd.Integer("impacts_reference", 0);
    r.impacts_engine = rd.Integer("impacts_engine", 0);
    r.impacts_matched = rd.Integer("impacts_matched", 0);
    r.overturn_agree = rd.Flag("overturn_agree");
    r.final_agree = rd.Flag("final_agree");
    // Non-finite results: the run is listed, not plotted.
    std::vector<NumberColumn> all = numbers;
    if (r.has_theta2) all.insert(all.end(), theta2.begin(), theta2.end());
    for (const NumberColumn& c : all) {
      if (!std::isfinite(*c.value)) {
        r.failure = std::string("non-finite ") + c.name + " (" + rd.Text(c.name) + ")";
        break;
      }
    }
    if (r.failure.empty() && !(r.wall_s > 0.0)) r.failure = "wall_s is not positive";
    rows.push_back(r);
  }
  return rows;
}

std::string SweepFamily(const SweepRecord& r) {
  if (r.engine != "reference") return r.family;
  return r.integrator == "dopri5" ? "reference dopri5" : "reference RK4";
}

double SweepSettingValue(const SweepRecord& r) {
  if (r.engine != "reference") return r.time_step_s;
  return r.integrator == "dopri5" ? r.rtol : r.rk4_step_s;
}

std::string SweepSettingLabel(const SweepRecord& r) {
  return r.setting;
}

double MaxAngleError(const SweepRecord& r) {
  return r.has_theta2 ? std::max(r.theta1_max_abs_error_rad, r.theta2_max_abs_error_rad)
                      : r.theta1_max_abs_error_rad;
}

double MaxPeakRelError(const SweepRecord& r) {
  const double a = std::fabs(r.theta1_peak_rel_error);
  return r.has_theta2 ? std::max(a, std::fabs(r.theta2_peak_rel_error)) : a;
}

bool ReachesPeakAgreement(const SweepRecord& r, double peak_tolerance) {
  return r.failure.empty() && MaxPeakRelError(r) <= peak_tolerance && r.overturn_agree;
}

std::vector<std::pair<std::string, std::vector<size_t>>> SweepFamilies(
    const std::vector<SweepRecord>& rows) {
  // Families in the order they first appear among the engines' rows (each engine's own grid
  // order), then reference dopri5 and RK4; within a family from the coarsest setting.
  std::map<std::string, size_t> first;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].engine != "reference") first.emplace(SweepFamily(rows[i]), first.size());
  }
  auto rank = [&](const SweepRecord& r) -> size_t {
    if (r.engine != "reference") return first.at(SweepFamily(r));
    return first.size() + (r.integrator == "dopri5" ? 0 : 1);
  };
  std::vector<size_t> order;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].failure.empty()) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const SweepRecord& x = rows[a];
    const SweepRecord& y = rows[b];
    if (rank(x) != rank(y)) return rank(x) < rank(y);
    return SweepSettingValue(x) > SweepSettingValue(y);
  });
  std::vector<std::pair<std::string, std::vector<size_t>>> out;
  for (size_t i : order) {
    const std::string f = SweepFamily(rows[i]);
    if (out.empty() || out.back().first != f) out.push_back({f, {}});
    out.back().second.push_back(i);
  }
  return out;
}

std::optional<double> ObservedOrder(const SweepRecord& coarse, const SweepRecord& fine) {
  const double ec = MaxAngleError(coarse), ef = MaxAngleError(fine);
  const double sc = SweepSettingValue(coarse), sf = SweepSettingValue(fine);
  if (!(ec > 0.0) || !(ef > 0.0) || !(sc > 0.0) || !(sf > 0.0) || sc == sf) return std::nullopt;
  return std::log(ec / ef) / std::log(sc / sf);
}

AgreementCriterion PeakAgreement(double tolerance, bool two_blocks) {
  AgreementCriterion c;
  c.name = Fmt("%g", tolerance * 100.0) + "% peak-angle agreement";
  c.definition = "|peak relative error| <= " + Fmt("%g", tolerance * 100.0) + "% for theta1" +
                 (two_blocks ? " and theta2" : "") +
                 ", and the same overturn outcome as the reference";
  c.reaches = [tolerance](const SweepRecord& r) { return ReachesPeakAgreement(r, tolerance); };
  return c;
}

AgreementCriterion HistoryAgreement(double fraction, double peak_theta1_rad,
                                    double peak_theta2_rad) {
  AgreementCriterion c;
  const double bound1 = fraction * peak_theta1_rad, bound2 = fraction * peak_theta2_rad;
  c.name = Fmt("%g", fraction * 100.0) + "% history agreement";
  c.definition = "max |angle error| over the whole run <= " + Fmt("%g", fraction * 100.0) +
                 "% of the reference's peak angle: " + Fmt("%.3g", bound1) + " rad for theta1" +
                 (peak_theta2_rad > 0.0 ? ", " + Fmt("%.3g", bound2) + " rad for theta2" : "") +
                 "; and the same overturn outcome";
  c.reaches = [bound1, bound2, two = peak_theta2_rad > 0.0](const SweepRecord& r) {
    if (!r.failure.empty() || !r.overturn_agree) return false;
    if (r.theta1_max_abs_error_rad > bound1) return false;
    return !two || !r.has_theta2 || r.theta2_max_abs_error_rad <= bound2;
  };
  return c;
}

CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows, double peak_tolerance,
                                    const std::string& engine) {
  return FindCheapestSetting(
      rows,
      PeakAgreement(peak_tolerance, std::any_of(rows.begin(), rows.end(),
                                                [](const SweepRecord& r) { return r.has_theta2; })),
      engine);
}

std::vector<std::string> SweepEngines(const std::vector<SweepRecord>& rows) {
  std::vector<std::string> out;
  for (const SweepRecord& r : rows) {
    if (r.engine != "reference" && std::find(out.begin(), out.end(), r.engine) == out.end()) {
      out.push_back(r.engine);
    }
  }
  return out;
}

CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows,
                                    const AgreementCriterion& criterion,
                                    const std::string& engine_name) {
  CheapestSetting out;
  const std::vector<std::string> engines = SweepEngines(rows);
  out.engine = !engine_name.empty() ? engine_name : (engines.empty() ? "" : engines.front());
  const std::string& engine = out.engine;
  auto reaches = [&](const SweepRecord& r) { return r.failure.empty() && criterion.reaches(r); };
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRecord& r = rows[i];
    if (r.engine != engine || !reaches(r)) continue;
    if (!out.engine_row || r.wall_s < rows[*out.engine_row].wall_s) out.engine_row = i;
  }
  if (!out.engine_row) {
    out.statement = "No " + (engine.empty() ? std::string("engine") : engine) +
                    " setting in this sweep reaches " + criterion.name + " (" +
                    criterion.definition + ").";
    // Say how close the sweep came: the smallest max angle error.
    std::optional<size_t> closest;
    for (size_t i = 0; i < rows.size(); ++i) {
      const SweepRecord& r = rows[i];
      if (r.engine != engine || !r.failure.empty()) continue;
      if (!closest || MaxAngleError(r) < MaxAngleError(rows[*closest])) closest = i;
    }
    if (closest) {
      const SweepRecord& c = rows[*closest];
      out.statement += " The most accurate is " + SettingDescription(c) + ": max angle error " +
                       Fmt("%.2e", MaxAngleError(c)) + " rad, |peak relative error| " +
                       Fmt("%.3g", MaxPeakRelError(c) * 100.0) + "%" +
                       (c.overturn_agree ? "" : ", and its overturn outcome differs") + ".";
    }
    return out;
  }
  const SweepRecord& b = rows[*out.engine_row];
  const double bullet_error = MaxAngleError(b);
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRecord& r = rows[i];
    if (r.engine != "reference" || !reaches(r) || MaxAngleError(r) > bullet_error) continue;
    if (!out.reference || r.wall_s < rows[*out.reference].wall_s) out.reference = i;
  }
  out.statement = "The cheapest " + engine + " setting reaching " + criterion.name + " (" +
                  criterion.definition + ") is " + SettingDescription(b) + ", at " +
                  Fmt("%.3g", b.wall_s) + " s wall (max angle error " + Fmt("%.2e", bullet_error) +
                  " rad, |peak relative error| " + Fmt("%.2g", MaxPeakRelError(b) * 100.0) + "%).";
  if (out.reference) {
    const SweepRecord& r = rows[*out.reference];
    out.statement +=
        " The reference reaches the same or better accuracy (max angle error, the "
        "max |error| over the run" +
        std::string(b.has_theta2 ? " (the larger of theta1's and theta2's)" : "") + ", <= the " +
        engine + " run's, and the same criterion) with " + SettingDescription(r) + " at " +
        Fmt("%.3g", r.wall_s) + " s wall (max angle error " + Fmt("%.2e", MaxAngleError(r)) +
        " rad), " + Fmt("%.3g", b.wall_s / r.wall_s) + " times cheaper.";
  } else {
    out.statement +=
        " No reference setting in this sweep reaches the same or better accuracy "
        "(max angle error <= the " +
        engine + " run's, and the same criterion).";
  }
  return out;
}

std::filesystem::path WriteSweepReport(const fs::path& sweep_dir, const fs::path& out_dir) {
  const fs::path csv = sweep_dir / "sweep.csv";
  const std::vector<SweepRecord> rows = ParseSweepCsv(ReadTextFile(csv), csv);
  const SweepInfo info = ReadSweepInfo(sweep_dir / "sweep.json");
  const std::string name = SweepReportName(sweep_dir);
  const fs::path page_dir = out_dir / name;
  const fs::path fig_dir = page_dir / "figures";
  fs::create_directories(fig_dir);

  std::string title = "Work-precision: ";
  title += info.present && !info.scene_title.empty() ? info.scene_title : name;
  Page page(title);
  std::vector<size_t> failed;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].failure.empty()) failed.push_back(i);
  }
  if (!failed.empty()) {
    page.Warning(std::to_string(failed.size()) + " of " + std::to_string(rows.size()) +
                 " runs failed or gave non-finite results; they are listed under \"Failed runs\" "
                 "and not plotted.");
  }
  if (!info.present) {
    page.Warning(
        "No sweep.json beside sweep.csv (a sweep from an older rockbench): the "
        "simulated duration is unknown, so real time is not marked.");
  }
  if (SweepEngines(rows).empty()) {
    page.Warning(
        "The sweep has no engine runs (built without engines?): there is nothing to "
        "compare the reference with.");
  }

  // The sweep itself.
  page.Heading("The sweep");
  std::string about = "Sweep folder: " + sweep_dir.string() + ", " + std::to_string(rows.size()) +
                      " runs, each compared with a tight reference (dopri5, rtol 1e-12, atol "
                      "1e-14) on the engine's sample times.";
  if (info.present) {
    about += " Scene: " + info.scene_path;
    for (const std::string& o : info.overrides) about += " --set " + o;
    about +=
        "; simulated duration " + Fmt("%g", info.duration_s) +
        " s. Grid: " + (info.quick ? "quick" : "full") + "; wall time of a run: the minimum of " +
        std::to_string(info.repeat) + " repetition" + (info.repeat == 1 ? "" : "s") + ", with " +
        (info.threads == 0
             ? std::string("one worker thread per core")
             : std::to_string(info.threads) + " worker thread" + (info.threads == 1 ? "" : "s")) +
        " (runs sharing cores read slower than alone). Machine: " + info.machine +
        ". The tight reference took " + Fmt("%.3g", info.tight_wall_s) + " s (status " +
        info.tight_status + ", peak |theta1| " + Fmt("%.4g", info.tight_peak1) + " rad" +
        (info.tight_peak2 > 0.0 ? ", peak |theta2| " + Fmt("%.4g", info.tight_peak2) + " rad"
                                : std::string()) +
        (info.overturn_block > 0
             ? ", block " + std::to_string(info.overturn_block) + " overturns at " +
                   Fmt("%.4g", info.overturn_t_s) + " s, where every run that overturns stops"
             : std::string()) +
        ").";
  }
  page.Paragraph(about);

  // The statement.
  page.Heading("Cheapest setting for 1% peak-angle agreement");
  for (const std::string& engine : SweepEngines(rows)) {
    const CheapestSetting cheapest = FindCheapestSetting(rows, 0.01, engine);
    page.Paragraph(cheapest.statement);
    if (info.present && cheapest.engine_row) {
      const SweepRecord& b = rows[*cheapest.engine_row];
      page.Paragraph("That " + engine + " run simulates " + Fmt("%.3g", info.span_s()) + " s in " +
                     Fmt("%.3g", b.wall_s) + " s: " + Fmt("%.3g", info.span_s() / b.wall_s) +
                     " times faster than real time.");
    }
  }
  // When the peak criterion cannot tell runs apart, say so, and give a stricter one.
  if (info.present) {
    std::vector<std::string> caveats;
    const double peak_t[2] = {info.tight_peak1_t, info.tight_peak2_t};
    const double peak[2] = {info.tight_peak1, info.tight_peak2};
    for (int b = 0; b < 2; ++b) {
      const std::string theta = "theta" + std::to_string(b + 1);
      if (info.overturn_block == b + 1) {
        caveats.push_back("block " + std::to_string(b + 1) + " overturns, so " + theta +
                          "'s peak is the overturn angle, which every run that overturns "
                          "reaches: the criterion checks little more than the outcome for " +
                          theta);
      } else if (peak[b] > 0.0 && peak_t[b] == 0.0) {
        caveats.push_back(theta +
                          "'s peak is its release angle (t = 0 s), where every run "
                          "starts: the criterion says nothing about " +
                          theta);
      }
    }
    if (!caveats.empty()) {
      std::string text = "On this scene ";
      for (size_t i = 0; i < caveats.size(); ++i) text += (i ? "; and " : "") + caveats[i];
      page.Paragraph(text + ". A stricter criterion, on the whole history:");
    } else {
      page.Paragraph("A stricter criterion, on the whole history:");
    }
    for (const std::string& engine : SweepEngines(rows)) {
      page.Paragraph(FindCheapestSetting(
                         rows, HistoryAgreement(0.01, info.tight_peak1, info.tight_peak2), engine)
                         .statement);
    }
  }
  page.Paragraph(
      "Wall times are measured: they vary from run to run and with the load of the "
      "machine, so a choice between two settings of close wall times can go either "
      "way when the sweep is repeated (sweep --repeat N takes the minimum of N).");

  // The figures.
  std::vector<std::string> not_drawn_error, not_drawn_peak;
  FigureSpec error_spec;
  error_spec.name = "work_precision";
  error_spec.ylabel = "max |angle error| over the run, max of θ_1, θ_2 (rad)";
  error_spec.value = &MaxAngleError;
  const double duration = info.present ? info.span_s() : 0.0;
  std::string real_time_label = "real time (" + Fmt("%.3g", duration) + " s simulated";
  if (info.span_s() < info.duration_s) {
    real_time_label += ": block " + std::to_string(info.overturn_block) + " overturns";
  }
  real_time_label += ")";
  RenderGnuplot(fig_dir,
                BuildFigure(rows, error_spec, duration, real_time_label, &not_drawn_error));
  FigureSpec peak_spec;
  peak_spec.name = "peak_error";
  peak_spec.ylabel = "|peak angle relative error|, max of θ_1, θ_2";
  peak_spec.value = &MaxPeakRelError;
  peak_spec.hline = 0.01;
  peak_spec.hline_label = "1% peak-angle agreement";
  RenderGnuplot(fig_dir, BuildFigure(rows, peak_spec, duration, real_time_label, &not_drawn_peak));
  page.Heading("Error against run time");
  page.Figure("figures/work_precision.svg",
              "Max angle error against wall time, log-log, one curve per engine and setting "
              "family; points labelled with their time step (Bullet, RK4; s) or rtol (dopri5)." +
                  std::string(duration > 0.0 ? " Left of the dotted line a run is faster than "
                                               "real time."
                                             : ""));
  if (!not_drawn_error.empty()) {
    std::string s =
        "Not drawn (zero error, e.g. the tight reference's own setting; no place "
        "on a log axis): ";
    for (size_t i = 0; i < not_drawn_error.size(); ++i) {
      s += (i ? "; " : "") + not_drawn_error[i];
    }
    page.Paragraph(s + ".");
  }
  page.Figure("figures/peak_error.svg",
              "|Peak relative error| (the larger of theta1's and theta2's) against wall time; the "
              "red line is the 1% criterion.");
  if (!not_drawn_peak.empty()) {
    std::string s = "Not drawn (zero peak error): ";
    for (size_t i = 0; i < not_drawn_peak.size(); ++i) s += (i ? "; " : "") + not_drawn_peak[i];
    page.Paragraph(s + ".");
  }

  // All runs, by family.
  page.Heading("All runs by family");
  page.Paragraph(
      "Max angle error: the max over the run of |theta_engine - theta_reference|, the "
      "larger of theta1's and theta2's. Order: the observed order of convergence "
      "from the previous (coarser) setting of the family, log(e_coarse/e_fine) / "
      "log(s_coarse/s_fine). Real-time factor: simulated time / wall time (the simulated "
      "time ends where the reference overturns, if it does).");
  std::vector<std::vector<std::string>> table;
  for (const auto& [family, indices] : SweepFamilies(rows)) {
    for (size_t k = 0; k < indices.size(); ++k) {
      const SweepRecord& r = rows[indices[k]];
      std::optional<double> order;
      if (k > 0) order = ObservedOrder(rows[indices[k - 1]], r);
      table.push_back(
          {family, SweepSettingLabel(r), Fmt("%.3g", r.wall_s),
           duration > 0.0 ? Fmt("%.3g", duration / r.wall_s) : "",
           Fmt("%.2e", r.theta1_max_abs_error_rad),
           r.has_theta2 ? Fmt("%.2e", r.theta2_max_abs_error_rad) : "",
           Fmt("%.2e", r.theta1_peak_rel_error),
           r.has_theta2 ? Fmt("%.2e", r.theta2_peak_rel_error) : "",
           std::to_string(r.impacts_matched) + "/" + std::to_string(r.impacts_reference),
           r.overturn_agree ? "yes" : "no", ReachesPeakAgreement(r, 0.01) ? "yes" : "no",
           order ? Fmt("%.2f", *order) : "", r.status});
    }
  }
  page.Table({"family", "setting", "wall (s)", "x real time", "max err θ1 (rad)",
              "max err θ2 (rad)", "peak rel err θ1", "peak rel err θ2", "impacts matched",
              "same overturn", "1% peak", "order", "status"},
             table);

  if (!failed.empty()) {
    page.Heading("Failed runs");
    std::vector<std::vector<std::string>> ft;
    for (size_t i : failed) {
      ft.push_back({std::to_string(rows[i].line), SweepFamily(rows[i]), SweepSettingLabel(rows[i]),
                    rows[i].failure});
    }
    page.Table({"sweep.csv line", "family", "setting", "why"}, ft);
  }
  page.Paragraph(
      "Each figure's gnuplot script (.gp) and data (.dat) are kept beside its SVG in "
      "figures/: edit the script and run `gnuplot NAME.gp` there to restyle it.");

  WriteFileAtomic(page_dir / "report.html", page.Html(page_dir));
  WriteFileAtomic(page_dir / "report.md", page.Markdown());
  return page_dir;
}

}  // namespace rockbench::report
