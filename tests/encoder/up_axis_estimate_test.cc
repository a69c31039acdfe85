// The encoder's up axis (encoder/src/capture/up_axis_estimate.h): the mean up of a rig's cameras,
// snapped to an axis, whatever the rig's world convention; nothing when it cancels out.
#include <gtest/gtest.h>

#include <cmath>

#include "encoder/src/capture/up_axis_estimate.h"
#include "m4d/m4d.h"

namespace m4d {
namespace {

// An OpenCV camera at `eye` looking at the origin with its image up along `up` (rows of the
// world-to-camera rotation: x right, y down, z forward).
Camera LookingAtOrigin(const double eye[3], const double up[3]) {
  double z[3] = {-eye[0], -eye[1], -eye[2]};
  double n = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (double& v : z) v /= n;
  const double dot = up[0] * z[0] + up[1] * z[1] + up[2] * z[2];
  double y[3] = {-(up[0] - dot * z[0]), -(up[1] - dot * z[1]), -(up[2] - dot * z[2])};
  n = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  for (double& v : y) v /= n;
  const double x[3] = {y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2],
                       y[0] * z[1] - y[1] * z[0]};
  Camera c;
  for (int k = 0; k < 3; ++k) {
    c.rotation[k] = static_cast<float>(x[k]);
    c.rotation[3 + k] = static_cast<float>(y[k]);
    c.rotation[6 + k] = static_cast<float>(z[k]);
  }
  return c;
}

// Six cameras on a ring around `up`, a little above the scene and rolled a few degrees.
std::vector<std::vector<Camera>> Ring(const double up[3], int frames = 2) {
  const double a[3] = {std::fabs(up[0]) < 0.9 ? 1.0 : 0.0, std::fabs(up[0]) < 0.9 ? 0.0 : 1.0, 0};
  double u[3] = {up[1] * a[2] - up[2] * a[1], up[2] * a[0] - up[0] * a[2],
                 up[0] * a[1] - up[1] * a[0]};
  const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& v : u) v /= nu;
  const double w[3] = {up[1] * u[2] - up[2] * u[1], up[2] * u[0] - up[0] * u[2],
                       up[0] * u[1] - up[1] * u[0]};
  std::vector<Camera> rig;
  for (int i = 0; i < 6; ++i) {
    const double t = 2 * M_PI * i / 6, roll = 0.1 * (i % 2 ? 1 : -1);
    double eye[3], tilt[3];
    for (int k = 0; k < 3; ++k) {
      eye[k] = 4 * std::cos(t) * u[k] + 4 * std::sin(t) * w[k] + 1.5 * up[k];
      tilt[k] = up[k] + roll * (std::cos(t) * w[k] - std::sin(t) * u[k]);
    }
    rig.push_back(LookingAtOrigin(eye, tilt));
  }
  return std::vector<std::vector<Camera>>(frames, rig);
}

TEST(UpAxisEstimate, FindsTheRigsUp) {
  const double opencv[3] = {0, -1, 0}, opengl[3] = {0, 1, 0}, z_up[3] = {0, 0, 1},
               x_down[3] = {-1, 0, 0};
  EXPECT_EQ(EstimateUpAxis(Ring(opencv)), M4D_UP_NEG_Y);
  EXPECT_EQ(EstimateUpAxis(Ring(opengl)), M4D_UP_POS_Y);
  EXPECT_EQ(EstimateUpAxis(Ring(z_up)), M4D_UP_POS_Z);
  EXPECT_EQ(EstimateUpAxis(Ring(x_down)), M4D_UP_NEG_X);
  // Not quite level: a world tilted 20 degrees still snaps to its nearest axis.
  const double tilted[3] = {std::sin(0.35), 0, std::cos(0.35)};
  EXPECT_EQ(EstimateUpAxis(Ring(tilted)), M4D_UP_POS_Z);
}

TEST(UpAxisEstimate, NothingWhenTheCamerasDisagree) {
  EXPECT_EQ(EstimateUpAxis({}), M4D_UP_UNKNOWN);
  const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  std::vector<std::vector<Camera>> both = Ring(up, 1);
  const std::vector<std::vector<Camera>> flipped = Ring(down, 1);
  both[0].insert(both[0].end(), flipped[0].begin(), flipped[0].end());
  EXPECT_EQ(EstimateUpAxis(both), M4D_UP_UNKNOWN);
}

TEST(UpAxisEstimate, ParsesTheOption) {
  int up = 0;
  ASSERT_TRUE(ParseUpAxis("auto", &up).ok());
  EXPECT_EQ(up, kUpAxisAuto);
  ASSERT_TRUE(ParseUpAxis("-y", &up).ok());
  EXPECT_EQ(up, M4D_UP_NEG_Y);
  ASSERT_TRUE(ParseUpAxis("+z", &up).ok());
  EXPECT_EQ(up, M4D_UP_POS_Z);
  ASSERT_TRUE(ParseUpAxis("none", &up).ok());
  EXPECT_EQ(up, M4D_UP_UNKNOWN);
  EXPECT_EQ(ParseUpAxis("y", &up).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(UpAxisName(M4D_UP_NEG_Y), "-y");
  EXPECT_EQ(UpAxisName(0), "not stated");
}

}  // namespace
}  // namespace m4d
