#include "encoder/src/dataset/dynamic3dgs_loader.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "encoder/src/dataset/file_listing.h"
#include "encoder/src/dataset/image_file_source.h"
#include "encoder/src/dataset/json_object.h"
#include "encoder/src/dataset/npz_archive.h"
#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace {

using Json = nlohmann::json;

constexpr size_t kMaxJsonBytes = size_t{1} << 28;

// Messages name the file: ParseMeta prefixes them.
Status Invalid(const std::string& message) { return Status(M4D_ERR_INVALID_ARG, message); }

// A rows x columns array of finite numbers (values beyond 1e15 are rejected as well).
Status ParseMatrix(const Json& json, int rows, int columns, double* out) {
  if (!json.is_array() || json.size() != static_cast<size_t>(rows)) {
    return Invalid("matrix of the wrong shape");
  }
  for (int r = 0; r < rows; ++r) {
    if (!json[r].is_array() || json[r].size() != static_cast<size_t>(columns)) {
      return Invalid("matrix of the wrong shape");
    }
    for (int c = 0; c < columns; ++c) {
      const Json& v = json[r][c];
      if (!v.is_number() || !(std::fabs(v.get<double>()) < 1e15)) {
        return Invalid("matrix values must be finite numbers");
      }
      out[columns * r + c] = v.get<double>();
    }
  }
  return Status::Ok();
}

// The per-frame list under `key`, one entry per camera of that frame.
Status FrameList(const Json& root, const char* key, size_t frame, size_t cameras,
                 const Json** list) {
  const Json& frames = root[key];
  if (!frames[frame].is_array() || frames[frame].size() != cameras) {
    return Invalid(std::string("'") + key + "' of frame " + std::to_string(frame) +
                   " does not match cam_id");
  }
  *list = &frames[frame];
  return Status::Ok();
}

Status ViewCamera(const Json& k, const Json& w2c, int width, int height, Camera* camera) {
  double intrinsics[9], pose[16];
  M4D_RETURN_IF_ERROR(ParseMatrix(k, 3, 3, intrinsics));
  M4D_RETURN_IF_ERROR(ParseMatrix(w2c, 4, 4, pose));
  camera->width = width;
  camera->height = height;
  camera->fx = static_cast<float>(intrinsics[0]);
  camera->cx = static_cast<float>(intrinsics[2]);
  camera->fy = static_cast<float>(intrinsics[4]);
  camera->cy = static_cast<float>(intrinsics[5]);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) camera->rotation[3 * r + c] = static_cast<float>(pose[4 * r + c]);
    camera->translation[r] = static_cast<float>(pose[4 * r + 3]);
  }
  return Status::Ok();
}

Status ParseSize(const Json& root, const char* key, int* size) {
  if (!root.contains(key) || !root[key].is_number_integer() || root[key].get<int64_t>() < 1 ||
      root[key].get<int64_t>() > kMaxImageSide) {
    return Invalid(std::string("'") + key + "' must be an image size");
  }
  *size = static_cast<int>(root[key].get<int64_t>());
  return Status::Ok();
}

// The sorted camera ids of frame 0; later frames must list the same set.
Status CameraIds(const Json& ids, std::vector<int64_t>* sorted) {
  for (const Json& id : ids) {
    if (!id.is_number_integer()) return Invalid("cam_id values must be integers");
    sorted->push_back(id.get<int64_t>());
  }
  std::sort(sorted->begin(), sorted->end());
  if (std::adjacent_find(sorted->begin(), sorted->end()) != sorted->end()) {
    return Invalid("a camera listed twice in a frame");
  }
  return Status::Ok();
}

// One meta file's cameras: ids sorted, per frame the cameras and image paths in id order.
struct MetaCameras {
  std::vector<int64_t> ids;
  std::vector<std::vector<Camera>> cameras;     // [frame][camera]
  std::vector<std::vector<std::string>> paths;  // [frame][camera]
};

Status ParseMetaFile(const std::string& dir, const char* file, MetaCameras* meta) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(ReadFileBytes(dir + "/" + file, kMaxJsonBytes, &bytes));
  Json root;
  M4D_RETURN_IF_ERROR(ParseJsonObject(dir + "/" + file, bytes, &root));
  int width, height;
  M4D_RETURN_IF_ERROR(ParseSize(root, "w", &width));
  M4D_RETURN_IF_ERROR(ParseSize(root, "h", &height));
  for (const char* key : {"k", "w2c", "fn", "cam_id"}) {
    if (!root.contains(key) || !root[key].is_array())
      return Invalid(std::string("no '") + key + "'");
  }
  const size_t frames = root["cam_id"].size();
  if (frames == 0 || !root["cam_id"][0].is_array()) return Invalid("no frames");
  for (const char* key : {"k", "w2c", "fn"}) {
    if (root[key].size() != frames) return Invalid(std::string("'") + key + "' frame count");
  }
  std::vector<int64_t>& ids = meta->ids;
  M4D_RETURN_IF_ERROR(CameraIds(root["cam_id"][0], &ids));
  meta->cameras.assign(frames, std::vector<Camera>(ids.size()));
  meta->paths.assign(frames, std::vector<std::string>(ids.size()));
  for (size_t f = 0; f < frames; ++f) {
    const Json *cam_ids, *ks, *w2cs, *files;
    M4D_RETURN_IF_ERROR(FrameList(root, "cam_id", f, ids.size(), &cam_ids));
    M4D_RETURN_IF_ERROR(FrameList(root, "k", f, ids.size(), &ks));
    M4D_RETURN_IF_ERROR(FrameList(root, "w2c", f, ids.size(), &w2cs));
    M4D_RETURN_IF_ERROR(FrameList(root, "fn", f, ids.size(), &files));
    std::vector<int64_t> frame_ids;
    M4D_RETURN_IF_ERROR(CameraIds(*cam_ids, &frame_ids));
    if (frame_ids != ids) return Invalid("frame " + std::to_string(f) + " has other cameras");
    for (size_t i = 0; i < ids.size(); ++i) {
      const size_t c =
          std::lower_bound(ids.begin(), ids.end(), (*cam_ids)[i].get<int64_t>()) - ids.begin();
      if (!(*files)[i].is_string()) return Invalid("'fn' values must be strings");
      meta->paths[f][c] = dir + "/ims/" + (*files)[i].get<std::string>();
      M4D_RETURN_IF_ERROR(ViewCamera((*ks)[i], (*w2cs)[i], width, height, &meta->cameras[f][c]));
    }
  }
  return Status::Ok();
}

Status ParseMeta(const std::string& dir, const char* file, MetaCameras* meta) {
  // nlohmann::json reports type errors by exceptions; none may escape.
  Status status;
  try {
    status = ParseMetaFile(dir, file, meta);
  } catch (const std::exception& e) {
    status = Invalid(e.what());
  }
  if (status.ok()) return status;
  return Status(status.code(), "dynamic3dgs: " + std::string(file) + ": " + status.message());
}

// Appends the test cameras after the training ones (same frame count, no shared id) and
// returns their indices.
Status AppendTestCameras(MetaCameras test, MetaCameras* all, std::vector<int>* indices) {
  if (test.cameras.size() != all->cameras.size()) {
    return Invalid("dynamic3dgs: test_meta.json has " + std::to_string(test.cameras.size()) +
                   " frames but train_meta.json " + std::to_string(all->cameras.size()));
  }
  for (int64_t id : test.ids) {
    if (std::binary_search(all->ids.begin(), all->ids.end(), id)) {
      return Invalid("dynamic3dgs: test_meta.json: camera " + std::to_string(id) +
                     " is also a training camera");
    }
  }
  for (size_t i = 0; i < test.ids.size(); ++i) {
    indices->push_back(static_cast<int>(all->ids.size() + i));
  }
  for (size_t f = 0; f < test.cameras.size(); ++f) {
    all->cameras[f].insert(all->cameras[f].end(), test.cameras[f].begin(), test.cameras[f].end());
    for (std::string& path : test.paths[f]) all->paths[f].push_back(std::move(path));
  }
  return Status::Ok();
}

// train_meta.json, and test_meta.json when present: its cameras are the held-out ones.
Status Load(const std::string& dir, Capture* capture) {
  MetaCameras meta;
  M4D_RETURN_IF_ERROR(ParseMeta(dir, "train_meta.json", &meta));
  std::vector<int64_t> names = meta.ids;
  if (IsRegularFile(dir + "/test_meta.json")) {
    MetaCameras test;
    M4D_RETURN_IF_ERROR(ParseMeta(dir, "test_meta.json", &test));
    names.insert(names.end(), test.ids.begin(), test.ids.end());
    M4D_RETURN_IF_ERROR(AppendTestCameras(std::move(test), &meta, &capture->test_cameras));
  }
  for (int64_t id : names) capture->camera_names.push_back(std::to_string(id));
  capture->frame_count = static_cast<int>(meta.cameras.size());
  capture->cameras = std::move(meta.cameras);
  capture->frames = std::make_unique<ImageFileSource>(std::move(meta.paths), capture->cameras);
  return Status::Ok();
}

Status LoadPoints(const std::string& path, PointCloud* points) {
  NpyArray array;
  M4D_RETURN_IF_ERROR(ReadNpzArray(path, "data", &array));
  if (array.shape.size() != 2 || array.shape[1] < 6) {
    return Status(M4D_ERR_INVALID_ARG, "dynamic3dgs: '" + path + "' data must be N x 7 (or N x 6)");
  }
  const size_t n = array.shape[0], columns = array.shape[1];
  points->positions.resize(3 * n);
  points->colors.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double position = array.values[i * columns + a];
      if (!(std::fabs(position) <= 1e30)) {
        return Status(M4D_ERR_INVALID_ARG, "dynamic3dgs: bad point in '" + path + "'");
      }
      points->positions[3 * i + a] = static_cast<float>(position);
      const double colour = array.values[i * columns + 3 + a];
      points->colors[3 * i + a] = colour > 1 ? 1.0f : colour >= 0 ? static_cast<float>(colour) : 0;
    }
  }
  return Status::Ok();
}

}  // namespace

Status LoadDynamic3dgs(const std::string& dir, const CaptureOptions& options, Capture* capture) {
  M4D_RETURN_IF_ERROR(CheckCaptureOptions(options));
  *capture = Capture();
  capture->layout = "dynamic3dgs";
  M4D_RETURN_IF_ERROR(Load(dir, capture));
  const std::string points = dir + "/init_pt_cld.npz";
  if (options.initial_points.empty() && IsRegularFile(points)) {
    M4D_RETURN_IF_ERROR(LoadPoints(points, &capture->initial_points));
  }
  return ApplyCaptureOptions(options, capture);
}

}  // namespace m4d
