// A GaussianSet as binary glTF (.glb) with the Khronos KHR_gaussian_splatting extension: one
// mesh primitive of POINTS whose attributes are POSITION, KHR_gaussian_splatting:ROTATION
// (unit quaternion x, y, z, w), :SCALE (linear), :OPACITY (after the sigmoid) and
// :SH_DEGREE_l_COEF_n (RGB), plus COLOR_0 (diffuse colour, linear as glTF defines it, and
// opacity) for viewers without the extension. The set is written as given: turn it to glTF's
// y-up first (axis_rotation.h, turn_gaussians.h).
#ifndef M4D_ENCODER_EXPORT_GLTF_SPLAT_WRITER_H_
#define M4D_ENCODER_EXPORT_GLTF_SPLAT_WRITER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// M4D_ERR_INVALID_ARG for arrays that do not match the set's size, or an empty set (glTF
// accessors hold at least one element).
Status EncodeGaussianGlb(const GaussianSet& set, std::vector<uint8_t>* bytes);
Status WriteGaussianGlb(const std::string& path, const GaussianSet& set);

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_GLTF_SPLAT_WRITER_H_
