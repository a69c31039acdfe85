// UndistortingFrameSource: serves a capture's images undistorted to pinhole cameras (see
// undistortion.h), and UndistortCapture, which sets a freshly loaded capture up with it.
#ifndef M4D_ENCODER_DATASET_UNDISTORTING_FRAME_SOURCE_H_
#define M4D_ENCODER_DATASET_UNDISTORTING_FRAME_SOURCE_H_

#include <memory>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/lens_distortion.h"
#include "encoder/src/dataset/undistortion.h"
#include "sdk/src/common/status.h"

namespace m4d {

class UndistortingFrameSource : public FrameSource {
 public:
  // One distinct lens: the intrinsics of the images as loaded, their distortion, the pinhole
  // camera they are undistorted to and the name errors give.
  struct Lens {
    Camera distorted;
    LensDistortion distortion;
    Camera pinhole;
    std::string what;
  };

  // lens_of[frame][camera] indexes `lenses`, or is -1 for a view served as loaded.
  UndistortingFrameSource(std::unique_ptr<FrameSource> distorted, std::vector<Lens> lenses,
                          std::vector<std::vector<int>> lens_of);
  Status Load(int frame, int camera, Image* rgb) override;

 private:
  // The remap table of a lens, built on first use and kept while the cache has room.
  Status Map(int lens, const UndistortionMap** map);

  std::unique_ptr<FrameSource> distorted_;
  std::vector<Lens> lenses_;
  std::vector<std::vector<int>> lens_of_;
  std::vector<std::unique_ptr<UndistortionMap>> maps_;  // per lens; null until cached
  size_t cached_bytes_ = 0;
  UndistortionMap uncached_;  // the last table built beyond the cache's room
  int uncached_lens_ = -1;
  Image image_;  // the distorted image
};

// Undistorts a loaded capture whose view (frame, camera) has lens distortion
// distortions[frame][camera]; views without distortion stay as they are. Each distinct lens
// (intrinsics and distortion) gets its pinhole camera once (UndistortedCamera), the views'
// cameras become those, capture->frames is wrapped and a note names the models and the
// change of focal length. Call it before ApplyCaptureOptions so that images are undistorted
// at their full resolution, before any downscaling.
Status UndistortCapture(const std::vector<std::vector<LensDistortion>>& distortions,
                        Capture* capture);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_UNDISTORTING_FRAME_SOURCE_H_
