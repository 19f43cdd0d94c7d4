#include "util/format.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rockbench {

std::string Format(const char* printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

double RoundTime_s(double t_s) {
  if (!std::isfinite(t_s)) return t_s;
  return std::strtod(Format("%.9f", t_s).c_str(), nullptr);
}

std::string QuotedList(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) {
    if (!out.empty()) out += ", ";
    out += '"';
    out += name;
    out += '"';
  }
  return out;
}

}  // namespace rockbench
