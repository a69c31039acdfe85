#include "encoder/src/run/encode_steps.h"

#include <algorithm>
#include <cstdio>

#include "encoder/src/capture/up_axis_estimate.h"
#include "encoder/src/distributed/chunked_encode.h"
#include "encoder/src/distributed/mpi_ranks.h"
#include "encoder/src/pipeline/gop_policy.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/pipeline/sequence_report_output.h"
#include "encoder/src/pipeline/stage_options.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/stream/frame_rate.h"

namespace m4d {

Status ChooseFrameRate(const std::string& fps, const Capture& capture, EncoderOptions* options) {
  if (!fps.empty()) return ParseFrameRate(fps, &options->fps_num, &options->fps_den);
  if (capture.fps_num > 0) {
    options->fps_num = capture.fps_num;
    options->fps_den = capture.fps_den;
    return Status::Ok();
  }
  options->fps_num = kDefaultFps;
  options->fps_den = 1;
  std::fprintf(stderr, "%s records no frame rate: %u fps assumed (--fps to set it)\n",
               capture.layout.c_str(), kDefaultFps);
  return Status::Ok();
}

Status ChooseUpAxis(const std::string& up, const Capture& capture, EncoderOptions* options) {
  M4D_RETURN_IF_ERROR(ParseUpAxis(up, &options->up_axis));
  if (options->up_axis != kUpAxisAuto) return Status::Ok();
  options->up_axis = EstimateUpAxis(capture.cameras);
  std::printf("up axis %s (the cameras' mean up; --up to state another)\n",
              UpAxisName(options->up_axis).c_str());
  return Status::Ok();
}

namespace {

// Whether a keyframe is trained from scratch: the first unless given (a keyframe source's
// frames are given too), and with a given first keyframe each later chunk's.
bool TrainsFromScratch(const EncodeArguments& args, const Capture& capture,
                       const EncoderOptions& options) {
  if (args.keyframe_source) return false;
  if (args.keyframe_ply.empty()) return true;
  const bool chunked = args.chunk_frames > 0 || CurrentRanks().size > 1;
  return chunked && PlanCaptureChunks(capture, options, args.chunk_frames).size() > 1;
}

// Whether a later GOP of a given first keyframe may retrain its keyframe: retraining takes the
// automatic prune share, bits and rate weight (not the start share), so they are chosen too.
bool RetrainsGivenKeyframe(const EncodeArguments& args, const Capture& capture,
                           const EncoderOptions& options) {
  if (args.keyframe_source || args.keyframe_ply.empty()) return false;
  const int left = capture.frame_count - options.first_frame;
  const int frames = options.frame_count > 0 ? std::min(options.frame_count, left) : left;
  return GopPolicy(options).MayRestart(options.first_frame, frames);
}

void ApplyKeyframeBits(const EncodeArguments& args, int chosen, EncoderOptions* options) {
  if (chosen <= 0) return;
  if (!options->keyframe_trained_for) options->keyframe_trained_for = options->quantization;
  options->quantization = EncodeKeyframeBits(args)[static_cast<size_t>(chosen)].quantization;
}

}  // namespace

std::vector<KeyframeBitsCandidate> EncodeKeyframeBits(const EncodeArguments& args) {
  const bool given = !args.keyframe_bits.empty() || !args.keyframe_codebooks.empty();
  const std::string point =
      args.rate_point.empty() ? RatePointForLambda(args.lambda).name : args.rate_point;
  return OfferedKeyframeBits(point, given);
}

Status ResolveAutomaticChoices(const EncodeArguments& args, const Capture& capture,
                               EncoderOptions* options, AutomaticChoices* choices) {
  choices->from_scratch = TrainsFromScratch(args, capture, *options);
  choices->trains_keyframe =
      choices->from_scratch || RetrainsGivenKeyframe(args, capture, *options);
  PruneShareArguments prune = args.prune;
  if (!choices->from_scratch) prune.sweep_share = options->keyframe.sweep_share;  // unused
  Status status = Status::Ok();
  if (CurrentRanks().rank == 0 && choices->trains_keyframe && !choices->from_scratch &&
      (prune.Automatic() || args.keyframe_rate.automatic)) {
    std::printf(
        "%s is given, but later GOPs may retrain their keyframes: the automatic keyframe "
        "choices are made on frame %d (give --prune-share and --keyframe-rate-weight "
        "to skip them)\n",
        args.keyframe_ply.c_str(), options->first_frame);
  }
  if (CurrentRanks().rank == 0 && choices->trains_keyframe &&
      (prune.Automatic() || prune.StartAutomatic())) {
    KeyframeTrainingOptions first = FirstKeyframeTraining(*options);
    KeyframeShareChoice chosen;
    status = ResolveKeyframeShares(capture, options->first_frame, prune, &first, &chosen);
    options->keyframe.sweep_share = first.sweep_share;
    options->keyframe.importance_prune_share = first.importance_prune_share;
    choices->start = chosen.start;
    choices->prune = std::move(chosen.prune);
    if (status.ok()) {
      status = ChooseKeyframeBits(EncodeKeyframeBits(args), args.prune.bits_max_loss_per_halving_db,
                                  choices->prune.branch, &choices->bits);
    }
    choices->prune.branch = HeldOutModel();                  // not needed past here
    ApplyKeyframeBits(args, choices->bits.chosen, options);  // before the rate weight's branches
  }
  if (status.ok() && CurrentRanks().rank == 0 && choices->trains_keyframe &&
      args.keyframe_rate.automatic) {
    RateWeightArguments rate = args.keyframe_rate;
    rate.max_loss_per_halving_db = args.prune.max_loss_per_halving_db;
    status = ResolveRateWeight(capture, options->first_frame, FirstKeyframeTraining(*options), rate,
                               options->keyframe_rate_weight, &options->keyframe_rate_weight,
                               &choices->rate);
  }
  if (!AllRanksOk(status.ok()))
    return status.ok() ? Status(M4D_ERR_INVALID_ARG, "rank 0 failed") : status;
  double chosen[4] = {options->keyframe.importance_prune_share, options->keyframe_rate_weight,
                      options->keyframe.sweep_share, static_cast<double>(choices->bits.chosen)};
  BroadcastDoubles(chosen, 4);
  options->keyframe.importance_prune_share = static_cast<float>(chosen[0]);
  options->keyframe_rate_weight = chosen[1];
  options->keyframe.sweep_share = static_cast<float>(chosen[2]);
  ApplyKeyframeBits(args, static_cast<int>(chosen[3]), options);
  return Status::Ok();
}

Status ReadFirstKeyframe(const EncodeArguments& args, int sh_degree, GaussianModel* model) {
  GaussianSet set;
  M4D_RETURN_IF_ERROR(ReadGaussianPly(args.keyframe_ply, &set));
  if (set.sh_degree < sh_degree) {
    return Status(M4D_ERR_INVALID_ARG, args.keyframe_ply + ": SH degree " +
                                           std::to_string(set.sh_degree) + " below the stream's " +
                                           std::to_string(sh_degree));
  }
  return ModelFromGaussianSet(set, sh_degree, model);
}

EncoderCallbacks EncodeProgress::Callbacks() {
  EncoderCallbacks callbacks;
  const bool several = CurrentRanks().size > 1;
  callbacks.training = [this, several](const std::string& stage, int frame,
                                       const TrainingProgress& p) {
    if (p.iteration == 0) return;
    const std::string label = stage + " " + std::to_string(frame);
    if (several) {
      const int quarter = 4 * p.iteration / std::max(1, p.iterations);
      if (quarter != last_quarter) {
        std::fprintf(stderr, "%s%s: %d/%d iterations\n", RankPrefix().c_str(), label.c_str(),
                     p.iteration, p.iterations);
      }
      last_quarter = quarter == 4 ? -1 : quarter;
      return;
    }
    bar.Update(p, label);
    if (p.iteration == p.iterations) bar.Finish();
  };
  callbacks.stage = [several](const std::string& stage, int frame) {
    if (!several) ShowStatus(stderr, "  frame " + std::to_string(frame) + ": " + stage);
  };
  callbacks.frame_coded = [this, several](const FrameReport& f) {
    ClearStatus(stderr);
    if (several) std::fputs(RankPrefix().c_str(), stdout);
    PrintFrameLine(stdout, f, header && !several);
    header = false;
  };
  return callbacks;
}

}  // namespace m4d
