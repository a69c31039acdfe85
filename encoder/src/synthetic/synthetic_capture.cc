#include "encoder/src/synthetic/synthetic_capture.h"

#include <memory>
#include <utility>
#include <vector>

#include "encoder/src/dataset/undistorting_frame_source.h"
#include "encoder/src/dataset/world_handedness.h"
#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/synthetic/lens_resampling.h"
#include "encoder/src/synthetic/synthetic_scene.h"

namespace m4d {
namespace {

// Serves views from memory; Load converts the bytes like reading the PNG would.
class MemoryFrameSource : public FrameSource {
 public:
  MemoryFrameSource(int width, int height, int cameras, std::vector<std::vector<uint8_t>> views)
      : width_(width), height_(height), cameras_(cameras), views_(std::move(views)) {}

  Status Load(int frame, int camera, Image* rgb) override {
    const size_t index = static_cast<size_t>(frame) * cameras_ + camera;
    if (frame < 0 || camera < 0 || camera >= cameras_ || index >= views_.size()) {
      return Status(M4D_ERR_INVALID_ARG, "synthetic capture: view out of range");
    }
    const std::vector<uint8_t>& bytes = views_[index];
    Reshape(width_, height_, 3, rgb);
    for (size_t i = 0; i < bytes.size(); ++i) rgb->pixels[i] = ByteToFloat(bytes[i]);
    return Status::Ok();
  }

 private:
  const int width_, height_, cameras_;
  std::vector<std::vector<uint8_t>> views_;  // frame-major
};

// What the writer's JPEG file would decode to: the same encoder, the same bytes.
Status JpegRoundTrip(int width, int height, int quality, std::vector<uint8_t>* rgb) {
  Image image(width, height, 3);
  for (size_t i = 0; i < rgb->size(); ++i) image.pixels[i] = ByteToFloat((*rgb)[i]);
  std::vector<uint8_t> jpeg;
  M4D_RETURN_IF_ERROR(EncodeJpeg(image, quality, &jpeg));
  M4D_RETURN_IF_ERROR(DecodeJpeg(jpeg.data(), jpeg.size(), &image));
  for (size_t i = 0; i < rgb->size(); ++i) (*rgb)[i] = FloatToByte(image.pixels[i]);
  return Status::Ok();
}

}  // namespace

Status GenerateSyntheticCapture(const SyntheticSceneOptions& options, Capture* capture,
                                const SceneProgress& progress) {
  M4D_RETURN_IF_ERROR(ValidateSyntheticSceneOptions(options));
  const size_t bytes =
      static_cast<size_t>(options.width) * options.height * 3 * options.cameras * options.frames;
  if (bytes > kMaxSyntheticCaptureBytes) {
    return LimitError("synthetic capture: " + std::to_string(bytes >> 20) +
                      " MiB of images is too much for memory; write the scene to files");
  }
  std::unique_ptr<SyntheticScene> scene;
  M4D_RETURN_IF_ERROR(SyntheticScene::Create(options, &scene));
  std::vector<std::vector<uint8_t>> views(static_cast<size_t>(options.frames) * options.cameras);
  const int quality = options.realism.jpeg_quality;
  for (int f = 0; f < options.frames; ++f) {
    for (int c = 0; c < options.cameras; ++c) {
      std::vector<uint8_t>& view = views[static_cast<size_t>(f) * options.cameras + c];
      M4D_RETURN_IF_ERROR(scene->RenderView(f, c, &view));
      if (quality > 0)
        M4D_RETURN_IF_ERROR(JpegRoundTrip(options.width, options.height, quality, &view));
    }
    if (progress) progress(f + 1, options.frames);
  }
  Capture result;
  result.layout = "synthetic";
  result.frame_count = options.frames;
  result.camera_names = scene->camera_names();
  result.cameras.assign(options.frames, scene->CalibrationCameras());
  if (options.cameras > 1) result.test_cameras = {0};
  result.initial_points = scene->InitialPoints();
  result.frames = std::make_unique<MemoryFrameSource>(options.width, options.height,
                                                      options.cameras, std::move(views));
  // As a loader gives a distorted capture: undistorted to pinhole cameras.
  const LensDistortion distortion = SceneLensDistortion(options.realism);
  if (HasDistortion(distortion)) {
    M4D_RETURN_IF_ERROR(UndistortCapture(
        std::vector<std::vector<LensDistortion>>(
            options.frames, std::vector<LensDistortion>(options.cameras, distortion)),
        &result));
  }
  // As a loader gives a left-handed capture: mirrored to a right-handed world.
  M4D_RETURN_IF_ERROR(MakeWorldRightHanded(&result));
  *capture = std::move(result);
  return Status::Ok();
}

}  // namespace m4d
