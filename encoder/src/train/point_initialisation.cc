#include "encoder/src/train/point_initialisation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "encoder/src/geometry/nearest_neighbours.h"
#include "encoder/src/raster/render_settings.h"

namespace m4d {
namespace {

Status CheckOptions(const PointInitialisationOptions& o) {
  if (o.sh_degree < 0 || o.sh_degree > 3 || !(o.opacity > 0.0f && o.opacity < 1.0f) ||
      o.neighbours < 1 || o.neighbours > 64 || !(o.min_squared_distance > 0.0f)) {
    return Status(M4D_ERR_INVALID_ARG, "point initialisation: bad options");
  }
  return Status::Ok();
}

// Mean squared distance of each point to its nearest neighbours (those that exist).
Status MeanNeighbourDistances(const PointCloud& points, const PointInitialisationOptions& o,
                              std::vector<float>* mean_d2) {
  NearestNeighbours knn;
  M4D_RETURN_IF_ERROR(knn.Build(points.positions.data(), points.size()));
  const size_t n = points.size();
  const size_t k = static_cast<size_t>(o.neighbours);
  std::vector<uint32_t> indices(n * k);
  std::vector<float> d2(n * k);
  knn.QueryAll(points.positions.data(), n, o.neighbours, true, o.threads, indices.data(),
               d2.data());
  mean_d2->resize(n);
  for (size_t i = 0; i < n; ++i) {
    double sum = 0;
    int found = 0;
    for (size_t j = 0; j < k; ++j) {
      if (indices[i * k + j] == kNoNeighbour) continue;
      sum += d2[i * k + j];
      ++found;
    }
    const float mean = found > 0 ? static_cast<float>(sum / found) : 0.0f;
    (*mean_d2)[i] = std::max(mean, o.min_squared_distance);
  }
  return Status::Ok();
}

}  // namespace

Status InitialiseFromPoints(const PointCloud& points, const PointInitialisationOptions& options,
                            GaussianModel* model) {
  M4D_RETURN_IF_ERROR(CheckOptions(options));
  if (points.positions.size() % 3 != 0 || points.colors.size() != points.positions.size()) {
    return Status(M4D_ERR_INVALID_ARG,
                  "point initialisation: positions and colours differ in size");
  }
  const size_t n = points.size();
  if (n > kMaxRenderGaussians) return LimitError("point initialisation: too many points");
  std::vector<float> mean_d2;
  M4D_RETURN_IF_ERROR(MeanNeighbourDistances(points, options, &mean_d2));

  model->sh_degree = options.sh_degree;
  model->Resize(0);
  model->Resize(n);
  const float logit = std::log(options.opacity / (1.0f - options.opacity));
  const size_t sh_floats = static_cast<size_t>(model->sh_floats());
  std::copy(points.positions.begin(), points.positions.end(), model->positions.begin());
  for (size_t i = 0; i < n; ++i) {
    const float log_scale = 0.5f * std::log(mean_d2[i]);  // log(sqrt(d))
    for (int a = 0; a < 3; ++a) model->log_scales[3 * i + a] = log_scale;
    model->rotations[4 * i] = 1.0f;  // w; x, y, z stay zero
    model->opacity_logits[i] = logit;
    for (int c = 0; c < 3; ++c) {
      model->sh[sh_floats * i + c] = (points.colors[3 * i + c] - 0.5f) / kShC0;
    }
  }
  return Status::Ok();
}

}  // namespace m4d
