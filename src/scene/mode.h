#pragma once
/// Rocking modes of two stacked blocks (Roussis 1999, section 4.2) and of one block, the contacts
/// each mode closes, and the rule that gives a tilt its contact.
#include <optional>
#include <string>
#include <string_view>

namespace rockbench {

/// Mode of response. Sign convention of the thesis: theta > 0 tilts right about the right corner.
/// - kRest: both blocks still.
/// - k1a/k1b: both rock, block 2 pivots on the same side as block 1 (1a: theta2 > theta1 > 0).
/// - k2a/k2b: both rock, block 2 pivots on the opposite side (2a: theta1 > 0, theta2 < theta1).
/// - k3a/k3b: locked together, theta2 = theta1 (3a: theta1 > 0).
/// - k4a/k4b: block 1 still, block 2 rocks on it (4a: theta2 > 0).
/// A single block (no block 2) uses kRest, k3a and k3b (the stack is the one block).
enum class Mode { kRest, k1a, k1b, k2a, k2b, k3a, k3b, k4a, k4b };

/// "rest", "1a", ..., "4b".
std::string_view ModeName(Mode mode);
/// Inverse of ModeName; nullopt for an unknown name.
std::optional<Mode> ParseMode(std::string_view name);

/// How a contact is closed: a whole face, or a single corner on the right (+x) or left side.
enum class Contact { kFace, kRight, kLeft };
struct Contacts {
  Contact ground = Contact::kFace;     ///< block 1 on the ground
  Contact interface = Contact::kFace;  ///< block 2 on block 1
};
/// The contacts of a mode (1a: right/right, 2a: right/left, 3a: right/face, 4a: face/right...).
/// Inline: the reference's event functions ask for it at every evaluation.
inline Contacts ContactsOf(Mode mode) {
  switch (mode) {
    case Mode::kRest:
      return {Contact::kFace, Contact::kFace};
    case Mode::k1a:
      return {Contact::kRight, Contact::kRight};
    case Mode::k1b:
      return {Contact::kLeft, Contact::kLeft};
    case Mode::k2a:
      return {Contact::kRight, Contact::kLeft};
    case Mode::k2b:
      return {Contact::kLeft, Contact::kRight};
    case Mode::k3a:
      return {Contact::kRight, Contact::kFace};
    case Mode::k3b:
      return {Contact::kLeft, Contact::kFace};
    case Mode::k4a:
      return {Contact::kFace, Contact::kRight};
    case Mode::k4b:
      return {Contact::kFace, Contact::kLeft};
  }
  return {};
}

/// The mode of a contact set (for one block the interface is ignored).
Mode ModeOf(Contacts contacts, bool two_blocks);

/// Below these a tilt gives no side. Zero (the default) is the rule for exact states, such as
/// the reference's: its closed contacts have exactly zero angle and rate. A noisy state, such as
/// an engine's readout, needs thresholds above its noise (the engines' monitor: MonitorConfig in
/// engines/common/monitor.h, 1e-5 rad to tilt, 5e-6 rad to land, 1e-2 rad/s).
struct TiltThresholds {
  double angle_rad = 0.0;   ///< |angle| at or below this gives no side, rad
  double rate_radps = 0.0;  ///< |rate| at or below this gives no side, rad/s
};

/// The contact of one tilt (block 1 on the ground: theta1, omega1; block 2 on block 1: theta2 -
/// theta1, omega2 - omega1): the right corner when the angle is beyond the threshold to the
/// right, the left corner to the left; a flat block turning faster than the rate threshold
/// pivots on the corner on the side of its rate (it is passing through zero, or starting to
/// rock); flat and still, it sits on its face (Contact::kFace). The one rule of the reference
/// (reference/observables.h ModeOfState) and of the engines' monitor.
Contact TiltContact(double angle_rad, double rate_radps, TiltThresholds thresholds = {});

/// The same rule when the angle's side is already decided (kRight, kLeft, or kFace for flat),
/// for example by a hysteresis on the angle: a flat tilt takes the side of its rate when
/// |rate| > rate_threshold_radps.
Contact TiltContact(Contact angle_side, double rate_radps, double rate_threshold_radps);

}  // namespace rockbench
