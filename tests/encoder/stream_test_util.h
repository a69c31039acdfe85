// Helpers for stream-level tests that write their streams: synthetic streams from the
// reference writer (the decoder-side helpers are tests/sdk/packet_test_util.h).
#ifndef M4D_TESTS_ENCODER_STREAM_TEST_UTIL_H_
#define M4D_TESTS_ENCODER_STREAM_TEST_UTIL_H_

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "m4d/m4d.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/decode/frame_hash.h"
#include "tests/sdk/packet_test_util.h"

namespace m4d {
namespace testing {

struct TestStreamShape {
  int gops = 3;
  int frames_per_gop = 4;
  int static_count = 1500;
  int dynamic_count = 400;
  int sh_degree = 1;
  uint64_t seed = 5;
  // GOPs after the first are dependent (bitstream 0.3). Each replaces every
  // static_change_step-th static Gaussian and adds 5 more with a STATIC_UPDATE (0: none).
  bool dependent_gops = false;
  int static_change_step = 0;
  // Inter frames change the dynamic set's colours with an APPEARANCE (bitstream 0.3).
  bool appearance = false;
  int version_minor = M4D_BITSTREAM_VERSION_MINOR;
};

// A dependent keyframe's static change of MakeTestStream.
inline SetChange TestStaticChange(const GaussianSet& static_set, const TestStreamShape& shape,
                                  uint64_t seed) {
  SetChange change;
  change.removed.assign(static_set.size(), 0);
  size_t removed = 0;
  for (int i = 0; shape.static_change_step > 0 && i < static_cast<int>(static_set.size());
       i += shape.static_change_step, ++removed) {
    change.removed[static_cast<size_t>(i)] = 1;
  }
  const float center[3] = {1, 0, 0};
  change.added = SyntheticGaussianSet(shape.static_change_step > 0 ? removed + 5 : 0,
                                      shape.sh_degree, seed, center, 1.0f);
  return change;
}

constexpr float kTestAppearanceStep = 0.0123f;

// APPEARANCE values for a set of n: every third Gaussian changes, by -7..7 steps.
inline std::vector<int32_t> TestAppearanceValues(size_t n, int frame) {
  std::vector<int32_t> values(3 * n, 0);
  for (size_t i = static_cast<size_t>(frame) % 3; i < n; i += 3) {
    for (int c = 0; c < 3; ++c) values[3 * i + c] = static_cast<int32_t>((i + 5 * c) % 15) - 7;
  }
  return values;
}

inline TestStream MakeTestStream(const TestStreamShape& shape = TestStreamShape()) {
  StreamWriterOptions options;
  options.sequence.sh_degree = shape.sh_degree;
  options.sequence.version_minor = shape.version_minor;
  options.sequence.grid.resolution[0] = 8;
  options.sequence.grid.resolution[1] = 12;
  options.sequence.grid.resolution[2] = 20;
  options.sequence.mlp.hidden_width = 16;
  StreamWriter writer(options);
  TestStream out;
  const float center[3] = {0, 0, 0}, fg_center[3] = {0.1f, 0.2f, -0.1f};
  for (int g = 0; g < shape.gops; ++g) {
    const uint64_t seed = shape.seed * 100 + g;
    DecodedFrame recon;
    const GaussianSet dynamic_set =
        SyntheticGaussianSet(shape.dynamic_count, shape.sh_degree, seed + 1, fg_center, 0.4f);
    const MlpWeights mlp =
        SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, seed);
    Status status =
        g > 0 && shape.dependent_gops
            ? writer.WriteDependentKeyframe(TestStaticChange(writer.static_set(), shape, seed * 3),
                                            dynamic_set, mlp, &recon)
            : writer.WriteKeyframe(
                  SyntheticGaussianSet(shape.static_count, shape.sh_degree, seed, center, 2.0f),
                  dynamic_set, mlp, &recon);
    if (!status.ok()) throw std::runtime_error(status.message());
    out.recon_hashes.push_back(FrameHashHex(recon));
    out.dynamic_counts.push_back(recon.dynamic_layer->size());
    for (int f = 1; f < shape.frames_per_gop; ++f) {
      status = writer.WriteMotion(
          SyntheticMotionGrid(options.sequence.grid, seed * 7 + f, -0.6f, 0.6f, 0.2f));
      if (!status.ok()) throw std::runtime_error(status.message());
      const size_t n = writer.moved_dynamic_set().size();
      if (shape.appearance) {
        status = writer.WriteAppearance(kTestAppearanceStep, TestAppearanceValues(n, f));
        if (!status.ok()) throw std::runtime_error(status.message());
      }
      std::vector<uint8_t> removed(n, 0);
      for (size_t i = static_cast<size_t>(f); i < n; i += 37) removed[i] = 1;
      status = writer.WriteCompensation(
          removed, SyntheticGaussianSet(20 + f, shape.sh_degree, seed * 13 + f, fg_center, 0.4f),
          &recon);
      if (!status.ok()) throw std::runtime_error(status.message());
      out.recon_hashes.push_back(FrameHashHex(recon));
      out.dynamic_counts.push_back(recon.dynamic_layer->size());
    }
  }
  out.packets = SplitPackets(writer.bytes());
  return out;
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_ENCODER_STREAM_TEST_UTIL_H_
