#include "encoder/src/dataset/capture_loader.h"

#include "encoder/src/dataset/colmap_loader.h"
#include "encoder/src/dataset/dynamic3dgs_loader.h"
#include "encoder/src/dataset/file_listing.h"
#include "encoder/src/dataset/n3dv_loader.h"
#include "encoder/src/dataset/nerfstudio_loader.h"

namespace m4d {

Status DetectCaptureLayout(const std::string& path, std::string* layout) {
  if (IsRegularFile(path) && path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0) {
    *layout = "nerfstudio";
  } else if (!IsDirectory(path)) {
    return Status(M4D_ERR_INVALID_ARG, "capture: '" + path + "' is not a directory");
  } else if (IsRegularFile(path + "/transforms.json")) {
    *layout = "nerfstudio";
  } else if (IsRegularFile(path + "/poses_bounds.npy")) {
    *layout = "n3dv";
  } else if (IsRegularFile(path + "/train_meta.json")) {
    *layout = "dynamic3dgs";
  } else if (!FindColmapModelDir(path).empty()) {
    *layout = "colmap";
  } else {
    return Status(M4D_ERR_INVALID_ARG,
                  "capture: no transforms.json, poses_bounds.npy, train_meta.json or COLMAP "
                  "model in '" +
                      path + "'");
  }
  return Status::Ok();
}

Status LoadCapture(const std::string& path, const CaptureOptions& options, Capture* capture) {
  std::string layout;
  M4D_RETURN_IF_ERROR(DetectCaptureLayout(path, &layout));
  if (layout == "nerfstudio") return LoadNerfstudio(path, options, capture);
  if (layout == "n3dv") return LoadN3dv(path, options, capture);
  if (layout == "dynamic3dgs") return LoadDynamic3dgs(path, options, capture);
  return LoadColmap(path, options, capture);
}

}  // namespace m4d
