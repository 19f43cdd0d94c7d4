#pragma once
// The rules a scene's values obey, shared by the scene's reader (scene_reader.cc) and its
// validation (scene.cc): the physical limits of the keys (scene/limits.h, docs/limits.md), what a
// number must be, the enum choices and the wording of their messages. Internal to src/scene.
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/limits.h"
#include "scene/scene.h"

namespace rockbench::scene_rules {

// A physical limit of a key (scene/limits.h, docs/limits.md): the closed range [lo, hi] of the
// value (of |value| when `magnitude`), and why.
struct Limit {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  const char* why = "";
  bool magnitude = false;
};

inline const Limit kLengthLimit{limits::kMinLength_m, limits::kMaxLength_m,
                                "a 0.1 mm grain to a 10 km slab; docs/limits.md"};
inline const Limit kMassLimit{limits::kMinMass_kg, limits::kMaxMass_kg, "docs/limits.md"};
inline const Limit kDensityLimit{limits::kMinDensity_kgpm3, limits::kMaxDensity_kgpm3,
                                 "air is 1.2, osmium 22,590; docs/limits.md"};
inline const Limit kAccelLimit{0.0, limits::kMaxAccel_g,
                               "far above any recorded ground motion (about 4 g); docs/limits.md",
                               true};
inline const Limit kFrequencyLimit{0.0, limits::kMaxFrequency_hz,
                                   "ground motion of structural interest is below 50 Hz; "
                                   "docs/limits.md"};
inline const Limit kDurationLimit{0.0, limits::kMaxDuration_s, "one day; docs/limits.md"};
inline const Limit kGravityLimit{limits::kMinGravity_mps2, limits::kMaxGravity_mps2,
                                 "Ceres 0.28, the Sun 274; docs/limits.md"};
inline const Limit kRtolLimit{limits::kMinRtol, 0.1,
                              "below 1e-15 the error estimate is rounding noise; docs/limits.md"};
inline const Limit kAtolLimit{limits::kMinAtol, 0.1, "docs/limits.md"};
inline const Limit kRateLimit{0.0, limits::kMaxRate_radps, "ten turns a second; docs/limits.md",
                              true};
inline const Limit kOverturnLimit{0.0, 1.5707963267948966,
                                  "a block tilted pi/2 lies on its side; docs/limits.md"};
inline const Limit kSamplePrecisionLimit{0.0, 100.0,
                                         "a record's samples are known to their printed digits; "
                                         "docs/limits.md"};
inline const Limit kSampleIntervalLimit{1e-6, 1.0,
                                        "records are sampled at 50 to 1000 Hz; docs/limits.md"};
inline const Limit kToleranceLimit{0.0, 1.5707963267948966, "docs/limits.md"};
// The largest finite friction coefficient: the reference's contact problem takes 1e4 for an
// infinite one (reference/unilateral/unilateral.cc, kLcpInfiniteFriction; its impact limit at mu =
// 1e4), so above it a Coulomb friction is no slip in the model; a larger value only risks the
// engines' arithmetic (MuJoCo's state is not finite at 1e100). No slip at all: leave friction out,
// or inf.
inline constexpr double kMaxFiniteFriction = 1e4;
inline const char kFrictionRange[] =
    "a number from 0 to 10000, or inf (above 1e4 the reference's contact problem treats a "
    "friction as infinite; leave friction out for no slip; docs/limits.md)";

// An acceleration in g for messages, to six digits.
std::string GText(double g);

bool Within(double v, const Limit& lim);

// " from LO to HI (why)" or " with |value| at most HI (why)".
std::string LimitText(const Limit& lim);

// What a number must be; the message text names it and the unit.
enum class Rule {
  kFinite,
  kPositive,
  kNonNegative,
  kNonNegativeOrInfinite,
  kFraction,
  kUnitInterval
};

std::string Expectation(Rule rule, std::string_view unit);

bool Satisfies(double v, Rule rule);

// One enum choice: its TOML string and value.
template <typename E>
using Choices = std::vector<std::pair<std::string_view, E>>;

template <typename E>
inline std::string ChoiceList(const Choices<E>& choices) {
  std::string out;
  for (size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) out += i + 1 == choices.size() ? " or " : ", ";
    out += '"';
    out += choices[i].first;
    out += '"';
  }
  return out;
}

inline const Choices<MotionKind> kKinds = {{"harmonic", MotionKind::kHarmonic},
                                           {"sine_pulse", MotionKind::kSinePulse},
                                           {"cosine_pulse", MotionKind::kCosinePulse},
                                           {"rectangular_pulse", MotionKind::kRectangularPulse},
                                           {"ricker", MotionKind::kRicker},
                                           {"kanai_tajimi", MotionKind::kKanaiTajimi}};
inline const Choices<SyntheticEnvelope> kEnvelopes = {{"jennings", SyntheticEnvelope::kJennings},
                                                      {"none", SyntheticEnvelope::kNone}};
inline const Choices<AccelUnits> kUnits = {
    {"g", AccelUnits::kG}, {"m/s2", AccelUnits::kMps2}, {"cm/s2", AccelUnits::kCmps2}};

// The message of block k (2..N) wider than block k - 1: its pivots would not be on the top face
// below it.
std::string WiderThanBelow(const Scene& s, int k);

// The file's name in messages ("scene" for a scene given as text).
std::string FileLabel(const std::filesystem::path& path);

}  // namespace rockbench::scene_rules
