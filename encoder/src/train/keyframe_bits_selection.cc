#include "encoder/src/train/keyframe_bits_selection.h"

#include "encoder/src/train/view_evaluation.h"
#include "sdk/src/common/byte_writer.h"

namespace m4d {
namespace {

// The model coded at `quantization`: its bytes, and the held-out views' PSNR of what a decoder
// reconstructs.
Status TryCandidate(const HeldOutModel& held_out, const GaussianSet& set,
                    const KeyframeBitsCandidate& candidate, RenderContext* context,
                    KeyframeBitsTrial* trial) {
  trial->name = candidate.name;
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  M4D_RETURN_IF_ERROR(WriteGaussianSet(set, candidate.quantization, &writer));
  trial->bytes = bytes.size();
  GaussianSet decoded;
  M4D_RETURN_IF_ERROR(ReconstructGaussianSet(set, candidate.quantization, &decoded));
  GaussianModel model;
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(decoded, held_out.model.sh_degree, &model));
  trial->gaussians = model.size();
  EvaluationResult quality;
  M4D_RETURN_IF_ERROR(
      EvaluateViews(model, held_out.validation, held_out.settings, context, &quality));
  trial->psnr = quality.mean_psnr;
  return Status::Ok();
}

}  // namespace

Status SelectKeyframeBits(const HeldOutModel& held_out,
                          const std::vector<KeyframeBitsCandidate>& candidates,
                          double max_loss_per_halving_db, KeyframeBitsChoice* choice) {
  *choice = KeyframeBitsChoice();
  if (candidates.empty() || held_out.validation.size() == 0) return Status::Ok();
  GaussianSet set;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(held_out.model, held_out.model.sh_degree, &set));
  RenderContext context;
  for (const KeyframeBitsCandidate& candidate : candidates) {
    choice->trials.emplace_back();
    M4D_RETURN_IF_ERROR(TryCandidate(held_out, set, candidate, &context, &choice->trials.back()));
  }
  const KeyframeBitsTrial& reference = choice->trials.front();
  for (size_t c = 1; c < choice->trials.size(); ++c) {
    const KeyframeBitsTrial& trial = choice->trials[c];
    const KeyframeBitsTrial& best = choice->trials[static_cast<size_t>(choice->chosen)];
    const bool within =
        reference.psnr - trial.psnr <= AllowedLoss(reference, trial, max_loss_per_halving_db);
    if (within && trial.bytes < best.bytes) choice->chosen = static_cast<int>(c);
  }
  return Status::Ok();
}

}  // namespace m4d
