// The public C API's contract: argument checks, EAGAIN semantics, logger and allocator hooks,
// allocation failure handling, error strings.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "tests/sdk/packet_test_util.h"

namespace m4d {
namespace testing {
namespace {

// Two-frame GOPs: packets 0-3 are frame 0 (a keyframe), 4 and 5 frame 1 (MOTION_GRID,
// COMPENSATION).
TestStream SmallStream() { return LoadConformanceStream("synth_sh0_short_gops"); }

TEST(Api, VersionAndErrorStrings) {
  EXPECT_STREQ(m4d_version(), "0.9.0");  // M4D_VERSION_* of m4d.h
  std::set<std::string> seen;
  for (int code = 0; code >= -7; --code) {
    ASSERT_NE(m4d_error_string(code), nullptr);
    seen.insert(m4d_error_string(code));
  }
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_STREQ(m4d_error_string(-1000), "unknown error");
}

TEST(Api, OpenRejectsBadSettings) {
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = reinterpret_cast<M4dContext*>(1);
  EXPECT_EQ(m4d_open(nullptr, &s), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_open(&ctx, nullptr), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ctx, nullptr);
  s.layers = 0;
  EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG);
  s.layers = 4;
  EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG);
  s = DefaultSettings();
  s.reserved[31] = 1;
  EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG);
  s = DefaultSettings();
  s.allocator.alloc = [](void*, size_t n) { return std::malloc(n); };
  EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG);
  s = DefaultSettings();
  s.verify_checksums = 2;
  EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG);
}

TEST(Api, NullArgumentsAreRejectedNotFollowed) {
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  M4dFrame frame;
  const uint8_t byte = 0;
  EXPECT_EQ(m4d_send_packet(nullptr, &byte, 1), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_send_packet(ctx, nullptr, 10), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_get_frame(nullptr, &frame), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_get_frame(ctx, nullptr), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_get_frame(ctx, &frame), M4D_ERR_AGAIN);
  EXPECT_EQ(m4d_set_background(nullptr, nullptr), M4D_ERR_INVALID_ARG);
  M4dGaussians bad;
  std::memset(&bad, 0, sizeof(bad));
  bad.count = 3;  // arrays missing
  bad.sh_coefficients = 1;
  EXPECT_EQ(m4d_set_background(ctx, &bad), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_frame_hash(nullptr, nullptr), M4D_ERR_INVALID_ARG);
  M4dPacketInfo info;
  EXPECT_EQ(m4d_parse_packet_header(nullptr, 0, &info), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_parse_packet_header(&byte, 1, &info), M4D_ERR_AGAIN);
  m4d_flush(nullptr);
  m4d_frame_unref(nullptr);
  std::memset(&frame, 0, sizeof(frame));
  m4d_frame_unref(&frame);
  m4d_close(&ctx);
  EXPECT_EQ(ctx, nullptr);
  m4d_close(&ctx);
  m4d_close(nullptr);
}

TEST(Api, SendReturnsAgainWhileAFrameIsPending) {
  const TestStream stream = SmallStream();
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(m4d_send_packet(ctx, stream.packets[i].data(), stream.packets[i].size()), M4D_OK);
  }
  // Frame 0 is ready: the next packet is refused until it is taken.
  EXPECT_EQ(m4d_send_packet(ctx, stream.packets[4].data(), stream.packets[4].size()),
            M4D_ERR_AGAIN);
  M4dFrame frame;
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  EXPECT_EQ(frame.frame_index, 0u);
  EXPECT_EQ(frame.is_keyframe, 1);
  EXPECT_EQ(HashOf(frame), stream.recon_hashes[0]);
  m4d_frame_unref(&frame);
  EXPECT_EQ(m4d_get_frame(ctx, &frame), M4D_ERR_AGAIN);
  EXPECT_EQ(m4d_send_packet(ctx, stream.packets[4].data(), stream.packets[4].size()), M4D_OK);
  EXPECT_EQ(m4d_get_frame(ctx, &frame), M4D_ERR_AGAIN);  // inter frame needs COMPENSATION
  ASSERT_EQ(m4d_send_packet(ctx, stream.packets[5].data(), stream.packets[5].size()), M4D_OK);
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  EXPECT_EQ(frame.is_keyframe, 0);
  EXPECT_EQ(HashOf(frame), stream.recon_hashes[1]);
  m4d_frame_unref(&frame);
  m4d_close(&ctx);
}

TEST(Api, PacketHeaderParserSplitsStreams) {
  const TestStream stream = SmallStream();
  std::vector<uint8_t> bytes;
  for (const Packet& p : stream.packets) bytes.insert(bytes.end(), p.begin(), p.end());
  M4dPacketInfo info;
  ASSERT_EQ(m4d_parse_packet_header(bytes.data(), bytes.size(), &info), M4D_OK);
  EXPECT_EQ(info.type, static_cast<uint32_t>(M4D_PACKET_SEQUENCE_HEADER));
  EXPECT_EQ(info.packet_size, stream.packets[0].size());
  EXPECT_EQ(info.end_of_frame, 0);
  // A partial packet asks for more data.
  EXPECT_EQ(m4d_parse_packet_header(bytes.data(), info.packet_size - 1, &info), M4D_ERR_AGAIN);
  EXPECT_EQ(SplitPackets(bytes).size(), stream.packets.size());
}

TEST(Api, FindPacketResynchronisesAfterGarbage) {
  const TestStream stream = SmallStream();
  std::vector<uint8_t> bytes(100, 'M');  // garbage, with the sync word's first byte
  bytes.insert(bytes.end(), stream.packets[1].begin(), stream.packets[1].end());
  size_t offset = 7;
  M4dPacketInfo info;
  ASSERT_EQ(m4d_find_packet(bytes.data(), bytes.size(), &offset, &info), M4D_OK);
  EXPECT_EQ(offset, 100u);
  EXPECT_EQ(info.packet_size, stream.packets[1].size());
  // Found, but the packet is incomplete.
  EXPECT_EQ(m4d_find_packet(bytes.data(), bytes.size() - 1, &offset, &info), M4D_ERR_AGAIN);
  EXPECT_EQ(offset, 100u);
  EXPECT_EQ(info.packet_size, stream.packets[1].size());
  // No header at all: all but the last 23 bytes can go.
  EXPECT_EQ(m4d_find_packet(bytes.data(), 100, &offset, &info), M4D_ERR_AGAIN);
  EXPECT_EQ(offset, 77u);
  EXPECT_EQ(info.packet_size, 0u);
  EXPECT_EQ(m4d_find_packet(bytes.data(), 10, &offset, &info), M4D_ERR_AGAIN);
  EXPECT_EQ(offset, 0u);
  EXPECT_EQ(m4d_find_packet(nullptr, 10, &offset, &info), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_find_packet(bytes.data(), 10, nullptr, &info), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_find_packet(bytes.data(), 10, &offset, nullptr), M4D_ERR_INVALID_ARG);
}

struct LogCapture {
  std::vector<std::string> messages;
};

TEST(Api, LoggerReceivesErrors) {
  const TestStream stream = SmallStream();
  LogCapture capture;
  M4dSettings s = DefaultSettings();
  s.logger.cookie = &capture;
  s.logger.callback = [](void* cookie, int level, const char* message) {
    if (level == M4D_LOG_ERROR) static_cast<LogCapture*>(cookie)->messages.push_back(message);
  };
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  Packet bad = stream.packets[1];
  bad[40] ^= 1;
  ASSERT_EQ(m4d_send_packet(ctx, stream.packets[0].data(), stream.packets[0].size()), M4D_OK);
  EXPECT_EQ(m4d_send_packet(ctx, bad.data(), bad.size()), M4D_ERR_CHECKSUM);
  ASSERT_EQ(capture.messages.size(), 1u);
  EXPECT_NE(capture.messages[0].find("KEYFRAME_STATIC"), std::string::npos);
  EXPECT_EQ(capture.messages[0], m4d_last_error(ctx));
  m4d_close(&ctx);
}

struct CountingAllocator {
  long live = 0;
  long total = 0;
  long fail_after = -1;  // fail every allocation once `total` reaches this (-1: never)
};

void* CountingAlloc(void* cookie, size_t size) {
  auto* a = static_cast<CountingAllocator*>(cookie);
  if (a->fail_after >= 0 && a->total >= a->fail_after) return nullptr;
  ++a->total;
  ++a->live;
  return std::malloc(size);
}

void CountingFree(void* cookie, void* p) {
  auto* a = static_cast<CountingAllocator*>(cookie);
  if (p) --a->live;
  std::free(p);
}

TEST(Api, AllocatorHooksServeTheLargeBuffers) {
  const TestStream stream = SmallStream();
  CountingAllocator counter;
  M4dSettings s = DefaultSettings();
  s.allocator = {&counter, CountingAlloc, CountingFree};
  const DecodeResult r = DecodeWith(s, stream.packets);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.hashes, stream.recon_hashes);
  EXPECT_GT(counter.total, 10);
  EXPECT_EQ(counter.live, 0);  // everything returned after close and unref
}

// m4d.h: frames stay valid after the context is closed; their buffers go back through the
// hooks (whose cookie the caller keeps alive), not through the closed context's settings.
TEST(Api, FramesOutliveTheirContext) {
  const TestStream stream = SmallStream();
  CountingAllocator counter;
  M4dSettings s = DefaultSettings();
  s.allocator = {&counter, CountingAlloc, CountingFree};
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  std::vector<M4dFrame> frames;
  for (const Packet& p : stream.packets) {
    if (m4d_send_packet(ctx, p.data(), p.size()) == M4D_ERR_AGAIN) {
      frames.emplace_back();
      ASSERT_EQ(m4d_get_frame(ctx, &frames.back()), M4D_OK);
      ASSERT_EQ(m4d_send_packet(ctx, p.data(), p.size()), M4D_OK);
    }
  }
  m4d_close(&ctx);
  std::memset(&s, 0xAB, sizeof(s));  // the settings the context was opened with are gone too
  ASSERT_GE(frames.size(), 2u);
  EXPECT_GT(counter.live, 0);
  for (size_t f = 0; f < frames.size(); ++f) {
    EXPECT_EQ(HashOf(frames[f]), stream.recon_hashes[f]) << f;
    m4d_frame_unref(&frames[f]);
  }
  EXPECT_EQ(counter.live, 0);
}

TEST(Api, AllocationFailureIsReportedAndDecodingRecovers) {
  const TestStream stream = SmallStream();
  for (long fail_after : {0L, 3L, 10L, 25L}) {
    CountingAllocator counter;
    counter.fail_after = fail_after;
    M4dSettings s = DefaultSettings();
    s.allocator = {&counter, CountingAlloc, CountingFree};
    M4dContext* ctx = nullptr;
    ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
    DecodeResult r = DecodePackets(ctx, stream.packets);
    ASSERT_FALSE(r.errors.empty()) << "fail_after " << fail_after;
    EXPECT_EQ(r.errors[0], M4D_ERR_NOMEM);
    // Memory is back: the same context decodes the stream exactly.
    counter.fail_after = -1;
    m4d_flush(ctx);
    r = DecodePackets(ctx, stream.packets);
    EXPECT_TRUE(r.errors.empty());
    EXPECT_EQ(r.hashes, stream.recon_hashes);
    m4d_close(&ctx);
    EXPECT_EQ(counter.live, 0);
  }
}

}  // namespace
}  // namespace testing
}  // namespace m4d
