// An encode run: a dataset coded into an M4D stream by the reference encoder, with the
// arguments a command line gives (`m4d encode`, `rd`, `ablate`, `bench`), reporting bytes,
// quality and time per frame (table on stdout, JSON beside the stream).
#ifndef M4D_ENCODER_RUN_ENCODE_RUN_H_
#define M4D_ENCODER_RUN_ENCODE_RUN_H_

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/pipeline/frame_report.h"
#include "encoder/src/run/capture_arguments.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/run/rate_weight_arguments.h"
#include "encoder/src/train/gaussian_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct EncodeArguments {
  CaptureArguments capture;
  EncoderOptions encoder;
  std::string rate_point;           // r1..r5, or empty for lambda's nearest
  double lambda = 1e-4;             // lambda_2 when rate_point is empty (1e-4: r4)
  int keyframe_iterations = 0;      // 0: the options' schedule
  bool random_init = false;         // KeyframeTrainingOptions::random_initialisation
  std::string strategy;             // KeyframeTrainingOptions::strategy (empty: the schedule's)
  int max_gaussians = 0;            // cap of keyframe training and retraining (0: the schedule's)
  double gaussians_per_pixel = -1;  // that cap per training pixel (< 0: the schedule's)
  int quantization_aware =
      -1;  // quantization-aware iterations of keyframe training (< 0: the schedule's)
  PruneShareArguments prune;       // importance pruning of keyframe training and retraining
  double prune_below = -1;         // its minimum importance in pixels (< 0: the schedule's)
  std::string keyframe_ply;        // first keyframe read from here instead of trained
  double lambda3 = -1;             // compensation's lambda_3 (< 0: the default)
  double tau_g = -1;               // compensation's replication threshold (< 0: the rate point's)
  std::vector<int> keyframe_bits;  // 6 bit depths (empty: the rate point's)
  std::vector<int> compensation_bits;   // 6 bit depths (empty: the rate point's)
  std::vector<int> keyframe_codebooks;  // scale, color, sh codebook sizes (empty: the point's)
  RateWeightArguments keyframe_rate;    // lambda_k of keyframe training
  std::string output = "out/default.m4d";
  std::string json;         // default: output + ".json"
  std::string views;        // held-out view beside its render, one PNG per frame, here ('' to skip)
  std::string fps;          // frame rate override ("30", "29.97", "30000/1001"); '' : the capture's
  std::string up = "auto";  // the world's up axis the stream states (ParseUpAxis)
  int chunk_frames = 0;     // chunked encoding (chunked_encode.h): frames per chunk (0: none)
  std::string checkpoint_dir;  // its checkpoints (default: output + ".chunks")
  int max_chunks = 0;          // stop after coding this many chunks (0: no limit)
  // Rate points of renditions coded from one first keyframe with aligned GOPs, each written to
  // RenditionPath(output, point), with the manifest at ManifestPath(output) (empty: one stream).
  std::vector<std::string> renditions;
  // Frame -> model trained earlier, for --independent-frames (empty: train each frame).
  std::function<Status(int frame, GaussianModel* model)> keyframe_source;
};

// The encoder options the arguments ask for: the rate point's settings (rate_point, or the one
// nearest lambda), then the explicit overrides, the GOP choice and the keyframe schedule.
Status ResolveEncoderOptions(const EncodeArguments& args, EncoderOptions* options);

// The keyframe training schedule the arguments ask for: the options' schedule, or the short
// schedule scaled to keyframe_iterations, capped at max_gaussians and
// gaussians_per_pixel, pruned by a given prune share (an automatic one is chosen later, once
// the capture is open), quantization_aware iterations at the end.
KeyframeTrainingOptions KeyframeSchedule(const EncodeArguments& args);

// What decides the stream and its report (the options a report records, and what `--reuse`
// compares).
nlohmann::json EncodeOptionsJson(const EncodeArguments& args);

// Encodes with progress on stderr and the frame table on stdout; writes stream and JSON.
Status RunEncode(const EncodeArguments& args, SequenceReport* report);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_ENCODE_RUN_H_
