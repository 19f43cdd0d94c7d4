#pragma once
/// How a run's messages say a value that stopped being finite and a time: the words of
/// summary.json's "non_finite" (status non_finite, engine/outcome.h) and of the status details,
/// shared by the reference (reference/simulate.cc) and the engines' monitor
/// (engines/common/monitor.cc).
#include <string>

namespace rockbench {

/// A value that is not finite, in words: "NaN", "+inf" or "-inf".
const char* NonFiniteValueText(double v);

/// A time for a message, s, to 9 significant digits ("%.9g").
std::string MessageTimeText(double t_s);

}  // namespace rockbench
