#include "encoder/src/synthetic/scene_writer.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "encoder/src/dataset/transforms_json_writer.h"
#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"
#include "encoder/src/io/shortest_decimal.h"
#include "encoder/src/ply/point_cloud_ply.h"
#include "encoder/src/synthetic/lens_resampling.h"
#include "encoder/src/synthetic/synthetic_scene.h"

namespace m4d {
namespace {

using Json = nlohmann::ordered_json;

constexpr char kPlyName[] = "points3d.ply";

Status MakeDirectories(const std::string& path) {
  std::error_code error;
  std::filesystem::create_directories(path, error);
  if (error) {
    return Status(M4D_ERR_INVALID_ARG, "cannot create directory " + path + ": " + error.message());
  }
  return Status::Ok();
}

// Writes one frame's views (RGB bytes, one per camera) as PNGs, or JPEGs at jpeg_quality
// when it is above 0.
Status WriteFrameImages(const std::string& root, const std::vector<std::string>& names, int frame,
                        int width, int height, int jpeg_quality,
                        const std::vector<std::vector<uint8_t>>& views) {
  Image image(width, height, 3);
  for (size_t c = 0; c < views.size(); ++c) {
    for (size_t i = 0; i < views[c].size(); ++i) image.pixels[i] = ByteToFloat(views[c][i]);
    const std::string path = root + "/" + SyntheticImagePath(names[c], frame, jpeg_quality > 0);
    M4D_RETURN_IF_ERROR(jpeg_quality > 0 ? WriteJpeg(path, image, jpeg_quality)
                                         : WritePng(path, image));
  }
  return Status::Ok();
}

Json RealismJson(const CaptureRealism& r) {
  Json json;
  json["noise_sigma"] = ShortestDecimal(r.noise_sigma);
  json["jpeg_quality"] = r.jpeg_quality;
  json["exposure_spread"] = ShortestDecimal(r.exposure_spread);
  json["white_balance_spread"] = ShortestDecimal(r.white_balance_spread);
  json["k1"] = ShortestDecimal(r.k1);
  json["k2"] = ShortestDecimal(r.k2);
  json["p1"] = ShortestDecimal(r.p1);
  json["p2"] = ShortestDecimal(r.p2);
  json["left_handed"] = r.left_handed;
  json["sparse_rig"] = r.sparse_rig;
  json["sparse_rig_arc_degrees"] = ShortestDecimal(r.sparse_rig_arc_degrees);
  json["background_sway"] = ShortestDecimal(r.background_sway);
  json["light_flicker"] = ShortestDecimal(r.light_flicker);
  return json;
}

// What the scene holds and when things happen, for tools and tests that need to know.
std::string SceneJsonText(const SyntheticScene& scene) {
  const SyntheticSceneOptions& o = scene.options();
  Json json;
  json["generator"] = "m4d synthetic scene";
  json["format_version"] = 1;
  json["cameras"] = o.cameras;
  json["width"] = o.width;
  json["height"] = o.height;
  json["frames"] = o.frames;
  json["horizontal_fov_degrees"] = o.horizontal_fov_degrees;
  json["test_camera"] = o.cameras > 1 ? 0 : -1;  // held out from training
  json["seed"] = o.seed;
  json["points"] = o.points;
  json["supersample"] = o.supersample;
  json["msaa_samples"] = o.msaa_samples;
  json["emergent_frame"] = o.emergent_frame;
  json["background_change_frame"] =
      o.background_change_frame >= 0 ? Json(o.background_change_frame) : Json(nullptr);
  Json events = Json::array();
  events.push_back(
      {{"frame", o.emergent_frame}, {"kind", "object_appears"}, {"object", "emergent_ball"}});
  if (o.background_change_frame >= 0) {
    events.push_back({{"frame", o.background_change_frame},
                      {"kind", "lamp_light_changes"},
                      {"object", "lamp_shade"}});
  }
  json["events"] = std::move(events);
  Json objects = Json::array();
  for (const SceneObject& object : scene.content().objects) {
    objects.push_back({{"name", object.name},
                       {"motion", ObjectMotionName(object.motion)},
                       {"triangles", object.mesh.triangle_count()}});
  }
  json["objects"] = std::move(objects);
  json["realism"] = RealismJson(o.realism);
  return json.dump(2) + "\n";
}

Status WriteText(const std::string& path, const std::string& text) {
  return WriteFileBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

}  // namespace

std::string SyntheticImagePath(const std::string& camera_name, int frame, bool jpeg) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.%s", frame, jpeg ? "jpg" : "png");
  return "images/" + camera_name + "/" + name;
}

Status WriteSyntheticScene(const SyntheticSceneOptions& options, const std::string& dir,
                           const SceneProgress& progress) {
  std::unique_ptr<SyntheticScene> scene;
  M4D_RETURN_IF_ERROR(SyntheticScene::Create(options, &scene));
  const std::string root = dir.empty() ? std::string(".") : dir;
  const std::vector<std::string>& names = scene->camera_names();
  for (const std::string& name : names) {
    M4D_RETURN_IF_ERROR(MakeDirectories(root + "/images/" + name));
  }
  // Image compression of one frame runs on a second thread while GL renders the next; two
  // sets of view buffers alternate between the two.
  std::vector<std::vector<uint8_t>> views[2];
  views[0].resize(options.cameras);
  views[1].resize(options.cameras);
  std::future<Status> writing;  // declared after views: destroyed (waited for) first
  for (int f = 0; f < options.frames; ++f) {
    std::vector<std::vector<uint8_t>>& frame_views = views[f & 1];
    for (int c = 0; c < options.cameras; ++c) {
      M4D_RETURN_IF_ERROR(scene->RenderView(f, c, &frame_views[c]));
    }
    if (writing.valid()) M4D_RETURN_IF_ERROR(writing.get());
    writing =
        std::async(std::launch::async, WriteFrameImages, root, std::cref(names), f, options.width,
                   options.height, options.realism.jpeg_quality, std::cref(frame_views));
    if (progress) progress(f + 1, options.frames);
  }
  M4D_RETURN_IF_ERROR(writing.get());
  M4D_RETURN_IF_ERROR(WritePointCloudPly(root + "/" + kPlyName, scene->InitialPoints()));
  TransformsJsonRig rig;
  rig.cameras = scene->cameras();
  rig.camera_names = names;
  rig.frame_count = options.frames;
  const bool jpeg = options.realism.jpeg_quality > 0;
  rig.image_path = [&names, jpeg](int frame, int camera) {
    return SyntheticImagePath(names[camera], frame, jpeg);
  };
  rig.ply_file_path = kPlyName;
  rig.mirror_world_x = options.realism.left_handed;
  rig.distortion = SceneLensDistortion(options.realism);
  M4D_RETURN_IF_ERROR(WriteTransformsJson(root + "/transforms.json", rig));
  return WriteText(root + "/scene.json", SceneJsonText(*scene));
}

}  // namespace m4d
