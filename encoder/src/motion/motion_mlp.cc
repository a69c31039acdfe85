#include "encoder/src/motion/motion_mlp.h"

#include <cmath>
#include <random>

namespace m4d {
namespace {

constexpr float kLeakySlope = 0.01f;  // bitstream-spec 6.3 step 3

using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Map<const RowMajor> Weights(const MlpLayer& layer) {
  return Eigen::Map<const RowMajor>(layer.weights.data(), layer.outputs, layer.inputs);
}

}  // namespace

MlpWeights InitialMotionMlp(int feature_count, const MlpConfig& config, float last_layer_scale,
                            uint32_t seed) {
  MlpWeights mlp;
  mlp.layers = MlpShapes(feature_count, config);
  std::mt19937 rng(seed);
  for (size_t j = 0; j < mlp.layers.size(); ++j) {
    MlpLayer& layer = mlp.layers[j];
    bool last = j + 1 == mlp.layers.size();
    float bound = (last ? last_layer_scale : std::sqrt(6.0f)) / std::sqrt(float(layer.inputs));
    std::uniform_real_distribution<float> uniform(-bound, bound);
    for (float& w : layer.weights) w = uniform(rng);
    std::fill(layer.biases.begin(), layer.biases.end(), 0.0f);
  }
  return mlp;
}

MlpWeights ZeroLike(const MlpWeights& mlp) {
  MlpWeights zero = mlp;
  for (MlpLayer& layer : zero.layers) {
    std::fill(layer.weights.begin(), layer.weights.end(), 0.0f);
    std::fill(layer.biases.begin(), layer.biases.end(), 0.0f);
  }
  return zero;
}

void ZeroMotionAtZeroFeatures(MlpWeights* mlp) {
  MlpBatch batch;
  MlpForward(*mlp, Eigen::MatrixXf::Zero(mlp->layers.front().inputs, 1), &batch);
  std::vector<float>& biases = mlp->layers.back().biases;
  for (size_t o = 0; o < biases.size(); ++o) biases[o] -= batch.outputs.back()(o, 0);
}

void MlpForward(const MlpWeights& mlp, const Eigen::MatrixXf& features, MlpBatch* batch) {
  const size_t layers = mlp.layers.size();
  batch->outputs.resize(layers);
  const Eigen::MatrixXf* x = &features;
  for (size_t j = 0; j < layers; ++j) {
    const MlpLayer& layer = mlp.layers[j];
    Eigen::Map<const Eigen::VectorXf> bias(layer.biases.data(), layer.outputs);
    Eigen::MatrixXf& y = batch->outputs[j];
    y.noalias() = Weights(layer) * *x;
    y.colwise() += bias;
    if (j + 1 < layers) y = y.cwiseMax(y * kLeakySlope);
    x = &y;
  }
}

void MlpBackward(const MlpWeights& mlp, const Eigen::MatrixXf& features, const MlpBatch& batch,
                 const Eigen::MatrixXf& d_outputs, MlpWeights* grad, Eigen::MatrixXf* d_features) {
  Eigen::MatrixXf d = d_outputs;  // dL/d(pre-activation) of the current layer
  for (size_t j = mlp.layers.size(); j-- > 0;) {
    const MlpLayer& layer = mlp.layers[j];
    const Eigen::MatrixXf& input = j == 0 ? features : batch.outputs[j - 1];
    if (grad) {
      MlpLayer& g = grad->layers[j];
      Eigen::Map<RowMajor>(g.weights.data(), layer.outputs, layer.inputs).noalias() +=
          d * input.transpose();
      // Into an aligned vector first: a row sum assigned straight into the (16-byte aligned)
      // vector sums its first rows in another order than the rest, by where the heap put it.
      const Eigen::VectorXf d_biases = d.rowwise().sum();
      Eigen::Map<Eigen::VectorXf>(g.biases.data(), layer.outputs) += d_biases;
    }
    if (j == 0 && d_features == nullptr) break;
    Eigen::MatrixXf d_input = Weights(layer).transpose() * d;
    if (j > 0) {
      // LeakyReLU: the output is positive exactly where the pre-activation is.
      d_input = (input.array() > 0.0f).select(d_input, d_input * kLeakySlope);
      d.swap(d_input);
    } else {
      d_features->swap(d_input);
    }
  }
}

}  // namespace m4d
