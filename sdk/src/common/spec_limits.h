// Constants and limits of the bitstream specification (bitstream-spec/README.md, section 8).
#ifndef M4D_SDK_COMMON_SPEC_LIMITS_H_
#define M4D_SDK_COMMON_SPEC_LIMITS_H_

#include <cstddef>
#include <cstdint>

namespace m4d {

constexpr uint32_t kMaxPayloadSize = 1u << 26;
constexpr uint32_t kMaxGaussiansPerSet = 1u << 22;
constexpr int kMaxGridLevels = 4;
constexpr int kMaxGridChannels = 8;
constexpr int kMaxGridResolution = 256;
constexpr uint32_t kMaxGridValues = 1u << 24;
constexpr int kMaxMlpHiddenLayers = 4;
constexpr int kMaxMlpWidth = 256;
constexpr uint32_t kMaxAlphabet = 4096;
// From version 0.6, a group's codebook (spec 5.4): at most this many entries, each component
// coded with at most kMaxCodebookBits bits.
constexpr uint32_t kMaxCodebookSize = 4096;
constexpr int kMaxCodebookBits = 12;
// From version 0.7, octree_positions() codes the Gaussians after the first at a leaf as
// low + kOctreeRepeatRadix * high, each within one symbol block's alphabet (spec 5.6).
constexpr int32_t kOctreeRepeatRadix = 4096;
constexpr int kBrickSize = 8;
constexpr int kRansPrecision = 15;
constexpr uint32_t kRansTotal = 1u << kRansPrecision;
constexpr uint32_t kRansLow = 1u << 23;
// From version 0.4, blocks of at least kRansInterleaveMinCount values interleave this many
// rANS states (spec 5.2).
constexpr uint32_t kRansInterleavedStates = 4;
constexpr uint32_t kRansInterleaveMinCount = 4096;
// From version 0.8, adaptive binary range coding (spec 5.7): 12-bit probabilities moved by
// 1/32 of their distance after each bit, a range kept at or above 2^24; attribute values code
// their kAdaptiveTreeBits most significant bits with a context's bit tree, the rest as bypass
// bits, the context being the top kAdaptiveContextBits of two neighbouring values. From 0.11,
// an SH DC channel after the first is conditioned on the top kAdaptiveChannelBits of the
// channel before it.
constexpr int kRangeProbabilityBits = 12;
constexpr int kRangeAdaptShift = 5;
constexpr uint32_t kRangeTop = 1u << 24;
constexpr int kAdaptiveTreeBits = 8;
constexpr int kAdaptiveContextBits = 3;
constexpr int kAdaptiveChannelBits = 5;
constexpr int32_t kMaxSymbolMagnitude = 1 << 23;
constexpr int kMaxAttributeBits = 24;
constexpr int kMlpOutputs = 7;
constexpr float kLeakyReluSlope = 0.01f;

constexpr size_t kPacketHeaderSize = 24;

}  // namespace m4d

#endif  // M4D_SDK_COMMON_SPEC_LIMITS_H_
