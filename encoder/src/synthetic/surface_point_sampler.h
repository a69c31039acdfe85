// Sampling the synthetic scene's surfaces into the initial point cloud: points spread over
// the visible objects in proportion to area, coloured like the renderer shades them (the
// texture's base level under the frame's lighting).
#ifndef M4D_ENCODER_SYNTHETIC_SURFACE_POINT_SAMPLER_H_
#define M4D_ENCODER_SYNTHETIC_SURFACE_POINT_SAMPLER_H_

#include <cstdint>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/synthetic/scene_animation.h"
#include "encoder/src/synthetic/scene_content.h"

namespace m4d {

// `count` points on the objects visible in `state`, where `state` puts them. The same seed
// gives the same points.
PointCloud SampleSurfacePoints(const SceneContent& content, const SceneFrameState& state, int count,
                               uint64_t seed);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SURFACE_POINT_SAMPLER_H_
