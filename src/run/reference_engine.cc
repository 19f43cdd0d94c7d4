#include "run/reference_engine.h"

#include <algorithm>
#include <cstdio>

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
