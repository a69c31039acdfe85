// The synthetic scene's sensor: per-camera exposure and white balance, and per-view Gaussian
// noise (CaptureRealism), applied to a rendered view before it is quantised to 8 bits. Every
// draw is a hash of (seed, camera, frame, sample), so views can be made in any order.
#ifndef M4D_ENCODER_SYNTHETIC_SENSOR_EFFECTS_H_
#define M4D_ENCODER_SYNTHETIC_SENSOR_EFFECTS_H_

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "encoder/src/synthetic/synthetic_scene_options.h"

namespace m4d {

// Exposure times white balance of `camera`: one gain per RGB channel, 1 when both are off.
glm::vec3 CameraColourGain(const SyntheticSceneOptions& options, int camera);

// Whether the sensor changes pixels at all (gains or noise).
bool HasSensorEffects(const CaptureRealism& realism);

// levels: the view's RGB samples in 8-bit levels (0..255, fractions allowed). Scales them by
// the camera's gains, adds the view's noise and rounds them into *rgb, clamped to 0..255.
void ApplySensorEffects(const SyntheticSceneOptions& options, int frame, int camera,
                        const std::vector<float>& levels, std::vector<uint8_t>* rgb);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SENSOR_EFFECTS_H_
