// Malformed streams: every damaged or out-of-range header field, every truncation, broken
// packet order and oversized declarations must give the documented error, never a crash,
// and decoding must resume at the next GOP.
#include <gtest/gtest.h>

#include <functional>

#include "encoder/src/bitstream/sequence_header_writer.h"
#include "sdk/src/common/byte_writer.h"
#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

class MalformedStream : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    TestStreamShape shape;
    shape.gops = 2;
    shape.frames_per_gop = 3;
    shape.static_count = 200;
    shape.dynamic_count = 100;
    stream_ = new TestStream(MakeTestStream(shape));
  }
  static void TearDownTestSuite() { delete stream_; }

  // Sends packets up to and including `index`, with packet `index` replaced by `bad`;
  // returns the result of sending `bad`.
  static int SendWithReplacement(size_t index, const Packet& bad) {
    M4dSettings s = DefaultSettings();
    M4dContext* ctx = nullptr;
    EXPECT_EQ(m4d_open(&ctx, &s), M4D_OK);
    std::vector<Packet> before(stream_->packets.begin(), stream_->packets.begin() + index);
    DecodeResult r = DecodePackets(ctx, before);
    EXPECT_TRUE(r.errors.empty());
    int result = m4d_send_packet(ctx, bad.data(), bad.size());
    if (result < 0) {
      EXPECT_STRNE(m4d_last_error(ctx), "");
    }
    m4d_close(&ctx);
    return result;
  }

  static Packet Edited(size_t index, const std::function<void(Packet*)>& edit, bool fix = true) {
    Packet p = stream_->packets[index];
    edit(&p);
    if (fix) FixCrcs(&p);
    return p;
  }

  // A SEQUENCE_HEADER packet with the given header fields.
  static Packet SequencePacket(const std::function<void(std::vector<uint8_t>*)>& edit) {
    SequenceHeader h;
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    EXPECT_TRUE(WriteSequenceHeader(h, &writer).ok());
    edit(&payload);
    Packet p;
    AppendPacket(M4D_PACKET_SEQUENCE_HEADER, 0, false, payload.data(), payload.size(), &p);
    return p;
  }

  static TestStream* stream_;
};
TestStream* MalformedStream::stream_ = nullptr;

TEST_F(MalformedStream, PacketHeaderFields) {
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[0] = 'X'; })), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, Edited(
                                       0, [](Packet* p) { (*p)[8] ^= 1; }, false)),
            M4D_ERR_CHECKSUM);
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[5] |= 2; })), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[7] = 1; })), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[4] = 9; })), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[4] = 0; })), M4D_ERR_UNSUPPORTED);
  // payload_size above 2^26.
  EXPECT_EQ(SendWithReplacement(0, Edited(0, [](Packet* p) { (*p)[15] = 0x10; })), M4D_ERR_LIMIT);
  // Payload CRC mismatch.
  EXPECT_EQ(SendWithReplacement(1, Edited(
                                       1, [](Packet* p) { (*p)[30] ^= 0x40; }, false)),
            M4D_ERR_CHECKSUM);
}

TEST_F(MalformedStream, PacketSizeMustMatchItsHeader) {
  Packet longer = stream_->packets[0];
  longer.push_back(0);
  EXPECT_EQ(SendWithReplacement(0, longer), M4D_ERR_BITSTREAM);
  for (size_t cut = 0; cut < stream_->packets[1].size(); cut += 7) {
    Packet shorter(stream_->packets[1].begin(), stream_->packets[1].begin() + cut);
    EXPECT_LT(SendWithReplacement(1, shorter), 0) << "cut at " << cut;
  }
}

TEST_F(MalformedStream, PayloadTruncatedAtEveryByteWithCrcsFixed) {
  // Every packet of the first two frames, cut at every length, with its CRCs made consistent
  // so the payload parser itself sees the truncation.
  for (size_t index = 0; index < 6; ++index) {
    const Packet& original = stream_->packets[index];
    const size_t step = original.size() > 600 ? original.size() / 150 : 1;
    for (size_t len = 24; len < original.size(); len += step) {
      Packet p(original.begin(), original.begin() + len);
      FixPayloadSize(&p);
      EXPECT_LT(SendWithReplacement(index, p), 0) << "packet " << index << " length " << len;
    }
  }
}

TEST_F(MalformedStream, TrailingBytesAfterAPayloadAreAnError) {
  for (size_t index = 0; index < 6; ++index) {
    Packet p = stream_->packets[index];
    p.push_back(0);
    FixPayloadSize(&p);
    EXPECT_EQ(SendWithReplacement(index, p), M4D_ERR_BITSTREAM) << "packet " << index;
  }
}

TEST_F(MalformedStream, PacketOrder) {
  // Inter packets of GOP 1 sent right after the keyframe's SEQUENCE_HEADER.
  EXPECT_EQ(SendWithReplacement(1, stream_->packets[4]), M4D_ERR_BITSTREAM);
  // MLP_WEIGHTS before KEYFRAME_DYNAMIC.
  EXPECT_EQ(SendWithReplacement(2, stream_->packets[3]), M4D_ERR_BITSTREAM);
  // COMPENSATION without its MOTION_GRID.
  EXPECT_EQ(SendWithReplacement(4, stream_->packets[5]), M4D_ERR_BITSTREAM);
  // A frame index that skips a frame.
  EXPECT_EQ(SendWithReplacement(4, Edited(4, [](Packet* p) { (*p)[8] += 1; })), M4D_ERR_BITSTREAM);
  // end_of_frame on a packet that does not end a frame, and missing where it must be.
  EXPECT_EQ(SendWithReplacement(4, Edited(4, [](Packet* p) { (*p)[5] = 1; })), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(3, Edited(3, [](Packet* p) { (*p)[5] = 0; })), M4D_ERR_BITSTREAM);
  // A KEYFRAME_DYNAMIC with another frame index than its SEQUENCE_HEADER.
  EXPECT_EQ(SendWithReplacement(2, Edited(2, [](Packet* p) { (*p)[8] = 9; })), M4D_ERR_BITSTREAM);
}

TEST_F(MalformedStream, SequenceHeaderFields) {
  // Payload offsets: 0 major, 1 minor, 2 profile, 3 sh_degree, 4 fps_num, 8 fps_den,
  // 12 num_frames, 16 levels, 17.. channels, then resolutions (u16), then MLP.
  auto set = [](size_t offset, uint8_t value) {
    return [offset, value](std::vector<uint8_t>* p) { (*p)[offset] = value; };
  };
  // Another major version, a minor version before the oldest decoded (0.2) and the next one.
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(0, 1))), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(1, 1))), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(1, M4D_BITSTREAM_VERSION_MINOR + 1))),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(2, 1))), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(3, 4))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) {
                                  for (int i = 4; i < 8; ++i) (*p)[i] = 0;
                                })),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(16, 0))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(16, 5))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(17, 0))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(17, 9))), M4D_ERR_BITSTREAM);
  // Resolution of level 0 (offset 20): 1 and 257.
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(20, 1))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) {
                                  (*p)[20] = 1;
                                  (*p)[21] = 1;
                                })),
            M4D_ERR_BITSTREAM);
  // Level 2 at 256^3 x 2 channels = 2^25 values: above the grid limit.
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) {
                                  (*p)[24] = 0;
                                  (*p)[25] = 1;
                                })),
            M4D_ERR_LIMIT);
  // MLP hidden layers (offset 26) 0 and 5, width (27..28) 0 and 257.
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(26, 0))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket(set(26, 5))), M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) {
                                  (*p)[27] = 0;
                                  (*p)[28] = 0;
                                })),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) {
                                  (*p)[27] = 1;
                                  (*p)[28] = 1;
                                })),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(
      SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) { p->push_back(0); })),
      M4D_ERR_BITSTREAM);
  EXPECT_EQ(SendWithReplacement(0, SequencePacket([](std::vector<uint8_t>* p) { p->resize(20); })),
            M4D_ERR_BITSTREAM);
}

TEST_F(MalformedStream, DecoderLimitsFromSettings) {
  M4dSettings s = DefaultSettings();
  s.max_gaussians = 150;  // the static set has 200
  DecodeResult r = DecodeWith(s, stream_->packets);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors.front(), M4D_ERR_LIMIT);
  s = DefaultSettings();
  s.max_grid_values = 1000;
  r = DecodeWith(s, stream_->packets);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors.front(), M4D_ERR_LIMIT);
  EXPECT_TRUE(r.hashes.empty());
}

// Spec 9, E33: a compensation that grows the dynamic set above the limit (here the decoder's:
// the spec's needs 2^22 Gaussians in memory).
TEST(MalformedStreamLimits, CompensationAboveTheLimit) {
  TestStreamShape shape;
  shape.gops = 1;
  shape.frames_per_gop = 2;
  shape.static_count = 50;
  shape.dynamic_count = 100;  // frame 1 removes 3 and adds 21
  const TestStream stream = MakeTestStream(shape);
  M4dSettings s = DefaultSettings();
  s.max_gaussians = 100;
  const DecodeResult r = DecodeWith(s, stream.packets);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors.front(), M4D_ERR_LIMIT);
  // The keyframe, and frame 1 with its dynamic layer concealed (spec 6.8).
  ASSERT_EQ(r.hashes.size(), 2u);
  EXPECT_EQ(r.hashes[0], stream.recon_hashes[0]);
  EXPECT_NE(r.hashes[1], stream.recon_hashes[1]);
  s.max_gaussians = 118;
  EXPECT_TRUE(DecodeWith(s, stream.packets).errors.empty());
}

TEST_F(MalformedStream, DecodingResumesAtTheNextGopAfterAnError) {
  std::vector<Packet> packets = stream_->packets;
  packets.erase(packets.begin() + 4);  // frame 1's MOTION_GRID lost: the packet order breaks
  const DecodeResult r = DecodeWith(DefaultSettings(), packets);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0], M4D_ERR_BITSTREAM);
  // Frame 0 decodes; frames 1 and 2 are lost; GOP 1 (frames 3..5) decodes exactly.
  ASSERT_EQ(r.hashes.size(), 4u);
  EXPECT_EQ(r.hashes[0], stream_->recon_hashes[0]);
  for (size_t i = 1; i < 4; ++i) EXPECT_EQ(r.hashes[i], stream_->recon_hashes[i + 2]);
}

// The frame a damaged COMPENSATION completes is output, concealed, with that packet's props.
TEST_F(MalformedStream, AConcealedFrameCarriesThePropsOfItsLastPacket) {
  std::vector<Packet> packets = stream_->packets;
  packets[5][40] ^= 0xff;  // frame 1's COMPENSATION payload (CRC now wrong)
  M4dContext* ctx = nullptr;
  M4dSettings settings = DefaultSettings();
  ASSERT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  std::vector<int64_t> timestamps;
  for (size_t i = 0; i < 6; ++i) {
    M4dDataProps props;
    m4d_default_data_props(&props);
    props.timestamp = static_cast<int64_t>(i);
    const int r = m4d_send_packet_props(ctx, packets[i].data(), packets[i].size(), &props);
    EXPECT_EQ(r, i == 5 ? M4D_ERR_CHECKSUM : M4D_OK);
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      timestamps.push_back(frame.props.timestamp);
      m4d_frame_unref(&frame);
    }
  }
  m4d_close(&ctx);
  EXPECT_EQ(timestamps, (std::vector<int64_t>{3, 5}));
}

// A damaged payload loses its layer, not the GOP (spec 6.8): the dynamic layer freezes at
// frame 0 for the rest of the GOP, flagged, and the static layer stays exact.
TEST_F(MalformedStream, ADamagedMotionGridFreezesTheDynamicLayerUntilTheNextKeyframe) {
  std::vector<Packet> packets = stream_->packets;
  packets[4][40] ^= 0xff;  // frame 1's MOTION_GRID payload (CRC now wrong)
  M4dContext* ctx = nullptr;
  M4dSettings settings = DefaultSettings();
  ASSERT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  std::vector<uint32_t> concealed;
  std::vector<uint32_t> dynamic_counts;
  for (const Packet& p : packets) {
    m4d_send_packet(ctx, p.data(), p.size());
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      concealed.push_back(frame.concealed_layers);
      dynamic_counts.push_back(frame.dynamic_layer.count);
      m4d_frame_unref(&frame);
    }
  }
  m4d_close(&ctx);
  const uint32_t d = M4D_LAYER_DYNAMIC;
  EXPECT_EQ(concealed, (std::vector<uint32_t>{0, d, d, 0, 0, 0}));
  const uint32_t frozen = static_cast<uint32_t>(stream_->dynamic_counts[0]);
  EXPECT_EQ(dynamic_counts[1], frozen);
  EXPECT_EQ(dynamic_counts[2], frozen);
}

TEST_F(MalformedStream, ByteFlipsInPayloadsNeverCrash) {
  // Flip bytes with CRCs fixed, so the damage reaches every payload parser (Draco included).
  SyntheticRandom rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Packet> packets(stream_->packets.begin(), stream_->packets.begin() + 6);
    const size_t index = rng.Next() % packets.size();
    Packet& p = packets[index];
    if (p.size() <= 24) continue;
    for (int k = 0; k < 1 + static_cast<int>(rng.Next() % 3); ++k) {
      p[24 + rng.Next() % (p.size() - 24)] ^= static_cast<uint8_t>(1 + rng.Next() % 255);
    }
    FixCrcs(&p);
    const DecodeResult r = DecodeWith(DefaultSettings(), packets);
    EXPECT_LE(r.hashes.size(), 2u);
  }
}

}  // namespace
}  // namespace testing
}  // namespace m4d
