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
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"
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
  const BlockDef& b1 = scene.blocks.at(0);
  row->p1_radps = p(b1);
  row->alpha1_rad = std::atan2(b1.width_m, b1.height_m);
  if (scene.block_count() >= 2) {
    const BlockDef& b2 = scene.blocks[1];
    row->p2_radps = p(b2);
    row->alpha2_rad = std::atan2(b2.width_m, b2.height_m);
  }
  for (int k = 2; k < scene.block_count(); ++k) {
    const BlockDef& b = scene.blocks[k];
    row->p_from3_radps.push_back(p(b));
    row->alpha_from3_rad.push_back(std::atan2(b.width_m, b.height_m));
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

void SetOutcome(const MemberOutcome& o, int blocks, MemberRow* row) {
  row->status = StatusText(o.status);
  row->overturned_block = o.overturned_block;
  row->overturn_t_s = o.overturn_t_s;
  row->peak_theta1_rad = o.peak_rad[0];
  row->peak_theta2_rad = o.peak_rad[1];
  row->peak_theta_from3_rad.clear();
  for (int b = 2; b < blocks; ++b) row->peak_theta_from3_rad.push_back(o.peak_rad[b]);
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
  if (IsReference(engine)) {
    if (keep_dir) WriteEngineFiles(ref_run, *keep_dir);
    SetOutcome(ref_outcome, scene.block_count(), row);
    row->wall_s = ref.nominal_wall_s;
    row->converged = ref.check && ref.check->converged;
    return;
  }
  // An engine member at rest after the motion can no longer start it rocking is decided.
  SimulateOptions options;
  options.stop_at_rest_after_s = SettledAfter_s(scene, motion);
  const EngineRun run = RunEngine(engine, scene, motion, options);
  if (keep_dir) WriteEngineFiles(run, *keep_dir);
  SetOutcome(OutcomeOf(run, scene, study.min_impact_rate_radps), scene.block_count(), row);
  row->wall_s = run.wall_s;
  row->detail = run.summary.value("status_detail", "");
  CompareOptions co;
  co.min_impact_rate_radps = study.min_impact_rate_radps;
  const EngineAgreement a = CompareWithReference(scene, ref.used(), run, co);
  MemberRow::Agreement g;
  g.theta1_max_abs_error_rad = a.theta1.max_abs_error_rad;
  g.theta1_horizon_s = a.theta1.horizon_s;
  if (a.theta2) {
    g.theta2_max_abs_error_rad = a.theta2->max_abs_error_rad;
    g.theta2_horizon_s = a.theta2->horizon_s;
  }
  for (const AngleAgreement& t : a.theta_from3) {
    g.theta_from3_max_abs_error_rad.push_back(t.max_abs_error_rad);
    g.theta_from3_horizon_s.push_back(t.horizon_s);
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

// A per-block list (blocks 3..N) of a row: absent when empty (one or two blocks).
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
  // The run: an error names the member and its values before the message.
  try {
    RunHere(study, engine, *scene, keep_dir, &row);
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
                      {"p1_radps", r.p1_radps},
                      {"alpha1_rad", r.alpha1_rad},
                      {"overturned_block", r.overturned_block},
                      {"overturn_t_s", r.overturn_t_s},
                      {"peak_theta1_rad", r.peak_theta1_rad},
                      {"peak_theta2_rad", r.peak_theta2_rad},
                      {"impacts", r.impacts},
                      {"wall_s", r.wall_s}};
  PutOptional(j, "p2_radps", r.p2_radps);
  PutOptional(j, "alpha2_rad", r.alpha2_rad);
  PutOptional(j, "pga_g", r.pga_g);
  PutOptional(j, "pgv_mps", r.pgv_mps);
  PutOptional(j, "pgd_m", r.pgd_m);
  PutOptional(j, "arias_mps", r.arias_mps);
  PutOptional(j, "d5_95_s", r.d5_95_s);
  PutOptional(j, "pulse_period_s", r.pulse_period_s);
  PutOptional(j, "converged", r.converged);
  PutVector(j, "p_from3_radps", r.p_from3_radps);
  PutVector(j, "alpha_from3_rad", r.alpha_from3_rad);
  PutVector(j, "peak_theta_from3_rad", r.peak_theta_from3_rad);
  if (r.agreement) {
    const MemberRow::Agreement& a = *r.agreement;
    nlohmann::json g = {{"theta1_max_abs_error_rad", a.theta1_max_abs_error_rad},
                        {"theta1_horizon_s", a.theta1_horizon_s},
                        {"impacts_matched", a.impacts_matched},
                        {"reference_impacts", a.reference_impacts}};
    PutOptional(g, "overturn_agree", a.overturn_agree);
    PutOptional(g, "theta2_max_abs_error_rad", a.theta2_max_abs_error_rad);
    PutOptional(g, "theta2_horizon_s", a.theta2_horizon_s);
    PutOptional(g, "reference_overturned_block", a.reference_overturned_block);
    PutVector(g, "theta_from3_max_abs_error_rad", a.theta_from3_max_abs_error_rad);
    PutVector(g, "theta_from3_horizon_s", a.theta_from3_horizon_s);
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
  r.p1_radps = j.at("p1_radps").get<double>();
  r.alpha1_rad = j.at("alpha1_rad").get<double>();
  r.overturned_block = j.at("overturned_block").get<int>();
  r.overturn_t_s = j.at("overturn_t_s").get<double>();
  r.peak_theta1_rad = j.at("peak_theta1_rad").get<double>();
  r.peak_theta2_rad = j.at("peak_theta2_rad").get<double>();
  r.impacts = j.at("impacts").get<int>();
  r.wall_s = j.at("wall_s").get<double>();
  r.p2_radps = GetOptional<double>(j, "p2_radps");
  r.alpha2_rad = GetOptional<double>(j, "alpha2_rad");
  r.pga_g = GetOptional<double>(j, "pga_g");
  r.pgv_mps = GetOptional<double>(j, "pgv_mps");
  r.pgd_m = GetOptional<double>(j, "pgd_m");
  r.arias_mps = GetOptional<double>(j, "arias_mps");
  r.d5_95_s = GetOptional<double>(j, "d5_95_s");
  r.pulse_period_s = GetOptional<double>(j, "pulse_period_s");
  r.converged = GetOptional<bool>(j, "converged");
  r.p_from3_radps = GetVector(j, "p_from3_radps");
  r.alpha_from3_rad = GetVector(j, "alpha_from3_rad");
  r.peak_theta_from3_rad = GetVector(j, "peak_theta_from3_rad");
  if (j.contains("agreement")) {
    const nlohmann::json& g = j.at("agreement");
    MemberRow::Agreement a;
    a.theta1_max_abs_error_rad = g.at("theta1_max_abs_error_rad").get<double>();
    a.theta1_horizon_s = g.at("theta1_horizon_s").get<double>();
    a.impacts_matched = g.at("impacts_matched").get<int>();
    a.reference_impacts = g.at("reference_impacts").get<int>();
    a.overturn_agree = GetOptional<bool>(g, "overturn_agree");
    a.theta2_max_abs_error_rad = GetOptional<double>(g, "theta2_max_abs_error_rad");
    a.theta2_horizon_s = GetOptional<double>(g, "theta2_horizon_s");
    a.reference_overturned_block = GetOptional<int>(g, "reference_overturned_block");
    a.theta_from3_max_abs_error_rad = GetVector(g, "theta_from3_max_abs_error_rad");
    a.theta_from3_horizon_s = GetVector(g, "theta_from3_horizon_s");
    r.agreement = a;
  }
  return r;
}

namespace {

// ",<stem>3<tail>,<stem>4<tail>,...,<stem>N<tail>": the columns of blocks 3..N (none for one or
// two blocks).
std::string From3Columns(int blocks, std::string_view stem, std::string_view tail) {
  std::string out;
  for (int b = 3; b <= blocks; ++b) out.append(",").append(Numbered(stem, b)).append(tail);
  return out;
}

}  // namespace

std::string MembersCsvHeader(const StudyDef& study) {
  std::string h = "member";
  for (const StudyAxis& a : study.axes) h += "," + a.key;
  std::string p_alpha;
  for (int b = 3; b <= study.blocks; ++b) {
    p_alpha.append(",").append(Numbered("p", b)).append("_radps,");
    p_alpha.append(Numbered("alpha", b)).append("_rad");
  }
  h += ",p1_radps,alpha1_rad,p2_radps,alpha2_rad";
  h += p_alpha;
  h += ",pga_g,pgv_mps,pgd_m,arias_mps,d5_95_s,"
       "pulse_period_s,engine,status,overturned_block,overturn_t_s,peak_theta1_rad,"
       "peak_theta2_rad";
  h += From3Columns(study.blocks, "peak_theta", "_rad");
  h += ",impacts,wall_s,converged,theta1_max_abs_error_rad,theta2_max_abs_error_rad";
  h += From3Columns(study.blocks, "theta", "_max_abs_error_rad");
  h += ",theta1_horizon_s,theta2_horizon_s";
  h += From3Columns(study.blocks, "theta", "_horizon_s");
  h += ",impacts_matched,reference_impacts,reference_overturned_block,overturn_agree,detail\n";
  return h;
}

std::string MembersCsvLine(const StudyDef& study, const MemberRow& r) {
  std::string s = std::to_string(r.member);
  const std::vector<int> idx = study.ValueIndices(r.member);
  for (size_t k = 0; k < study.axes.size(); ++k) {
    s += ",";
    s += TextCell(study.axes[k].values[idx[k]].text);
  }
  const auto add = [&](const std::string& cell) {
    s += ",";
    s += cell;
  };
  const bool res = r.has_result;
  add(res ? ShortestText(r.p1_radps) : "");
  add(res ? ShortestText(r.alpha1_rad) : "");
  add(Cell(r.p2_radps));
  add(Cell(r.alpha2_rad));
  // Blocks 3..N: a row without a result (crash, error) leaves them empty.
  const auto from3 = [&](const std::vector<double>& v, int k) {
    add(k < static_cast<int>(v.size()) ? ShortestText(v[k]) : std::string());
  };
  for (int k = 0; k + 3 <= study.blocks; ++k) {
    from3(r.p_from3_radps, k);
    from3(r.alpha_from3_rad, k);
  }
  for (const auto* v :
       {&r.pga_g, &r.pgv_mps, &r.pgd_m, &r.arias_mps, &r.d5_95_s, &r.pulse_period_s}) {
    add(Cell(*v));
  }
  add(r.engine);
  add(TextCell(r.status));
  add(res && r.overturned_block != 0 ? std::to_string(r.overturned_block) : "");
  add(res && r.overturned_block != 0 ? ShortestText(r.overturn_t_s) : "");
  add(res ? ShortestText(r.peak_theta1_rad) : "");
  add(res ? ShortestText(r.peak_theta2_rad) : "");
  for (int k = 0; k + 3 <= study.blocks; ++k) from3(r.peak_theta_from3_rad, k);
  add(res ? std::to_string(r.impacts) : "");
  add(ShortestText(r.wall_s));
  add(r.converged ? (*r.converged ? "true" : "false") : "");
  if (r.agreement) {
    const MemberRow::Agreement& a = *r.agreement;
    add(ShortestText(a.theta1_max_abs_error_rad));
    add(Cell(a.theta2_max_abs_error_rad));
    for (int k = 0; k + 3 <= study.blocks; ++k) from3(a.theta_from3_max_abs_error_rad, k);
    add(ShortestText(a.theta1_horizon_s));
    add(Cell(a.theta2_horizon_s));
    for (int k = 0; k + 3 <= study.blocks; ++k) from3(a.theta_from3_horizon_s, k);
    add(std::to_string(a.impacts_matched));
    add(std::to_string(a.reference_impacts));
    add(a.reference_overturned_block && *a.reference_overturned_block != 0
            ? std::to_string(*a.reference_overturned_block)
            : "");
    add(a.overturn_agree ? (*a.overturn_agree ? "true" : "false") : "");
  } else {
    for (int i = 0; i < 8 + 2 * std::max(0, study.blocks - 2); ++i) add("");
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
  // member, axes, 10 member columns, engine and 17 run columns; N >= 3 blocks: 2 more member
  // columns and 3 more run columns per block beyond the second.
  const size_t extra = static_cast<size_t>(std::max(0, study.blocks - 2));
  const size_t member_columns = 10 + 2 * extra;
  const size_t expected = 1 + study.axes.size() + member_columns + 1 + 17 + 3 * extra;
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
