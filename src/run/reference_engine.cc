#include "run/reference_engine.h"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <vector>

#include "run/cylinder_reference.h"
#include "run/summary.h"

namespace rockbench {

std::string ReferenceEngine::version() const {
  return "rocking stack of N blocks (Roussis 1999; Spanos, Roussis & Politis 2001) with a "
         "unilateral model of sliding, lift-off and Coulomb impacts (docs/sliding.md)";
}

const EngineSettingsSchema& ReferenceEngine::settings_schema() const {
  static const EngineSettingsSchema kNone{"reference", {}};
  return kNone;
}

SweepSetting ReferenceEngine::TolerancePoint(Integrator integrator, double rtol) {
  SweepSetting s;
  s.family = std::string("reference ") + IntegratorName(integrator);
  s.label = TimeStepLabel(rtol);
  s.integrator = IntegratorSetting{integrator, rtol, rtol * 1e-2, 0.0};
  return s;
}

SweepSetting ReferenceEngine::Rk4Point(double step_s) {
  SweepSetting s;
  s.family = "reference RK4";
  s.label = TimeStepLabel(step_s);
  s.time_step_s = step_s;
  s.integrator = IntegratorSetting{Integrator::kRk4, 0.0, 0.0, step_s};
  return s;
}

std::vector<SweepSetting> ReferenceEngine::SweepGrid(bool quick) const {
  std::vector<SweepSetting> grid;
  auto add_adaptive = [&grid](Integrator integrator, std::initializer_list<double> rtols) {
    for (double rtol : rtols) grid.push_back(TolerancePoint(integrator, rtol));
  };
  if (quick) {
    add_adaptive(Integrator::kDopri5, {1e-4, 1e-6, 1e-8});
  } else {
    add_adaptive(Integrator::kDopri5, {1e-4, 1e-6, 1e-8, 1e-10, 1e-12});
    // The higher-order pair on the full grid only, from rtol 1e-6 to the default.
    add_adaptive(Integrator::kDop853, {1e-6, 1e-8, 1e-10, 1e-12});
  }
  for (double h : quick ? std::vector<double>{1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4}) {
    grid.push_back(Rk4Point(h));
  }
  return grid;
}

Scene ReferenceEngine::SceneForSetting(const Scene& base, const SweepSetting& setting) const {
  Scene s = base;
  if (!setting.integrator) return s;
  const IntegratorSetting& i = *setting.integrator;
  s.model.integrator = i.integrator;
  if (i.integrator != Integrator::kRk4) {
    s.model.rtol = i.rtol;
    s.model.atol = i.atol;
  } else {
    s.model.step_s = i.step_s;
  }
  return s;
}

std::vector<std::string> ReferenceEngine::body_shapes() const {
  return {"block", std::string(kCylinderShape)};
}

EngineResult ReferenceEngine::Simulate(const Scene& scene, const GroundMotion& motion,
                                       const SimulateOptions& options) const {
  if (scene.three_dimensional()) return SimulateCylinderReference(scene, motion, options);
  auto extension = std::make_shared<ReferenceExtension>();
  extension->checked = RunCheckedReference(scene, motion, options.check_convergence);
  const CheckedReference& checked = extension->checked;
  const reference::Result& used = checked.used();
  EngineResult r;
  r.wall_s = checked.nominal_wall_s;
  r.summary = ReferenceSummaryJson(scene, used, r.wall_s);
  if (checked.check) r.summary["convergence"] = ConvergenceJson(scene, *checked.check);
  r.history = used.history;
  r.outcome = ReferenceOutcome(used);
  r.extension = std::move(extension);
  return r;
}

std::string ReferenceEngine::SummaryLine(const EngineResult& result) const {
  if (const auto* cylinder =
          dynamic_cast<const CylinderReferenceExtension*>(result.extension.get())) {
    return CylinderSummaryLine(*cylinder);
  }
  const CheckedReference& checked = *ReferenceResultOf(result.extension.get());
  const reference::Summary& s = checked.used().summary;
  // Every block's peak (block 2's is 0 for one block).
  std::string text = std::string("reference: ") + StatusText(s.status);
  // Where the model stopped deciding the motion: the history after it is one rule's choice.
  if (s.undetermined_from_s) {
    char when[96];
    std::snprintf(when, sizeof when, " (UNDETERMINED from %.4f s: ", *s.undetermined_from_s);
    text += when + s.undetermined_detail + ")";
  }
  for (int k = 0; k < std::max(s.blocks(), 2); ++k) {
    char peak[128];
    std::snprintf(peak, sizeof peak, ", peak |theta%d| %.4g rad at %.3f s", k + 1,
                  k < s.blocks() ? s.peak_theta_rad[k] : 0.0,
                  k < s.blocks() ? s.peak_theta_t_s[k] : 0.0);
    text += peak;
  }
  char tail[128];
  std::snprintf(tail, sizeof tail, ", %d impacts, %.3g ms", s.impacts(), result.wall_s * 1e3);
  text += tail;
  if (checked.check && !checked.check->converged) {
    text += "\n  WARNING: ";
    text += ConvergenceWarning(*checked.check);
  }
  return text;
}

const ReferenceEngine& TheReference() {
  static const ReferenceEngine kReference;
  return kReference;
}

const CheckedReference* ReferenceResultOf(const EngineResultExtension* extension) {
  const auto* e = dynamic_cast<const ReferenceExtension*>(extension);
  return e != nullptr ? &e->checked : nullptr;
}

}  // namespace rockbench
