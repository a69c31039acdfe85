#include "encoder/src/dataset/video_frame_source.h"

namespace m4d {

Status VideoFrameSource::Open(const std::vector<std::string>& paths,
                              std::unique_ptr<VideoFrameSource>* source) {
  auto result = std::make_unique<VideoFrameSource>();
  for (const std::string& path : paths) {
    // One cached frame per camera: requests come frame by frame for all cameras, and
    // full-resolution frames of many cameras add up (N3DV: 16 MB each).
    VideoReaderOptions options;
    options.cache_frames = 1;
    CameraVideo camera;
    M4D_RETURN_IF_ERROR(VideoReader::Open(path, options, &camera.reader));
    camera.mutex = std::make_unique<std::mutex>();
    result->cameras_.push_back(std::move(camera));
  }
  *source = std::move(result);
  return Status::Ok();
}

Status VideoFrameSource::Load(int frame, int camera, Image* rgb) {
  CameraVideo& video = cameras_[camera];
  std::lock_guard<std::mutex> lock(*video.mutex);
  return video.reader->ReadFrame(frame, rgb);
}

}  // namespace m4d
