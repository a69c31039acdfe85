#include "encoder/src/stream/frame_rate.h"

#include <cmath>
#include <cstdlib>

namespace m4d {
namespace {

constexpr double kMaxTerm = 2147483648.0;  // 2^31, the header's limit

Status Bad(const std::string& text) {
  return Status(M4D_ERR_INVALID_ARG, "frame rate '" + text +
                                         "': give frames per second as 30, 29.97 or 30000/1001 "
                                         "(terms 1..2^31)");
}

// A positive number spanning the whole text.
bool ParseNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value) && *value > 0;
}

bool IsTerm(double v) { return v >= 1 && v <= kMaxTerm && v == std::floor(v); }

}  // namespace

Status ParseFrameRate(const std::string& text, uint32_t* num, uint32_t* den) {
  const size_t slash = text.find('/');
  double n = 0, d = 1;
  if (slash != std::string::npos) {
    if (!ParseNumber(text.substr(0, slash), &n) || !ParseNumber(text.substr(slash + 1), &d) ||
        !IsTerm(n) || !IsTerm(d)) {
      return Bad(text);
    }
  } else {
    double rate = 0;
    if (!ParseNumber(text, &rate) || rate > kMaxTerm) return Bad(text);
    const double ntsc = std::round(rate * 1.001);
    if (rate != std::floor(rate) && std::fabs(rate - ntsc * 1000.0 / 1001.0) < 1e-3) {
      n = ntsc * 1000;
      d = 1001;
    } else {
      d = rate == std::floor(rate) ? 1 : 1000;
      n = std::round(rate * d);
    }
    if (!IsTerm(n)) return Bad(text);
  }
  *num = static_cast<uint32_t>(n);
  *den = static_cast<uint32_t>(d);
  return Status::Ok();
}

}  // namespace m4d
