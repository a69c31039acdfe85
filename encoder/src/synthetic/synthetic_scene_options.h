// SyntheticSceneOptions: what the built-in multi-view dynamic scene is made of (rig, image
// size, length, when things happen, seeds, the flaws of a real capture), and their validation.
#ifndef M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_OPTIONS_H_
#define M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_OPTIONS_H_

#include <cstdint>

#include "sdk/src/common/status.h"

namespace m4d {

// Limits that keep a mistyped option from asking for terabytes.
constexpr int kMaxSyntheticCameras = 256;
constexpr int kMaxSyntheticSide = 4096;
constexpr int kMaxSyntheticFrames = 10000;
constexpr int kMaxSyntheticPoints = 10000000;

// The flaws of a real capture, all off by default (the clean scene). Random draws depend on
// SyntheticSceneOptions::seed only, so the same options give the same images.
struct CaptureRealism {
  // Sensor noise: Gaussian, standard deviation in 8-bit levels, drawn anew for every sample
  // of every view. 0: none.
  float noise_sigma = 0.0f;
  // Images go through JPEG at this quality (1..100): written as .jpg, and the in-memory
  // capture decodes the same bytes. 0: lossless PNG.
  int jpeg_quality = 0;
  // Per-camera exposure: each camera's gain is 1 + exposure_spread * u, u uniform in [-1, 1],
  // fixed for the camera. 0: all cameras alike.
  float exposure_spread = 0.0f;
  // Per-camera white balance: each channel's gain is 1 + white_balance_spread * u on top of
  // the exposure. 0: neutral.
  float white_balance_spread = 0.0f;
  // Lens distortion, OpenCV's radial-tangential model on normalised coordinates, written to
  // transforms.json and applied to the images. All 0: pinhole.
  float k1 = 0.0f, k2 = 0.0f, p1 = 0.0f, p2 = 0.0f;
  // A left-handed calibration: the world's x axis is negated in what is written (camera
  // poses with determinant -1, the point cloud); the images are the same. false: right-handed.
  bool left_handed = false;
  // Cameras on one wide arc (sparse_rig_arc_degrees across, at head height) instead of the
  // front-facing rows; camera 0, held out, is still the one nearest the middle. false: rows.
  bool sparse_rig = false;
  float sparse_rig_arc_degrees = 90.0f;
  // A potted plant in a back corner whose leaves sway by this much at their top, in metres.
  // 0: no plant.
  float background_sway = 0.0f;
  // Every frame all lights' strength is scaled by 1 + light_flicker * u, u uniform in
  // [-1, 1] drawn per frame. 0: steady.
  float light_flicker = 0.0f;
};

struct SyntheticSceneOptions {
  int cameras = 16;  // on a front-facing rig; camera 0 (held out) sits inside it
  int width = 320;
  int height = 240;
  int frames = 20;
  float horizontal_fov_degrees = 60.0f;
  // The frame at which the emergent object appears; -1: frames / 2.
  int emergent_frame = -1;
  // The frame at which the lamp changes colour and strength (a background change for an
  // adaptive GOP to react to); -1: never.
  int background_change_frame = -1;
  uint32_t seed = 1;   // furniture layout, book colours, texture noise, point sampling
  int points = 50000;  // initial point cloud size
  // Anti-aliasing: render at `supersample` times the size, then average blocks. Multisampling
  // on top costs several times more with a software rasterizer, for little.
  int supersample = 2;
  int msaa_samples = 1;  // multisamples of the supersampled render (1: none)
  CaptureRealism realism;

  // The default scene with every flaw of CaptureRealism on at a plausible strength and a
  // sparse rig of 4 cameras (values in README.md here).
  static SyntheticSceneOptions Realistic();
};

// M4D_ERR_INVALID_ARG naming the first bad option (counts below 1 or above the limits,
// event frames outside [0, frames), a field of view outside (10, 150) degrees, a realism
// strength outside its range, a lens distortion that folds the image over).
Status ValidateSyntheticSceneOptions(const SyntheticSceneOptions& options);

// emergent_frame with the default resolved.
int EmergentFrame(const SyntheticSceneOptions& options);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SYNTHETIC_SCENE_OPTIONS_H_
