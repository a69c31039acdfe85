// AppearanceUpdate: the colour change of the dynamic set at one inter frame (bitstream-spec
// 4.7, version 0.3): one integer per Gaussian and colour channel, added to the SH DC
// coefficient after dequantization (6.7). Shading of moving parts changes as they turn; the
// colours a keyframe fixed for its GOP cannot follow it.
#ifndef M4D_SDK_LAYERS_APPEARANCE_UPDATE_H_
#define M4D_SDK_LAYERS_APPEARANCE_UPDATE_H_

#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/hooked_allocator.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

struct AppearanceUpdate {
  AppearanceUpdate() = default;
  explicit AppearanceUpdate(const M4dAllocator* hooks) : values(HookedAllocator<int32_t>(hooks)) {}
  float step = 0;
  Buffer<int32_t> values;  // 3 per Gaussian of the dynamic set: r, g, b
};

// Reads an APPEARANCE payload for a dynamic set of `count` Gaussians.
Status ReadAppearanceUpdate(ByteReader* reader, RansLayout layout, uint32_t count,
                            AppearanceUpdate* update);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_APPEARANCE_UPDATE_H_
