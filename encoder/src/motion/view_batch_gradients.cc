#include "encoder/src/motion/view_batch_gradients.h"

#include <algorithm>

#include "encoder/src/raster/splat_renderer.h"

namespace m4d {

struct ViewBatchGradients::Slot {
  RenderContext context;
  BackwardWorkspace workspace;
  FocusedLoss loss;
  Image rendered, loss_grad;
  std::vector<float> d_p, d_q, d_scales, d_logits, d_sh;
  const ProjectedSplats* static_projection = nullptr;
  const Image* static_render = nullptr;
  double loss_value = 0;
  Status status;

  explicit Slot(double ssim_weight) : loss(ssim_weight) {}
};

ViewBatchGradients::ViewBatchGradients(const TrainingViews& views, const RenderSettings& settings,
                                       double ssim_weight, FrozenLayerViews* static_views)
    : views_(views),
      settings_(settings),
      ssim_weight_(ssim_weight),
      static_views_(static_views),
      pool_(std::make_unique<ThreadPool>(settings.threads)) {
  settings_.focus_layer = 1;  // the static layer alone is the same in every step
  settings_.focus_margin = 0;
}

ViewBatchGradients::~ViewBatchGradients() = default;

Status ViewBatchGradients::RenderView(int view, const M4dGaussians layers[2], int threads,
                                      Slot* slot) {
  const Camera& camera = views_.cameras[view];
  RenderSettings settings = settings_;
  settings.threads = threads;
  M4D_RETURN_IF_ERROR(
      RenderForward(camera, layers, 2, settings, nullptr, slot->static_projection, &slot->context));
  slot->rendered.width = camera.width;
  slot->rendered.height = camera.height;
  slot->rendered.channels = 3;
  slot->rendered.pixels = slot->context.color;
  PhotometricLossValue value;
  M4D_RETURN_IF_ERROR(slot->loss.Evaluate(slot->rendered, views_.images[view], slot->context.focus,
                                          slot->static_render, &value, &slot->loss_grad));
  slot->loss_value = value.loss;
  const size_t n = layers[1].count;
  slot->d_p.resize(3 * n);
  slot->d_q.resize(4 * n);
  slot->d_scales.resize(3 * n);
  slot->d_logits.resize(n);
  slot->d_sh.resize(n * 3 * ShCoefficients(layers[1].sh_degree));
  LayerGradients layer_grads[2];  // the static layer stays frozen
  layer_grads[1] = {slot->d_p.data(), slot->d_scales.data(), slot->d_q.data(),
                    slot->d_logits.data(), slot->d_sh.data()};
  SplatGradients outputs;
  outputs.layers = layer_grads;
  outputs.layer_count = 2;
  return RenderBackward(slot->loss_grad.pixels.data(), nullptr, &slot->context, outputs,
                        &slot->workspace);
}

Status ViewBatchGradients::Compute(const M4dGaussians layers[2], const std::vector<int>& batch,
                                   bool with_dc, ViewBatchResult* result) {
  while (slots_.size() < batch.size()) slots_.push_back(std::make_unique<Slot>(ssim_weight_));
  for (size_t b = 0; b < batch.size(); ++b) {
    const int view = batch[b];
    M4D_RETURN_IF_ERROR(
        static_views_->Projection(view, views_.cameras[view], &slots_[b]->static_projection));
    M4D_RETURN_IF_ERROR(
        static_views_->Render(view, views_.cameras[view], &slots_[b]->static_render));
  }
  // One thread per view, or all of them on a single view's tiles.
  const int threads = batch.size() > 1 && pool_->size() > 1 ? 1 : settings_.threads;
  auto render = [&](size_t b, int) {
    slots_[b]->status = RenderView(batch[b], layers, threads, slots_[b].get());
  };
  if (batch.size() > 1) {
    pool_->Run(batch.size(), render);
  } else {
    render(0, 0);
  }
  const size_t n = layers[1].count;
  const size_t sh_stride = 3 * static_cast<size_t>(ShCoefficients(layers[1].sh_degree));
  result->positions.assign(3 * n, 0.0f);
  result->rotations.assign(4 * n, 0.0f);
  result->dc.assign(with_dc ? 3 * n : 0, 0.0f);
  result->losses.clear();
  // L_color is the mean over the step's views: their gradients are averaged.
  const float w = 1.0f / static_cast<float>(batch.size());
  for (size_t b = 0; b < batch.size(); ++b) {
    const Slot& slot = *slots_[b];
    M4D_RETURN_IF_ERROR(slot.status);
    for (size_t k = 0; k < 3 * n; ++k) result->positions[k] += w * slot.d_p[k];
    for (size_t k = 0; k < 4 * n; ++k) result->rotations[k] += w * slot.d_q[k];
    for (size_t k = 0; k < result->dc.size(); ++k) {
      result->dc[k] += w * slot.d_sh[(k / 3) * sh_stride + k % 3];
    }
    result->losses.push_back(slot.loss_value);
  }
  return Status::Ok();
}

}  // namespace m4d
