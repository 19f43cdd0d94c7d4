#include "run/cylinder_reference.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "run/reference_witness.h"
#include "run/summary.h"
#include "run/tolerance.h"
#include "run/wall_clock.h"
#include "scene/body_kind.h"

namespace rockbench {
namespace {

using reference::cylinder::CylinderResult;
using reference::cylinder::CylinderSummary;
using reference::cylinder::SimulateCylinder;

// The tilt vector of every output row of a history (event rows, at other times, left out).
std::map<double, std::pair<double, double>> TiltVectors(const History& h) {
  StateQuantityReader tilt_x(h, "tilt_x"), tilt_y(h, "tilt_y");
  std::map<double, std::pair<double, double>> out;
  for (const Sample& s : h.samples) out[s.t_s] = {tilt_x(s, 1), tilt_y(s, 1)};
  return out;
}

}  // namespace

EngineResult SimulateCylinderReference(const Scene& scene, const GroundMotion& motion,
                                       const SimulateOptions& options) {
  auto run = std::make_shared<CylinderReferenceExtension>();
  {
    const auto start = std::chrono::steady_clock::now();
    run->nominal = SimulateCylinder(scene, motion);
    run->nominal_wall_s = SecondsSince(start);
  }
  run->tolerance_rad = AngleTolerance_rad(scene, 1, run->nominal.summary.peak_tilt_rad);
  if (options.check_convergence) {
    Scene witness_scene = scene;
    witness_scene.model = WitnessModel(scene.model);
    const auto start = std::chrono::steady_clock::now();
    run->witness = SimulateCylinder(witness_scene, motion);
    run->witness_wall_s = SecondsSince(start);
    const auto a = TiltVectors(run->nominal.history), b = TiltVectors(run->witness->history);
    for (const auto& [t, v] : a) {
      const auto it = b.find(t);
      if (it == b.end()) continue;
      run->max_abs_diff_rad =
          std::max(run->max_abs_diff_rad,
                   std::hypot(v.first - it->second.first, v.second - it->second.second));
    }
    run->same_status = run->nominal.summary.status == run->witness->summary.status;
  }
  EngineResult r;
  r.wall_s = run->nominal_wall_s;
  const CylinderResult& used = run->used();
  r.history = used.history;
  RunOutcome& o = r.outcome = RunOutcome(1);
  const CylinderSummary& s = used.summary;
  o.status = s.status;
  o.end_t_s = s.end_s;
  o.peak_theta_rad[0] = s.peak_tilt_rad;
  o.peak_theta_t_s[0] = s.peak_tilt_t_s;
  o.impacts_at[0] = s.landings;
  if (s.overturn_t_s) {
    o.overturned_block = 1;
    o.overturn_t_s = *s.overturn_t_s;
  }
  r.summary = CylinderSummaryJson(scene, *run);
  r.extension = std::move(run);
  return r;
}

nlohmann::json CylinderSummaryJson(const Scene& scene, const CylinderReferenceExtension& run) {
  const CylinderSummary& s = run.used().summary;
  nlohmann::json j;
  j["status"] = StatusText(s.status);
  if (!s.status_detail.empty()) j["status_detail"] = s.status_detail;
  j["wall_s"] = run.nominal_wall_s;
  j["model_kind"] = "cylinder";
  j["peaks"]["tilt1"] = {{"abs_rad", s.peak_tilt_rad}, {"t_s", s.peak_tilt_t_s}};
  j["impacts"] = {{"total", s.landings}, {"ground", s.landings}, {"rests", s.rests}};
  j["initiations"] = s.initiations;
  if (s.overturn_t_s) {
    j["overturn"] = {
        {"block", 1}, {"t_s", *s.overturn_t_s}, {"azimuth_rad", s.overturn_azimuth_rad}};
  } else {
    j["overturn"] = nullptr;
  }
  j["landing"] = {{"clearance_rel", scene.model.landing_clearance_rel},
                  {"tilt_rad", s.landing_tilt_rad},
                  {"planar", s.planar},
                  {"passes_near_upright", s.passes},
                  {"min_pass_tilt_rad", s.min_pass_tilt_rad}};
  j["rim"] = {{"friction_needed", s.friction_needed}, {"min_normal_rel", s.min_normal_rel}};
  j["steps"] = {{"accepted", s.steps_accepted}, {"rejected", s.steps_rejected}};
  if (run.witness) {
    nlohmann::json c;
    c["witness"] = ModelOptionsJson(WitnessModel(scene.model));
    c["max_abs_diff_rad"] = run.max_abs_diff_rad;
    c["tolerance_rad"] = run.tolerance_rad;
    c["same_status"] = run.same_status;
    c["converged"] = run.converged();
    c["used"] = run.converged() ? "nominal" : "witness";
    c["witness_wall_s"] = run.witness_wall_s;
    j["convergence"] = c;
  }
  j["model"] = ModelOptionsJson(scene.model);
  j["model"]["landing_clearance_rel"] = scene.model.landing_clearance_rel;
  return j;
}

std::string CylinderSummaryLine(const CylinderReferenceExtension& run) {
  const CylinderSummary& s = run.used().summary;
  char text[256];
  std::snprintf(text, sizeof text, "reference: %s, peak tilt %.4g rad at %.3f s, %d landings",
                StatusText(s.status), s.peak_tilt_rad, s.peak_tilt_t_s, s.landings);
  std::string out = text;
  if (s.overturn_t_s) {
    std::snprintf(text, sizeof text, ", overturned at %.4f s toward azimuth %.4f rad",
                  *s.overturn_t_s, s.overturn_azimuth_rad);
    out += text;
  }
  std::snprintf(text, sizeof text, ", %.3g ms", run.nominal_wall_s * 1e3);
  out += text;
  if (!run.converged()) {
    std::snprintf(
        text, sizeof text,
        "\n  WARNING: the reference and its witness differ by %.3g rad in tilt (tolerance "
        "%.3g rad)%s; the witness is used",
        run.max_abs_diff_rad, run.tolerance_rad, run.same_status ? "" : " and end differently");
    out += text;
  }
  return out;
}

}  // namespace rockbench
