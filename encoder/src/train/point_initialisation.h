// Initial Gaussians of a keyframe, as the reference 3DGS makes them from a point cloud: one
// isotropic Gaussian per point with log scale log(sqrt(d)), d the mean squared distance to
// its 3 nearest neighbours (at least 1e-7), identity rotation, opacity 0.1 and the point's
// colour as the SH DC term ((c - 0.5) / C0), higher bands zero. Without points, Gaussians
// are placed uniformly at random in a box and get random colours.
#ifndef M4D_ENCODER_TRAIN_POINT_INITIALISATION_H_
#define M4D_ENCODER_TRAIN_POINT_INITIALISATION_H_

#include <cstddef>
#include <cstdint>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/train/gaussian_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

constexpr float kShC0 = 0.28209479177387814f;  // the degree-0 SH basis constant

struct PointInitialisationOptions {
  int sh_degree = 3;     // SH stored by the model (trained up to it)
  float opacity = 0.1f;  // initial opacity (stored as its logit)
  int neighbours = 3;    // for the scale
  float min_squared_distance = 1e-7f;
  int threads = 0;  // for the neighbour search; 0: the hardware's
};

// Fails with M4D_ERR_INVALID_ARG for inconsistent arrays, non-finite points or bad options,
// M4D_ERR_LIMIT beyond kMaxRenderGaussians points.
Status InitialiseFromPoints(const PointCloud& points, const PointInitialisationOptions& options,
                            GaussianModel* model);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_POINT_INITIALISATION_H_
