#include "encoder/src/synthetic/synthetic_scene.h"

#include "encoder/src/dataset/world_handedness.h"
#include "encoder/src/synthetic/camera_rig.h"
#include "encoder/src/synthetic/scene_animation.h"
#include "encoder/src/synthetic/scene_random.h"
#include "encoder/src/synthetic/sensor_effects.h"
#include "encoder/src/synthetic/surface_point_sampler.h"

namespace m4d {

Status SyntheticScene::Create(const SyntheticSceneOptions& options,
                              std::unique_ptr<SyntheticScene>* scene) {
  M4D_RETURN_IF_ERROR(ValidateSyntheticSceneOptions(options));
  std::unique_ptr<SyntheticScene> created(new SyntheticScene());
  created->options_ = options;
  created->options_.emergent_frame = EmergentFrame(options);
  created->cameras_ = MakeCameraRig(options);
  created->camera_names_ = CameraNames(options.cameras);
  created->content_ = BuildSceneContent(options.seed, options.realism.background_sway > 0.0f);
  created->render_cameras_ = created->cameras_;
  const LensDistortion distortion = SceneLensDistortion(options.realism);
  if (HasDistortion(distortion)) {
    M4D_RETURN_IF_ERROR(LensResampler::Create(created->cameras_[0], distortion, &created->lens_));
    for (Camera& camera : created->render_cameras_) camera = created->lens_->Canvas(camera);
  }
  const Camera& canvas = created->render_cameras_[0];
  M4D_RETURN_IF_ERROR(SceneRenderer::Create(created->content_, canvas.width, canvas.height,
                                            options.supersample, options.msaa_samples,
                                            &created->renderer_));
  *scene = std::move(created);
  return Status::Ok();
}

Status SyntheticScene::RenderView(int frame, int camera, std::vector<uint8_t>* rgb) {
  if (frame < 0 || frame >= options_.frames || camera < 0 || camera >= options_.cameras) {
    return Status(M4D_ERR_INVALID_ARG, "synthetic scene: view (frame " + std::to_string(frame) +
                                           ", camera " + std::to_string(camera) + ") out of range");
  }
  const SceneFrameState state = SceneStateAt(content_, options_, frame);
  if (!lens_ && !HasSensorEffects(options_.realism)) {
    return renderer_->Render(state, cameras_[camera], rgb);
  }
  M4D_RETURN_IF_ERROR(renderer_->Render(state, render_cameras_[camera], &pinhole_));
  if (lens_) {
    M4D_RETURN_IF_ERROR(lens_->Distort(pinhole_, &levels_));
  } else {
    levels_.assign(pinhole_.begin(), pinhole_.end());
  }
  ApplySensorEffects(options_, frame, camera, levels_, rgb);
  return Status::Ok();
}

std::vector<Camera> SyntheticScene::CalibrationCameras() const {
  if (!options_.realism.left_handed) return cameras_;
  std::vector<Camera> mirrored;
  for (const Camera& camera : cameras_) mirrored.push_back(MirrorWorldX(camera));
  return mirrored;
}

PointCloud SyntheticScene::InitialPoints() const {
  PointCloud points = SampleSurfacePoints(content_, SceneStateAt(content_, options_, 0),
                                          options_.points, MixBits(options_.seed * 7919 + 11));
  if (options_.realism.left_handed) MirrorWorldX(&points);
  return points;
}

}  // namespace m4d
