// Steps that `m4d encode` shares between one stream (encode_command.cc) and renditions
// (rendition_encode.cc): the frame rate and up axis the capture decides, the automatic keyframe
// settings, a given first keyframe, and the progress on stderr with the frame table on stdout.
#ifndef M4D_ENCODER_RUN_ENCODE_STEPS_H_
#define M4D_ENCODER_RUN_ENCODE_STEPS_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/run/encode_run.h"
#include "encoder/src/run/keyframe_bits_choice.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/run/rate_weight_arguments.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/progress_bar.h"
#include "sdk/src/common/status.h"

namespace m4d {

// --fps, else the capture's recorded rate, else kDefaultFps (said on stderr).
Status ChooseFrameRate(const std::string& fps, const Capture& capture, EncoderOptions* options);

// --up, or the capture cameras' up with "auto" (said on stdout: players and exporters turn
// the content by it).
Status ChooseUpAxis(const std::string& up, const Capture& capture, EncoderOptions* options);

// What the automatic keyframe settings chose (when this encode trains a keyframe: the first,
// unless given, a later chunk's, or a GOP's retrained one).
struct AutomaticChoices {
  bool trains_keyframe = false;
  bool from_scratch = false;  // a keyframe is trained from scratch: the start share is chosen
  StartSizeChoice start;
  PruneShareChoice prune;
  KeyframeBitsChoice bits;
  RateWeightChoice rate;
};

// The keyframe bits the encode's arguments offer (keyframe_bits_choice.h).
std::vector<KeyframeBitsCandidate> EncodeKeyframeBits(const EncodeArguments& args);

// The automatic start share, prune share, keyframe bits (keyframe_bits_choice.h) and keyframe
// rate weight, chosen by training on the first frame when any keyframe is trained: with a given
// first keyframe, chunks after the first train theirs and GOPs after the first retrain theirs.
// Under MPI rank 0 chooses for every rank.
Status ResolveAutomaticChoices(const EncodeArguments& args, const Capture& capture,
                               EncoderOptions* options, AutomaticChoices* choices);

// The first keyframe of args.keyframe_ply at the stream's SH degree (an error when below it).
Status ReadFirstKeyframe(const EncodeArguments& args, int sh_degree, GaussianModel* model);

// Progress on stderr and the frame table on stdout; under MPI each rank's lines are prefixed
// with it, and keyframe training reports every quarter instead of drawing a bar.
struct EncodeProgress {
  ProgressBar bar;
  bool header = true;
  int last_quarter = -1;

  EncoderCallbacks Callbacks();
};

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_ENCODE_STEPS_H_
