#include "engines/dart/dart_settings.h"

#include <string>

namespace rockbench::dart_engine {

const EngineSettingsSchema& DartSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "dart";
    const DartSettings d;
    AddTimeStepSetting(s, "1e-3 s", "fixed step");
    AddDriveSetting(s);
    s.Choice("collision", DartCollisionName(d.collision), {"dart", "fcl"}, "fcl",
             "collision detector; DART's own box-box gives the corner-edge and face contacts");
    s.Choice("lcp_solver", DartLcpSolverName(d.lcp_solver), {"dantzig", "pgs"}, "dantzig",
             "boxed LCP solver of the contact constraints");
    s.Flag("pgs_fallback", d.pgs_fallback, "true",
           "PGS when Dantzig fails (it fails on 12-22% of the stack's steps)");
    s.Integer("pgs_iterations", d.pgs_iterations, 1, 1000000, "30", "PGS iterations");
    s.Number("restitution", d.restitution, R::kUnitInterval, "", "0",
             "per body (DART multiplies the two)");
    s.Number("friction", d.friction, R::kNonNegative, "", "1",
             "per body (DART takes the smaller); with 1 block 2 slides 9 mm on the stack");
    s.Number("erp", d.erp, R::kUnitInterval, "", "0.01",
             "contact error reduction (process-wide in DART)");
    s.Number("error_allowance", d.error_allowance_m, R::kNonNegative, "m", "0 m",
             "penetration tolerated without correction (process-wide)");
    s.Number("max_erv", d.max_erv_mps, R::kNonNegative, "m/s", "1e-3 m/s",
             "cap on the correction velocity (process-wide)");
    s.Number("cfm", d.cfm, R::kNonNegative, "", "1e-5",
             "relative constraint force mixing; DART's floor is 1e-9", {.min = 1e-9});
    s.Integer("max_contacts", d.max_contacts, 1, 1000000, "1000", "contacts per collision query");
    s.Number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(s);
    return s;
  }();
  return kSchema;
}

DartRun MakeDartRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, DartSettingsSchema());
  DartRun run;
  run.input = MakeEngineInput(scene, motion, "dart", set, stop_at_rest_after_s);
  DartSettings& s = run.settings;
  s.collision = set.Choice("collision") == "fcl" ? DartCollision::kFcl : DartCollision::kDart;
  s.lcp_solver = set.Choice("lcp_solver") == "pgs" ? DartLcpSolver::kPgs : DartLcpSolver::kDantzig;
  s.pgs_fallback = set.Flag("pgs_fallback");
  s.pgs_iterations = static_cast<int>(set.Integer("pgs_iterations"));
  s.restitution = set.Number("restitution");
  s.friction = set.Number("friction");
  s.erp = set.Number("erp");
  s.error_allowance_m = set.Number("error_allowance");
  s.max_erv_mps = set.Number("max_erv");
  s.cfm = set.Number("cfm");
  s.max_contacts = static_cast<int>(set.Integer("max_contacts"));
  s.ground_depth_m = set.Number("ground_depth");
  return run;
}

}  // namespace rockbench::dart_engine
