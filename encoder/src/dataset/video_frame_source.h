// VideoFrameSource: a FrameSource over one video file per camera (frame f of camera c is
// frame f of video c), for layouts such as N3DV that ship videos.
#ifndef M4D_ENCODER_DATASET_VIDEO_FRAME_SOURCE_H_
#define M4D_ENCODER_DATASET_VIDEO_FRAME_SOURCE_H_

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/video/video_reader.h"
#include "sdk/src/common/status.h"

namespace m4d {

class VideoFrameSource : public FrameSource {
 public:
  // Opens every video (to learn sizes and frame counts). M4D errors from VideoReader::Open.
  static Status Open(const std::vector<std::string>& paths,
                     std::unique_ptr<VideoFrameSource>* source);

  int camera_count() const { return static_cast<int>(cameras_.size()); }
  const VideoReader& video(int camera) const { return *cameras_[camera].reader; }

  // Requests for one camera are serialised (its decoder has state); cameras decode in
  // parallel.
  Status Load(int frame, int camera, Image* rgb) override;

 private:
  struct CameraVideo {
    std::unique_ptr<VideoReader> reader;
    std::unique_ptr<std::mutex> mutex;
  };
  std::vector<CameraVideo> cameras_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_VIDEO_FRAME_SOURCE_H_
