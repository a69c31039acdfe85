// A training run (`m4d train`): one frame's 3DGS model trained with the keyframe stage, its
// held-out quality and speed reported, optionally its coded quality, a quality-over-time
// curve, a render beside the ground truth and the model as a 3DGS PLY.
#ifndef M4D_ENCODER_RUN_TRAIN_RUN_H_
#define M4D_ENCODER_RUN_TRAIN_RUN_H_

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/run/capture_arguments.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/run/rate_weight_arguments.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct TrainArguments {
  CaptureArguments capture;
  int frame = 0;
  int iterations = 0;  // 0: the schedule's
  bool reference_schedule = false;
  int sh_degree = 3;
  int threads = 0;
  uint64_t seed = 1;
  bool random_init = false;
  std::string strategy;             // empty: the schedule's
  int max_gaussians = 0;            // 0: the schedule's
  int background_shell = -1;        // points (< 0: the schedule's)
  double gaussians_per_pixel = -1;  // < 0: the schedule's
  double smoothing_filter = -1;     // < 0: the schedule's
  int coarse_levels = -1;           // < 0: the schedule's
  double coarse_until = -1;         // share of the run (< 0: the schedule's)
  PruneShareArguments prune;
  double prune_below = -1;         // < 0: the schedule's
  int quantization_aware = -1;     // iterations (< 0: the schedule's)
  RateWeightArguments rate;        // lambda_k of the keyframe's rate term
  std::string rate_point = "r4";   // the keyframe bits the model is trained and coded for
  std::vector<int> keyframe_bits;  // 6 bit depths (empty: the rate point's)
  // Written only when asked for: a training run leaves nothing in the current folder unasked.
  std::string ply;     // the model (empty: none)
  std::string render;  // the held-out view beside its ground truth (empty: none)
  std::string curve;   // CSV of held-out quality over time (empty: none)
  bool force = false;  // replace those files when they exist
  std::vector<double> curve_minutes = {1, 2, 5, 10, 15, 20};
};

// Trains and reports (tables on stdout, progress on stderr); writes what the arguments ask for.
Status RunTrain(const TrainArguments& args);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_TRAIN_RUN_H_
