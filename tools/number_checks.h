// Checks of numeric options: NaN and infinity are refused when the command line is parsed (not
// hours later), and bounds are printed as people write them (CLI11's Range prints the largest
// double with 309 digits and lets NaN through).
#ifndef M4D_TOOLS_NUMBER_CHECKS_H_
#define M4D_TOOLS_NUMBER_CHECKS_H_

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace m4d {

// 3, 0.25, 1e-4, 4194304: whole numbers in full, others in %g.
inline std::string HumanNumber(double value) {
  char text[32];
  const bool whole = value == std::floor(value) && std::fabs(value) < 1e15;
  std::snprintf(text, sizeof(text), whole ? "%.0f" : "%g", value);
  return text;
}

// A finite number in [min, max] (max infinite: no upper bound); CLI11 prefixes the option name.
inline CLI::Validator Within(double min, double max) {
  const bool bounded = max < std::numeric_limits<double>::infinity();
  const std::string range = bounded ? "from " + HumanNumber(min) + " to " + HumanNumber(max)
                                    : HumanNumber(min) + " or more";
  return CLI::Validator(
      [min, max, range](std::string& input) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(input.c_str(), &end);
        if (input.empty() || *end != '\0' || !std::isfinite(value) || errno == ERANGE) {
          return "'" + input + "' is not a finite number";
        }
        if (value < min || value > max) return input + " is out of range: give a number " + range;
        return std::string();
      },
      bounded ? "in " + HumanNumber(min) + ".." + HumanNumber(max) : ">= " + HumanNumber(min));
}

// A finite number >= min.
inline CLI::Validator AtLeast(double min) {
  return Within(min, std::numeric_limits<double>::infinity());
}

// A finite number > 0.
inline CLI::Validator Positive() {
  CLI::Validator inner = AtLeast(0);
  return CLI::Validator(
      [inner](std::string& input) -> std::string {
        std::string copy = input;
        const std::string error = inner(copy);
        if (!error.empty()) return error;
        if (std::strtod(input.c_str(), nullptr) == 0) return input + " must be more than 0";
        return std::string();
      },
      "> 0");
}

// Any finite number.
inline CLI::Validator Finite() {
  CLI::Validator check =
      Within(-std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity());
  check.description("finite");
  return check;
}

}  // namespace m4d

#endif  // M4D_TOOLS_NUMBER_CHECKS_H_
