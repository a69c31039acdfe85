// Video writing and reading (video/): round trips through the encoder, frame-exact random
// access, and errors for bad arguments and files.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/metrics/psnr.h"
#include "encoder/src/video/video_reader.h"
#include "encoder/src/video/video_writer.h"
#include "tests/capture_input/dataset_test_util.h"

namespace m4d {
namespace {

using testing::TempDir;
using testing::ViewImage;

constexpr int kWidth = 64, kHeight = 48, kFrames = 12;

std::string WriteVideo(const TempDir& dir, const std::string& codec) {
  const std::string path = dir.path() + "/clip.mp4";
  VideoWriterOptions options;
  options.codec = codec;
  options.fps = 25;
  std::unique_ptr<VideoWriter> writer;
  EXPECT_TRUE(VideoWriter::Open(path, kWidth, kHeight, options, &writer).ok());
  if (!writer) return path;
  if (!codec.empty()) {
    EXPECT_EQ(writer->codec_name(), codec);
  }
  for (int f = 0; f < kFrames; ++f) {
    const Status status = writer->Write(ViewImage(kWidth, kHeight, f, 0));
    EXPECT_TRUE(status.ok()) << status.message();
  }
  EXPECT_EQ(writer->frames_written(), kFrames);
  const Status finished = writer->Finish();
  EXPECT_TRUE(finished.ok()) << finished.message();
  EXPECT_EQ(writer->Write(ViewImage(kWidth, kHeight, 0, 0)).code(), M4D_ERR_INVALID_ARG);
  return path;
}

void ExpectRoundTrip(const std::string& codec) {
  TempDir dir;
  const std::string path = WriteVideo(dir, codec);
  std::unique_ptr<VideoReader> reader;
  const Status opened = VideoReader::Open(path, VideoReaderOptions(), &reader);
  ASSERT_TRUE(opened.ok()) << opened.message();
  EXPECT_EQ(reader->width(), kWidth);
  EXPECT_EQ(reader->height(), kHeight);
  EXPECT_EQ(reader->frame_count(), kFrames);
  EXPECT_NEAR(reader->fps(), 25.0, 1e-6);
  std::vector<Image> frames(kFrames);
  for (int f = 0; f < kFrames; ++f) {
    const Status status = reader->ReadFrame(f, &frames[f]);
    ASSERT_TRUE(status.ok()) << status.message();
    double psnr = 0;
    ASSERT_TRUE(Psnr(frames[f], ViewImage(kWidth, kHeight, f, 0), &psnr).ok());
    EXPECT_GT(psnr, 30.0) << codec << " frame " << f;
  }
  // Any order gives the same frames: cached, decoded forward, or after a rewind.
  for (int f : {11, 10, 3, 3, 7, 0, 11, 1}) {
    Image again;
    ASSERT_TRUE(reader->ReadFrame(f, &again).ok());
    EXPECT_EQ(again.pixels, frames[f].pixels) << "frame " << f;
  }
  Image image;
  EXPECT_EQ(reader->ReadFrame(kFrames, &image).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(reader->ReadFrame(-1, &image).code(), M4D_ERR_INVALID_ARG);
}

TEST(VideoTest, RoundTripDefaultCodec) { ExpectRoundTrip(""); }

TEST(VideoTest, RoundTripMpeg4) { ExpectRoundTrip("mpeg4"); }

TEST(VideoTest, WriterRejectsBadArguments) {
  TempDir dir;
  std::unique_ptr<VideoWriter> writer;
  const std::string path = dir.path() + "/bad.mp4";
  EXPECT_EQ(VideoWriter::Open(path, 63, 48, VideoWriterOptions(), &writer).code(),
            M4D_ERR_INVALID_ARG);
  VideoWriterOptions options;
  options.fps = 0;
  EXPECT_EQ(VideoWriter::Open(path, 64, 48, options, &writer).code(), M4D_ERR_INVALID_ARG);
  options = VideoWriterOptions();
  options.crf = 52;
  EXPECT_EQ(VideoWriter::Open(path, 64, 48, options, &writer).code(), M4D_ERR_INVALID_ARG);
  options = VideoWriterOptions();
  options.codec = "no-such-codec";
  EXPECT_EQ(VideoWriter::Open(path, 64, 48, options, &writer).code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(
      VideoWriter::Open(dir.path() + "/missing/dir/x.mp4", 64, 48, VideoWriterOptions(), &writer)
          .code(),
      M4D_OK);

  ASSERT_TRUE(VideoWriter::Open(path, 64, 48, VideoWriterOptions(), &writer).ok());
  EXPECT_EQ(writer->Write(Image(32, 48, 3)).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(writer->Write(Image(64, 48, 1)).code(), M4D_ERR_INVALID_ARG);
}

TEST(VideoTest, ReaderRejectsBadFiles) {
  TempDir dir;
  std::unique_ptr<VideoReader> reader;
  EXPECT_EQ(VideoReader::Open(dir.path() + "/missing.mp4", VideoReaderOptions(), &reader).code(),
            M4D_ERR_INVALID_ARG);
  const std::string garbage = dir.path() + "/garbage.mp4";
  ASSERT_TRUE(WriteFileBytes(garbage, std::vector<uint8_t>(4096, 0x5a)).ok());
  EXPECT_NE(VideoReader::Open(garbage, VideoReaderOptions(), &reader).code(), M4D_OK);
  VideoReaderOptions options;
  options.cache_frames = 0;
  EXPECT_EQ(VideoReader::Open(garbage, options, &reader).code(), M4D_ERR_INVALID_ARG);
}

TEST(VideoTest, TruncatedVideoFailsCleanly) {
  TempDir dir;
  const std::string path = WriteVideo(dir, "");
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(ReadFileBytes(path, 1 << 24, &bytes).ok());
  // Keep the header but drop most of the frame data: opening or decoding must fail with a
  // status, or give fewer frames, never crash.
  bytes.resize(bytes.size() / 2);
  const std::string cut = dir.path() + "/cut.mp4";
  ASSERT_TRUE(WriteFileBytes(cut, bytes).ok());
  std::unique_ptr<VideoReader> reader;
  if (!VideoReader::Open(cut, VideoReaderOptions(), &reader).ok()) return;
  Image image;
  Status status;
  for (int f = 0; f < reader->frame_count() && status.ok(); ++f) {
    status = reader->ReadFrame(f, &image);
  }
  if (!status.ok()) {
    EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
  }
}

}  // namespace
}  // namespace m4d
