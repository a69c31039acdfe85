// VideoReader: decodes a video file (MP4 and whatever else FFmpeg opens) into RGB images,
// frame by frame, addressed by frame index. Frames are numbered in presentation order as
// the decoder outputs them, so indices are exact whatever the timestamps say.
//
// Access is cheapest in increasing order. A request behind the newest decoded frame is
// served from a small cache of recent frames, or else by reopening the file and decoding
// from the start: slow, but always the right frame.
#ifndef M4D_ENCODER_VIDEO_VIDEO_READER_H_
#define M4D_ENCODER_VIDEO_VIDEO_READER_H_

#include <memory>
#include <string>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct VideoReaderOptions {
  int cache_frames = 2;  // recent frames kept (as 8-bit RGB) for requests just behind
  int threads = 1;       // decoder threads; 0 lets FFmpeg choose
};

class VideoReader {
 public:
  // Opens the file's best video stream. The frame count is the container's, or counted by
  // reading every packet when the container does not declare it. M4D_ERR_INVALID_ARG for a
  // file that cannot be opened, M4D_ERR_UNSUPPORTED without a decodable video stream,
  // M4D_ERR_LIMIT for frames beyond kMaxImageBytes as RGB floats.
  static Status Open(const std::string& path, const VideoReaderOptions& options,
                     std::unique_ptr<VideoReader>* reader);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  int width() const;
  int height() const;
  double fps() const;  // average frame rate; 0 when the file does not say
  int frame_count() const;

  // Frame `index` (0-based) as RGB in [0, 1]. M4D_ERR_INVALID_ARG outside [0, frame_count),
  // M4D_ERR_BITSTREAM when decoding fails or the stream ends early.
  Status ReadFrame(int index, Image* rgb);

 private:
  struct State;
  explicit VideoReader(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_VIDEO_VIDEO_READER_H_
