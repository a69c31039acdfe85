#include "encoder/src/train/background_shell.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/train/view_sampling.h"

namespace m4d {
namespace {

// Camera centre and viewing direction in the world (rotation is world-to-camera, row-major).
void CentreAndAxis(const Camera& c, Eigen::Vector3d* centre, Eigen::Vector3d* axis) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = c.rotation[i];
  const Eigen::Vector3d t(c.translation[0], c.translation[1], c.translation[2]);
  *centre = -r.transpose() * t;
  *axis = r.row(2).transpose().normalized();
}

}  // namespace

BackgroundShell CameraShell(const TrainingViews& views, float radius_scale) {
  BackgroundShell shell;
  if (views.size() < 2) return shell;
  // The point nearest every optical axis: sum (I - d d^T) x = sum (I - d d^T) c.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centres;
  for (const Camera& camera : views.cameras) {
    Eigen::Vector3d c, d;
    CentreAndAxis(camera, &c, &d);
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - d * d.transpose();
    a += p;
    b += p * c;
    centres.push_back(c);
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d s = svd.singularValues();
  if (!(s(2) > 1e-6 * s(0))) return shell;  // parallel axes: no point they look at
  const Eigen::Vector3d x = svd.solve(b);
  std::vector<double> distances;
  for (const Eigen::Vector3d& c : centres) distances.push_back((c - x).norm());
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  for (int k = 0; k < 3; ++k) shell.centre[k] = static_cast<float>(x(k));
  shell.radius = static_cast<float>(radius_scale * distances[distances.size() / 2]);
  return shell;
}

Status BackgroundShellPoints(const TrainingViews& views, const BackgroundShellOptions& options,
                             PointCloud* points) {
  *points = PointCloud();
  if (views.size() == 0) return Status(M4D_ERR_INVALID_ARG, "background shell: no views");
  if (!(options.radius_scale > 0.0f) || options.min_views < 1 || options.points == 0) {
    return Status(M4D_ERR_INVALID_ARG, "background shell: bad options");
  }
  const BackgroundShell shell = CameraShell(views, options.radius_scale);
  if (!(shell.radius > 0.0f)) return Status::Ok();
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));  // radians
  const double n = static_cast<double>(options.points);
  for (size_t i = 0; i < options.points; ++i) {
    const double y = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / n;
    const double ring = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = golden * static_cast<double>(i);
    const double dir[3] = {ring * std::cos(phi), y, ring * std::sin(phi)};
    float p[3];
    for (int k = 0; k < 3; ++k) p[k] = shell.centre[k] + static_cast<float>(shell.radius * dir[k]);
    float rgb[3];
    if (!MeanViewColour(views, p, options.min_views, rgb)) continue;
    points->positions.insert(points->positions.end(), p, p + 3);
    points->colors.insert(points->colors.end(), rgb, rgb + 3);
  }
  return Status::Ok();
}

}  // namespace m4d
