// A stress row as the child prints it (one line of JSON) and as stress.csv holds it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "run/engine_run.h"
#include "scene/body_kind.h"
#include "stress/stress.h"
#include "util/format.h"

namespace rockbench {
namespace {

// CSV-safe free text: no commas, no line breaks.
std::string Clean(std::string s) {
  for (char& ch : s) {
    if (ch == ',') ch = ';';
    if (ch == '\n' || ch == '\r' || ch == '"') ch = ' ';
  }
  return s;
}

// A list of numbers (NaN as null) and back.
nlohmann::json NumList(const std::vector<double>& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const double x : v) out.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json());
  return out;
}
std::vector<double> NumListFrom(const nlohmann::json& j, const char* key) {
  std::vector<double> out;
  if (!j.contains(key)) return out;
  for (const nlohmann::json& v : j.at(key)) {
    out.push_back(v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>());
  }
  return out;
}

}  // namespace

nlohmann::json StressRowToJson(const StressRow& r) {
  // Non-finite numbers become null (JSON has no NaN) and come back as NaN.
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json j;
  j["case"] = r.case_name;
  j["engine"] = r.engine;
  j["finished"] = r.finished;
  j["status"] = r.status;
  j["detail"] = r.detail;
  j["nan"] = r.nan;
  j["max_energy_gain_rel"] = num(r.max_energy_gain_rel);
  j["energy_impacts"] = r.energy_impacts;
  j["events"] = r.events;
  j["impacts"] = r.impacts;
  j["min_event_gap_s"] = num(r.min_event_gap_s);
  j["wall_s"] = num(r.wall_s);
  j["peak_theta_rad"] = NumList(r.peak_theta_rad);
  j["has_settings"] = r.has_settings;
  j["dt_s"] = r.dt_s;
  j["settings"] = r.settings;
  j["violations"] = r.violations;
  j["has_agreement"] = r.has_agreement;
  j["max_abs_error_rad"] = NumList(r.max_abs_error_rad);
  j["peak_rel_error"] = NumList(r.peak_rel_error);
  j["impacts_matched"] = r.impacts_matched;
  j["reference_impacts"] = r.reference_impacts;
  return j;
}

StressRow StressRowFromJson(const nlohmann::json& j) {
  auto num = [&](const char* key) {
    const nlohmann::json& v = j.at(key);
    return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
  };
  StressRow r;
  r.case_name = j.at("case").get<std::string>();
  r.engine = j.at("engine").get<std::string>();
  r.finished = j.at("finished").get<bool>();
  r.status = j.at("status").get<std::string>();
  r.detail = j.at("detail").get<std::string>();
  r.nan = j.at("nan").get<bool>();
  r.max_energy_gain_rel = num("max_energy_gain_rel");
  r.energy_impacts = j.at("energy_impacts").get<int>();
  r.events = j.at("events").get<int>();
  r.impacts = j.at("impacts").get<int>();
  r.min_event_gap_s = num("min_event_gap_s");
  r.wall_s = num("wall_s");
  r.peak_theta_rad = NumListFrom(j, "peak_theta_rad");
  r.has_settings = j.at("has_settings").get<bool>();
  r.dt_s = j.at("dt_s").get<double>();
  r.settings = j.at("settings").get<std::string>();
  r.violations = j.at("violations").get<std::string>();
  r.has_agreement = j.at("has_agreement").get<bool>();
  r.max_abs_error_rad = NumListFrom(j, "max_abs_error_rad");
  r.peak_rel_error = NumListFrom(j, "peak_rel_error");
  r.impacts_matched = j.at("impacts_matched").get<int>();
  r.reference_impacts = j.at("reference_impacts").get<int>();
  return r;
}

std::string StressCsv(const std::vector<StressRow>& rows) {
  int blocks = 2;
  for (const StressRow& r : rows) blocks = std::max(blocks, r.column_blocks());
  std::string peaks, errors;
  for (int b = 1; b <= blocks; ++b) {
    peaks.append(",").append(BodyColumn("peak_theta", b)).append("_rad");
    errors.append(",").append(BodyColumn("theta", b)).append("_max_abs_error_rad,");
    errors.append(BodyColumn("theta", b)).append("_peak_rel_error");
  }
  std::string out =
      "case,engine,finished,status,nan,max_energy_gain_rel,energy_impacts,events,impacts,"
      "min_event_gap_s,wall_s";
  out += peaks;
  out += ",dt_s,settings,violations";
  out += errors;
  out += ",impacts_matched,reference_impacts,detail\n";
  auto g = [](double v) { return Format("%.6g", v); };
  // Body k's (0-based) cell of a per-body list, after its comma: empty when not `filled`, and
  // beyond the row's stack; bodies 1 and 2 always have a value (0 for a body the stack does
  // not have: their columns are shared by one- and two-block cases).
  const auto body = [&](const std::vector<double>& v, int k, bool filled) {
    out += ',';
    if (!filled) return;
    if (k < static_cast<int>(v.size())) {
      out += g(v[k]);
    } else if (k < 2) {
      out += g(0.0);
    }
  };
  for (const StressRow& r : rows) {
    // Peaks of a run that stopped early are those of its computed part.
    const std::optional<RunStatus> status = ParseRunStatus(r.status);
    const bool ran = r.finished || status == RunStatus::kBlowUp ||
                     status == RunStatus::kNonFinite || r.status == "error";
    out += Clean(r.case_name) + "," + r.engine + "," + (r.finished ? "1" : "0") + "," +
           Clean(r.status) + "," + (r.nan ? "1" : "0") + ",";
    out += (r.energy_impacts > 0 ? Format("%.3e", r.max_energy_gain_rel) : "") + "," +
           std::to_string(r.energy_impacts) + ",";
    out += std::to_string(r.events) + "," + std::to_string(r.impacts) + ",";
    out += (r.min_event_gap_s >= 0.0 ? Format("%.6e", r.min_event_gap_s) : "") + ",";
    out += Format("%.4f", r.wall_s);
    for (int k = 0; k < blocks; ++k) body(r.peak_theta_rad, k, ran);
    out += ",";
    out += r.has_settings
               ? Format("%.6g", r.dt_s) + "," + Clean(r.settings) + "," + Clean(r.violations)
               : ",,";
    for (int k = 0; k < blocks; ++k) {
      body(r.max_abs_error_rad, k, r.has_agreement);
      body(r.peak_rel_error, k, r.has_agreement);
    }
    out += ',';
    if (r.has_agreement) {
      out += std::to_string(r.impacts_matched) + "," + std::to_string(r.reference_impacts);
    } else {
      out += ",";
    }
    out += ',';
    out += Clean(r.detail);
    out += '\n';
  }
  return out;
}

}  // namespace rockbench
