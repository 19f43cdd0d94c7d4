#include "engine/non_finite.h"

#include <cmath>
#include <cstdio>

namespace rockbench {

const char* NonFiniteValueText(double v) {
  return std::isnan(v) ? "NaN" : (v > 0.0 ? "+inf" : "-inf");
}

std::string MessageTimeText(double t_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", t_s);
  return buf;
}

}  // namespace rockbench
