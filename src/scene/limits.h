#pragma once
/// Physical and resource limits of a run, checked before anything is allocated or simulated
/// (docs/limits.md gives the reason for each figure). A value past a limit is bad input: a
/// SceneError naming the file, key, value and the limit.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace rockbench {
namespace limits {

/// Largest |base acceleration| (a record's sample after units and scale, an analytic amplitude
/// times scale), in standard g. The largest accelerations ever recorded in earthquakes are about
/// 4 g (vertical; horizontal about 2.7 g); 100 g is far above any ground motion, and below it a
/// double keeps every product the models form finite.
inline constexpr double kMaxAccel_g = 100.0;
/// Block sizes (width, height, depth), m: a 0.1 mm grain to a 10 km slab. Outside, the
/// engines' contact tolerances (of order 1e-3 to 1e-2 m) or the double's range, not rocking,
/// decide the motion; a denormal or zero size is refused here, not run slowly.
inline constexpr double kMinLength_m = 1e-4;
inline constexpr double kMaxLength_m = 1e4;
/// Block mass, kg, and density, kg/m^3 (air ~1.2; osmium 22,590).
inline constexpr double kMinMass_kg = 1e-9;
inline constexpr double kMaxMass_kg = 1e15;
inline constexpr double kMinDensity_kgpm3 = 1e-3;
inline constexpr double kMaxDensity_kgpm3 = 1e5;
/// Gravity of the run, m/s^2 (Ceres 0.28; the Sun's surface 274).
inline constexpr double kMinGravity_mps2 = 1e-2;
inline constexpr double kMaxGravity_mps2 = 1e3;
/// Simulated duration, s (one day: ten times the longest strong-motion record).
inline constexpr double kMaxDuration_s = 86400.0;
/// Analytic base-motion frequency, Hz: ground motion of structural interest is below 50 Hz,
/// records are sampled at 50 to 1000 Hz.
inline constexpr double kMaxFrequency_hz = 1000.0;
/// Smallest [model] rtol: a few units of double rounding (2.2e-16); below, the error estimate
/// is rounding noise and the step size collapses.
inline constexpr double kMinRtol = 1e-15;
/// Smallest [model] atol, rad and rad/s.
inline constexpr double kMinAtol = 1e-20;
/// Largest initial rate |omega|, rad/s (a block spinning ten turns a second).
inline constexpr double kMaxRate_radps = 100.0;
/// Largest input file (scene, study, record), bytes: the longest real records are a few MB
/// (1e6 samples); 256 MiB holds about 1.6e7 samples of PEER's 16-character values.
inline constexpr double kMaxInputFile_bytes = 256.0 * 1024 * 1024;
/// Default estimated wall time of one command, s (six hours); --wall-limit sets it.
inline constexpr double kDefaultTimeBudget_s = 6.0 * 3600.0;
/// Default memory budget of one command, bytes (raise it with --memory-budget GIB).
inline constexpr double kDefaultMemoryBudget_bytes = 2.0 * 1024 * 1024 * 1024;

}  // namespace limits

/// What one command may use. The estimate of a run (rows x columns, samples, frames, steps)
/// is checked against it before allocating.
struct ResourceBudget {
  double memory_bytes = limits::kDefaultMemoryBudget_bytes;  ///< bytes
  /// Estimated wall time a command may take up front, s: --wall-limit when given, else
  /// limits::kDefaultTimeBudget_s. (The wall-clock limit itself stops a run that takes longer.)
  double wall_s = limits::kDefaultTimeBudget_s;
};

/// The memory budget of this process's command: set once by the CLI from --memory-budget
/// before any scene is read (the readers check records and synthetic motions against it).
void SetProcessBudget(const ResourceBudget& budget);
const ResourceBudget& ProcessBudget();

/// Why `path` cannot be read as an input file of the kind `what` ("scene file", "record
/// file", ...), or "" when it can: it must exist, be a regular file (not a folder, device,
/// pipe or socket), have a path without NUL characters and of a sane length, and be at most
/// `max_bytes` long. The message starts with the path (cut to an excerpt) and says what was
/// expected.
std::string InputFileProblem(const std::filesystem::path& path, const std::string& what,
                             double max_bytes = limits::kMaxInputFile_bytes);

/// Throws SceneError "WHERE: KEY: needs an estimated X GiB (WHAT), more than the memory budget
/// of Y GiB: shorten or coarsen it, or raise the budget with --memory-budget GIB" when
/// `estimate_bytes` exceeds the budget (or is not finite).
void CheckMemoryEstimate(double estimate_bytes, const ResourceBudget& budget,
                         const std::string& where, const std::string& key, const std::string& what);

/// "1.5 GiB", "120 MiB", "3 KiB": a byte count for messages.
std::string ByteText(double bytes);

/// A short excerpt of text for a message: at most `max_chars` characters, control characters
/// and bytes outside printable ASCII escaped (\r, \n, \t, \0, \xHH), followed by
/// "... (N bytes)" when cut. Messages never echo a long value or a file's content in full.
std::string Excerpt(std::string_view text, size_t max_chars = 60);

}  // namespace rockbench
