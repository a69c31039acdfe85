// Glue between FFmpeg and the encoder's error handling: FFmpeg's own log output is silenced
// unless asked for, and FFmpeg error codes become Status messages.
#ifndef M4D_ENCODER_VIDEO_FFMPEG_STATUS_H_
#define M4D_ENCODER_VIDEO_FFMPEG_STATUS_H_

#include <string>

#include "sdk/src/common/status.h"

namespace m4d {

// Lets FFmpeg print its warnings and errors to stderr (verbose) or keeps it quiet, the
// default. Failures are reported as Status either way.
void SetFfmpegLogging(bool verbose);

// Applies the default (quiet) log level unless SetFfmpegLogging chose one; every video
// reader and writer calls it before using FFmpeg.
void InitFfmpegLogging();

// `code` from `m4d_code`, with "<what>: <FFmpeg's description of error>".
Status FfmpegError(int m4d_code, const std::string& what, int error);

}  // namespace m4d

#endif  // M4D_ENCODER_VIDEO_FFMPEG_STATUS_H_
