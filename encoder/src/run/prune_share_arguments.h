// --start-share, --prune-share and --prune-max-loss, shared by m4d train, encode and rd: the
// share of the photo-consistent sweep a keyframe without points starts from
// (start_size_selection.h) and the share importance pruning removes from it
// (prune_share_selection.h), each given or chosen per capture. They are chosen together: the
// chosen start's trunk is the prune share's.
#ifndef M4D_ENCODER_RUN_PRUNE_SHARE_ARGUMENTS_H_
#define M4D_ENCODER_RUN_PRUNE_SHARE_ARGUMENTS_H_

#include <nlohmann/json.hpp>

#include "encoder/src/capture/capture.h"
#include "encoder/src/train/keyframe_bits_selection.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/prune_share_selection.h"
#include "encoder/src/train/start_size_selection.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct PruneShareArguments {
  double share = -1;        // < 0: chosen per capture ("auto")
  double sweep_share = -1;  // < 0: chosen per capture ("auto")
  double max_loss_per_halving_db = PruneShareSelectionOptions().max_loss_per_halving_db;
  // The keyframe bits' own bound on the same views (keyframe_bits_selection.h).
  double bits_max_loss_per_halving_db = kKeyframeBitsMaxLossPerHalvingDb;
  bool Automatic() const { return share < 0; }
  bool StartAutomatic() const { return sweep_share < 0; }
};

// What the selections chose and tried.
struct KeyframeShareChoice {
  StartSizeChoice start;
  PruneShareChoice prune;
};

// The sweep share and the prune share for a keyframe of `frame` trained with `options` (whose
// sweep_share and importance_prune_share are replaced): the given ones, or the selections'
// (with progress on stderr and their tables on stdout; `choice` holds their trials).
Status ResolveKeyframeShares(const Capture& capture, int frame, const PruneShareArguments& args,
                             KeyframeTrainingOptions* options, KeyframeShareChoice* choice);

// What a report records of the prune share's selection (null when the share was given).
nlohmann::json PruneShareJson(const PruneShareArguments& args, const PruneShareChoice& choice);

// What a report records of the start size's selection (null when the share was given).
nlohmann::json StartSizeJson(const PruneShareArguments& args, const StartSizeChoice& choice);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_PRUNE_SHARE_ARGUMENTS_H_
