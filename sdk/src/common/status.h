// Status: an error code from the public header plus a message, returned by every
// internal function that can fail on bad input. No exceptions cross this boundary.
#ifndef M4D_SDK_COMMON_STATUS_H_
#define M4D_SDK_COMMON_STATUS_H_

#include <string>
#include <utility>

#include "m4d/m4d.h"

namespace m4d {

class Status {
 public:
  Status() = default;
  Status(int code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }
  bool ok() const { return code_ == M4D_OK; }
  int code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  int code_ = M4D_OK;
  std::string message_;
};

inline Status BitstreamError(std::string message) {
  return Status(M4D_ERR_BITSTREAM, std::move(message));
}
inline Status LimitError(std::string message) { return Status(M4D_ERR_LIMIT, std::move(message)); }

}  // namespace m4d

#define M4D_RETURN_IF_ERROR(expr)              \
  do {                                         \
    ::m4d::Status m4d_status_ = (expr);        \
    if (!m4d_status_.ok()) return m4d_status_; \
  } while (0)

#endif  // M4D_SDK_COMMON_STATUS_H_
