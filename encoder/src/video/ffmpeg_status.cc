#include "encoder/src/video/ffmpeg_status.h"

#include <atomic>

extern "C" {
#include <libavutil/error.h>
#include <libavutil/log.h>
}

namespace m4d {
namespace {

std::atomic<bool> log_level_chosen{false};

}  // namespace

void SetFfmpegLogging(bool verbose) {
  log_level_chosen = true;
  av_log_set_level(verbose ? AV_LOG_WARNING : AV_LOG_QUIET);
}

void InitFfmpegLogging() {
  if (!log_level_chosen.exchange(true)) av_log_set_level(AV_LOG_QUIET);
}

Status FfmpegError(int m4d_code, const std::string& what, int error) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(error, text, sizeof(text));
  return Status(m4d_code, what + ": " + text);
}

}  // namespace m4d
