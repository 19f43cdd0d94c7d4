#pragma once
/// Rocking modes of two stacked blocks (Roussis 1999, section 4.2) and of one block, the contacts
/// each mode closes, and the rule that gives a tilt its contact.
#include <cstdint>
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

/// The mode of a contact set (for one block the interface is ignored). Inline: the thesis's
/// equations ask for it at every evaluation.
inline Mode ModeOf(Contacts c, bool two_blocks) {
  if (!two_blocks) c.interface = Contact::kFace;
  if (c.ground == Contact::kFace) {
    if (c.interface == Contact::kFace) return Mode::kRest;
    return c.interface == Contact::kRight ? Mode::k4a : Mode::k4b;
  }
  const bool right = c.ground == Contact::kRight;
  if (c.interface == Contact::kFace) return right ? Mode::k3a : Mode::k3b;
  const bool same = c.interface == c.ground;
  if (right) return same ? Mode::k1a : Mode::k2a;
  return same ? Mode::k1b : Mode::k2b;
}

/// Most blocks a stack may have (the scene reader and ValidateScene check a scene against it).
inline constexpr int kMaxBlocks = 64;
/// The most blocks the reference's unilateral model (sliding and lift-off, docs/sliding.md)
/// takes: a stack with a finite friction has at most this many.
inline constexpr int kUnilateralMaxBlocks = 20;

/// The contact state of a stack of N blocks: one Contact per interface, bottom first. Interface
/// k (1-based) is block k on its support (the ground for k = 1, block k - 1 above it): closed on
/// its face, or rocking about block k's right or left base corner. N = 1 and N = 2 are the
/// thesis's modes (ConfigurationOf / ModeOfConfiguration); N >= 3 has 3^N of them, named by
/// their letters. A value type of 24 bytes (no allocation), so that every history sample and
/// every event can carry one.
class Configuration {
 public:
  /// No interfaces (an empty stack).
  Configuration() = default;
  /// `interfaces` interfaces (0..kMaxBlocks), every one closed on its face: the stack at rest.
  explicit Configuration(int interfaces);

  /// Number of interfaces (= blocks).
  int size() const { return size_; }
  /// Interface k's contact, k = 0 (the ground) .. size() - 1.
  Contact operator[](int k) const {
    return static_cast<Contact>((bits_[k >> 5] >> (2 * (k & 31))) & 3u);
  }
  void set(int k, Contact c) {
    const int shift = 2 * (k & 31);
    bits_[k >> 5] =
        (bits_[k >> 5] & ~(uint64_t{3} << shift)) | (uint64_t{static_cast<unsigned>(c)} << shift);
  }
  /// Every interface closed on its face.
  bool at_rest() const { return bits_[0] == 0 && bits_[1] == 0; }
  /// Number of interfaces that rock (the degrees of freedom).
  int open_count() const;
  friend bool operator==(const Configuration& a, const Configuration& b) {
    return a.size_ == b.size_ && a.bits_[0] == b.bits_[0] && a.bits_[1] == b.bits_[1];
  }
  friend bool operator!=(const Configuration& a, const Configuration& b) { return !(a == b); }

 private:
  // Two bits per interface (Contact's value: face 0, right 1, left 2), 32 per word.
  uint64_t bits_[2] = {0, 0};
  int32_t size_ = 0;
};
static_assert(static_cast<int>(Contact::kFace) == 0, "a zeroed Configuration is at rest");

/// The configuration of a thesis mode in a stack of `blocks` (1 or 2) blocks: its contacts
/// (ContactsOf), the interface dropped for one block.
Configuration ConfigurationOf(Mode mode, int blocks);
/// The thesis mode of a configuration of 1 or 2 interfaces; nullopt for more.
/// Inline, by table (ModeOf's answers): the thesis's equations ask for it at every evaluation.
inline std::optional<Mode> ModeOfConfiguration(const Configuration& configuration) {
  // [ground][interface], by Contact's values (face, right, left).
  static constexpr Mode kModes[3][3] = {{Mode::kRest, Mode::k4a, Mode::k4b},
                                        {Mode::k3a, Mode::k1a, Mode::k2a},
                                        {Mode::k3b, Mode::k2b, Mode::k1b}};
  const int size = configuration.size();
  if (size != 1 && size != 2) return std::nullopt;
  const int ground = static_cast<int>(configuration[0]);
  return kModes[ground][size == 2 ? static_cast<int>(configuration[1]) : 0];
}

/// The text of a configuration, as histories and events write it: the thesis's mode name for 1
/// or 2 blocks ("rest", "3a", "1b", ...), else one letter per interface, bottom first: 'f' a
/// closed face, 'r' the right corner, 'l' the left corner ("frr": block 1 at rest, blocks 2 and 3
/// rocking on their right corners).
std::string ConfigurationName(const Configuration& configuration);
/// Inverse of ConfigurationName for a stack of `blocks` blocks; the letter form is read for any
/// number of blocks. nullopt for a text that names no configuration of that stack.
std::optional<Configuration> ParseConfiguration(std::string_view text, int blocks);

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
/// (reference/thesis/observables.h ModeOfState) and of the engines' monitor.
Contact TiltContact(double angle_rad, double rate_radps, TiltThresholds thresholds = {});

/// The same rule when the angle's side is already decided (kRight, kLeft, or kFace for flat),
/// for example by a hysteresis on the angle: a flat tilt takes the side of its rate when
/// |rate| > rate_threshold_radps.
Contact TiltContact(Contact angle_side, double rate_radps, double rate_threshold_radps);

}  // namespace rockbench
