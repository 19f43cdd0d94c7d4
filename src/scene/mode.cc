#include "scene/mode.h"

#include <array>
#include <cmath>

namespace rockbench {
namespace {
constexpr std::array<std::string_view, 9> kNames = {"rest", "1a", "1b", "2a", "2b",
                                                    "3a",   "3b", "4a", "4b"};
}  // namespace

std::string_view ModeName(Mode mode) {
  return kNames[static_cast<int>(mode)];
}

std::optional<Mode> ParseMode(std::string_view name) {
  for (size_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) return static_cast<Mode>(i);
  }
  return std::nullopt;
}

Mode ModeOf(Contacts c, bool two_blocks) {
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

Contact TiltContact(Contact angle_side, double rate_radps, double rate_threshold_radps) {
  if (angle_side != Contact::kFace) return angle_side;
  if (!(std::abs(rate_radps) > rate_threshold_radps)) return Contact::kFace;
  return rate_radps > 0.0 ? Contact::kRight : Contact::kLeft;
}

Contact TiltContact(double angle_rad, double rate_radps, TiltThresholds thresholds) {
  Contact angle_side = Contact::kFace;
  if (std::abs(angle_rad) > thresholds.angle_rad) {
    angle_side = angle_rad > 0.0 ? Contact::kRight : Contact::kLeft;
  }
  return TiltContact(angle_side, rate_radps, thresholds.rate_radps);
}

}  // namespace rockbench
