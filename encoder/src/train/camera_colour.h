// CameraColour: a colour gain and offset per training view, learnt with the Gaussians
// (render' = exp(g) * render + o per channel), as Dynamic 3D Gaussians learns them: the
// cameras of a rig differ in exposure and white balance, and without these terms the Gaussians
// absorb the differences as view-dependent colour and fog that held-out cameras see. Only
// training applies them; the model renders in the cameras' common colour.
//
// Measured on Panoptic basketball, the realistic synthetic scene and the default scene: the
// held-out cameras gain on all three, most where the cameras differ most
// (docs/results/2026-11-30-readme-notebook.md, "Cameras differ in colour").
#ifndef M4D_ENCODER_TRAIN_CAMERA_COLOUR_H_
#define M4D_ENCODER_TRAIN_CAMERA_COLOUR_H_

#include <vector>

#include "encoder/src/image/image.h"

namespace m4d {

class CameraColour {
 public:
  // Identity terms for `views` views, stepped by Adam at `learning_rate` (0: off).
  void Init(int views, float learning_rate);
  bool enabled() const { return learning_rate_ > 0; }

  // render <- exp(g) * render + o, with the view's terms.
  void Apply(int view, Image* render) const;
  // Given the loss gradient with respect to the corrected render (which Apply wrote), turns
  // it into the gradient with respect to the raw render and steps the view's terms.
  void Backward(int view, const Image& corrected, Image* gradient);

  // The view's terms: gains' logarithms then offsets, per channel.
  const float* terms(int view) const { return &state_[kStride * static_cast<size_t>(view)]; }

 private:
  // What all views share, a gain and offset the Gaussians' colours could carry as well, is taken
  // out after every step, so that the model stays in the cameras' mean colour: left free, the
  // shared part drifted and the default scene's held-out camera lost much of its quality
  // (docs/results/2026-11-30-comment-measurements.md).
  void RemoveCommonPart();

  static constexpr size_t kStride = 18;  // 6 terms, then Adam's first and second moments
  std::vector<float> state_;
  float learning_rate_ = 0;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_CAMERA_COLOUR_H_
