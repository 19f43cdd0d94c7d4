// One run of a study member and its row of members.csv.
#include "study/study_member.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "run/cylinder_reference.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench {
namespace {

std::string Cell(const std::optional<double>& v) {
  return v ? ShortestText(*v) : std::string();
}

// A free-text cell: no separators or line breaks.
std::string TextCell(std::string s) {
  for (char& c : s) {
    if (c == ',' || c == '\n' || c == '\r' || c == '"') c = c == ',' ? ';' : ' ';
  }
  return s;
}

void SetGeometry(const Scene& scene, MemberRow* row) {
  const auto p = [&](const BlockDef& b) {
    return std::sqrt(3.0 * scene.run.gravity_mps2 /
                     (4.0 * std::hypot(b.width_m / 2.0, b.height_m / 2.0)));
  };
  row->p_radps.clear();
  row->alpha_rad.clear();
  for (const BlockDef& b : scene.blocks) {
    row->p_radps.push_back(p(b));
    row->alpha_rad.push_back(std::atan2(b.width_m, b.height_m));
  }
}

void SetIntensity(const Scene& scene, const GroundMotion& motion, MemberRow* row) {
  if (!motion.horizontal()) return;
  const IntensityMeasures im = MeasureIntensity(*motion.horizontal(), scene.run.duration_s);
  row->pga_g = im.pga_mps2 / kStandardGravity_mps2;
  row->pgv_mps = im.pgv_mps;
  row->pgd_m = im.pgd_m;
  row->arias_mps = im.arias_mps;
  row->d5_95_s = im.significant_duration_s;
  row->pulse_period_s = im.pulse_period_s;
}

// A cylinder's p = sqrt(m g R_c / I_O), its planar limit's (docs/three-d.md): I_O = I_t +
// m (R^2 + h^2) = m (15 R^2 + 4 H^2) / 12 about a rim point, R_c = sqrt(R^2 + h^2), R = D / 2,
// h = H / 2; alpha = atan(D / H).
void SetCylinderGeometry(const Scene& scene, MemberRow* row) {
  const BlockDef& b = scene.blocks.front();
  const double r = b.diameter_m / 2.0, h = b.height_m / 2.0;
  const double i_o_per_m = (15.0 * r * r + 4.0 * b.height_m * b.height_m) / 12.0;
  row->p_radps = {std::sqrt(scene.run.gravity_mps2 * std::hypot(r, h) / i_o_per_m)};
  row->alpha_rad = {std::atan2(b.diameter_m, b.height_m)};
}

// The run of a cylinder member: the reference (with its witness) or the engine, the overturn's
// time and azimuth from its summary, and an engine's overturn against the member's reference.
void RunCylinderHere(const std::string& engine, const Scene& scene,
                     const std::optional<std::filesystem::path>& keep_dir, MemberRow* row) {
  SetCylinderGeometry(scene, row);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  SetIntensity(scene, motion, row);
  row->pga_resultant_g =
      MeasureResultantPga(motion.horizontal(), motion.transverse(), scene.run.duration_s).pga_mps2 /
      kStandardGravity_mps2;
  const EngineRun ref_run = RunEngine(std::string(kReferenceEngine), scene, motion);
  std::optional<EngineRun> own;
  if (engine != ref_run.engine) own = RunEngine(engine, scene, motion);
  const EngineRun& run = own ? *own : ref_run;
  if (keep_dir) WriteEngineFiles(run, *keep_dir);
  const RunOutcome& o = run.outcome;
  row->status = StatusText(o.status);
  row->detail = run.summary.is_object() ? run.summary.value("status_detail", "") : "";
  row->overturned_block = o.overturned() ? 1 : 0;
  // An overturned cylinder's peak is the overturn angle, whatever step an engine stopped on
  // past it (as OutcomeOf does for blocks).
  row->peak_theta_rad = {o.overturned() ? scene.model.overturn_rad : o.peak_theta_rad.at(0)};
  if (o.overturned()) {
    row->overturn_t_s = o.overturn_t_s;
    const nlohmann::json& over = run.summary.at("overturn");
    row->overturn_azimuth_rad = over.at("azimuth_rad").get<double>();
  }
  row->has_result = true;
  if (const auto* ext = dynamic_cast<const CylinderReferenceExtension*>(run.extension.get())) {
    row->wall_s = ext->nominal_wall_s;
    row->converged = ext->witness.has_value() && ext->converged();
  } else {
    row->wall_s = run.wall_s;
  }
  if (!own) return;
  MemberRow::Agreement g;
  const RunStatus ref_status = ref_run.outcome.status;
  if (ref_status != RunStatus::kAssumptionViolated && !IsNonFinite(ref_status)) {
    g.reference_overturned_block = ref_run.outcome.overturned() ? 1 : 0;
    g.overturn_agree = *g.reference_overturned_block == row->overturned_block;
  }
  row->agreement = g;
}

void SetOutcome(const MemberOutcome& o, int blocks, MemberRow* row) {
  row->status = StatusText(o.status);
  row->overturned_block = o.overturned_block;
  row->overturn_t_s = o.overturn_t_s;
  row->peak_theta_rad.assign(o.peak_rad.begin(), o.peak_rad.begin() + blocks);
  row->impacts = o.impacts;
  row->has_result = true;
}

void RunHere(const StudyDef& study, const std::string& engine, const Scene& scene,
             const std::optional<std::filesystem::path>& keep_dir, MemberRow* row) {
  SetGeometry(scene, row);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  SetIntensity(scene, motion, row);
  const EngineRun ref_run = RunEngine(std::string(kReferenceEngine), scene, motion);
  const CheckedReference& ref = *ReferenceResultOf(ref_run.extension.get());
  const MemberOutcome ref_outcome = OutcomeOf(ref_run, scene, study.min_impact_rate_radps);
  // The member's reference run is what every engine's run is compared with; the row of the
  // engine that made it reuses it (run once) and has nothing to be compared with.
  std::optional<EngineRun> own;
  if (engine != ref_run.engine) {
    // An engine member at rest after the motion can no longer start it rocking is decided.
    SimulateOptions options;
    options.stop_at_rest_after_s = SettledAfter_s(scene, motion);
    own = RunEngine(engine, scene, motion, options);
  }
  const EngineRun& run = own ? *own : ref_run;
  if (keep_dir) WriteEngineFiles(run, *keep_dir);
  SetOutcome(OutcomeOf(run, scene, study.min_impact_rate_radps), scene.block_count(), row);
  // A run checked against its witness says whether it converged; its wall time is the nominal
  // run's.
  if (const CheckedReference* checked = ReferenceResultOf(run.extension.get())) {
    row->wall_s = checked->nominal_wall_s;
    row->converged = checked->check && checked->check->converged;
  } else {
    row->wall_s = run.wall_s;
  }
  if (!own) return;
  row->detail = run.summary.value("status_detail", "");
  CompareOptions co;
  co.min_impact_rate_radps = study.min_impact_rate_radps;
  const EngineAgreement a = CompareWithReference(scene, ref.used(), run, co);
  MemberRow::Agreement g;
  for (const BodyAgreement& body : a.bodies) {
    g.max_abs_error_rad.push_back(body.angle.max_abs_error_rad);
    g.horizon_s.push_back(body.angle.horizon_s);
  }
  g.impacts_matched = a.impacts.matched;
  g.reference_impacts = a.impacts.reference_impacts;
  if (ref_outcome.valid()) {
    g.overturn_agree = ref_outcome.overturned_block == row->overturned_block;
    g.reference_overturned_block = ref_outcome.overturned_block;
  }
  row->agreement = g;
}

template <typename T>
void PutOptional(nlohmann::json& j, const char* key, const std::optional<T>& v) {
  if (v) j[key] = *v;
}

template <typename T>
std::optional<T> GetOptional(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  return j.at(key).get<T>();
}

// A per-body list of a row: absent when empty (a run with no result).
void PutVector(nlohmann::json& j, const char* key, const std::vector<double>& v) {
  if (!v.empty()) j[key] = v;
}

std::vector<double> GetVector(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return {};
  return j.at(key).get<std::vector<double>>();
}

}  // namespace

MemberRow RunMemberHere(const StudyDef& study, int64_t member, const std::string& engine,
                        const std::optional<std::filesystem::path>& keep_dir) {
  MemberRow row;
  row.member = member;
  row.engine = engine;
  // The member's scene: its errors name the study, the axis and value (or set entry) at fault
  // and the member's values (MemberScene).
  std::optional<Scene> scene;
  try {
    scene = MemberScene(study, member);
  } catch (const std::bad_alloc&) {
    return FailedRow(
        member, engine, "error",
        "out of memory (std::bad_alloc) building the scene of " + MemberText(study, member));
  } catch (const std::exception& e) {
    return FailedRow(member, engine, "error", e.what());
  }
  // Every member has the study's stack (the columns of members.csv are the study's).
  if (scene->block_count() != study.blocks) {
    return FailedRow(member, engine, "error",
                     MemberText(study, member) + ": " + std::to_string(scene->block_count()) +
                         " blocks, the study's members have " + std::to_string(study.blocks));
  }
  if (scene->three_dimensional() != study.cylinder) {
    return FailedRow(
        member, engine, "error",
        MemberText(study, member) + ": a " + (study.cylinder ? "planar body" : "cylinder") +
            ", the study's members are " + (study.cylinder ? "cylinders" : "planar bodies"));
  }
  // The run: an error names the member and its values before the message.
  try {
    if (study.cylinder) {
      RunCylinderHere(engine, *scene, keep_dir, &row);
    } else {
      RunHere(study, engine, *scene, keep_dir, &row);
    }
  } catch (const std::bad_alloc&) {
    return FailedRow(member, engine, "error",
                     "out of memory (std::bad_alloc) in the " + engine + " run of " +
                         MemberText(study, member) +
                         ": it needed more memory than the machine gave, beyond its estimate "
                         "(docs/limits.md); the study's other runs go on");
  } catch (const std::exception& e) {
    return FailedRow(member, engine, "error",
                     "the " + engine + " run of " + MemberText(study, member) + ": " + e.what());
  }
  return row;
}

MemberRow FailedRow(int64_t member, const std::string& engine, const std::string& status,
                    const std::string& detail) {
  MemberRow row;
  row.member = member;
  row.engine = engine;
  row.status = status;
  row.detail = detail;
  return row;
}

nlohmann::json MemberRowToJson(const MemberRow& r) {
  nlohmann::json j = {{"member", r.member},
                      {"engine", r.engine},
                      {"status", r.status},
                      {"detail", r.detail},
                      {"has_result", r.has_result},
                      {"overturned_block", r.overturned_block},
                      {"overturn_t_s", r.overturn_t_s},
                      {"impacts", r.impacts},
                      {"wall_s", r.wall_s}};
  PutOptional(j, "pga_g", r.pga_g);
  PutOptional(j, "pgv_mps", r.pgv_mps);
  PutOptional(j, "pgd_m", r.pgd_m);
  PutOptional(j, "arias_mps", r.arias_mps);
  PutOptional(j, "d5_95_s", r.d5_95_s);
  PutOptional(j, "pulse_period_s", r.pulse_period_s);
  PutOptional(j, "converged", r.converged);
  PutOptional(j, "pga_resultant_g", r.pga_resultant_g);
  PutOptional(j, "overturn_azimuth_rad", r.overturn_azimuth_rad);
  PutVector(j, "p_radps", r.p_radps);
  PutVector(j, "alpha_rad", r.alpha_rad);
  PutVector(j, "peak_theta_rad", r.peak_theta_rad);
  if (r.agreement) {
    const MemberRow::Agreement& a = *r.agreement;
    nlohmann::json g = {{"max_abs_error_rad", a.max_abs_error_rad},
                        {"horizon_s", a.horizon_s},
                        {"impacts_matched", a.impacts_matched},
                        {"reference_impacts", a.reference_impacts}};
    PutOptional(g, "overturn_agree", a.overturn_agree);
    PutOptional(g, "reference_overturned_block", a.reference_overturned_block);
    j["agreement"] = g;
  }
  return j;
}

MemberRow MemberRowFromJson(const nlohmann::json& j) {
  MemberRow r;
  r.member = j.at("member").get<int64_t>();
  r.engine = j.at("engine").get<std::string>();
  r.status = j.at("status").get<std::string>();
  r.detail = j.at("detail").get<std::string>();
  r.has_result = j.at("has_result").get<bool>();
  r.overturned_block = j.at("overturned_block").get<int>();
  r.overturn_t_s = j.at("overturn_t_s").get<double>();
  r.impacts = j.at("impacts").get<int>();
  r.wall_s = j.at("wall_s").get<double>();
  r.pga_g = GetOptional<double>(j, "pga_g");
  r.pgv_mps = GetOptional<double>(j, "pgv_mps");
  r.pgd_m = GetOptional<double>(j, "pgd_m");
  r.arias_mps = GetOptional<double>(j, "arias_mps");
  r.d5_95_s = GetOptional<double>(j, "d5_95_s");
  r.pulse_period_s = GetOptional<double>(j, "pulse_period_s");
  r.converged = GetOptional<bool>(j, "converged");
  r.pga_resultant_g = GetOptional<double>(j, "pga_resultant_g");
  r.overturn_azimuth_rad = GetOptional<double>(j, "overturn_azimuth_rad");
  r.p_radps = GetVector(j, "p_radps");
  r.alpha_rad = GetVector(j, "alpha_rad");
  r.peak_theta_rad = GetVector(j, "peak_theta_rad");
  if (j.contains("agreement")) {
    const nlohmann::json& g = j.at("agreement");
    MemberRow::Agreement a;
    a.max_abs_error_rad = g.at("max_abs_error_rad").get<std::vector<double>>();
    a.horizon_s = g.at("horizon_s").get<std::vector<double>>();
    a.impacts_matched = g.at("impacts_matched").get<int>();
    a.reference_impacts = g.at("reference_impacts").get<int>();
    a.overturn_agree = GetOptional<bool>(g, "overturn_agree");
    a.reference_overturned_block = GetOptional<int>(g, "reference_overturned_block");
    r.agreement = a;
  }
  return r;
}

namespace {

// ",<stem>1<tail>,<stem>2<tail>,...": a per-body column of every body of the file.
std::string BodyColumns(int bodies, std::string_view stem, std::string_view tail) {
  std::string out;
  for (int b = 1; b <= bodies; ++b) out.append(",").append(BodyColumn(stem, b)).append(tail);
  return out;
}

}  // namespace

int MembersCsvBodies(const StudyDef& study) {
  return std::max(2, study.blocks);
}

namespace {

// A cylinder study's header (one body; the tilt for theta, the overturn's azimuth, the
// resultant's PGA; no impacts or angle errors: an engine cannot tell a landing from a roll round
// the rim, and the comparison does not take a cylinder yet).
std::string CylinderCsvHeader(const StudyDef& study) {
  std::string h = "member";
  for (const StudyAxis& a : study.axes) h += "," + a.key;
  h += ",p1_radps,alpha1_rad,pga_g,pga_resultant_g,pgv_mps,pgd_m,arias_mps,d5_95_s,"
       "pulse_period_s,engine,status,overturned_block,overturn_t_s,overturn_azimuth_rad,"
       "peak_tilt1_rad,wall_s,converged,reference_overturned_block,overturn_agree,detail\n";
  return h;
}

// A row's first cells: the member and its value on every axis.
std::string MemberAndAxesCells(const StudyDef& study, int64_t member) {
  std::string s = std::to_string(member);
  const std::vector<int> idx = study.ValueIndices(member);
  for (size_t k = 0; k < study.axes.size(); ++k) {
    s += ",";
    s += TextCell(study.axes[k].values[idx[k]].text);
  }
  return s;
}

std::string CylinderCsvLine(const StudyDef& study, const MemberRow& r) {
  std::string s = MemberAndAxesCells(study, r.member);
  const auto add = [&](const std::string& cell) {
    s += ",";
    s += cell;
  };
  const bool res = r.has_result;
  add(r.p_radps.empty() ? "" : ShortestText(r.p_radps[0]));
  add(r.alpha_rad.empty() ? "" : ShortestText(r.alpha_rad[0]));
  for (const auto* v : {&r.pga_g, &r.pga_resultant_g, &r.pgv_mps, &r.pgd_m, &r.arias_mps,
                        &r.d5_95_s, &r.pulse_period_s}) {
    add(Cell(*v));
  }
  add(r.engine);
  add(TextCell(r.status));
  const bool over = res && r.overturned_block != 0;
  add(over ? "1" : "");
  add(over ? ShortestText(r.overturn_t_s) : "");
  add(over ? Cell(r.overturn_azimuth_rad) : "");
  add(res && !r.peak_theta_rad.empty() ? ShortestText(r.peak_theta_rad[0]) : "");
  add(ShortestText(r.wall_s));
  add(r.converged ? (*r.converged ? "true" : "false") : "");
  const bool ref = r.agreement && r.agreement->reference_overturned_block;
  add(ref && *r.agreement->reference_overturned_block != 0 ? "1" : "");
  add(r.agreement && r.agreement->overturn_agree ? (*r.agreement->overturn_agree ? "true" : "false")
                                                 : "");
  add(TextCell(r.detail));
  s += "\n";
  return s;
}

}  // namespace

std::string MembersCsvHeader(const StudyDef& study) {
  if (study.cylinder) return CylinderCsvHeader(study);
  const int nb = MembersCsvBodies(study);
  std::string h = "member";
  for (const StudyAxis& a : study.axes) h += "," + a.key;
  for (int b = 1; b <= nb; ++b) {
    h.append(",").append(BodyColumn("p", b)).append("_radps,");
    h.append(BodyColumn("alpha", b)).append("_rad");
  }
  h += ",pga_g,pgv_mps,pgd_m,arias_mps,d5_95_s,"
       "pulse_period_s,engine,status,overturned_block,overturn_t_s";
  h += BodyColumns(nb, "peak_theta", "_rad");
  h += ",impacts,wall_s,converged";
  h += BodyColumns(nb, "theta", "_max_abs_error_rad");
  h += BodyColumns(nb, "theta", "_horizon_s");
  h += ",impacts_matched,reference_impacts,reference_overturned_block,overturn_agree,detail\n";
  return h;
}

std::string MembersCsvLine(const StudyDef& study, const MemberRow& r) {
  if (study.cylinder) return CylinderCsvLine(study, r);
  const int nb = MembersCsvBodies(study);
  std::string s = MemberAndAxesCells(study, r.member);
  const auto add = [&](const std::string& cell) {
    s += ",";
    s += cell;
  };
  const bool res = r.has_result;
  // Body k's value of a per-body list; empty past the list's end (a body the member does not
  // have, or a row without a result).
  const auto body = [&](const std::vector<double>& v, int k) {
    add(k < static_cast<int>(v.size()) ? ShortestText(v[k]) : std::string());
  };
  for (int k = 0; k < nb; ++k) {
    body(r.p_radps, k);
    body(r.alpha_rad, k);
  }
  for (const auto* v :
       {&r.pga_g, &r.pgv_mps, &r.pgd_m, &r.arias_mps, &r.d5_95_s, &r.pulse_period_s}) {
    add(Cell(*v));
  }
  add(r.engine);
  add(TextCell(r.status));
  add(res && r.overturned_block != 0 ? std::to_string(r.overturned_block) : "");
  add(res && r.overturned_block != 0 ? ShortestText(r.overturn_t_s) : "");
  // A run with a result has a peak for every column (0 for a body its stack does not have).
  for (int k = 0; k < nb; ++k) {
    const bool has = k < static_cast<int>(r.peak_theta_rad.size());
    add(res ? ShortestText(has ? r.peak_theta_rad[k] : 0.0) : "");
  }
  add(res ? std::to_string(r.impacts) : "");
  add(ShortestText(r.wall_s));
  add(r.converged ? (*r.converged ? "true" : "false") : "");
  if (r.agreement) {
    const MemberRow::Agreement& a = *r.agreement;
    for (int k = 0; k < nb; ++k) body(a.max_abs_error_rad, k);
    for (int k = 0; k < nb; ++k) body(a.horizon_s, k);
    add(std::to_string(a.impacts_matched));
    add(std::to_string(a.reference_impacts));
    add(a.reference_overturned_block && *a.reference_overturned_block != 0
            ? std::to_string(*a.reference_overturned_block)
            : "");
    add(a.overturn_agree ? (*a.overturn_agree ? "true" : "false") : "");
  } else {
    for (int i = 0; i < 4 + 2 * nb; ++i) add("");
  }
  add(TextCell(r.detail));
  s += "\n";
  return s;
}

std::optional<RowKey> MembersCsvKey(const StudyDef& study, const std::string& line) {
  if (line.empty() || line.back() != '\n') return std::nullopt;
  std::vector<std::string> cells;
  size_t start = 0;
  for (size_t i = 0; i + 1 <= line.size(); ++i) {
    if (line[i] == ',' || line[i] == '\n') {
      cells.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  // member, axes, the member's columns (6 and 2 per body), engine and the run's columns (11 and
  // 3 per body).
  const auto nb = static_cast<size_t>(MembersCsvBodies(study));
  // A cylinder study: member, axes, 9 member columns, engine and 10 run columns.
  const size_t member_columns = study.cylinder ? 9 : 6 + 2 * nb;
  const size_t expected = study.cylinder ? 1 + study.axes.size() + member_columns + 1 + 10
                                         : 1 + study.axes.size() + member_columns + 1 + 11 + 3 * nb;
  if (cells.size() != expected) return std::nullopt;
  RowKey key;
  const std::string& m = cells[0];
  const auto res = std::from_chars(m.data(), m.data() + m.size(), key.member);
  if (res.ec != std::errc() || res.ptr != m.data() + m.size()) return std::nullopt;
  if (key.member < 0 || key.member >= study.member_count()) return std::nullopt;
  key.engine = cells[1 + study.axes.size() + member_columns];
  if (std::find(study.engines.begin(), study.engines.end(), key.engine) == study.engines.end()) {
    return std::nullopt;
  }
  return key;
}

}  // namespace rockbench
