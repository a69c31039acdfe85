#include "encoder/src/synthetic/lens_resampling.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/io/shortest_decimal.h"

namespace m4d {
namespace {

// Pixels kept beyond the farthest undistorted position, for the bilinear lookup.
constexpr int kGuard = 2;

}  // namespace

LensDistortion SceneLensDistortion(const CaptureRealism& realism) {
  // The coefficients as transforms.json gives them to a loader, so that the files and the
  // in-memory capture agree to the last bit.
  LensDistortion distortion;
  distortion.k[0] = ShortestDecimal(realism.k1);
  distortion.k[1] = ShortestDecimal(realism.k2);
  distortion.p1 = ShortestDecimal(realism.p1);
  distortion.p2 = ShortestDecimal(realism.p2);
  distortion.model = HasDistortion(distortion) ? LensModel::kOpenCv : LensModel::kNone;
  return distortion;
}

Status LensResampler::Create(const Camera& camera, const LensDistortion& distortion,
                             std::unique_ptr<LensResampler>* resampler) {
  const int w = camera.width, h = camera.height;
  // Undistorted positions of the view's pixel centres, in view pixels.
  std::vector<float> positions(2 * static_cast<size_t>(w) * h);
  float u_min = 0, u_max = static_cast<float>(w), v_min = 0, v_max = static_cast<float>(h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      double x, y;
      if (!Undistort(distortion, (i + 0.5 - camera.cx) / camera.fx,
                     (j + 0.5 - camera.cy) / camera.fy, &x, &y)) {
        return Status(M4D_ERR_UNSUPPORTED, "synthetic scene: lens distortion not invertible");
      }
      float* p = &positions[2 * (static_cast<size_t>(j) * w + i)];
      p[0] = static_cast<float>(camera.fx * x + camera.cx);
      p[1] = static_cast<float>(camera.fy * y + camera.cy);
      u_min = std::min(u_min, p[0]), u_max = std::max(u_max, p[0]);
      v_min = std::min(v_min, p[1]), v_max = std::max(v_max, p[1]);
    }
  }
  std::unique_ptr<LensResampler> created(new LensResampler());
  created->margin_x_ = static_cast<int>(std::ceil(-u_min)) + kGuard;
  created->margin_y_ = static_cast<int>(std::ceil(-v_min)) + kGuard;
  UndistortionMap& map = created->map_;
  map.width = w;
  map.height = h;
  map.source_width = static_cast<int>(std::ceil(u_max)) + kGuard + created->margin_x_;
  map.source_height = static_cast<int>(std::ceil(v_max)) + kGuard + created->margin_y_;
  // Canvas pixel indices have their centres at integers: u - 0.5.
  for (size_t i = 0; i < positions.size(); i += 2) {
    positions[i] += created->margin_x_ - 0.5f;
    positions[i + 1] += created->margin_y_ - 0.5f;
  }
  map.source = std::move(positions);
  *resampler = std::move(created);
  return Status::Ok();
}

Camera LensResampler::Canvas(const Camera& camera) const {
  Camera canvas = camera;
  canvas.width = map_.source_width;
  canvas.height = map_.source_height;
  canvas.cx += margin_x_;
  canvas.cy += margin_y_;
  return canvas;
}

Status LensResampler::Distort(const std::vector<uint8_t>& canvas_rgb, std::vector<float>* levels) {
  Reshape(map_.source_width, map_.source_height, 3, &canvas_);
  if (canvas_rgb.size() != canvas_.pixels.size()) {
    return Status(M4D_ERR_INVALID_ARG, "synthetic scene: canvas size differs from the lens's");
  }
  for (size_t i = 0; i < canvas_rgb.size(); ++i) canvas_.pixels[i] = canvas_rgb[i];
  M4D_RETURN_IF_ERROR(Remap(map_, canvas_, &view_));
  levels->assign(view_.pixels.begin(), view_.pixels.end());
  return Status::Ok();
}

}  // namespace m4d
