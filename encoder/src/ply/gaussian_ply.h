// GaussianSet import and export in the de-facto 3DGS PLY layout that viewers and training
// code exchange: one "vertex" element with float properties x y z nx ny nz f_dc_0..2
// f_rest_0.. opacity scale_0..2 rot_0..3, values before activation (log scales, opacity
// logits, unnormalised w x y z quaternions), f_rest channel-major (f_rest[c * (K - 1) + k]
// is coefficient k + 1 of channel c, K = ShCoefficients(degree)).
#ifndef M4D_ENCODER_PLY_GAUSSIAN_PLY_H_
#define M4D_ENCODER_PLY_GAUSSIAN_PLY_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// Import accepts any format (ASCII, binary of either byte order), property order and type,
// and extra properties and elements (ignored). The SH degree follows from the number of
// f_rest properties: 0, 9, 24 or 45 for degrees 0 to 3; f_rest_0..n-1 must all be there.
// M4D_ERR_BITSTREAM for missing properties, truncated data or non-finite values,
// M4D_ERR_UNSUPPORTED for other f_rest counts or a file that is not PLY.
Status DecodeGaussianPly(const uint8_t* data, size_t size, GaussianSet* set);
Status ReadGaussianPly(const std::string& path, GaussianSet* set);

// Export writes exactly the de-facto layout: binary little-endian floats, normals zero.
// M4D_ERR_INVALID_ARG when the set's arrays do not match its size or its degree is not 0..3.
Status EncodeGaussianPly(const GaussianSet& set, std::vector<uint8_t>* bytes);
Status WriteGaussianPly(const std::string& path, const GaussianSet& set);

}  // namespace m4d

#endif  // M4D_ENCODER_PLY_GAUSSIAN_PLY_H_
