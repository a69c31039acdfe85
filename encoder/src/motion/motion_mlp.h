// Training of the shared motion MLP (paper section 3.3): the network of bitstream-spec 6.3
// step 3 (linear layers, LeakyReLU 0.01 between them, 7 outputs) evaluated for a batch of
// Gaussians at once, with its backward pass. Training arithmetic is free (Eigen, FMA); the
// decoder's normative evaluation runs on what the stream carries.
#ifndef M4D_ENCODER_MOTION_MOTION_MLP_H_
#define M4D_ENCODER_MOTION_MOTION_MLP_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sdk/src/layers/mlp_weights.h"

namespace m4d {

// Column i of every matrix is Gaussian i.
struct MlpBatch {
  std::vector<Eigen::MatrixXf> outputs;  // per layer, after its activation (the last: raw)
};

// Weights of the configured shapes: layer 0 He-uniform, later layers uniform in
// +-init_scale / sqrt(inputs); biases zero, so zero features give exactly zero motion.
MlpWeights InitialMotionMlp(int feature_count, const MlpConfig& config, float last_layer_scale,
                            uint32_t seed);

// features: F x N. Fills batch->outputs; the motion outputs are batch->outputs.back() (7 x N).
void MlpForward(const MlpWeights& mlp, const Eigen::MatrixXf& features, MlpBatch* batch);

// Given dL/d(outputs) (7 x N), adds dL/dweights and dL/dbiases into *grad (same shapes as mlp;
// null for a frozen MLP) and writes dL/dfeatures (F x N) into *d_features (may be null).
void MlpBackward(const MlpWeights& mlp, const Eigen::MatrixXf& features, const MlpBatch& batch,
                 const Eigen::MatrixXf& d_outputs, MlpWeights* grad, Eigen::MatrixXf* d_features);

// Zeroed weights of mlp's shapes.
MlpWeights ZeroLike(const MlpWeights& mlp);

// Shifts the last layer's biases so that zero features give zero motion, as they do at
// initialisation. Without it the biases learn the first inter frame's mean motion, and every
// later frame of the GOP moves each dynamic Gaussian by it unless the grid spends bits to
// cancel it (realistic scene: 4.6 mm and about 1 degree per frame).
void ZeroMotionAtZeroFeatures(MlpWeights* mlp);

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_MOTION_MLP_H_
