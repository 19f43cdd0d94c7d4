#include "scene/scene_rules.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "util/format.h"

namespace rockbench::scene_rules {

std::string GText(double g) {
  return Format("%.6g", g);
}

bool Within(double v, const Limit& lim) {
  const double x = lim.magnitude ? std::abs(v) : v;
  return x >= lim.lo && x <= lim.hi;
}

std::string LimitText(const Limit& lim) {
  // Six digits when they read back as the same number (0.0001, 86400), else every digit.
  const auto num = [](double v) {
    std::array<char, 64> buf{};
    std::snprintf(buf.data(), buf.size(), "%.6g", v);
    return std::strtod(buf.data(), nullptr) == v ? std::string(buf.data()) : ShortestText(v);
  };
  std::string out;
  if (lim.magnitude) {
    out = " with magnitude at most " + num(lim.hi);
  } else if (lim.lo > 0.0) {
    out = " from " + num(lim.lo) + " to " + num(lim.hi);
  } else {
    out = " at most " + num(lim.hi);
  }
  if (lim.why[0] != '\0') out += std::string(" (") + lim.why + ")";
  return out;
}

std::string Expectation(Rule rule, std::string_view unit) {
  std::string what;
  switch (rule) {
    case Rule::kFinite:
      what = "a finite number";
      break;
    case Rule::kPositive:
      what = "a positive number";
      break;
    case Rule::kNonNegative:
      what = "a number >= 0";
      break;
    case Rule::kNonNegativeOrInfinite:
      what = "a number >= 0 or inf";
      break;
    case Rule::kFraction:
      what = "a number in (0, 1]";
      break;
    case Rule::kUnitInterval:
      what = "a number in [0, 1]";
      break;
  }
  if (!unit.empty()) what += " (" + std::string(unit) + ")";
  return what;
}

bool Satisfies(double v, Rule rule) {
  if (rule == Rule::kNonNegativeOrInfinite) return v >= 0.0;  // NaN fails
  if (!std::isfinite(v)) return false;
  switch (rule) {
    case Rule::kFinite:
      return true;
    case Rule::kPositive:
      return v > 0.0;
    case Rule::kNonNegative:
    case Rule::kNonNegativeOrInfinite:
      return v >= 0.0;
    case Rule::kFraction:
      return v > 0.0 && v <= 1.0;
    case Rule::kUnitInterval:
      return v >= 0.0 && v <= 1.0;
  }
  return false;
}

std::string WiderThanBelow(const Scene& s, int k) {
  const std::string below = std::to_string(k - 1), self = std::to_string(k);
  return "expected at most block" + below + ".width (" + ShortestText(s.blocks[k - 2].width_m) +
         " m: block " + self + " would pivot outside block " + below +
         "'s top face, which the model does not describe), got " +
         ShortestText(s.blocks[k - 1].width_m);
}

std::string FileLabel(const std::filesystem::path& path) {
  return path.empty() ? std::string("scene") : Excerpt(path.string(), 200);
}

}  // namespace rockbench::scene_rules
