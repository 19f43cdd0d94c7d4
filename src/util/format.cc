#include "util/format.h"

#include <cstdio>

namespace rockbench {

std::string Format(const char* printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

}  // namespace rockbench
