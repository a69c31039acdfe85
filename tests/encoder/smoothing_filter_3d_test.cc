// Mip-Splatting's 3D smoothing filter (smoothing_filter_3d.h): its size follows the finest
// camera, it keeps each footprint's integral, its gradients are the filtered values'
// derivatives, and frozen Gaussians stay exactly as they are.
#include <gtest/gtest.h>

#include <cmath>

#include "encoder/src/train/smoothing_filter_3d.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// Gaussians on the camera's axis at depths 2, 4 and behind it, a camera at the origin.
GaussianModel Row(std::vector<Camera>* cameras) {
  const float eye[3] = {0, 0, 0}, target[3] = {0, 0, 1};
  cameras->push_back(test::LookAtCamera(64, 48, 60.0f, 0, 0, eye, target));
  GaussianModel model;
  model.sh_degree = 0;
  model.Resize(3);
  const float z[3] = {2.0f, 4.0f, -3.0f};
  for (size_t i = 0; i < 3; ++i) {
    model.positions[3 * i + 2] = z[i];
    model.rotations[4 * i] = 1.0f;
    for (int a = 0; a < 3; ++a) model.log_scales[3 * i + a] = std::log(0.01f * (a + 1));
    model.opacity_logits[i] = 0.3f * static_cast<float>(i) - 0.2f;
  }
  return model;
}

TEST(SmoothingFilter3dTest, SizeFollowsTheFinestCameraAndKeepsTheIntegral) {
  std::vector<Camera> cameras;
  const GaussianModel model = Row(&cameras);
  SmoothingFilter3d filter;
  filter.Fit(model, cameras, 0.2f);
  const float root = std::sqrt(0.2f);
  EXPECT_NEAR(filter.sigma()[0], root * 2.0f / cameras[0].fx, 1e-6f);
  EXPECT_NEAR(filter.sigma()[1], root * 4.0f / cameras[0].fx, 1e-6f);
  EXPECT_EQ(filter.sigma()[2], filter.sigma()[1]);  // unseen: the largest
  filter.Apply(model);
  GaussianModel baked = model;
  filter.Bake(&baked);
  for (size_t i = 0; i < model.size(); ++i) {
    double before = Sigmoid(model.opacity_logits[i]), after = Sigmoid(baked.opacity_logits[i]);
    for (int a = 0; a < 3; ++a) {
      const double s = std::exp(model.log_scales[3 * i + a]);
      const double filtered = std::exp(baked.log_scales[3 * i + a]);
      const double sigma = filter.sigma()[i];
      EXPECT_NEAR(filtered * filtered, s * s + sigma * sigma, 1e-5 * (s * s + sigma * sigma));
      before *= s;
      after *= filtered;
    }
    EXPECT_NEAR(after, before, 1e-5 * before);
  }
}

// d/dx of sum(weights x filtered values), against central differences.
TEST(SmoothingFilter3dTest, GradientsAreTheFilteredValuesDerivatives) {
  std::vector<Camera> cameras;
  GaussianModel model = Row(&cameras);
  SmoothingFilter3d filter;
  filter.Fit(model, cameras, 0.36f);  // a filter about the size of the Gaussians
  auto objective = [&](const GaussianModel& m) {
    SmoothingFilter3d f = filter;
    f.Apply(m);
    GaussianModel baked = m;
    f.Bake(&baked);
    double sum = 0;
    for (size_t i = 0; i < m.size(); ++i) {
      for (int a = 0; a < 3; ++a) sum += (a + 1) * baked.log_scales[3 * i + a];
      sum += 2.0 * baked.opacity_logits[i];
    }
    return sum;
  };
  filter.Apply(model);
  GaussianModel gradients = model;
  for (size_t i = 0; i < model.size(); ++i) {
    for (int a = 0; a < 3; ++a) gradients.log_scales[3 * i + a] = static_cast<float>(a + 1);
    gradients.opacity_logits[i] = 2.0f;
  }
  filter.Backward(model, &gradients);
  const float h = 1e-2f;
  for (size_t i = 0; i < model.size(); ++i) {
    for (int a = 0; a < 4; ++a) {
      float& x = a < 3 ? model.log_scales[3 * i + a] : model.opacity_logits[i];
      const float g = a < 3 ? gradients.log_scales[3 * i + a] : gradients.opacity_logits[i];
      const float x0 = x;
      x = x0 + h;
      const double up = objective(model);
      x = x0 - h;
      const double down = objective(model);
      x = x0;
      EXPECT_NEAR(g, (up - down) / (2 * h), 1e-3) << "Gaussian " << i << " value " << a;
    }
  }
}

TEST(SmoothingFilter3dTest, FrozenGaussiansStayExactly) {
  std::vector<Camera> cameras;
  const GaussianModel model = Row(&cameras);
  SmoothingFilter3d filter;
  filter.Fit(model, cameras, 0.2f, 2);
  filter.Apply(model);
  GaussianModel baked = model;
  filter.Bake(&baked);
  for (size_t i = 0; i < 2; ++i) {
    for (int a = 0; a < 3; ++a) EXPECT_EQ(baked.log_scales[3 * i + a], model.log_scales[3 * i + a]);
    EXPECT_EQ(baked.opacity_logits[i], model.opacity_logits[i]);
  }
  EXPECT_GT(baked.log_scales[6], model.log_scales[6]);
}

}  // namespace
}  // namespace m4d
