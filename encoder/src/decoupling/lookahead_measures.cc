#include "encoder/src/decoupling/lookahead_measures.h"

#include <cmath>
#include <limits>

namespace m4d {
namespace {

struct Projection {
  float u, v, z;
};

Projection Project(const Camera& c, const float* p) {
  const float* r = c.rotation;
  float x = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + c.translation[0];
  float y = r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + c.translation[1];
  float z = r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + c.translation[2];
  return {c.fx * x / z + c.cx, c.fy * y / z + c.cy, z};
}

bool Sees(const Camera& c, const Projection& p) {
  return p.z > c.near_plane && p.u >= 0 && p.u <= c.width && p.v >= 0 && p.v <= c.height;
}

}  // namespace

LookaheadMeasures MeasureLookahead(const std::vector<Camera>& cameras, const LookaheadInput& in) {
  LookaheadMeasures m;
  m.displacement.assign(in.count, 0.0f);
  m.scale_change.assign(in.count, 0.0f);
  m.error.assign(in.count, std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < in.count; ++i) {
    double sum = 0;
    int seen = 0;
    for (const Camera& camera : cameras) {
      Projection before = Project(camera, in.positions_before + 3 * i);
      if (!Sees(camera, before)) continue;
      Projection after = Project(camera, in.positions_after + 3 * i);
      if (!(after.z > camera.near_plane)) continue;
      sum += std::hypot(after.u - before.u, after.v - before.v) / before.z;
      ++seen;
    }
    m.displacement[i] = seen ? static_cast<float>(sum / seen) : 0.0f;
    float ds2 = 0;
    for (int a = 0; a < 3; ++a) {
      float d = in.log_scales_after[3 * i + a] - in.log_scales_before[3 * i + a];
      ds2 += d * d;
    }
    m.scale_change[i] = std::sqrt(ds2);
    if (in.blend_weight[i] > 0) m.error[i] = in.error_weight[i] / in.blend_weight[i];
  }
  return m;
}

}  // namespace m4d
