#include "encoder/src/run/keyframe_bits_choice.h"

#include <cstdio>

#include "encoder/src/pipeline/rate_points.h"

namespace m4d {
namespace {

void PrintChoice(const std::vector<KeyframeBitsCandidate>& candidates,
                 const KeyframeBitsChoice& choice, double bound) {
  std::printf("keyframe bits selection      the prune share's branch on its held-out views\n");
  std::printf("  %-4s %-32s %11s  %9s  %8s  %8s\n", "bits", "depths", "coded", "held out", "loss",
              "allowed");
  const KeyframeBitsTrial& reference = choice.trials.front();
  for (size_t c = 0; c < choice.trials.size(); ++c) {
    const KeyframeBitsTrial& t = choice.trials[c];
    std::printf("  %-4s %-32s %8.1f KB  %6.2f dB", t.name.c_str(),
                QuantizationName(candidates[c].quantization).c_str(), t.bytes / 1000.0, t.psnr);
    if (c > 0) {
      std::printf("  %+5.2f dB  %5.2f dB", t.psnr - reference.psnr,
                  AllowedLoss(reference, t, bound));
    }
    std::printf("%s\n", static_cast<int>(c) == choice.chosen ? "  chosen" : "");
  }
}

}  // namespace

std::vector<KeyframeBitsCandidate> OfferedKeyframeBits(const std::string& rate_point,
                                                       bool bits_given) {
  if (bits_given) return {};
  return KeyframeBitsCandidates(rate_point);
}

Status ChooseKeyframeBits(const std::vector<KeyframeBitsCandidate>& offered, double bound,
                          const HeldOutModel& branch, KeyframeBitsChoice* choice) {
  M4D_RETURN_IF_ERROR(SelectKeyframeBits(branch, offered, bound, choice));
  if (!choice->trials.empty()) PrintChoice(offered, *choice, bound);
  return Status::Ok();
}

nlohmann::json KeyframeBitsJson(const std::vector<KeyframeBitsCandidate>& offered, double bound,
                                const KeyframeBitsChoice& choice) {
  if (choice.trials.empty()) return nullptr;
  const std::vector<KeyframeBitsCandidate>& candidates = offered;
  nlohmann::json trials = nlohmann::json::array();
  for (size_t c = 0; c < choice.trials.size(); ++c) {
    const KeyframeBitsTrial& t = choice.trials[c];
    trials.push_back({{"name", t.name},
                      {"bits", QuantizationName(candidates[c].quantization)},
                      {"bytes", t.bytes},
                      {"psnr", t.psnr}});
  }
  return {{"max_loss_per_halving_db", bound},
          {"trials", trials},
          {"chosen", choice.trials[static_cast<size_t>(choice.chosen)].name}};
}

}  // namespace m4d
