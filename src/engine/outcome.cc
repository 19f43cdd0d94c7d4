#include "engine/outcome.h"

#include <array>
#include <charconv>
#include <ostream>
#include <string>
#include <utility>

namespace rockbench {
namespace {

constexpr std::array<std::pair<RunStatus, const char*>, 7> kStatusTexts = {{
    {RunStatus::kCompleted, "completed"},
    {RunStatus::kOverturned, "overturned"},
    {RunStatus::kAtRest, "at_rest"},
    {RunStatus::kAssumptionViolated, "assumption_violated"},
    {RunStatus::kBlowUp, "blow_up"},
    {RunStatus::kNonFinite, "non_finite"},
    {RunStatus::kLeftSupport, "left_support"},
}};

}  // namespace

const char* StatusText(RunStatus status) {
  for (const auto& [s, text] : kStatusTexts) {
    if (s == status) return text;
  }
  return "unknown";
}

std::optional<RunStatus> ParseRunStatus(std::string_view text) {
  for (const auto& [s, t] : kStatusTexts) {
    if (text == t) return s;
  }
  return std::nullopt;
}

std::string InterfaceName(int k, int blocks) {
  if (k == 0) return "ground";
  if (blocks <= 2) return "interface";
  return "interface" + std::to_string(k + 1);
}

int ImpactInterface(std::string_view kind) {
  if (kind == "ground_impact") return 0;
  if (kind == "interface_impact") return 1;
  constexpr std::string_view kHead = "interface", kTail = "_impact";
  if (kind.size() <= kHead.size() + kTail.size() || kind.substr(0, kHead.size()) != kHead ||
      kind.substr(kind.size() - kTail.size()) != kTail) {
    return -1;
  }
  const std::string_view digits =
      kind.substr(kHead.size(), kind.size() - kHead.size() - kTail.size());
  int block = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), block);
  if (ec != std::errc() || end != digits.data() + digits.size() || block < 2) return -1;
  return block - 1;
}

std::ostream& operator<<(std::ostream& os, RunStatus status) {
  return os << StatusText(status);
}

}  // namespace rockbench
