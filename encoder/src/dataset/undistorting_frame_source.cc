#include "encoder/src/dataset/undistorting_frame_source.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

namespace m4d {
namespace {

// Remap tables kept: 1 GiB, sixteen 4K cameras. Beyond it tables are rebuilt when needed,
// which costs about as much as decoding the image.
constexpr size_t kMaxCachedMapBytes = size_t{1} << 30;

// Views share a lens when their image size, intrinsics and distortion are the same bytes.
std::string LensKey(const Camera& c, const LensDistortion& d) {
  const int ints[3] = {c.width, c.height, static_cast<int>(d.model)};
  const float intrinsics[4] = {c.fx, c.fy, c.cx, c.cy};
  const double coefficients[8] = {d.k[0], d.k[1], d.k[2], d.k[3], d.k[4], d.k[5], d.p1, d.p2};
  std::string key(reinterpret_cast<const char*>(ints), sizeof(ints));
  key.append(reinterpret_cast<const char*>(intrinsics), sizeof(intrinsics));
  key.append(reinterpret_cast<const char*>(coefficients), sizeof(coefficients));
  return key;
}

// E.g. "colmap: 3 of 4 cameras undistorted (OPENCV) to pinhole, focal lengths x0.953 to
// x0.968 at the same image size".
std::string Note(const Capture& capture, size_t cameras, const std::set<std::string>& models,
                 double min_scale, double max_scale) {
  std::string note = capture.layout + ": ";
  if (cameras < capture.camera_names.size()) {
    note += std::to_string(cameras) + " of " + std::to_string(capture.camera_names.size());
  } else {
    note += std::to_string(cameras);
  }
  note += cameras == 1 ? " camera undistorted (" : " cameras undistorted (";
  for (const std::string& model : models) {
    note += (model == *models.begin() ? "" : ", ") + model;
  }
  char scales[64];
  std::snprintf(scales, sizeof(scales), "x%.3g to x%.3g", min_scale, max_scale);
  return note + ") to pinhole, focal lengths " + scales + " at the same image size";
}

}  // namespace

UndistortingFrameSource::UndistortingFrameSource(std::unique_ptr<FrameSource> distorted,
                                                 std::vector<Lens> lenses,
                                                 std::vector<std::vector<int>> lens_of)
    : distorted_(std::move(distorted)),
      lenses_(std::move(lenses)),
      lens_of_(std::move(lens_of)),
      maps_(lenses_.size()) {}

Status UndistortingFrameSource::Load(int frame, int camera, Image* rgb) {
  const int lens = lens_of_[frame][camera];
  if (lens < 0) return distorted_->Load(frame, camera, rgb);
  // The image first: its size is checked against the camera's before a table is allocated.
  M4D_RETURN_IF_ERROR(distorted_->Load(frame, camera, &image_));
  const UndistortionMap* map;
  M4D_RETURN_IF_ERROR(Map(lens, &map));
  return Remap(*map, image_, rgb);
}

Status UndistortingFrameSource::Map(int lens, const UndistortionMap** map) {
  if (maps_[lens]) {
    *map = maps_[lens].get();
    return Status::Ok();
  }
  if (lens == uncached_lens_) {
    *map = &uncached_;
    return Status::Ok();
  }
  const Lens& l = lenses_[lens];
  auto built = std::make_unique<UndistortionMap>();
  M4D_RETURN_IF_ERROR(
      BuildUndistortionMap(l.distorted, l.distortion, l.pinhole, l.what, built.get()));
  const size_t bytes = built->source.size() * sizeof(float);
  if (cached_bytes_ + bytes <= kMaxCachedMapBytes) {
    cached_bytes_ += bytes;
    maps_[lens] = std::move(built);
    *map = maps_[lens].get();
  } else {
    uncached_ = std::move(*built);
    uncached_lens_ = lens;
    *map = &uncached_;
  }
  return Status::Ok();
}

Status UndistortCapture(const std::vector<std::vector<LensDistortion>>& distortions,
                        Capture* capture) {
  std::vector<UndistortingFrameSource::Lens> lenses;
  std::map<std::string, int> lens_index;  // LensKey -> index into lenses
  std::vector<std::vector<int>> lens_of(capture->frame_count);
  std::set<int> cameras;
  std::set<std::string> models;
  double min_scale = 1e300, max_scale = 0;
  for (int f = 0; f < capture->frame_count; ++f) {
    lens_of[f].assign(capture->camera_count(), -1);
    for (int c = 0; c < capture->camera_count(); ++c) {
      const LensDistortion& distortion = distortions[f][c];
      if (!HasDistortion(distortion)) continue;
      Camera& camera = capture->cameras[f][c];
      const std::string what = capture->layout + ": camera '" + capture->camera_names[c] + "'";
      const auto found = lens_index.emplace(LensKey(camera, distortion), lenses.size());
      if (found.second) {
        UndistortingFrameSource::Lens lens{camera, distortion, Camera(), what};
        M4D_RETURN_IF_ERROR(UndistortedCamera(camera, distortion, what, &lens.pinhole));
        lenses.push_back(std::move(lens));
      }
      const Camera& pinhole = lenses[found.first->second].pinhole;
      const double sx = static_cast<double>(pinhole.fx) / camera.fx;
      const double sy = static_cast<double>(pinhole.fy) / camera.fy;
      min_scale = std::min({min_scale, sx, sy});
      max_scale = std::max({max_scale, sx, sy});
      camera.fx = pinhole.fx;
      camera.fy = pinhole.fy;
      camera.cx = pinhole.cx;
      camera.cy = pinhole.cy;
      lens_of[f][c] = found.first->second;
      cameras.insert(c);
      models.insert(LensModelName(distortion.model));
    }
  }
  if (lenses.empty()) return Status::Ok();
  capture->notes.push_back(Note(*capture, cameras.size(), models, min_scale, max_scale));
  capture->frames = std::make_unique<UndistortingFrameSource>(
      std::move(capture->frames), std::move(lenses), std::move(lens_of));
  return Status::Ok();
}

}  // namespace m4d
