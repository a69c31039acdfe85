#include "encoder/src/io/shortest_decimal.h"

#include <cstdio>
#include <cstdlib>

namespace m4d {

double ShortestDecimal(float value) {
  char text[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) break;
  }
  return std::strtod(text, nullptr) + 0.0;  // + 0.0: no "-0.0" in the file
}

}  // namespace m4d
