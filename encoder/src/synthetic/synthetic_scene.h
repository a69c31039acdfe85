// SyntheticScene: the project's built-in multi-view dynamic scene, ready to render: a
// textured room with furniture, a walking and waving figure, a spinning cube, a ball that
// appears mid-sequence and a lamp that may change colour, seen by a front-facing rig (see
// README.md in this directory), optionally with the flaws of a real capture (CaptureRealism).
// Rendering uses a headless OpenGL ES context on the thread that created the scene.
#ifndef M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_H_
#define M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/synthetic/lens_resampling.h"
#include "encoder/src/synthetic/scene_content.h"
#include "encoder/src/synthetic/scene_renderer.h"
#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

class SyntheticScene {
 public:
  // Validates the options, builds the content and the renderer. Errors: bad options
  // (M4D_ERR_INVALID_ARG, M4D_ERR_LIMIT), no GL (M4D_ERR_UNSUPPORTED).
  static Status Create(const SyntheticSceneOptions& options,
                       std::unique_ptr<SyntheticScene>* scene);

  // The options with the emergent frame resolved.
  const SyntheticSceneOptions& options() const { return options_; }
  // The rig in the scene's own (right-handed) world, as it renders.
  const std::vector<Camera>& cameras() const { return cameras_; }
  // The rig as the capture's calibration gives it: cameras(), mirrored when left-handed.
  std::vector<Camera> CalibrationCameras() const;
  const std::vector<std::string>& camera_names() const { return camera_names_; }
  const SceneContent& content() const { return content_; }
  const std::string& renderer_description() const { return renderer_->description(); }

  // Renders view (frame, camera): width * height * 3 bytes of RGB, row 0 at the top, through
  // the lens and with the sensor's gains and noise (not JPEG, which the writer and the
  // capture apply). Same options, same bytes.
  Status RenderView(int frame, int camera, std::vector<uint8_t>* rgb);

  // options.points points on the surfaces present at frame 0, where they are then, in the
  // calibration's world (mirrored when left-handed).
  PointCloud InitialPoints() const;

 private:
  SyntheticScene() = default;

  SyntheticSceneOptions options_;
  std::vector<Camera> cameras_;
  std::vector<std::string> camera_names_;
  SceneContent content_;
  std::unique_ptr<SceneRenderer> renderer_;
  std::unique_ptr<LensResampler> lens_;  // null for a pinhole lens
  std::vector<Camera> render_cameras_;   // cameras_, or their canvases with a lens
  std::vector<uint8_t> pinhole_;         // a view as rendered, before the lens and sensor
  std::vector<float> levels_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_H_
