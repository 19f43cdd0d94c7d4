#include "run/reference_witness.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "run/summary.h"
#include "run/wall_clock.h"
#include "scene/body_kind.h"
#include "scene/limits.h"
#include "util/format.h"

namespace rockbench {
namespace {

// A run with no solution after its end: stopped on a violated assumption, or at its last finite
// state.
bool EndsEarly(const reference::Result& r) {
  return r.summary.status == RunStatus::kAssumptionViolated || IsNonFinite(r.summary.status);
}

}  // namespace

ModelConfig WitnessModel(const ModelConfig& model) {
  ModelConfig w = model;
  if (model.events == EventScheme::kThesis) {
    w.step_s = model.step_s / 10.0;
  } else if (model.integrator == Integrator::kRk4) {
    w.step_s = model.step_s / 4.0;
  } else {
    w.integrator =
        model.integrator == Integrator::kDop853 ? Integrator::kDopri5 : Integrator::kDop853;
    // A hundred times tighter, never below the floors the scene reader holds tolerances to
    // (scene/limits.h): at the floor the witness still differs by its integrator.
    w.rtol = std::max(model.rtol / 100.0, limits::kMinRtol);
    w.atol = std::max(model.atol / 100.0, limits::kMinAtol);
  }
  return w;
}

ConvergenceCheck CompareWithWitness(const Scene& scene, const reference::Result& nominal,
                                    const reference::Result& witness) {
  ConvergenceCheck c;
  c.witness = WitnessModel(scene.model);
  const int nb = scene.block_count();
  // One entry per block, at least two (one block's second is 0, as it always was).
  c.tolerance_rad.assign(std::max(nb, 2), 0.0);
  c.max_abs_diff_rad.assign(std::max(nb, 2), 0.0);
  for (int b = 0; b < nb; ++b) {
    c.tolerance_rad[b] = AngleTolerance_rad(scene, b + 1, nominal.summary.peak_theta_rad[b]);
  }
  // A run that stops on a violated assumption has no solution after its end: compare up to the
  // earlier end. An overturned run stays overturned (Trajectory::At clamps to its end).
  double until = scene.run.duration_s;
  if (EndsEarly(nominal)) until = std::min(until, nominal.trajectory.end_s());
  if (EndsEarly(witness)) until = std::min(until, witness.trajectory.end_s());
  std::vector<double> grid;
  grid.reserve(nominal.history.samples.size() + witness.history.samples.size());
  for (const auto* r : {&nominal, &witness}) {
    for (const Sample& s : r->history.samples) {
      if (s.t_s <= until) grid.push_back(s.t_s);
    }
  }
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  for (double t : grid) {
    const Sample a = nominal.trajectory.At(t), b = witness.trajectory.At(t);
    for (int k = 0; k < nb; ++k) {
      const double d = std::abs(a.theta_rad[k] - b.theta_rad[k]);
      c.max_abs_diff_rad[k] = std::max(c.max_abs_diff_rad[k], d);
      if (!c.diverges_at_s && d > c.tolerance_rad[k]) c.diverges_at_s = t;
    }
  }
  c.same_status = nominal.summary.status == witness.summary.status &&
                  nominal.summary.overturn_block == witness.summary.overturn_block;
  c.nominal_status = nominal.summary.status;
  c.witness_status = witness.summary.status;
  c.nominal_end_s = nominal.trajectory.end_s();
  c.witness_end_s = witness.trajectory.end_s();
  c.converged = !c.diverges_at_s && c.same_status;
  c.nominal_non_finite = IsNonFinite(nominal.summary.status);
  c.witness_non_finite = IsNonFinite(witness.summary.status);
  return c;
}

CheckedReference RunCheckedReference(const Scene& scene, const GroundMotion& motion,
                                     bool with_witness) {
  CheckedReference out;
  auto start = std::chrono::steady_clock::now();
  out.nominal = reference::Simulate(scene, motion);
  out.nominal_wall_s = SecondsSince(start);
  if (!with_witness) return out;
  Scene tight = scene;
  tight.model = WitnessModel(scene.model);
  start = std::chrono::steady_clock::now();
  out.witness = reference::Simulate(tight, motion);
  const double witness_wall_s = SecondsSince(start);
  out.check = CompareWithWitness(scene, out.nominal, *out.witness);
  out.check->witness_wall_s = witness_wall_s;
  return out;
}

nlohmann::json ConvergenceJson(const Scene& scene, const ConvergenceCheck& c) {
  nlohmann::json j;
  j["witness"] = ModelOptionsJson(c.witness);
  j["max_abs_diff_rad"] = c.max_abs_diff();
  j["max_abs_diff_rad_per_block"] = nlohmann::json::object();
  j["tolerance_rad"] = nlohmann::json::object();
  const int nb = std::min(scene.block_count(), static_cast<int>(c.tolerance_rad.size()));
  for (int b = 0; b < nb; ++b) {
    const std::string th = BodyColumn("theta", b + 1);
    j["max_abs_diff_rad_per_block"][th] = c.max_abs_diff_rad[b];
    j["tolerance_rad"][th] = c.tolerance_rad[b];
  }
  j["converged"] = c.converged;
  j["diverges_at_s"] = c.diverges_at_s ? nlohmann::json(*c.diverges_at_s) : nullptr;
  j["same_status"] = c.same_status;
  j["used"] = c.use_witness() ? "witness" : "nominal";
  j["witness_wall_s"] = c.witness_wall_s;
  return j;
}

std::string ConvergenceWarning(const ConvergenceCheck& c) {
  if (c.converged) return "";
  if (c.nominal_non_finite || c.witness_non_finite) {
    // The run's status says what failed; say which of the two runs it was.
    return c.nominal_non_finite && c.witness_non_finite
               ? "both the reference and its witness (a tighter tolerance) ended non_finite"
           : c.nominal_non_finite
               ? "the reference ended non_finite, its witness (a tighter tolerance) did not; "
                 "the run reports the failure"
               : "the reference's witness (a tighter tolerance) ended non_finite; the run reports "
                 "the witness's failure";
  }
  char buf[512];
  if (c.diverges_at_s) {
    std::snprintf(buf, sizeof buf,
                  "the reference is NOT converged: its witness (a tighter tolerance) differs by "
                  "%.3g rad (more than the comparison tolerance) from t = %.3f s on; the "
                  "comparison uses the witness (set a smaller model.rtol and atol, or model.step)",
                  c.max_abs_diff(), *c.diverges_at_s);
  } else {
    std::snprintf(buf, sizeof buf,
                  "the reference is NOT converged: at a tighter tolerance the run ends "
                  "differently (the default run: %s at %.3f s; the tighter: %s at %.3f s); the "
                  "comparison uses the tighter solution, to its end",
                  StatusText(c.nominal_status), c.nominal_end_s, StatusText(c.witness_status),
                  c.witness_end_s);
  }
  return buf;
}

}  // namespace rockbench
