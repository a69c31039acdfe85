#include "encoder/src/dataset/colmap_model.h"

#include <filesystem>
#include <system_error>

#include "encoder/src/dataset/colmap_binary.h"
#include "encoder/src/dataset/colmap_text.h"
#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace {

struct ModelInfo {
  const char* name;
  int params;
};

// Indexed by COLMAP's model id.
constexpr ModelInfo kModels[] = {{"SIMPLE_PINHOLE", 3},
                                 {"PINHOLE", 4},
                                 {"SIMPLE_RADIAL", 4},
                                 {"RADIAL", 5},
                                 {"OPENCV", 8},
                                 {"OPENCV_FISHEYE", 8},
                                 {"FULL_OPENCV", 12},
                                 {"FOV", 5},
                                 {"SIMPLE_RADIAL_FISHEYE", 4},
                                 {"RADIAL_FISHEYE", 5},
                                 {"THIN_PRISM_FISHEYE", 12}};
constexpr int kModelCount = static_cast<int>(sizeof(kModels) / sizeof(kModels[0]));

enum ModelId {
  kSimplePinhole = 0,
  kPinhole = 1,
  kSimpleRadial = 2,
  kRadial = 3,
  kOpenCv = 4,
  kOpenCvFisheye = 5,
  kFullOpenCv = 6
};

// The lens model and where its coefficients sit in COLMAP's parameter list: k1..k6, p1, p2
// (-1: not a parameter of the model).
struct LensLayout {
  LensModel model;
  int k[6];
  int p1, p2;
};

LensLayout ColmapLensLayout(int model_id) {
  switch (model_id) {
    case kSimpleRadial:  // f, cx, cy, k
      return {LensModel::kRadial, {3, -1, -1, -1, -1, -1}, -1, -1};
    case kRadial:  // f, cx, cy, k1, k2
      return {LensModel::kRadial, {3, 4, -1, -1, -1, -1}, -1, -1};
    case kOpenCv:  // fx, fy, cx, cy, k1, k2, p1, p2
      return {LensModel::kOpenCv, {4, 5, -1, -1, -1, -1}, 6, 7};
    case kOpenCvFisheye:  // fx, fy, cx, cy, k1, k2, k3, k4
      return {LensModel::kFisheye, {4, 5, 6, 7, -1, -1}, -1, -1};
    case kFullOpenCv:  // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
      return {LensModel::kFullOpenCv, {4, 5, 8, 9, 10, 11}, 6, 7};
    default:  // the pinhole models
      return {LensModel::kNone, {-1, -1, -1, -1, -1, -1}, -1, -1};
  }
}

bool Exists(const std::string& path) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

// Reads <dir>/<stem>.bin with parse_binary, or else <dir>/<stem>.txt with parse_text.
template <typename T>
Status ReadModelFile(const std::string& dir, const std::string& stem,
                     Status (*parse_binary)(const uint8_t*, size_t, T*),
                     Status (*parse_text)(const std::string&, T*), T* out) {
  const std::string binary = dir + "/" + stem + ".bin";
  const bool is_binary = Exists(binary);
  const std::string path = is_binary ? binary : dir + "/" + stem + ".txt";
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxColmapFileBytes, &bytes);
  if (status.ok()) {
    status = is_binary ? parse_binary(bytes.data(), bytes.size(), out)
                       : parse_text(std::string(bytes.begin(), bytes.end()), out);
  }
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

}  // namespace

const char* ColmapModelName(int model_id) {
  return model_id >= 0 && model_id < kModelCount ? kModels[model_id].name : nullptr;
}

int ColmapModelParamCount(int model_id) {
  return model_id >= 0 && model_id < kModelCount ? kModels[model_id].params : -1;
}

int ColmapModelId(const std::string& name) {
  for (int id = 0; id < kModelCount; ++id) {
    if (name == kModels[id].name) return id;
  }
  return -1;
}

Status ColmapIntrinsics(const ColmapCamera& camera, double* fx, double* fy, double* cx, double* cy,
                        LensDistortion* distortion) {
  const std::vector<double>& p = camera.params;
  if (static_cast<int>(p.size()) != ColmapModelParamCount(camera.model_id)) {
    return Status(M4D_ERR_INVALID_ARG, "colmap: camera parameter count does not match its model");
  }
  // Models with one focal length list f, cx, cy first; the others fx, fy, cx, cy.
  switch (camera.model_id) {
    case kSimplePinhole:
    case kSimpleRadial:
    case kRadial:
      *fx = *fy = p[0];
      *cx = p[1];
      *cy = p[2];
      break;
    case kPinhole:
    case kOpenCv:
    case kOpenCvFisheye:
    case kFullOpenCv:
      *fx = p[0];
      *fy = p[1];
      *cx = p[2];
      *cy = p[3];
      break;
    default:
      return Status(M4D_ERR_UNSUPPORTED, std::string("colmap: camera model ") +
                                             ColmapModelName(camera.model_id) +
                                             " (need a pinhole, radial or OpenCV model)");
  }
  const LensLayout layout = ColmapLensLayout(camera.model_id);
  *distortion = LensDistortion();
  distortion->model = layout.model;
  for (int i = 0; i < 6; ++i) distortion->k[i] = layout.k[i] < 0 ? 0 : p[layout.k[i]];
  distortion->p1 = layout.p1 < 0 ? 0 : p[layout.p1];
  distortion->p2 = layout.p2 < 0 ? 0 : p[layout.p2];
  return Status::Ok();
}

Status ReadColmapModel(const std::string& dir, bool with_points, ColmapModel* model) {
  M4D_RETURN_IF_ERROR(ReadModelFile(dir, "cameras", ParseColmapCamerasBinary,
                                    ParseColmapCamerasText, &model->cameras));
  M4D_RETURN_IF_ERROR(
      ReadModelFile(dir, "images", ParseColmapImagesBinary, ParseColmapImagesText, &model->images));
  model->points = PointCloud();
  if (!with_points) return Status::Ok();
  return ReadColmapPoints(dir, &model->points);
}

Status ReadColmapPoints(const std::string& dir, PointCloud* points) {
  return ReadModelFile(dir, "points3D", ParseColmapPointsBinary, ParseColmapPointsText, points);
}

bool IsColmapModelDir(const std::string& dir) {
  return Exists(dir + "/cameras.bin") || Exists(dir + "/cameras.txt");
}

}  // namespace m4d
