#include "encoder/src/dataset/transforms_json_writer.h"

#include <nlohmann/json.hpp>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/io/shortest_decimal.h"

namespace m4d {
namespace {

using Json = nlohmann::ordered_json;

// Camera-to-world in OpenGL axes (x right, y up, z backward): the OpenCV camera's axes are
// the rows of R; y and z flip. Mirroring the world negates the first row.
Json CameraToWorld(const Camera& camera, bool mirror_world_x) {
  float centre[3];
  CameraCentre(camera, centre);
  const float* r = camera.rotation;
  Json m = Json::array();
  for (int i = 0; i < 3; ++i) {
    const float s = i == 0 && mirror_world_x ? -1.0f : 1.0f;
    m.push_back({ShortestDecimal(s * r[i]), ShortestDecimal(-s * r[3 + i]),
                 ShortestDecimal(-s * r[6 + i]), ShortestDecimal(s * centre[i])});
  }
  m.push_back({0, 0, 0, 1});
  return m;
}

void PutIntrinsics(const Camera& camera, Json* json) {
  (*json)["w"] = camera.width;
  (*json)["h"] = camera.height;
  (*json)["fl_x"] = ShortestDecimal(camera.fx);
  (*json)["fl_y"] = ShortestDecimal(camera.fy);
  (*json)["cx"] = ShortestDecimal(camera.cx);
  (*json)["cy"] = ShortestDecimal(camera.cy);
}

Status PutDistortion(const LensDistortion& d, Json* json) {
  if (d.model == LensModel::kNone) return Status::Ok();
  if (d.model != LensModel::kOpenCv) {
    return Status(M4D_ERR_INVALID_ARG, std::string("transforms.json: cannot write lens model ") +
                                           LensModelName(d.model) + ", only OPENCV");
  }
  M4D_RETURN_IF_ERROR(CheckLensDistortion(d, "transforms.json"));
  (*json)["k1"] = ShortestDecimal(static_cast<float>(d.k[0]));
  (*json)["k2"] = ShortestDecimal(static_cast<float>(d.k[1]));
  if (d.k[2] != 0) (*json)["k3"] = ShortestDecimal(static_cast<float>(d.k[2]));
  (*json)["p1"] = ShortestDecimal(static_cast<float>(d.p1));
  (*json)["p2"] = ShortestDecimal(static_cast<float>(d.p2));
  return Status::Ok();
}

bool SameIntrinsics(const Camera& a, const Camera& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy;
}

}  // namespace

Status TransformsJsonText(const TransformsJsonRig& rig, std::string* text) {
  if (rig.cameras.empty() || rig.camera_names.size() != rig.cameras.size() || rig.frame_count < 1 ||
      !rig.image_path) {
    return Status(M4D_ERR_INVALID_ARG, "transforms.json: empty rig or mismatched camera names");
  }
  for (const Camera& camera : rig.cameras) M4D_RETURN_IF_ERROR(ValidateCamera(camera));
  Json json;
  json["camera_model"] = "OPENCV";
  PutIntrinsics(rig.cameras[0], &json);
  M4D_RETURN_IF_ERROR(PutDistortion(rig.distortion, &json));
  if (!rig.ply_file_path.empty()) json["ply_file_path"] = rig.ply_file_path;
  Json frames = Json::array();
  const double last = rig.frame_count > 1 ? rig.frame_count - 1 : 1;
  for (int f = 0; f < rig.frame_count; ++f) {
    for (size_t c = 0; c < rig.cameras.size(); ++c) {
      Json entry;
      entry["file_path"] = rig.image_path(f, static_cast<int>(c));
      entry["transform_matrix"] = CameraToWorld(rig.cameras[c], rig.mirror_world_x);
      entry["camera"] = rig.camera_names[c];
      entry["time_index"] = f;
      entry["time"] = f / last;
      if (!SameIntrinsics(rig.cameras[c], rig.cameras[0])) PutIntrinsics(rig.cameras[c], &entry);
      frames.push_back(std::move(entry));
    }
  }
  json["frames"] = std::move(frames);
  try {
    *text = json.dump(2) + "\n";
  } catch (const nlohmann::json::exception& e) {
    // Only a path or name that is not UTF-8 can fail here.
    return Status(M4D_ERR_INVALID_ARG, std::string("transforms.json: ") + e.what());
  }
  return Status::Ok();
}

Status WriteTransformsJson(const std::string& path, const TransformsJsonRig& rig) {
  std::string text;
  M4D_RETURN_IF_ERROR(TransformsJsonText(rig, &text));
  return WriteFileBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

}  // namespace m4d
