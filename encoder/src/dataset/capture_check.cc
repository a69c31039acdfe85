#include "encoder/src/dataset/capture_check.h"

#include <algorithm>
#include <string>

namespace m4d {

Status CheckCaptureViews(const Capture& capture, int first_frame, int frame_count,
                         const std::function<void(int done, int total)>& progress) {
  if (first_frame < 0 || first_frame >= capture.frame_count || frame_count < 0) {
    return Status(M4D_ERR_INVALID_ARG, "capture check: frame range outside the capture");
  }
  const int last = frame_count > 0 ? std::min(capture.frame_count, first_frame + frame_count)
                                   : capture.frame_count;
  std::string listed;
  int problems = 0;
  Image image;
  for (int f = first_frame; f < last; ++f) {
    for (int c = 0; c < capture.camera_count(); ++c) {
      const Status status = capture.LoadImage(f, c, &image);
      if (status.ok()) continue;
      if (++problems <= kMaxListedCaptureProblems) {
        listed += "\n  camera " + capture.camera_names[c] + ", frame " + std::to_string(f) + ": " +
                  status.message();
      }
    }
    if (progress) progress(f - first_frame + 1, last - first_frame);
  }
  if (problems == 0) return Status::Ok();
  if (problems > kMaxListedCaptureProblems) {
    listed += "\n  ... and " + std::to_string(problems - kMaxListedCaptureProblems) + " more";
  }
  return Status(M4D_ERR_INVALID_ARG,
                capture.layout + ": " + std::to_string(problems) + " of " +
                    std::to_string((last - first_frame) * capture.camera_count()) +
                    " views cannot be used:" + listed);
}

}  // namespace m4d
