#include "report/common/number_text.h"

#include <cmath>
#include <cstdio>

namespace rockbench::report {

std::string Num(double v, int significant) {
  if (std::isnan(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}

std::string Fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace rockbench::report
