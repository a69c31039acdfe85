// --rate-point checked when the command line is parsed: an unknown name is a usage error
// (exit 2), not a failure found after the capture is loaded.
#ifndef M4D_TOOLS_M4D_RATE_POINT_NAME_H_
#define M4D_TOOLS_M4D_RATE_POINT_NAME_H_

#include <CLI/CLI.hpp>
#include <string>

#include "encoder/src/pipeline/rate_points.h"

namespace m4d {

inline CLI::Validator RatePointName() {
  return CLI::Validator(
      [](std::string& name) {
        RatePointSettings point;
        const Status status = FindRatePoint(name, &point);
        return status.ok() ? std::string() : status.message();
      },
      "r1..r5");
}

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_RATE_POINT_NAME_H_
