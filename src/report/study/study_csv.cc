// members.csv and study.json read back for the ensemble report.
#include "report/study/study_csv.h"

#include <charconv>
#include <nlohmann/json.hpp>
#include <sstream>

#include "files/atomic_file.h"
#include "report/common/names.h"
#include "report/run/run_report.h"
#include "scene/body_kind.h"
#include "scene/history.h"
#include "scene/limits.h"
#include "scene/mode.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  size_t start = 0;
  for (size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      cells.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  return cells;
}

std::optional<double> Number(const std::string& cell, const std::string& where) {
  if (cell.empty()) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (r.ec != std::errc() || r.ptr != cell.data() + cell.size()) {
    throw ReportInputError(where + ": \"" + Excerpt(cell) + "\" is not a number");
  }
  return v;
}

}  // namespace

int EnsembleData::Axis(const std::string& key) const {
  for (size_t i = 0; i < axes.size(); ++i) {
    if (axes[i] == key) return static_cast<int>(i);
  }
  return -1;
}

bool IsEnsembleFolder(const std::filesystem::path& dir) {
  return std::filesystem::exists(dir / "study.json") &&
         std::filesystem::exists(dir / "members.csv");
}

EnsembleData ReadEnsemble(const std::filesystem::path& dir) {
  EnsembleData d;
  const std::filesystem::path json_path = dir / "study.json";
  try {
    const nlohmann::json j = nlohmann::json::parse(ReadTextFile(json_path));
    d.title = j.value("title", "");
    for (const auto& a : j.at("axes")) d.axes.push_back(a.at("key").get<std::string>());
    d.engines = j.at("engines").get<std::vector<std::string>>();
    // Engine names reach file names, figures and pages: the engine-name alphabet only.
    for (const std::string& e : d.engines) RequireEngineName(e, "key 'engines'");
    d.members = j.at("members").get<long long>();
    d.ranks = j.value("ranks", 1);
    d.jobs = j.value("jobs_per_rank", 1);
    d.wall_s = j.value("wall_s", 0.0);
    d.serial_s = j.value("serial_s", 0.0);
  } catch (const std::exception& e) {
    throw ReportInputError(json_path.string() + ": " + e.what());
  }
  const std::filesystem::path csv = dir / "members.csv";
  std::istringstream in(ReadTextFile(csv));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = SplitCsv(line);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  // A cylinder study's file (study/study_member.h): the tilt for theta, one body.
  d.cylinder = col.count("peak_tilt1_rad") > 0;
  const std::vector<const char*> planar_columns = {
      "member",    "engine",  "status", "overturned_block", "peak_theta1_rad", "peak_theta2_rad",
      "wall_s",    "impacts", "pga_g",  "pgv_mps",          "pulse_period_s",  "p1_radps",
      "alpha1_rad"};
  const std::vector<const char*> cylinder_columns = {
      "member",         "engine",   "status",     "overturned_block",    "overturn_t_s",
      "peak_tilt1_rad", "wall_s",   "pga_g",      "pga_resultant_g",     "pgv_mps",
      "pulse_period_s", "p1_radps", "alpha1_rad", "overturn_azimuth_rad"};
  for (const char* need : d.cylinder ? cylinder_columns : planar_columns) {
    if (!col.count(need)) {
      throw ReportInputError(csv.string() + ":1: no column " + need);
    }
  }
  if (d.cylinder) d.blocks = 1;
  for (const std::string& a : d.axes) {
    if (!col.count(a)) throw ReportInputError(csv.string() + ":1: no column for axis " + a);
  }
  // N >= 3 blocks: peak_theta3_rad, ... as long as the header has them.
  while (!d.cylinder && d.blocks < kMaxBlocks &&
         col.count(BodyColumn("peak_theta", d.blocks + 1) + "_rad")) {
    ++d.blocks;
  }
  for (int n = 2; std::getline(in, line); ++n) {
    const std::string where = csv.string() + ":" + std::to_string(n);
    const std::vector<std::string> c = SplitCsv(line);
    if (c.size() != header.size()) {
      throw ReportInputError(where + ": " + std::to_string(c.size()) + " fields, expected " +
                             std::to_string(header.size()));
    }
    EnsembleRecord r;
    r.line = n;
    r.member = static_cast<long long>(*Number(c[col["member"]], where));
    for (const std::string& a : d.axes) r.axis_values.push_back(c[col[a]]);
    r.engine = c[col["engine"]];
    if (!IsEngineName(r.engine)) {
      try {
        RequireEngineName(r.engine, where + ": column engine");
      } catch (const std::runtime_error& e) {
        throw ReportInputError(e.what());
      }
    }
    r.status = c[col["status"]];
    r.pga_g = Number(c[col["pga_g"]], where);
    r.pgv_mps = Number(c[col["pgv_mps"]], where);
    r.pulse_period_s = Number(c[col["pulse_period_s"]], where);
    r.p1_radps = Number(c[col["p1_radps"]], where);
    r.alpha1_rad = Number(c[col["alpha1_rad"]], where);
    const std::optional<double> peak1 =
        Number(c[col[d.cylinder ? "peak_tilt1_rad" : "peak_theta1_rad"]], where);
    r.has_result = peak1.has_value();
    r.peak_theta1_rad = peak1.value_or(0.0);
    if (d.cylinder) {
      r.peak_theta_rad = {r.peak_theta1_rad};
      r.pga_resultant_g = Number(c[col["pga_resultant_g"]], where);
      r.overturn_azimuth_rad = Number(c[col["overturn_azimuth_rad"]], where);
      r.overturn_t_s = Number(c[col["overturn_t_s"]], where).value_or(0.0);
    } else {
      r.peak_theta2_rad = Number(c[col["peak_theta2_rad"]], where).value_or(0.0);
      r.peak_theta_rad = {r.peak_theta1_rad, r.peak_theta2_rad};
      for (int b = 3; b <= d.blocks; ++b) {
        r.peak_theta_rad.push_back(
            Number(c[col[BodyColumn("peak_theta", b) + "_rad"]], where).value_or(0.0));
      }
      r.impacts = static_cast<int>(Number(c[col["impacts"]], where).value_or(0));
    }
    r.overturned_block = static_cast<int>(Number(c[col["overturned_block"]], where).value_or(0));
    r.wall_s = Number(c[col["wall_s"]], where).value_or(0.0);
    d.records.push_back(std::move(r));
  }
  return d;
}

}  // namespace rockbench::report
