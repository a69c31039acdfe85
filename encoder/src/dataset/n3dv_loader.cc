#include "encoder/src/dataset/n3dv_loader.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/dataset/colmap_model.h"
#include "encoder/src/dataset/file_listing.h"
#include "encoder/src/dataset/image_file_source.h"
#include "encoder/src/dataset/npy_array.h"
#include "encoder/src/dataset/video_frame_source.h"
#include "encoder/src/image_io/image_file.h"

namespace m4d {
namespace {

constexpr int kPoseValues = 17;

bool IsCameraName(const std::string& name) { return name.compare(0, 3, "cam") == 0; }

bool HasSuffix(const std::string& name, const std::string& suffix) {
  return name.size() > suffix.size() &&
         name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Camera directories holding extracted frames: <dir>/camXX/images or <dir>/frames/camXX.
Status FindFrameDirectories(const std::string& dir, std::vector<std::string>* names,
                            std::vector<std::string>* frame_dirs) {
  std::vector<std::string> subdirs;
  M4D_RETURN_IF_ERROR(ListDirectory(dir, EntryKind::kDirectories, &subdirs));
  for (const std::string& name : subdirs) {
    if (IsCameraName(name) && IsDirectory(dir + "/" + name + "/images")) {
      names->push_back(name);
      frame_dirs->push_back(dir + "/" + name + "/images");
    }
  }
  if (!names->empty() || !IsDirectory(dir + "/frames")) return Status::Ok();
  M4D_RETURN_IF_ERROR(ListDirectory(dir + "/frames", EntryKind::kDirectories, &subdirs));
  for (const std::string& name : subdirs) {
    if (!IsCameraName(name)) continue;
    names->push_back(name);
    frame_dirs->push_back(dir + "/frames/" + name);
  }
  return Status::Ok();
}

// Reads each camera's image list and the size of its first image.
Status LoadExtractedFrames(const std::vector<std::string>& frame_dirs,
                           std::vector<std::vector<std::string>>* files,
                           std::vector<std::pair<int, int>>* sizes) {
  for (const std::string& frame_dir : frame_dirs) {
    std::vector<std::string> names;
    M4D_RETURN_IF_ERROR(ListImageFiles(frame_dir, &names));
    if (names.empty()) return Status(M4D_ERR_INVALID_ARG, "n3dv: no images in '" + frame_dir + "'");
    for (std::string& name : names) name = frame_dir + "/" + name;
    Image first;
    M4D_RETURN_IF_ERROR(ReadImageFile(names[0], &first));
    sizes->emplace_back(first.width, first.height);
    files->push_back(std::move(names));
  }
  return Status::Ok();
}

// Frame count of the capture: the shortest camera's, with a note when they differ.
int CommonFrameCount(const std::vector<int>& counts, const std::vector<std::string>& names,
                     std::vector<std::string>* notes) {
  const int count = *std::min_element(counts.begin(), counts.end());
  for (size_t c = 0; c < counts.size(); ++c) {
    if (counts[c] != count) {
      notes->push_back("n3dv: " + names[c] + " has " + std::to_string(counts[c]) +
                       " frames; using the first " + std::to_string(count));
    }
  }
  return count;
}

Status LoadFrames(const std::string& dir, Capture* capture,
                  std::vector<std::pair<int, int>>* sizes) {
  std::vector<std::string> frame_dirs;
  M4D_RETURN_IF_ERROR(FindFrameDirectories(dir, &capture->camera_names, &frame_dirs));
  std::vector<int> counts;
  if (!frame_dirs.empty()) {
    std::vector<std::vector<std::string>> files;  // [camera][frame]
    M4D_RETURN_IF_ERROR(LoadExtractedFrames(frame_dirs, &files, sizes));
    for (const auto& list : files) counts.push_back(static_cast<int>(list.size()));
    capture->frame_count = CommonFrameCount(counts, capture->camera_names, &capture->notes);
    std::vector<std::vector<std::string>> paths(capture->frame_count);  // [frame][camera]
    for (int f = 0; f < capture->frame_count; ++f) {
      for (const auto& list : files) paths[f].push_back(list[f]);
    }
    capture->cameras.assign(capture->frame_count, std::vector<Camera>(files.size()));
    for (auto& row : capture->cameras) {
      for (size_t c = 0; c < row.size(); ++c) {
        row[c].width = (*sizes)[c].first;
        row[c].height = (*sizes)[c].second;
      }
    }
    capture->frames = std::make_unique<ImageFileSource>(std::move(paths), capture->cameras);
    return Status::Ok();
  }
  std::vector<std::string> files, videos;
  M4D_RETURN_IF_ERROR(ListDirectory(dir, EntryKind::kFiles, &files));
  for (const std::string& name : files) {
    if (IsCameraName(name) && HasSuffix(name, ".mp4")) {
      capture->camera_names.push_back(name.substr(0, name.size() - 4));
      videos.push_back(dir + "/" + name);
    }
  }
  if (videos.empty()) {
    return Status(M4D_ERR_INVALID_ARG,
                  "n3dv: no camXX.mp4, camXX/images or frames/camXX in '" + dir + "'");
  }
  std::unique_ptr<VideoFrameSource> source;
  M4D_RETURN_IF_ERROR(VideoFrameSource::Open(videos, &source));
  for (int c = 0; c < source->camera_count(); ++c) {
    counts.push_back(source->video(c).frame_count());
    sizes->emplace_back(source->video(c).width(), source->video(c).height());
  }
  capture->frame_count = CommonFrameCount(counts, capture->camera_names, &capture->notes);
  capture->frames = std::move(source);
  return Status::Ok();
}

}  // namespace

Status N3dvCamera(const double* row, int width, int height, Camera* camera) {
  // m(r, c) of the 3x5 matrix: columns 0..2 are the camera's down, right and back axes in
  // world coordinates, column 3 its centre, column 4 (H, W, f).
  auto m = [row](int r, int c) { return row[5 * r + c]; };
  const double source_width = m(1, 4), focal = m(2, 4);
  if (!(source_width > 0) || !(focal > 0) || !std::isfinite(source_width) ||
      !std::isfinite(focal)) {
    return Status(M4D_ERR_INVALID_ARG, "n3dv: poses_bounds row with a bad W or f");
  }
  for (int i = 0; i < 15; ++i) {
    if (!(std::fabs(row[i]) <= 1e30)) return Status(M4D_ERR_INVALID_ARG, "n3dv: bad pose value");
  }
  // OpenCV axes (right, down, forward) are LLFF's (column 1, column 0, -column 2); the
  // world-to-camera rotation has them as rows.
  const double axes[3][3] = {
      {m(0, 1), m(1, 1), m(2, 1)}, {m(0, 0), m(1, 0), m(2, 0)}, {-m(0, 2), -m(1, 2), -m(2, 2)}};
  for (int r = 0; r < 3; ++r) {
    double t = 0;
    for (int c = 0; c < 3; ++c) {
      camera->rotation[3 * r + c] = static_cast<float>(axes[r][c]);
      t -= axes[r][c] * m(c, 3);
    }
    camera->translation[r] = static_cast<float>(t);
  }
  const double f = focal * width / source_width;
  camera->width = width;
  camera->height = height;
  camera->fx = camera->fy = static_cast<float>(f);
  camera->cx = 0.5f * width;
  camera->cy = 0.5f * height;
  return Status::Ok();
}

Status LoadN3dv(const std::string& dir, const CaptureOptions& options, Capture* capture) {
  M4D_RETURN_IF_ERROR(CheckCaptureOptions(options));
  *capture = Capture();
  capture->layout = "n3dv";
  capture->fps_num = 30;  // the N3DV captures' rate; the files do not record it
  NpyArray poses;
  M4D_RETURN_IF_ERROR(ReadNpyFile(dir + "/poses_bounds.npy", &poses));
  if (poses.shape.size() != 2 || poses.shape[1] != kPoseValues) {
    return Status(M4D_ERR_INVALID_ARG, "n3dv: poses_bounds.npy must be N x 17");
  }
  std::vector<std::pair<int, int>> sizes;
  M4D_RETURN_IF_ERROR(LoadFrames(dir, capture, &sizes));
  if (poses.shape[0] != sizes.size()) {
    return Status(M4D_ERR_INVALID_ARG, "n3dv: " + std::to_string(poses.shape[0]) + " poses for " +
                                           std::to_string(sizes.size()) + " cameras in '" + dir +
                                           "'");
  }
  std::vector<Camera> rig(sizes.size());
  for (size_t c = 0; c < rig.size(); ++c) {
    M4D_RETURN_IF_ERROR(
        N3dvCamera(&poses.values[c * kPoseValues], sizes[c].first, sizes[c].second, &rig[c]));
  }
  capture->cameras.assign(capture->frame_count, rig);
  const std::string sparse = dir + "/sparse/0";
  if (options.initial_points.empty() && IsColmapModelDir(sparse)) {
    M4D_RETURN_IF_ERROR(ReadColmapPoints(sparse, &capture->initial_points));
  }
  return ApplyCaptureOptions(options, capture);
}

}  // namespace m4d
