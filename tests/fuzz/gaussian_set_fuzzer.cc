// libFuzzer target for gaussian_set() (KEYFRAME_STATIC, KEYFRAME_DYNAMIC and the added set of
// COMPENSATION): the first byte picks the SH degree (bits 0-1), the rotation coding (bit 2) and
// whether groups have codebook fields (bit 3, version 0.6), whether positions are an octree
// (bit 4, version 0.7) and whether sets have attribute_coding (bit 5, version 0.8), the rest is
// the payload. A set that
// decodes has arrays of its count's sizes; a count above the limit never allocates.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/layers/gaussian_set_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int sh_degree = data[0] & 3;
  m4d::GaussianSetSyntax syntax;
  syntax.rotation = (data[0] & 4) != 0 ? m4d::RotationCoding::kSmallestThree
                                       : m4d::RotationCoding::kFourComponents;
  syntax.codebooks = (data[0] & 8) != 0;
  syntax.octree_positions = (data[0] & 16) != 0;
  syntax.adaptive_attributes = (data[0] & 32) != 0;
  m4d::ByteReader reader(data + 1, size - 1);
  m4d::GaussianSet set;
  if (m4d::ReadGaussianSet(&reader, sh_degree, syntax, 1u << 16, &set).ok()) {
    const size_t n = set.size();
    if (n > (1u << 16) || set.positions.size() != 3 * n || set.rotations.size() != 4 * n ||
        set.opacity_logits.size() != n ||
        set.sh.size() != static_cast<size_t>(set.sh_floats()) * n) {
      std::abort();
    }
  }
  return 0;
}
