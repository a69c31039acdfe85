#include "encoder/src/dataset/nerfstudio_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include <nlohmann/json.hpp>

#include "encoder/src/dataset/file_listing.h"
#include "encoder/src/dataset/image_file_source.h"
#include "encoder/src/dataset/json_object.h"
#include "encoder/src/dataset/undistorting_frame_source.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/ply/point_cloud_ply.h"

namespace m4d {
namespace {

using Json = nlohmann::json;

constexpr size_t kMaxJsonBytes = size_t{1} << 28;
constexpr size_t kMaxViews = size_t{1} << 22;

struct View {
  std::string file_path;
  double pose[16] = {};
  Camera camera;
  LensDistortion distortion;
  bool has_camera = false, has_time_index = false, has_time = false;
  std::string camera_name;
  double time = 0;  // time_index or time, whichever orders frames
  int frame = 0;
  int camera_index = 0;
};

Status Invalid(const std::string& message) {
  return Status(M4D_ERR_INVALID_ARG, "transforms.json: " + message);
}

// The number under `key` of the frame entry, else of the shared keys; *present false when
// neither has it.
Status LookupNumber(const Json& shared, const Json& entry, const char* key, bool* present,
                    double* value) {
  const Json* holder = entry.contains(key) ? &entry : shared.contains(key) ? &shared : nullptr;
  *present = holder != nullptr;
  if (!holder) return Status::Ok();
  const Json& item = (*holder)[key];
  if (!item.is_number() || !std::isfinite(item.get<double>())) {
    return Invalid(std::string("'") + key + "' must be a finite number");
  }
  *value = item.get<double>();
  return Status::Ok();
}

Status RequireNumber(const Json& shared, const Json& entry, const char* key, double* value) {
  bool present;
  M4D_RETURN_IF_ERROR(LookupNumber(shared, entry, key, &present, value));
  return present ? Status::Ok() : Invalid(std::string("no '") + key + "'");
}

Status ParseSize(const Json& shared, const Json& entry, const char* key, int* size) {
  double value;
  M4D_RETURN_IF_ERROR(RequireNumber(shared, entry, key, &value));
  if (value != std::floor(value) || value < 1 || value > kMaxImageSide) {
    return Invalid(std::string("'") + key + "' must be an image size");
  }
  *size = static_cast<int>(value);
  return Status::Ok();
}

// nerfstudio's OPENCV (also taken for PINHOLE, SIMPLE_PINHOLE or no camera_model) has radial
// k1, k2, k3 and tangential p1, p2; OPENCV_FISHEYE has k1..k4.
Status ParseDistortion(const Json& shared, const Json& entry, LensDistortion* distortion) {
  const Json* model = entry.contains("camera_model")    ? &entry["camera_model"]
                      : shared.contains("camera_model") ? &shared["camera_model"]
                                                        : nullptr;
  const std::string name = !model ? "OPENCV" : model->is_string() ? model->get<std::string>() : "";
  const bool fisheye = name == "OPENCV_FISHEYE";
  if (!fisheye && name != "OPENCV" && name != "PINHOLE" && name != "SIMPLE_PINHOLE") {
    return Status(M4D_ERR_UNSUPPORTED, "transforms.json: camera_model '" + name + "'");
  }
  distortion->model = fisheye ? LensModel::kFisheye : LensModel::kOpenCv;
  double* targets[6] = {&distortion->k[0], &distortion->k[1], &distortion->k[2],
                        &distortion->k[3], &distortion->p1,   &distortion->p2};
  const char* keys[6] = {"k1", "k2", "k3", "k4", "p1", "p2"};
  for (int i = 0; i < 6; ++i) {
    bool present;
    M4D_RETURN_IF_ERROR(LookupNumber(shared, entry, keys[i], &present, targets[i]));
    const bool unused = fisheye ? i >= 4 : i == 3;
    if (present && unused && *targets[i] != 0.0) {
      return Status(M4D_ERR_UNSUPPORTED, std::string("transforms.json: '") + keys[i] +
                                             "' with camera_model '" + name + "'");
    }
  }
  return Status::Ok();
}

Status ParseIntrinsics(const Json& shared, const Json& entry, View* view) {
  M4D_RETURN_IF_ERROR(ParseDistortion(shared, entry, &view->distortion));
  Camera& camera = view->camera;
  M4D_RETURN_IF_ERROR(ParseSize(shared, entry, "w", &camera.width));
  M4D_RETURN_IF_ERROR(ParseSize(shared, entry, "h", &camera.height));
  double fx, fy, cx, cy;
  bool present;
  M4D_RETURN_IF_ERROR(RequireNumber(shared, entry, "fl_x", &fx));
  M4D_RETURN_IF_ERROR(LookupNumber(shared, entry, "fl_y", &present, &fy));
  if (!present) fy = fx;
  M4D_RETURN_IF_ERROR(LookupNumber(shared, entry, "cx", &present, &cx));
  if (!present) cx = 0.5 * camera.width;
  M4D_RETURN_IF_ERROR(LookupNumber(shared, entry, "cy", &present, &cy));
  if (!present) cy = 0.5 * camera.height;
  if (!(std::fabs(fx) < 1e9 && std::fabs(fy) < 1e9 && std::fabs(cx) < 1e9 && std::fabs(cy) < 1e9)) {
    return Invalid("intrinsics out of range");
  }
  camera.fx = static_cast<float>(fx);
  camera.fy = static_cast<float>(fy);
  camera.cx = static_cast<float>(cx);
  camera.cy = static_cast<float>(cy);
  return Status::Ok();
}

// A 4x4 (or 3x4) array of finite numbers; the last row is taken to be 0 0 0 1.
Status ParsePose(const Json& matrix, double pose[16]) {
  if (!matrix.is_array() || (matrix.size() != 4 && matrix.size() != 3)) {
    return Invalid("transform_matrix must be 4x4");
  }
  for (int r = 0; r < 3; ++r) {
    const Json& row = matrix[r];
    if (!row.is_array() || row.size() != 4) return Invalid("transform_matrix must be 4x4");
    for (int c = 0; c < 4; ++c) {
      if (!row[c].is_number() || !(std::fabs(row[c].get<double>()) < 1e15)) {
        return Invalid("transform_matrix values must be finite numbers");
      }
      pose[4 * r + c] = row[c].get<double>();
    }
  }
  pose[12] = pose[13] = pose[14] = 0;
  pose[15] = 1;
  return Status::Ok();
}

Status ParseView(const Json& shared, const Json& entry, View* view) {
  if (!entry.is_object()) return Invalid("frames must hold objects");
  if (!entry.contains("file_path") || !entry["file_path"].is_string()) {
    return Invalid("a frame without file_path");
  }
  std::string file = entry["file_path"].get<std::string>();
  if (file.compare(0, 2, "./") == 0) file.erase(0, 2);
  view->file_path = file;
  if (!entry.contains("transform_matrix")) return Invalid("'" + file + "' has no transform_matrix");
  M4D_RETURN_IF_ERROR(ParsePose(entry["transform_matrix"], view->pose));
  NerfstudioPose(view->pose, &view->camera);
  M4D_RETURN_IF_ERROR(ParseIntrinsics(shared, entry, view));
  if (entry.contains("camera")) {
    if (!entry["camera"].is_string()) return Invalid("'camera' must be a string");
    view->has_camera = true;
    view->camera_name = entry["camera"].get<std::string>();
  }
  bool present;
  double index;
  M4D_RETURN_IF_ERROR(LookupNumber(Json::object(), entry, "time_index", &present, &index));
  if (present) {
    if (index != std::floor(index) || index < 0 || index > 1e9) {
      return Invalid("'time_index' must be a non-negative integer");
    }
    view->has_time_index = true;
    view->time = index;
  } else {
    M4D_RETURN_IF_ERROR(LookupNumber(Json::object(), entry, "time", &view->has_time, &view->time));
  }
  return Status::Ok();
}

// Either every view has the key or none has; *all tells which.
Status Consistent(const std::vector<View>& views, bool View::*has, const char* key, bool* all) {
  size_t count = 0;
  for (const View& view : views) count += view.*has ? 1 : 0;
  if (count != 0 && count != views.size()) {
    return Invalid(std::string("'") + key + "' on some frames but not all");
  }
  *all = count != 0;
  return Status::Ok();
}

// Frame numbers: the rank of each view's time among the distinct times.
int AssignFrames(bool dynamic, std::vector<View>* views) {
  if (!dynamic) return 1;
  std::vector<double> times;
  for (const View& view : *views) times.push_back(view.time);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  for (View& view : *views) {
    view.frame =
        static_cast<int>(std::lower_bound(times.begin(), times.end(), view.time) - times.begin());
  }
  return static_cast<int>(times.size());
}

// The bytes of a view's transform and intrinsics: views of one physical camera share them.
std::string RigKey(const View& view) {
  const Camera& c = view.camera;
  std::string key(reinterpret_cast<const char*>(view.pose), sizeof(view.pose));
  const float intrinsics[4] = {c.fx, c.fy, c.cx, c.cy};
  const int size[2] = {c.width, c.height};
  key.append(reinterpret_cast<const char*>(intrinsics), sizeof(intrinsics));
  key.append(reinterpret_cast<const char*>(size), sizeof(size));
  return key;
}

// Gives every view without an explicit camera name one (see the header), then numbers the
// cameras by sorted name.
std::vector<std::string> AssignCameras(bool named, bool dynamic, std::vector<View>* views) {
  if (!named && dynamic) {
    std::map<std::string, const View*> first_view;  // rig key -> its earliest view
    for (const View& view : *views) {
      const View*& first = first_view[RigKey(view)];
      if (!first || view.frame < first->frame) first = &view;
    }
    for (View& view : *views) view.camera_name = first_view[RigKey(view)]->file_path;
  } else if (!named) {
    for (View& view : *views) view.camera_name = view.file_path;
  }
  std::vector<std::string> names;
  for (const View& view : *views) names.push_back(view.camera_name);
  std::sort(names.begin(), names.end(), FrameNameLess);
  names.erase(std::unique(names.begin(), names.end()), names.end());
  for (View& view : *views) {
    view.camera_index = static_cast<int>(
        std::lower_bound(names.begin(), names.end(), view.camera_name, FrameNameLess) -
        names.begin());
  }
  return names;
}

// Every (frame, camera) pair must have exactly one view: in (frame, camera) order the views
// must count 0, 1, 2, ... through frames x cameras.
Status CheckEveryViewOnce(const std::vector<View>& views, int frames,
                          const std::vector<std::string>& names) {
  std::vector<size_t> slots;
  for (const View& view : views) slots.push_back(view.frame * names.size() + view.camera_index);
  std::sort(slots.begin(), slots.end());
  const size_t expected = static_cast<size_t>(frames) * names.size();
  for (size_t i = 0; i <= slots.size(); ++i) {
    if (i < slots.size() && slots[i] == i) continue;
    // The first slot out of place names the pair: doubled if seen just before, else missing.
    const bool doubled = i > 0 && i < slots.size() && slots[i] == slots[i - 1];
    const size_t slot = doubled ? slots[i] : i;
    if (!doubled && slot >= expected) return Status::Ok();
    return Invalid(std::string(doubled ? "two views" : "no view") + " of camera '" +
                   names[slot % names.size()] + "' at frame " +
                   std::to_string(slot / names.size()));
  }
  return Status::Ok();
}

Status ReadJson(const std::string& path, Json* json) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(ReadFileBytes(path, kMaxJsonBytes, &bytes));
  return ParseJsonObject(path, bytes, json);
}

std::string ResolvePath(const std::string& dir, const std::string& file) {
  return !file.empty() && file[0] == '/' ? file : dir + "/" + file;
}

Status Load(const std::string& path, Capture* capture) {
  const bool is_dir = IsDirectory(path);
  const std::string file = is_dir ? path + "/transforms.json" : path;
  const size_t slash = file.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : file.substr(0, slash);
  Json root;
  M4D_RETURN_IF_ERROR(ReadJson(file, &root));
  if (!root.contains("frames") || !root["frames"].is_array() || root["frames"].empty()) {
    return Invalid("no frames");
  }
  const Json& entries = root["frames"];
  if (entries.size() > kMaxViews) return LimitError("transforms.json: too many frames");
  std::vector<View> views(entries.size());
  for (size_t i = 0; i < views.size(); ++i) {
    M4D_RETURN_IF_ERROR(ParseView(root, entries[i], &views[i]));
  }
  bool named, indexed, timed = false;
  M4D_RETURN_IF_ERROR(Consistent(views, &View::has_camera, "camera", &named));
  M4D_RETURN_IF_ERROR(Consistent(views, &View::has_time_index, "time_index", &indexed));
  if (!indexed) M4D_RETURN_IF_ERROR(Consistent(views, &View::has_time, "time", &timed));
  const bool dynamic = indexed || timed;
  capture->frame_count = AssignFrames(dynamic, &views);
  capture->camera_names = AssignCameras(named, dynamic, &views);
  const size_t cameras = capture->camera_names.size();
  M4D_RETURN_IF_ERROR(CheckEveryViewOnce(views, capture->frame_count, capture->camera_names));
  capture->cameras.assign(capture->frame_count, std::vector<Camera>(cameras));
  std::vector<std::vector<std::string>> paths(capture->frame_count,
                                              std::vector<std::string>(cameras));
  std::vector<std::vector<LensDistortion>> distortions(capture->frame_count,
                                                       std::vector<LensDistortion>(cameras));
  for (View& view : views) {
    capture->cameras[view.frame][view.camera_index] = view.camera;
    paths[view.frame][view.camera_index] = ResolvePath(dir, view.file_path);
    distortions[view.frame][view.camera_index] = view.distortion;
  }
  capture->frames = std::make_unique<ImageFileSource>(std::move(paths), capture->cameras);
  M4D_RETURN_IF_ERROR(UndistortCapture(distortions, capture));
  if (root.contains("ply_file_path")) {
    if (!root["ply_file_path"].is_string()) return Invalid("'ply_file_path' must be a string");
    M4D_RETURN_IF_ERROR(ReadPointCloudPly(
        ResolvePath(dir, root["ply_file_path"].get<std::string>()), &capture->initial_points));
  }
  return Status::Ok();
}

}  // namespace

void NerfstudioPose(const double c2w[16], Camera* camera) {
  // OpenCV camera axes are OpenGL's with y and z negated: columns 0, -1, -2 of the
  // camera-to-world rotation. The world-to-camera rotation has them as rows.
  const double sign[3] = {1, -1, -1};
  for (int r = 0; r < 3; ++r) {
    double t = 0;
    for (int c = 0; c < 3; ++c) {
      const double value = sign[r] * c2w[4 * c + r];
      camera->rotation[3 * r + c] = static_cast<float>(value);
      t -= value * c2w[4 * c + 3];
    }
    camera->translation[r] = static_cast<float>(t);
  }
}

Status LoadNerfstudio(const std::string& path, const CaptureOptions& options, Capture* capture) {
  M4D_RETURN_IF_ERROR(CheckCaptureOptions(options));
  *capture = Capture();
  capture->layout = "nerfstudio";
  // nlohmann::json reports type errors by exceptions; none may escape.
  try {
    M4D_RETURN_IF_ERROR(Load(path, capture));
  } catch (const std::exception& e) {
    return Invalid(e.what());
  }
  return ApplyCaptureOptions(options, capture);
}

}  // namespace m4d
