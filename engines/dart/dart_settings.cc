#include "engines/dart/dart_settings.h"

#include <string>

namespace rockbench::dart_engine {
namespace {

// The [dart] table: each key once, bound to the DartSettings member it sets.
const SettingsTable<DartSettings>& DartTable() {
  using R = SettingRange;
  using S = DartSettings;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("dart");
    AddTimeStepSetting(t.unbound(), "1e-3 s", "fixed step");
    AddDriveSetting(t.unbound());
    t.Choice("collision", &S::collision, {DartCollision::kDart, DartCollision::kFcl},
             DartCollisionName, "fcl",
             "collision detector; DART's own box-box gives the corner-edge and face contacts");
    t.Choice("lcp_solver", &S::lcp_solver, {DartLcpSolver::kDantzig, DartLcpSolver::kPgs},
             DartLcpSolverName, "dantzig", "boxed LCP solver of the contact constraints");
    t.Flag("pgs_fallback", &S::pgs_fallback, "true",
           "PGS when Dantzig fails (it fails on 12-22% of the stack's steps)");
    t.Integer("pgs_iterations", &S::pgs_iterations, 1, 1000000, "30", "PGS iterations");
    t.Number("restitution", &S::restitution, R::kUnitInterval, "", "0",
             "per body (DART multiplies the two)");
    t.Number("friction", &S::friction, R::kNonNegative, "", "1",
             "per body (DART takes the smaller); with 1 block 2 slides 9 mm on the stack");
    t.Number("erp", &S::erp, R::kUnitInterval, "", "0.01",
             "contact error reduction (process-wide in DART)");
    t.Number("error_allowance", &S::error_allowance_m, R::kNonNegative, "m", "0 m",
             "penetration tolerated without correction (process-wide)");
    t.Number("max_erv", &S::max_erv_mps, R::kNonNegative, "m/s", "1e-3 m/s",
             "cap on the correction velocity (process-wide)");
    t.Number("cfm", &S::cfm, R::kNonNegative, "", "1e-5",
             "relative constraint force mixing; DART's floor is 1e-9", {.min = 1e-9});
    t.Integer("max_contacts", &S::max_contacts, 1, 1000000, "1000", "contacts per collision query");
    t.Number("ground_depth", &S::ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(t.unbound());
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& DartSettingsSchema() {
  return DartTable().schema();
}

DartRun MakeDartRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  return MakeEngineRunInput(scene, motion, DartTable(), stop_at_rest_after_s);
}

}  // namespace rockbench::dart_engine
