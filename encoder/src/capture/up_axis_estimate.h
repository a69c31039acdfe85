// Which world axis is up in a capture, for the stream's up_axis (bitstream-spec 4.1). People
// hold cameras level more often than not, so the cameras' mean up direction (-y of each
// OpenCV camera: the negated second row of its world-to-camera rotation) points near the
// world's up; it is snapped to the nearest axis.
#ifndef M4D_ENCODER_CAPTURE_UP_AXIS_ESTIMATE_H_
#define M4D_ENCODER_CAPTURE_UP_AXIS_ESTIMATE_H_

#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "sdk/src/common/status.h"

namespace m4d {

// M4dUpAxis 1..6 of the cameras of every frame, or 0 (not stated) without cameras or when
// their up directions cancel out (a rig looking at the scene from all sides, upside down
// as often as not).
int EstimateUpAxis(const std::vector<std::vector<Camera>>& cameras);

// The --up option: "auto" (kUpAxisAuto), "none" (0) or +x, -x, +y, -y, +z, -z (1..6).
// M4D_ERR_INVALID_ARG for anything else.
constexpr int kUpAxisAuto = -1;
Status ParseUpAxis(const std::string& text, int* up_axis);
// "+y" etc. for 1..6, "not stated" for 0.
std::string UpAxisName(int up_axis);

}  // namespace m4d

#endif  // M4D_ENCODER_CAPTURE_UP_AXIS_ESTIMATE_H_
