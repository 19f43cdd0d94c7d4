#include "run/summary.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rockbench {

nlohmann::json ModelOptionsJson(const ModelConfig& m) {
  return {{"integrator", IntegratorName(m.integrator)},
          {"rtol", m.rtol},
          {"atol", m.atol},
          {"step_s", m.step_s},
          {"events", m.events == EventScheme::kLocated ? "located" : "thesis"},
          {"equations", m.equations == Equations::kNonlinear ? "nonlinear" : "linearized"},
          {"overturn_angle_rad", m.overturn_rad},
          {"rest_rate_rel", m.rest_rate_rel},
          {"check_transitions", m.check_transitions}};
}

nlohmann::json BaseMotionJson(const GroundMotion& motion) {
  nlohmann::json base = nlohmann::json::object();
  auto one = [](const MotionComponent& c) {
    const MotionInfo& i = c.info();
    nlohmann::json j = {{"source", i.source},
                        {"format", i.format},
                        {"npts", i.npts},
                        {"dt_s", i.dt_s},
                        {"duration_s", std::isfinite(i.duration_s) ? nlohmann::json(i.duration_s)
                                                                   : nlohmann::json(nullptr)},
                        {"peak_g", i.peak_g},
                        {"peak_t_s", i.peak_t_s},
                        {"padded_samples", i.padded_samples}};
    return j;
  };
  if (motion.horizontal()) base["horizontal"] = one(*motion.horizontal());
  if (motion.vertical()) base["vertical"] = one(*motion.vertical());
  return base;
}

nlohmann::json ReferenceSummaryJson(const Scene& scene, const reference::Result& result,
                                    double wall_s) {
  const reference::Summary& s = result.summary;
  nlohmann::json j;
  j["status"] = StatusText(s.status);
  if (!s.status_detail.empty()) j["status_detail"] = s.status_detail;
  if (s.status == RunStatus::kNonFinite) {
    // What stopped being finite, and where the computed part (the history, the peaks, the
    // counts below) ends.
    j["non_finite"] = {{"quantity", s.non_finite_quantity},
                       {"value", s.non_finite_value},
                       {"t_s", s.non_finite_t_s},
                       {"last_finite_t_s", s.non_finite_last_t_s}};
  }
  j["wall_s"] = wall_s;
  const int n = s.blocks();
  for (int k = 0; k < n; ++k) {
    j["peaks"]["theta" + std::to_string(k + 1)] = {{"abs_rad", s.peak_theta_rad[k]},
                                                   {"t_s", s.peak_theta_t_s[k]}};
  }
  j["impacts"] = {{"total", s.impacts()},
                  {"ground", s.impacts_ground()},
                  {"inadmissible", s.impacts_inadmissible},
                  {"ambiguous", s.impacts_ambiguous},
                  {"energy_gain", s.impacts_energy_gain}};
  // Where the model stops deciding the motion: the first impact with no admissible outcome or
  // several (null: every impact had exactly one).
  if (s.undetermined_from_s) {
    j["undetermined"] = {{"t_s", *s.undetermined_from_s}, {"detail", s.undetermined_detail}};
  } else {
    j["undetermined"] = nullptr;
  }
  // Per interface: "interface" for one block (0) or two; "interface2", ... beyond.
  if (n <= 2) {
    j["impacts"]["interface"] = s.impacts_interface();
  } else {
    for (int k = 1; k < n; ++k) j["impacts"][InterfaceName(k, n)] = s.impacts_at[k];
  }
  // Where the stack left the thesis's assumptions (a block slipped or lifted off) and the
  // unilateral model took over (null: never; docs/sliding.md).
  if (s.unilateral_from_s) {
    j["unilateral"] = {{"from_t_s", *s.unilateral_from_s},
                       {"reason", s.unilateral_reason},
                       {"slip_starts", s.slip_starts},
                       {"lift_offs", s.lift_offs},
                       {"friction_work_j", s.friction_work_j}};
  } else {
    j["unilateral"] = nullptr;
  }
  j["transitions"] = s.transitions;
  j["initiations"] = s.initiations;
  if (s.overturn_block) {
    j["overturn"] = {{"block", *s.overturn_block}, {"t_s", s.overturn_t_s}};
  } else {
    j["overturn"] = nullptr;
  }
  // The block that slid off its support (null: none; not an overturn).
  if (s.left_support_block) {
    j["left_support"] = {{"block", *s.left_support_block}, {"t_s", s.left_support_t_s}};
  } else {
    j["left_support"] = nullptr;
  }
  j["friction_required"] = {{"ground", s.friction_required[0]}};
  if (n <= 2) {
    j["friction_required"]["interface"] = n == 2 ? s.friction_required[1] : 0.0;
  } else {
    for (int k = 1; k < n; ++k)
      j["friction_required"][InterfaceName(k, n)] = s.friction_required[k];
  }
  // Smallest normal reactions along the solution (null when no step was taken).
  const auto finite_or_null = [](double v) -> nlohmann::json {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  j["min_normal_force_n"] = {{"ground", finite_or_null(s.min_normal_n[0])}};
  for (int k = 1; k < n; ++k) {
    j["min_normal_force_n"][InterfaceName(k, n)] = finite_or_null(s.min_normal_n[k]);
  }
  j["integration"] = {{"steps_accepted", s.steps_accepted},
                      {"steps_rejected", s.steps_rejected},
                      {"rhs_evaluations", s.rhs_evaluations}};
  j["model"] = ModelOptionsJson(scene.model);
  return j;
}

RunOutcome ReferenceOutcome(const reference::Result& result) {
  const reference::Summary& s = result.summary;
  RunOutcome o(s.blocks());
  o.status = s.status;
  o.overturned_block = s.overturn_block.value_or(0);
  if (s.overturn_block) o.overturn_t_s = s.overturn_t_s;
  o.left_support_block = s.left_support_block.value_or(0);
  if (s.left_support_block) o.left_support_t_s = s.left_support_t_s;
  o.end_t_s = result.history.samples.empty() ? 0.0 : result.history.samples.back().t_s;
  o.peak_theta_rad = s.peak_theta_rad;
  o.peak_theta_t_s = s.peak_theta_t_s;
  o.impacts_at = s.impacts_at;
  return o;
}

nlohmann::json RunSummaryJson(const std::filesystem::path& scene_path,
                              const std::vector<std::string>& overrides, const Scene& scene,
                              const GroundMotion& motion,
                              const std::vector<const EngineRun*>& runs) {
  nlohmann::json summary;
  const std::string path = scene_path.empty()
                               ? std::string()
                               : std::filesystem::absolute(scene_path).lexically_normal().string();
  summary["scene"] = {
      {"path", path}, {"overrides", overrides}, {"two_blocks", scene.block_count() == 2}};
  summary["base"] = BaseMotionJson(motion);
  for (const EngineRun* run : runs) AddRunSummary(summary, *run);
  return summary;
}

std::vector<std::string> PaddingNotes(const GroundMotion& motion) {
  std::vector<std::string> notes;
  for (const char* name : {"horizontal", "vertical"}) {
    const auto& c = std::string(name) == "horizontal" ? motion.horizontal() : motion.vertical();
    if (c && c->info().padded_samples > 0) {
      notes.push_back("base." + std::string(name) + " padded with " +
                      std::to_string(c->info().padded_samples) +
                      " zero samples to match the other component's length");
    }
  }
  return notes;
}

}  // namespace rockbench
