// SyntheticSceneOptions: what the built-in multi-view dynamic scene is made of (rig, image
// size, length, when things happen, seeds), and their validation.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_SYNTHETIC_SCENE_OPTIONS_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_SYNTHETIC_SCENE_OPTIONS_H_

#include <cstdint>

#include "common/status.h"

namespace m4d {

// Limits that keep a mistyped option from asking for terabytes.
constexpr int kMaxSyntheticCameras = 256;
constexpr int kMaxSyntheticSide = 4096;
constexpr int kMaxSyntheticFrames = 10000;
constexpr int kMaxSyntheticPoints = 10000000;

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
};

// M4D_ERR_INVALID_ARG naming the first bad option (counts below 1 or above the limits,
// event frames outside [0, frames), a field of view outside (10, 150) degrees).
Status ValidateSyntheticSceneOptions(const SyntheticSceneOptions& options);

// emergent_frame with the default resolved.
int EmergentFrame(const SyntheticSceneOptions& options);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_SYNTHETIC_SCENE_OPTIONS_H_
