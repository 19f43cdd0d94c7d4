#pragma once
/// Numbers as text, for messages, CSV cells and report pages.
#include <string>

namespace rockbench {

/// `v` printed with one printf conversion, e.g. Format("%.2e", v) -> "1.25e-03".
std::string Format(const char* printf_format, double v);

}  // namespace rockbench
