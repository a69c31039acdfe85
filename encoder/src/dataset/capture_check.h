// The check every command runs on a capture before any training: hours of work must not end
// on a missing or truncated image of a late frame, and a user fixing a capture wants every
// problem at once, not one per run.
#ifndef M4D_ENCODER_DATASET_CAPTURE_CHECK_H_
#define M4D_ENCODER_DATASET_CAPTURE_CHECK_H_

#include <functional>

#include "encoder/src/capture/capture.h"
#include "sdk/src/common/status.h"

namespace m4d {

// At most this many problems are spelled out; the rest are counted.
constexpr int kMaxListedCaptureProblems = 20;

// Loads every view of frames [first_frame, first_frame + frame_count) (frame_count 0: to the
// end): each image must exist, decode and have its camera's size. Returns one
// M4D_ERR_INVALID_ARG whose message lists every failing view (camera name, frame, reason).
// progress(done, total), if set, is called after each frame.
Status CheckCaptureViews(const Capture& capture, int first_frame, int frame_count,
                         const std::function<void(int done, int total)>& progress = nullptr);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_CAPTURE_CHECK_H_
