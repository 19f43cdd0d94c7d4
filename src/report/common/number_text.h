#pragma once
/// Numbers as the report pages write them.
#include <string>

namespace rockbench::report {

/// `significant` significant digits (printf %g); "n/a" for NaN.
std::string Num(double v, int significant = 4);

/// `decimals` digits after the point (printf %f).
std::string Fixed(double v, int decimals);

}  // namespace rockbench::report
