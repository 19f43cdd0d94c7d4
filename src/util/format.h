#pragma once
/// Numbers as text, for messages, CSV cells and report pages.
#include <string>
#include <string_view>
#include <vector>

namespace rockbench {

/// `v` printed with one printf conversion, e.g. Format("%.2e", v) -> "1.25e-03".
std::string Format(const char* printf_format, double v);

/// A time on a grid of whole nanoseconds, as the double nearest its decimal text: k * dt
/// computed in binary (614 * 0.01 = 6.140000000000001) is written as 6.14. Output only.
double RoundTime_s(double t_s);

/// Names in double quotes, joined by ", " for a message: {"block", "drum"} -> "block", "drum".
std::string QuotedList(const std::vector<std::string>& names);

}  // namespace rockbench
