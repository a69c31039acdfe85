// Loader for nerfstudio-style transforms.json captures, static or multi-view video.
//
// Shared keys: camera_model (OPENCV, PINHOLE, SIMPLE_PINHOLE: distortion k1, k2, k3, p1, p2;
// OPENCV_FISHEYE: k1..k4), w, h, fl_x, fl_y (default fl_x), cx, cy (default w / 2, h / 2),
// ply_file_path (initial points, see point_cloud_ply.h). Views with distortion are
// undistorted to pinhole cameras of the same image size (noted in Capture::notes). Each
// entry of "frames" has file_path (relative to the file's directory), transform_matrix
// (camera-to-world, OpenGL axes: x right, y up, z back) and may override any intrinsic,
// camera_model and distortion coefficients included. Extensions for video: "camera" names
// the physical camera, "time_index" the frame (else "time", the sorted distinct values
// giving frame numbers).
//
// Grouping: views belong to cameras by "camera" when present, else (video) by identical
// transform and intrinsics, named after their first frame's file_path, else (static, one
// frame) each view is a camera named by its file_path. Camera names sort to give indices.
// Every (frame, camera) pair must be present exactly once.
#ifndef M4D_ENCODER_DATASET_NERFSTUDIO_LOADER_H_
#define M4D_ENCODER_DATASET_NERFSTUDIO_LOADER_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

// `path` is the transforms.json file or the directory holding it.
Status LoadNerfstudio(const std::string& path, const CaptureOptions& options, Capture* capture);

// The OpenCV world-to-camera camera of a nerfstudio camera-to-world matrix (row-major 4x4,
// OpenGL axes); intrinsics are left as they are.
void NerfstudioPose(const double camera_to_world[16], Camera* camera);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_NERFSTUDIO_LOADER_H_
