// The colour a training view sees at a world point: the starts of keyframe training colour
// their points from the views this way (occlusion ignored).
#ifndef M4D_ENCODER_TRAIN_VIEW_SAMPLING_H_
#define M4D_ENCODER_TRAIN_VIEW_SAMPLING_H_

#include <algorithm>

#include "encoder/src/image/image.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// The pixel's colour if the camera sees the point (in front of its near plane, inside).
inline bool SampleView(const Camera& camera, const Image& image, const float p[3], float rgb[3]) {
  const float* r = camera.rotation;
  const float* t = camera.translation;
  const float z = r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2];
  if (!(z > camera.near_plane)) return false;
  const float x = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0];
  const float y = r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1];
  const float u = camera.fx * x / z + camera.cx, v = camera.fy * y / z + camera.cy;
  if (!(u >= 0 && v >= 0 && u < camera.width && v < camera.height)) return false;
  const float* px = image.row(static_cast<int>(v)) + 3 * static_cast<int>(u);
  std::copy_n(px, 3, rgb);
  return true;
}

// The mean colour the views see at p, if at least min_views of them see it.
inline bool MeanViewColour(const TrainingViews& views, const float p[3], int min_views,
                           float rgb[3]) {
  double sum[3] = {0, 0, 0};
  int seen = 0;
  for (int v = 0; v < views.size(); ++v) {
    float sample[3];
    if (!SampleView(views.cameras[v], views.images[v], p, sample)) continue;
    ++seen;
    for (int c = 0; c < 3; ++c) sum[c] += sample[c];
  }
  if (seen < min_views || seen == 0) return false;
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<float>(sum[c] / seen);
  return true;
}

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_VIEW_SAMPLING_H_
