#pragma once
/// The scene: what a run simulates. Read from TOML (see README "Scene files"); every field has
/// the documented default, so a scene that omits a key gets exactly what the README says.
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/engine_settings.h"
#include "scene/mode.h"
#include "scene/synthetic_motion_def.h"

namespace rockbench {

/// One rigid body of a stack: a rectangular block (planar dynamics depend on width, height and
/// mass only), or a solid circular cylinder (shape "cylinder", one body, rocking in 3-D).
struct BlockDef {
  double width_m = 0.0;        ///< full width B = 2b, m (a cylinder's: its diameter)
  double height_m = 0.0;       ///< full height H = 2h, m
  double depth_m = 1.0;        ///< out-of-plane depth, m (a cylinder's: its diameter)
  double mass_kg = 0.0;        ///< mass, kg (given, or density times the volume)
  double density_kgpm3 = 0.0;  ///< density, kg/m^3 (0 when the scene gave the mass)
  /// Coulomb friction coefficient between this block's base and its support (the ground for
  /// block 1, the block below otherwise), dimensionless, >= 0; infinity (the default, the key
  /// absent): no sliding, the thesis's assumption (docs/sliding.md).
  double friction = std::numeric_limits<double>::infinity();
  /// The body's kind (`shape`, scene/body_kind.h): "block", the planar rigid block, unless the
  /// table names another registered kind. Every body of a stack is of one kind.
  std::string shape = "block";
  /// A cylinder's diameter D, m (0 for a block). Its width and depth are D too: the bounding
  /// box, and the planar section of its planar limit (critical angle atan(D / H)). Last, so that
  /// a block's fields keep their order (width, height, depth, mass, density, ...).
  double diameter_m = 0.0;
};

/// A body's volume, m^3: width * height * depth for a block, pi D^2 H / 4 for a cylinder.
double BodyVolume_m3(const BlockDef& body);

/// Initial state, thesis sign convention (theta > 0 tilts right about the right-hand corner):
/// block k's absolute angle and rate at index k - 1 (bottom first). A fixed capacity on purpose:
/// code that sets an entry (initial.theta_rad[1]) can never write out of bounds. The entries at
/// and beyond the scene's block_count() are zero (ValidateScene checks it).
struct InitialState {
  std::array<double, kMaxBlocks> theta_rad{};    ///< rad
  std::array<double, kMaxBlocks> omega_radps{};  ///< rad/s
  /// A cylinder's state (shape "cylinder"; zero for blocks), docs/three-d.md: the tilt of its
  /// axis from vertical (>= 0), the azimuth toward which its top leans (from +x toward +y), and
  /// the rates of tilt, azimuth and spin about its axis.
  std::array<double, kMaxBlocks> tilt_rad{};            ///< rad, >= 0
  std::array<double, kMaxBlocks> azimuth_rad{};         ///< rad
  std::array<double, kMaxBlocks> tilt_rate_radps{};     ///< rad/s
  std::array<double, kMaxBlocks> azimuth_rate_radps{};  ///< rad/s
  std::array<double, kMaxBlocks> spin_rate_radps{};     ///< rad/s

  /// At rest. (Declared, so that the old four-number braces {theta1, theta2, omega1, omega2}
  /// no longer compile: they would fill theta_rad.)
  InitialState() = default;
};

enum class AccelUnits { kG, kMps2, kCmps2 };
enum class MotionKind {
  kFile,
  kHarmonic,
  kSinePulse,
  kCosinePulse,
  kRectangularPulse,
  kRicker,
  kKanaiTajimi,  ///< synthetic: filtered white noise with an envelope (synthetic_motion.h)
};

/// One component of base motion: a record (a file, or its samples given in the scene) or an
/// analytic kind. Acceleration is positive along +x (to the right) for horizontal, +y for
/// transverse (3-D bodies) and upwards for vertical.
struct MotionDef {
  std::string key;  ///< "base.horizontal", "base.transverse" or "base.vertical" (for messages)
  /// kFile: a sampled record, read from `file` or, when `file` is empty, given by `samples`.
  MotionKind kind = MotionKind::kFile;
  std::filesystem::path file;   ///< resolved path (relative paths are relative to the scene)
  std::string file_as_written;  ///< the path as the scene wrote it
  /// `samples = [...]`: the record's values in `units`, one every dt_s from start_s (kind kFile,
  /// `file` empty); the same record as a one-column file of their shortest texts (ShortestText).
  std::vector<double> samples;
  /// `resolution = R` with samples: every sample is known to +-R/2 (in `units`; 0: exact, as
  /// computed samples are), which compare.sample_precision perturbs. Absent: one unit of the
  /// last digit of each sample's shortest decimal text, as a one-column file of those texts.
  std::optional<double> samples_resolution;
  AccelUnits units = AccelUnits::kG;
  bool units_given = false;   ///< false: AT2 -> g; plain files and samples need units
  double scale = 1.0;         ///< multiplies the acceleration
  double dt_s = 0.0;          ///< sample interval of a one-column file or samples (0: not given)
  double amplitude_g = 0.0;   ///< analytic kinds: amplitude A, in g
  double frequency_hz = 0.0;  ///< analytic kinds: frequency f
  double duration_s = std::numeric_limits<double>::infinity();  ///< harmonic/rectangular length
  double start_s = 0.0;  ///< first sample time / pulse start t0
  /// kind = "harmonic": its phase, degrees: A sin(2 pi f (t - t0) + phase). Two harmonics a
  /// quarter period apart (phase_deg 0 and 90) make a rotating field.
  double phase_deg = 0.0;
  /// kind = "kanai_tajimi": the process, its envelope, sampling and seed. amplitude_g, when
  /// given, is the generated record's peak (its intensity then plays no part); the peak is read
  /// from amplitude_g alone (SyntheticProcess), never from synthetic.target_peak_mps2.
  SyntheticMotionDef synthetic;

  /// The synthetic process to generate: `synthetic` with its target peak amplitude_g, in m/s^2.
  SyntheticMotionDef SyntheticProcess() const;
  /// Whether the record is given by `samples` (kind kFile, no file).
  bool from_samples() const {
    return kind == MotionKind::kFile && file.empty() && !samples.empty();
  }
};

/// Why a record's sample `value` (in `units`, times def.scale) is beyond the physical
/// acceleration limit (limits::kMaxAccel_g), or "" within it: " = VALUE UNITS[ times
/// KEY.scale = S][ is A g]; expected an acceleration with magnitude at most 100 g (...)", to
/// follow the sample's name ("FILE:LINE: sample 4", "base.horizontal.samples[3]").
std::string SampleAccelProblem(const MotionDef& def, AccelUnits units, double value);

struct RunConfig {
  double duration_s = 10.0;         ///< simulated time, s
  double output_interval_s = 0.01;  ///< history sample interval, s (events are added)
  /// Gravitational acceleration of the simulation, m/s^2. Not the unit g of records and
  /// amplitude_g, which is standard gravity (kStandardGravity_mps2) whatever this says.
  double gravity_mps2 = 9.81;
};

enum class Integrator { kDopri5, kRk4, kDop853 };
enum class EventScheme { kLocated, kThesis };
enum class Equations { kNonlinear, kLinearized };
/// Which equations the reference runs on (mechanics.h): the thesis's explicit ones (one or two
/// blocks) or the N-block pivot chain (any N). kAuto: the thesis's for one or two blocks.
/// kUnilateral: the unilateral model (sliding and lift-off, docs/sliding.md) from t = 0, which
/// otherwise takes over only where a block slips or lifts off (a cross-check of the two).
enum class Formulation { kAuto, kThesis, kChain, kUnilateral };

/// Options of the reference model ([model] table).
struct ModelConfig {
  /// "dopri5" (adaptive 5(4), dense), "dop853" (adaptive 8(5,3), dense) or "rk4" (fixed)
  Integrator integrator = Integrator::kDopri5;
  double rtol = 1e-12;   ///< dopri5 / dop853 relative tolerance
  double atol = 1e-14;   ///< dopri5 / dop853 absolute tolerance, rad and rad/s
  double step_s = 1e-3;  ///< rk4 fixed step, s
  EventScheme events = EventScheme::kLocated;   ///< "located" or "thesis" (O(h) detection)
  Equations equations = Equations::kNonlinear;  ///< "nonlinear" or "linearized" (4.3.3)
  double overturn_rad = 1.5707963267948966;     ///< |theta_i| at which a block overturns
  /// Rest rule, dimensionless: a contact that would open after an impact with a relative rate
  /// below rest_rate_rel * sqrt(g / R) stays closed (R: the contact's pivot to the mass centre
  /// of what rests on it; README "Coming to rest"). 0: never. An excursion launched at that
  /// rate would rise (2/3) rest_rate_rel^2 / sin(theta_c): 2e-14 rad for the thesis's stack.
  double rest_rate_rel = 1e-7;
  bool check_transitions = true;  ///< evaluate no-impact transition criteria in every mode
  /// "thesis" (one or two blocks) or "chain" (any N); absent: the thesis's equations for one or
  /// two blocks, the chain beyond (docs/n-blocks.md).
  Formulation formulation = Formulation::kAuto;
  /// A cylinder (docs/three-d.md): a pass near upright lands its face when the far rim's
  /// clearance 2 R sin(tilt) falls to landing_clearance_rel * D, i.e. at the downward crossing
  /// of tilt = asin(landing_clearance_rel); a motion that keeps one vertical plane lands at tilt
  /// 0 exactly, as the planar model. 0: only at tilt 0 (a pass with azimuthal motion then
  /// never lands: it rolls round the rim).
  double landing_clearance_rel = 1e-4;
};

/// Comparison settings ([compare] table).
struct CompareConfig {
  /// Agreement-horizon tolerance, rad; nullopt: 10% of the reference's peak |theta| of that
  /// block, and never below 1% of the block's critical angle atan(B/H) (a block that barely
  /// moves would otherwise be held to a tolerance of zero).
  std::optional<double> tolerance_rad;
  /// Reference ensemble members run on perturbed inputs (the predictability horizon); 0: none.
  int members = 32;
  /// Engine members on the same perturbed inputs as the first reference members (the
  /// statistical comparison beyond the horizon); 0: none. At most `members` are used.
  int engine_members = 16;
  /// Each member's record (or pulse) amplitude is scaled by 1 + u * amplitude_rel, u uniform in
  /// [-1, 1], one u per component: what a record's scaling is known to (instrument, baseline
  /// correction, scale factor: 1e-2 at best).
  double amplitude_rel = 1e-2;
  /// Each record sample moves by u * sample_precision * (half a unit of its last printed digit),
  /// u uniform in [-1, 1]: the samples are known to their printed precision.
  double sample_precision = 1.0;
  /// Each nonzero initial angle and rate is scaled by 1 + u * initial_rel (a state at rest
  /// stays at rest: a block standing on its face is known exactly).
  double initial_rel = 1e-2;
  /// Seed of the perturbations: member i's inputs depend only on (seed, i).
  uint64_t seed = 1;
};

/// An engine run through the external-engine protocol (docs/external-engines.md), as a scene's
/// table [external.<name>] or a registry file names it: its manifest, or a bare command (an engine
/// with the protocol's standard settings only).
struct ExternalEngineRef {
  std::string name;   ///< the engine's name and the name of its settings table: "rapier"
  std::string where;  ///< "FILE:LINE" of the [external.<name>] table
  /// The manifest file (absolute, or relative to the file that named it: resolved here).
  std::filesystem::path manifest;
  /// Without a manifest: the command, run with the input file's path appended; a relative
  /// argument that names a file beside the naming file is made absolute.
  std::vector<std::string> command;
  /// The folder of the file that named the engine (relative paths of `command`).
  std::filesystem::path base_dir;
};

struct Scene {
  std::filesystem::path path;  ///< the scene file (empty for a scene built in code)
  std::string title;           ///< optional free text
  /// The stack, bottom first: blocks[0] stands on the ground, blocks[k] sits centred on
  /// blocks[k - 1]. 1 (Housner's block) to kMaxBlocks blocks.
  std::vector<BlockDef> blocks;
  InitialState initial;
  std::optional<MotionDef> horizontal;
  /// The second horizontal component, along +y ([base.transverse]): bodies rocking in 3-D only.
  std::optional<MotionDef> transverse;
  std::optional<MotionDef> vertical;
  RunConfig run;
  ModelConfig model;
  /// Every other top-level table: an engine's settings ([bullet], [ode], ...), as written;
  /// the engine checks its own (scene/engine_settings.h).
  std::map<std::string, RawEngineTable, std::less<>> engine_tables;
  /// The external engines the scene names ([external.<name>] tables), in file order.
  std::vector<ExternalEngineRef> external_engines;
  CompareConfig compare;

  /// Number of blocks of the stack.
  int block_count() const { return static_cast<int>(blocks.size()); }
  /// Whether the bodies rock in three dimensions (a cylinder), not in the x-z plane.
  bool three_dimensional() const;
  /// Whether some interface has a finite friction coefficient.
  bool has_finite_friction() const;
  /// Whether the motion may leave the thesis's assumptions: a finite friction somewhere or a
  /// vertical base motion. Histories then carry each block's slip and lift (u1..uN, z1..zN).
  bool tracks_slip_and_lift() const { return has_finite_friction() || vertical.has_value(); }
};

/// A scene error: names the file, line and key and what was expected.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads a scene file. `overrides` are "key=value" strings (dotted keys, TOML values, for
/// example "run.duration=3" or "base.horizontal.scale=0.5"), applied before validation.
/// Throws SceneError.
Scene LoadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});

/// Parses a scene from TOML text; `path` is used for messages and relative files.
Scene ParseScene(std::string_view toml_text, const std::filesystem::path& path,
                 const std::vector<std::string>& overrides = {});

/// Reads a registry file of external engines: [external.<name>] tables only, each with either
/// `manifest = "FILE"` or `command = ["PROGRAM", "ARG", ...]`. Throws SceneError naming the file,
/// line and key.
std::vector<ExternalEngineRef> LoadExternalEngineRegistry(const std::filesystem::path& path);

/// Checks a scene built in code (the same checks as the reader). Throws SceneError.
void ValidateScene(const Scene& scene);

/// The entry check of a part of the harness that simulates, draws or analyses one or two blocks
/// only (issue 23 generalises it): throws SceneError "FILE: WHO: N-block scenes (N blocks) are
/// not simulated yet (issue 23); 1 or 2 blocks" for a scene of 3 or more blocks. `who` names the
/// part ("reference model", "engine bullet", "render", ...).
void RequireAtMostTwoBlocks(const Scene& scene, std::string_view who);

/// The entry check of a part of the harness that compares, sweeps, studies, draws or reports
/// planar blocks only: throws SceneError "FILE: block1.shape: WHO: ..." for a scene of a body
/// rocking in 3-D (a cylinder), which `rockbench run` runs with the reference and the 3-D engines
/// (docs/three-d.md).
void RequirePlanarBodies(const Scene& scene, std::string_view who);

/// True when a record file is read as PEER AT2: its name ends in ".AT2" (any case). Any other
/// file is read as a plain column file.
bool IsAt2File(const std::filesystem::path& file);
/// "harmonic", "sine_pulse", ...; "file" for kFile.
std::string_view MotionKindName(MotionKind kind);
/// The shortest text that reads back as the same double ("-1", "0.15", "1e-10", "inf", "nan"):
/// the same bytes for the same number on every run and machine.
std::string ShortestText(double v);
/// "g", "m/s2", "cm/s2".
std::string_view AccelUnitsName(AccelUnits units);
/// "thesis" or "chain" as a scene writes model.formulation; nullopt for another text.
std::optional<Formulation> ParseFormulation(std::string_view text);
/// "dopri5", "dop853", "rk4": the [model] integrator's name as a scene writes it.
const char* IntegratorName(Integrator integrator);
/// The unit g of records, `units = "g"` and `amplitude_g`: standard gravity, m/s^2 by
/// definition (3rd CGPM, 1901), independent of the scene's [run] gravity.
inline constexpr double kStandardGravity_mps2 = 9.80665;
/// Metres per second squared in one unit (g is kStandardGravity_mps2).
double AccelUnitsToMps2(AccelUnits units);

}  // namespace rockbench
