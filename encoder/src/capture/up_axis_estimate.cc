#include "encoder/src/capture/up_axis_estimate.h"

#include <cmath>

namespace m4d {
namespace {

const char* const kNames[] = {"none", "+x", "-x", "+y", "-y", "+z", "-z"};

}  // namespace

int EstimateUpAxis(const std::vector<std::vector<Camera>>& cameras) {
  double up[3] = {0, 0, 0};
  size_t count = 0;
  for (const std::vector<Camera>& frame : cameras) {
    for (const Camera& camera : frame) {
      for (int k = 0; k < 3; ++k) up[k] -= camera.rotation[3 + k];
      ++count;
    }
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::fabs(up[k]) > std::fabs(up[axis])) axis = k;
  }
  // Cancelled out: a mean up shorter than a tenth of a camera's says nothing.
  if (count == 0 || std::fabs(up[axis]) < 0.1 * static_cast<double>(count)) return 0;
  return 2 * axis + (up[axis] > 0 ? 1 : 2);
}

Status ParseUpAxis(const std::string& text, int* up_axis) {
  if (text == "auto") {
    *up_axis = kUpAxisAuto;
    return Status::Ok();
  }
  for (int i = 0; i <= 6; ++i) {
    if (text == kNames[i]) {
      *up_axis = i;
      return Status::Ok();
    }
  }
  return Status(M4D_ERR_INVALID_ARG, "--up " + text + ": not auto, none, +x, -x, +y, -y, +z or -z");
}

std::string UpAxisName(int up_axis) {
  return up_axis >= 1 && up_axis <= 6 ? kNames[up_axis] : "not stated";
}

}  // namespace m4d
