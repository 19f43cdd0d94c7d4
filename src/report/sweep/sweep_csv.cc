#include "report/sweep/sweep_csv.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "report/common/names.h"
#include "run/engine_registry.h"
#include "scene/body_kind.h"
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

// A number column of a row and where it goes.
struct NumberColumn {
  std::string name;
  double* value;
};

// Body `body`'s five columns (thetaK_max_abs_error_rad, ...), in the file's order.
std::vector<NumberColumn> BodyColumns(int body, SweepBodyErrors& e) {
  const std::string th = BodyColumn("theta", body);
  return {{th + "_max_abs_error_rad", &e.max_abs_error_rad},
          {th + "_rms_error_rad", &e.rms_error_rad},
          {th + "_horizon_s", &e.horizon_s},
          {th + "_peak_rel_error", &e.peak_rel_error},
          {th + "_peak_time_error_s", &e.peak_time_error_s}};
}

// Whether body 2's columns are filled: all (two or more blocks) or none (one block); a row
// with some of them empty is an error.
bool SecondBodyFilled(const RowReader& rd) {
  SweepBodyErrors unused;
  const std::vector<NumberColumn> columns = BodyColumns(2, unused);
  int filled = 0;
  for (const NumberColumn& c : columns) filled += rd.Text(c.name).empty() ? 0 : 1;
  if (filled != 0 && filled != static_cast<int>(columns.size())) {
    for (const NumberColumn& c : columns) {
      if (rd.Text(c.name).empty()) rd.Fail(c.name, "empty while other theta2 columns are set");
    }
  }
  return filled > 0;
}

// The results of a run that did not fail: wall time, each body's errors, impacts, agreement
// flags; marks the row failed when a result is not finite or the wall time not positive.
void ReadRunResults(const RowReader& rd, SweepRecord& r) {
  if (r.status.empty()) rd.Fail("status", "expected the run's status, got an empty field");
  // Bodies 1 and 2 (when filled), then 3, 4, ... as long as the file has their columns.
  int bodies = SecondBodyFilled(rd) ? 2 : 1;
  while (bodies >= 2 && bodies < kMaxBlocks &&
         rd.Has(BodyColumn("theta", bodies + 1) + "_max_abs_error_rad")) {
    ++bodies;
  }
  r.bodies.resize(static_cast<size_t>(bodies));
  // In the order a non-finite value is reported: wall time, body 1, the impact time, the rest.
  std::vector<NumberColumn> numbers = {{"wall_s", &r.wall_s}};
  for (NumberColumn& c : BodyColumns(1, r.bodies[0])) numbers.push_back(std::move(c));
  numbers.push_back({"max_abs_impact_time_error_s", &r.max_abs_impact_time_error_s});
  for (int b = 2; b <= bodies; ++b) {
    for (NumberColumn& c : BodyColumns(b, r.bodies[static_cast<size_t>(b - 1)])) {
      numbers.push_back(std::move(c));
    }
  }
  for (const NumberColumn& c : numbers) *c.value = rd.Number(c.name);
  r.impacts_reference = rd.Integer("impacts_reference", 0);
  r.impacts_engine = rd.Integer("impacts_engine", 0);
  r.impacts_matched = rd.Integer("impacts_matched", 0);
  r.overturn_agree = rd.Flag("overturn_agree");
  r.final_agree = rd.Flag("final_agree");
  // Non-finite results: the run is listed, not plotted.
  for (const NumberColumn& c : numbers) {
    if (!std::isfinite(*c.value)) {
      r.failure = "non-finite " + c.name + " (" + rd.Text(c.name) + ")";
      break;
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
  // From body 1's (as read: a non-finite value stays), none for a failed row.
  double e = r.bodies.empty() ? 0.0 : r.bodies[0].max_abs_error_rad;
  for (const SweepBodyErrors& b : r.bodies) e = std::max(e, b.max_abs_error_rad);
  return e;
}

double MaxPeakRelError(const SweepRecord& r) {
  double e = r.bodies.empty() ? 0.0 : std::fabs(r.bodies[0].peak_rel_error);
  for (const SweepBodyErrors& b : r.bodies) e = std::max(e, std::fabs(b.peak_rel_error));
  return e;
}

std::string SweepSettingDescription(const SweepRecord& r) {
  if (!IsReference(r.engine)) return r.family + ", time step " + SweepSettingLabel(r) + " s";
  if (r.integrator == "rk4") return "reference RK4, step " + SweepSettingLabel(r) + " s";
  return "reference " + r.integrator + ", rtol " + SweepSettingLabel(r);
}

}  // namespace rockbench::report
