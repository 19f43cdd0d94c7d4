#pragma once
/// What a fixed-step engine simulates, whatever the engine: the scene's N blocks, initial state,
/// time step and drive, and the base motion sampled on the engine's step grid. Every engine
/// (and Bullet's single-precision helper program) sees bit-identical excitation.
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "motion/ground_displacement.h"
#include "motion/ground_motion.h"
#include "scene/engine_settings.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench {

/// Base motion on the step grid t_n = n * time_step_s, n = 0..steps.
struct DriveSamples {
  /// Inertial drive: base acceleration applied during step n (from t_n to t_{n+1}), m/s^2,
  /// evaluated at t_n (the leapfrog force time of Bullet's symplectic Euler step). Empty when
  /// the scene has no base motion (all zero).
  std::vector<double> ax_mps2, ay_mps2;
  /// Inertial drive: the transverse base acceleration (+y of a 3-D body's world, the scene's
  /// [base.transverse]) during step n, m/s^2; empty when the scene has none.
  std::vector<double> at_mps2;
  /// Kinematic drive: ground displacement at t_n (n = 0..steps), m, after baseline correction
  /// (IntegrateGroundPath, scene/ground_displacement.h). Empty for the inertial drive.
  std::vector<double> ux_m, uy_m;
  /// Kinematic drive: the transverse ground displacement at t_n, m (empty without a transverse
  /// component), and its velocity before step 0, m/s.
  std::vector<double> ut_m;
  double ut0_mps = 0.0;
  /// Kinematic drive: ground velocity before step 0 (so that the blocks start at rest relative
  /// to the ground), m/s.
  double ux0_mps = 0.0, uy0_mps = 0.0;
  /// Kinematic drive: max |second difference of u / dt^2 - record|, the acceleration the
  /// baseline correction removed, m/s^2 (horizontal, vertical).
  double correction_max_x_mps2 = 0.0, correction_max_y_mps2 = 0.0;
  /// Kinematic drive: peak |u| before and after the correction, m.
  double raw_peak_x_m = 0.0, raw_peak_y_m = 0.0, peak_x_m = 0.0, peak_y_m = 0.0;
};

/// How the base motion reaches the blocks.
enum class DriveKind {
  kInertial,   ///< a still ground, the base acceleration as an inertial force (gravity tilts)
  kKinematic,  ///< the ground moves along the twice-integrated record
};

/// "inertial" or "kinematic".
const char* DriveKindName(DriveKind kind);

/// Everything one engine run needs.
struct EngineInput {
  /// The stack, bottom first: blocks[0] stands on the ground, blocks[k] sits centred on
  /// blocks[k - 1] (Scene::blocks). 1 to kMaxBlocks blocks.
  std::vector<BlockDef> blocks;
  InitialState initial;
  RunConfig run;
  double time_step_s = 1e-4;  ///< the engine's fixed step, s
  DriveKind drive_kind = DriveKind::kInertial;
  /// Kinematic drive: baseline-correction corner, Hz; 0 = none.
  double kinematic_highpass_hz = 0.0;
  double overturn_rad = 1.5707963267948966;  ///< |theta| that counts as overturned (model's)
  std::int64_t steps = 0;                    ///< number of steps, ceil(duration / dt)
  double motion_end_s = 0.0;                 ///< time after which the base is still, s
  /// After this time (s) the base motion cannot start rocking from rest any more (every later
  /// base acceleration keeps every corner force of the stack at rest compressive): a run that is
  /// then at rest stops with status "at_rest", its outcome decided. Infinity (default): never.
  /// Set for ensemble members, whose outcomes are all that is kept; never for a run whose
  /// history is compared.
  double stop_at_rest_after_s = std::numeric_limits<double>::infinity();
  /// Whether the history carries each block's slip and lift, u1..uN and z1..zN
  /// (Scene::tracks_slip_and_lift: a finite friction somewhere or a vertical base motion).
  bool slip_and_lift = false;
  DriveSamples drive;

  /// Number of blocks of the stack.
  int block_count() const { return static_cast<int>(blocks.size()); }
};

/// Whether some block of the stack has a finite friction coefficient (BlockDef::friction).
bool HasFiniteFriction(const EngineInput& input);

/// The Coulomb coefficient of the contact between block k + 1 (index k, bottom first) and its
/// support (the ground for k = 0, block k otherwise): the block's `friction` where it is finite
/// (the scene's value wins over the engine's table), else `engine_mu`, the coefficient the
/// engine's own settings give that contact (dimensionless).
double InterfaceFriction(const EngineInput& input, int k, double engine_mu);

/// Builds the input of a run of step `time_step_s` (s) with `drive`: samples the base motion on
/// the step grid. Throws SceneError naming `engine`.time_step when the run would take more than
/// 2e9 steps.
EngineInput MakeEngineInput(const Scene& scene, const GroundMotion& motion,
                            const std::string& engine, double time_step_s, DriveKind drive,
                            double kinematic_highpass_hz);

/// The input of a run from an engine's resolved table (`settings`, of the engine `engine`): its
/// time_step (the one place an engine reads that key: every engine steps by
/// EngineInput::time_step_s and keeps no copy of it), its drive ("inertial" or "kinematic";
/// inertial when the table has no drive key) and kinematic_highpass_hz when the table has it (0
/// otherwise), stopping at rest after stop_at_rest_after_s.
EngineInput MakeEngineInput(const Scene& scene, const GroundMotion& motion,
                            const std::string& engine, const EngineSettings& settings,
                            double stop_at_rest_after_s);

/// The key `time_step` of every engine's table, which MakeEngineInput reads: the fixed step, s,
/// a positive number, ours 1e-4 s (kDefaultTimeStep_s); `engine_default` is the engine's own
/// default as text ("1/60 s"), `doc` one line on it.
inline constexpr double kDefaultTimeStep_s = 1e-4;
inline constexpr char kTimeStepKey[] = "time_step";
void AddTimeStepSetting(EngineSettingsSchema& schema, std::string engine_default, std::string doc);

/// The two other keys of an engine's table that MakeEngineInput reads, defined once for every
/// engine: `drive`, one of `drives` (DriveKindName's words; the first is the default; `doc` one
/// line on it), and `kinematic_highpass_hz` (the kinematic drive's baseline-correction corner,
/// default 0: none).
void AddDriveSetting(EngineSettingsSchema& schema,
                     const std::vector<std::string>& drives = {"inertial", "kinematic"},
                     std::string doc =
                         "base motion as tilted gravity (inertial) or a moving "
                         "ground (kinematic)");
void AddKinematicHighpassSetting(EngineSettingsSchema& schema);

/// One built-in engine's run: the common input and the engine's own settings.
template <class S>
struct EngineRunInput {
  EngineInput input;
  S settings;
};

/// Resolves the scene's table of `table`'s engine (SceneError naming FILE:LINE and the key for
/// a bad value), samples the base motion on its step and reads the engine's settings.
template <class S>
EngineRunInput<S> MakeEngineRunInput(const Scene& scene, const GroundMotion& motion,
                                     const SettingsTable<S>& table, double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, table.schema());
  return {MakeEngineInput(scene, motion, table.schema().engine, set, stop_at_rest_after_s),
          table.Read(set)};
}

/// summary.json "kinematic" of a kinematic-drive run: the baseline correction and the peak
/// displacements before and after it.
nlohmann::json KinematicDriveJson(const EngineInput& input);

}  // namespace rockbench
