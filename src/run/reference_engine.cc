#include "run/reference_engine.h"

#include <cstdio>

#include "run/summary.h"

namespace rockbench {

std::string ReferenceEngine::version() const {
  return "two-block rocking model (Roussis 1999; Spanos, Roussis & Politis 2001)";
}

const EngineSettingsSchema& ReferenceEngine::settings_schema() const {
  static const EngineSettingsSchema kNone{"reference", {}};
  return kNone;
}

EngineResult ReferenceEngine::Simulate(const Scene& scene, const GroundMotion& motion,
                                       const SimulateOptions& options) const {
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
  const CheckedReference& checked = *ReferenceResultOf(result.extension.get());
  const reference::Summary& s = checked.used().summary;
  char line[256];
  std::snprintf(line, sizeof line,
                "reference: %s, peak |theta1| %.4g rad at %.3f s, peak |theta2| %.4g rad at "
                "%.3f s, %d impacts, %.3g ms",
                StatusText(s.status), s.peak_theta1_rad, s.peak_theta1_t_s, s.peak_theta2_rad,
                s.peak_theta2_t_s, s.impacts_ground + s.impacts_interface, result.wall_s * 1e3);
  std::string text = line;
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
