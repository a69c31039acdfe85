// VideoWriter: encodes RGB images into a video file (MP4 or another container FFmpeg knows
// from the file name) with H.264 through libx264 when FFmpeg has it, else MPEG-4 Part 2.
// Frames are stored as 4:2:0 YUV in BT.709 limited range, tagged so players convert back.
#ifndef M4D_ENCODER_VIDEO_VIDEO_WRITER_H_
#define M4D_ENCODER_VIDEO_VIDEO_WRITER_H_

#include <memory>
#include <string>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct VideoWriterOptions {
  double fps = 30.0;
  // Quality as x264's constant rate factor: 0 (best) .. 51; 18 is visually near-lossless.
  // MPEG-4 uses the fixed quantiser 2^((crf - 12) / 6) clamped to 1..31, which likewise
  // doubles the step every 6.
  int crf = 18;
  std::string codec;              // "libx264", "mpeg4", or empty: libx264 if available
  std::string preset = "medium";  // x264's speed preset
  int threads = 0;                // encoder threads; 0 lets FFmpeg choose
};

class VideoWriter {
 public:
  // Creates the file for frames of width x height (both even, as 4:2:0 needs).
  // M4D_ERR_INVALID_ARG for bad sizes or options or an unwritable path,
  // M4D_ERR_UNSUPPORTED when the codec or container is not available.
  static Status Open(const std::string& path, int width, int height,
                     const VideoWriterOptions& options, std::unique_ptr<VideoWriter>* writer);
  // Releases everything; a writer never finished leaves an incomplete file.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Appends one frame: RGB, 3 channels, the size given to Open, values clamped to [0, 1].
  Status Write(const Image& rgb);
  // Flushes the encoder and completes the file; no Write afterwards.
  Status Finish();

  const std::string& codec_name() const;
  int frames_written() const;

 private:
  struct State;
  explicit VideoWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_VIDEO_VIDEO_WRITER_H_
