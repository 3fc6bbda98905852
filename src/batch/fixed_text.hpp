#pragma once
// Numbers as the batch's CSV files and its HTML summary print them: fixed digits, "C" locale.
#include <cstdio>
#include <string>

namespace cropsight::batch::detail {

inline std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace cropsight::batch::detail
