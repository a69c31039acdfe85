// SEQUENCE_HEADER's up_axis (bitstream 0.9, spec 4.1): written and read back, absent from
// 0.8 streams, out of range above 6, and reported by m4d_get_stream_info.
#include <gtest/gtest.h>

#include "encoder/src/bitstream/sequence_header_writer.h"
#include "sdk/src/bitstream/sequence_header.h"
#include "sdk/src/common/byte_writer.h"
#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

std::vector<uint8_t> HeaderBytes(const SequenceHeader& h) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  EXPECT_TRUE(WriteSequenceHeader(h, &writer).ok());
  return payload;
}

Status ReadHeader(const std::vector<uint8_t>& payload, SequenceHeader* out) {
  ByteReader reader(payload.data(), payload.size());
  M4D_RETURN_IF_ERROR(ReadSequenceHeader(&reader, 1u << 24, out));
  EXPECT_EQ(reader.remaining(), 0u);
  return Status::Ok();
}

TEST(UpAxis, RoundTripsEveryValue) {
  for (int up = 0; up <= 6; ++up) {
    SequenceHeader h;
    h.up_axis = up;
    SequenceHeader back;
    ASSERT_TRUE(ReadHeader(HeaderBytes(h), &back).ok());
    EXPECT_EQ(back.up_axis, up);
  }
}

TEST(UpAxis, AbsentBeforeVersion09) {
  SequenceHeader h09, h08;
  h08.version_minor = 8;
  const std::vector<uint8_t> with = HeaderBytes(h09), without = HeaderBytes(h08);
  EXPECT_EQ(with.size(), without.size() + 1);  // the byte at the end
  SequenceHeader back;
  back.up_axis = 5;
  ASSERT_TRUE(ReadHeader(without, &back).ok());
  EXPECT_EQ(back.version_minor, 8);
  EXPECT_EQ(back.up_axis, 0);  // not stated
  h08.up_axis = M4D_UP_NEG_Y;  // a 0.8 stream cannot state it
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  EXPECT_FALSE(WriteSequenceHeader(h08, &writer).ok());
}

TEST(UpAxis, AboveSixIsABitstreamError) {
  std::vector<uint8_t> payload = HeaderBytes(SequenceHeader());
  payload.back() = 7;
  SequenceHeader back;
  const Status status = ReadHeader(payload, &back);
  EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
  EXPECT_NE(status.message().find("up_axis"), std::string::npos);
  payload.pop_back();  // a 0.9 header without it is cut short
  EXPECT_EQ(ReadHeader(payload, &back).code(), M4D_ERR_BITSTREAM);
}

TEST(UpAxis, ReportedInStreamInfo) {
  TestStreamShape shape;
  shape.gops = 1;
  shape.frames_per_gop = 2;
  shape.static_count = 20;
  shape.dynamic_count = 10;
  TestStream stream = MakeTestStream(shape);
  // Packet 0 is the SEQUENCE_HEADER; its last payload byte is up_axis.
  stream.packets[0].back() = M4D_UP_POS_Z;
  FixCrcs(&stream.packets[0]);
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  ASSERT_EQ(m4d_send_packet(ctx, stream.packets[0].data(), stream.packets[0].size()), M4D_OK);
  M4dStreamInfo info;
  ASSERT_EQ(m4d_get_stream_info(ctx, &info), M4D_OK);
  EXPECT_EQ(info.up_axis, static_cast<uint32_t>(M4D_UP_POS_Z));
  EXPECT_EQ(info.bitstream_minor, static_cast<uint32_t>(M4D_BITSTREAM_VERSION_MINOR));
  m4d_close(&ctx);
}

}  // namespace
}  // namespace testing
}  // namespace m4d
