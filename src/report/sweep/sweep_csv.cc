#include "report/sweep/sweep_csv.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "report/common/names.h"
#include "run/engine_registry.h"
#include "scene/limits.h"
#include "scene/mode.h"
#include "util/format.h"

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

// Reads one row's fields by column name, with messages naming file, line and column.
class RowReader {
 public:
  RowReader(const fs::path& path, int line, const std::map<std::string, size_t>& index,
            const std::vector<std::string>& fields)
      : path_(path), line_(line), index_(index), fields_(fields) {}

  const std::string& Text(const std::string& column) const { return fields_.at(index_.at(column)); }
  bool Has(const std::string& column) const { return index_.count(column) != 0; }
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
    if (end != t.c_str() + t.size()) Fail(column, "expected a number, got '" + Excerpt(t) + "'");
    return v;
  }
  double Positive(const std::string& column) const {
    const double v = Number(column);
    if (!(v > 0.0) || !std::isfinite(v)) {
      Fail(column, "expected a positive finite number, got '" + Excerpt(Text(column)) + "'");
    }
    return v;
  }
  int Integer(const std::string& column, int min_value) const {
    const double v = Number(column);
    if (!std::isfinite(v) || v != std::floor(v) || v < min_value || v > 1e9) {
      Fail(column, "expected an integer >= " + std::to_string(min_value) + ", got '" +
                       Excerpt(Text(column)) + "'");
    }
    return static_cast<int>(v);
  }
  bool Flag(const std::string& column) const {
    const std::string& t = Text(column);
    if (t != "0" && t != "1") Fail(column, "expected 0 or 1, got '" + Excerpt(t) + "'");
    return t == "1";
  }

 private:
  const fs::path& path_;
  int line_;
  const std::map<std::string, size_t>& index_;
  const std::vector<std::string>& fields_;
};

// sweep.csv's lines, without a trailing '\r' each, and without the empty lines at the end.
std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(l);
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

// The header's column indices; every column of kColumns must be there.
std::map<std::string, size_t> ReadHeader(const std::vector<std::string>& header,
                                         const std::string& where) {
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < header.size(); ++i) index[header[i]] = i;
  for (const std::string& c : kColumns) {
    if (!index.count(c)) {
      throw std::runtime_error(where + "1: header lacks column '" + c +
                               "' (is this a sweep.csv from `rockbench sweep`?)");
    }
  }
  return index;
}

// What was run: the engine and its settings, or the reference's integrator and tolerances.
void ReadRunSettings(const RowReader& rd, SweepRecord& r) {
  r.engine = rd.Text("engine");
  if (r.engine.empty()) rd.Fail("engine", "expected an engine name or reference, got ''");
  if (!IsEngineName(r.engine)) {
    rd.Fail("engine",
            "expected an engine name or reference (lower-case letters, digits and '_', "
            "starting with a letter), got \"" +
                Excerpt(r.engine) + "\"");
  }
  r.setting = rd.Text("setting");
  if (r.setting.empty()) rd.Fail("setting", "expected the point's label, got ''");
  if (!IsReference(r.engine)) {
    r.family = rd.Text("family");
    r.settings = rd.Text("settings");
    if (r.family.empty()) rd.Fail("family", "expected the engine's settings family, got ''");
    r.time_step_s = rd.Positive("time_step_s");
  } else {
    r.integrator = rd.Text("integrator");
    if (r.integrator == "dopri5" || r.integrator == "dop853") {
      r.rtol = rd.Positive("rtol");
      r.atol = rd.Positive("atol");
    } else if (r.integrator == "rk4") {
      r.rk4_step_s = rd.Positive("rk4_step_s");
    } else {
      rd.Fail("integrator", "expected dopri5, dop853 or rk4, got '" + Excerpt(r.integrator) + "'");
    }
  }
}

// The results of a run that did not fail: wall time, errors, impacts, agreement flags; marks the
// row failed when a result is not finite or the wall time not positive.
void ReadRunResults(const RowReader& rd, SweepRecord& r) {
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
  // N >= 3 blocks: theta3_*, theta4_*, ... as long as the file has them.
  std::vector<std::string> from3_names;
  for (int b = 3; b <= kMaxBlocks && rd.Has(Numbered("theta", b) + "_max_abs_error_rad"); ++b) {
    const std::string th = Numbered("theta", b);
    r.theta_from3_max_abs_error_rad.push_back(rd.Number(th + "_max_abs_error_rad"));
    r.theta_from3_peak_rel_error.push_back(rd.Number(th + "_peak_rel_error"));
    from3_names.push_back(th + "_max_abs_error_rad");
    from3_names.push_back(th + "_peak_rel_error");
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
  for (size_t k = 0; k < from3_names.size() && r.failure.empty(); ++k) {
    const double v =
        k % 2 == 0 ? r.theta_from3_max_abs_error_rad[k / 2] : r.theta_from3_peak_rel_error[k / 2];
    if (!std::isfinite(v)) {
      r.failure = "non-finite " + from3_names[k] + " (" + rd.Text(from3_names[k]) + ")";
    }
  }
  if (r.failure.empty() && !(r.wall_s > 0.0)) r.failure = "wall_s is not positive";
}

}  // namespace

std::vector<SweepRecord> ParseSweepCsv(const std::string& text, const fs::path& path) {
  const std::vector<std::string> lines = SplitLines(text);
  const std::string where = path.string() + ":";
  if (lines.empty())
    throw std::runtime_error(where + "1: empty file (expected sweep.csv's header)");
  const std::vector<std::string> header = SplitCsv(lines[0]);
  const std::map<std::string, size_t> index = ReadHeader(header, where);
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
    ReadRunSettings(rd, r);
    r.status = rd.Text("status");
    r.error = rd.Text("error");
    if (!r.error.empty() || r.status == "error") {
      r.failure = r.error.empty() ? "failed (no message)" : r.error;
    } else {
      ReadRunResults(rd, r);
    }
    rows.push_back(r);
  }
  return rows;
}

std::string SweepFamily(const SweepRecord& r) {
  if (!IsReference(r.engine)) return r.family;
  return r.integrator == "rk4" ? "reference RK4" : "reference " + r.integrator;
}

double SweepSettingValue(const SweepRecord& r) {
  if (!IsReference(r.engine)) return r.time_step_s;
  return r.integrator == "rk4" ? r.rk4_step_s : r.rtol;
}

std::string SweepSettingLabel(const SweepRecord& r) {
  return r.setting;
}

double MaxAngleError(const SweepRecord& r) {
  double e = r.has_theta2 ? std::max(r.theta1_max_abs_error_rad, r.theta2_max_abs_error_rad)
                          : r.theta1_max_abs_error_rad;
  for (const double v : r.theta_from3_max_abs_error_rad) e = std::max(e, v);
  return e;
}

double MaxPeakRelError(const SweepRecord& r) {
  const double a = std::fabs(r.theta1_peak_rel_error);
  double e = r.has_theta2 ? std::max(a, std::fabs(r.theta2_peak_rel_error)) : a;
  for (const double v : r.theta_from3_peak_rel_error) e = std::max(e, std::fabs(v));
  return e;
}

std::string SweepSettingDescription(const SweepRecord& r) {
  if (!IsReference(r.engine)) return r.family + ", time step " + SweepSettingLabel(r) + " s";
  if (r.integrator == "rk4") return "reference RK4, step " + SweepSettingLabel(r) + " s";
  return "reference " + r.integrator + ", rtol " + SweepSettingLabel(r);
}

}  // namespace rockbench::report
