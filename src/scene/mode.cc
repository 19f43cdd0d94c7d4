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

Configuration::Configuration(int interfaces) : size_(interfaces) {}

int Configuration::open_count() const {
  int n = 0;
  for (int k = 0; k < size_; ++k) n += (*this)[k] != Contact::kFace;
  return n;
}

Configuration ConfigurationOf(Mode mode, int blocks) {
  const Contacts c = ContactsOf(mode);
  Configuration out(blocks);
  out.set(0, c.ground);
  if (blocks >= 2) out.set(1, c.interface);
  return out;
}

std::string ConfigurationName(const Configuration& configuration) {
  if (const std::optional<Mode> mode = ModeOfConfiguration(configuration)) {
    return std::string(ModeName(*mode));
  }
  std::string text(static_cast<size_t>(configuration.size()), 'f');
  for (int k = 0; k < configuration.size(); ++k) {
    if (configuration[k] == Contact::kRight) text[k] = 'r';
    if (configuration[k] == Contact::kLeft) text[k] = 'l';
  }
  return text;
}

std::optional<Configuration> ParseConfiguration(std::string_view text, int blocks) {
  if (blocks < 1 || blocks > kMaxBlocks) return std::nullopt;
  if (blocks <= 2) {
    if (const std::optional<Mode> mode = ParseMode(text)) {
      // One block has only rest, 3a and 3b (its block-2 contact is a face).
      if (blocks == 1 && ContactsOf(*mode).interface != Contact::kFace) return std::nullopt;
      return ConfigurationOf(*mode, blocks);
    }
  }
  if (text.size() != static_cast<size_t>(blocks)) return std::nullopt;
  Configuration out(blocks);
  for (int k = 0; k < blocks; ++k) {
    switch (text[k]) {
      case 'f':
        break;
      case 'r':
        out.set(k, Contact::kRight);
        break;
      case 'l':
        out.set(k, Contact::kLeft);
        break;
      default:
        return std::nullopt;
    }
  }
  return out;
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
