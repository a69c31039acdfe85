// MotionField: the differentiable motion of one frame (paper section 3.3): grid features at
// each dynamic Gaussian (trilinear, MotionStencil), the shared MLP, the rigid update. Grid
// values are in quantization steps (the integers the stream carries are their rounding);
// the simulated quantization noise of training is added by the caller.
#ifndef M4D_ENCODER_MOTION_MOTION_FIELD_H_
#define M4D_ENCODER_MOTION_MOTION_FIELD_H_

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "encoder/src/motion/motion_mlp.h"
#include "encoder/src/motion/motion_stencil.h"
#include "sdk/src/layers/mlp_weights.h"

namespace m4d {

// The trainable values of one frame's motion.
struct MotionParameters {
  // Per level: active voxels (stencil order) x channels, in quantization steps.
  std::vector<float> grid[kMaxGridLevels];
  MlpWeights mlp;
};

// Zero grid values for every active voxel of the stencil.
void ZeroGrid(const GridConfig& config, const MotionStencil& stencil, MotionParameters* params);

class MotionField {
 public:
  // Moves the Gaussians of the stencil: positions (3 each) and rotations (4 each, w x y z) to
  // moved_positions and moved_rotations (all arrays of stencil.gaussian_count Gaussians).
  // Gaussians outside the box are copied unchanged. Keeps what Backward needs.
  void Forward(const GridConfig& config, const float* steps, const MotionStencil& stencil,
               const MotionParameters& params, const float* positions, const float* rotations,
               float* moved_positions, float* moved_rotations);

  // Given dL/d(moved positions) and dL/d(moved rotations) of the last Forward, adds
  // dL/d(grid values), and with `mlp_gradient` dL/d(MLP), into *grad (shaped like the
  // parameters). A GOP's later frames keep its MLP: its gradient was a third of this pass.
  void Backward(const float* d_positions, const float* d_rotations, bool mlp_gradient,
                MotionParameters* grad);

  // The 7 MLP outputs of each moved Gaussian of the last Forward (translation, quaternion
  // increment), 7 x (moved count), and which Gaussian each column is.
  const Eigen::MatrixXf& outputs() const { return batch_.outputs.back(); }
  const std::vector<uint32_t>& moved() const { return moved_; }
  const MlpBatch& mlp_batch() const { return batch_; }

 private:
  const GridConfig* config_ = nullptr;
  const float* steps_ = nullptr;
  const MotionStencil* stencil_ = nullptr;
  const MotionParameters* params_ = nullptr;
  const float* rotations_ = nullptr;
  std::vector<uint32_t> moved_;  // Gaussians inside the box
  Eigen::MatrixXf features_;     // F x moved
  MlpBatch batch_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_MOTION_FIELD_H_
