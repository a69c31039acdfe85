#include "layers/log_scale_floor.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace m4d {
namespace {

struct Ray {
  Eigen::Vector3d centre, direction;  // the camera's centre and optical axis, in world space
};

Ray CameraRay(const Camera& camera) {
  float centre[3];
  CameraCentre(camera, centre);
  Ray ray;
  ray.centre = Eigen::Vector3d(centre[0], centre[1], centre[2]);
  // The camera's +z axis in world coordinates: the third row of the world-to-camera rotation.
  ray.direction = Eigen::Vector3d(camera.rotation[6], camera.rotation[7], camera.rotation[8]);
  ray.direction.normalize();
  return ray;
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The median depth, along each optical axis, of the point nearest all of them (least squares);
// 0 when the axes are near parallel or that point is not in front of most cameras.
double FocusDepth(const std::vector<Ray>& rays) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const Ray& ray : rays) {
    const Eigen::Matrix3d p =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    a += p;
    b += p * ray.centre;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a);
  if (!(eigen.eigenvalues()(0) > 1e-3 * eigen.eigenvalues()(2))) return 0.0;
  const Eigen::Vector3d focus = a.ldlt().solve(b);
  std::vector<double> depths;
  for (const Ray& ray : rays) depths.push_back(ray.direction.dot(focus - ray.centre));
  const double depth = Median(depths);
  return std::isfinite(depth) && depth > 0.0 ? depth : 0.0;
}

// The median distance of the camera centres from their mean.
double SpreadDistance(const std::vector<Ray>& rays) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Ray& ray : rays) mean += ray.centre / static_cast<double>(rays.size());
  std::vector<double> distances;
  for (const Ray& ray : rays) distances.push_back((ray.centre - mean).norm());
  return Median(distances);
}

}  // namespace

float LogScaleFloor(const std::vector<Camera>& cameras) {
  const float none = -std::numeric_limits<float>::infinity();
  if (cameras.size() < 2) return none;
  std::vector<Ray> rays;
  float focal = 0.0f;
  for (const Camera& camera : cameras) {
    rays.push_back(CameraRay(camera));
    focal = std::max({focal, camera.fx, camera.fy});
  }
  const double focus = FocusDepth(rays);
  const double distance = focus > 0.0 ? focus : SpreadDistance(rays);
  if (!(distance > 0.0) || !(focal > 0.0f)) return none;
  return static_cast<float>(std::log(kInvisibleAxisPixels * distance / focal));
}

float TrainingLogScaleFloor(const Capture& capture, int frame) {
  std::vector<Camera> cameras;
  for (int index : capture.TrainCameras()) cameras.push_back(capture.camera(frame, index));
  return LogScaleFloor(cameras);
}

}  // namespace m4d
