// --prune-share and --prune-max-loss, shared by m4d train, encode and rd: the share importance
// pruning removes from a keyframe, given or chosen per capture (prune_share_selection.h).
#ifndef M4D_TOOLS_M4D_PRUNE_SHARE_ARGUMENTS_H_
#define M4D_TOOLS_M4D_PRUNE_SHARE_ARGUMENTS_H_

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/status.h"
#include "dataset/capture.h"
#include "train/keyframe_trainer.h"
#include "train/prune_share_selection.h"

namespace m4d {

struct PruneShareArguments {
  double share = -1;  // < 0: chosen per capture ("auto")
  double max_loss_per_halving_db = PruneShareSelectionOptions().max_loss_per_halving_db;
  bool Automatic() const { return share < 0; }
};

// Adds both options to a command (`what` says which trainings the share applies to).
void AddPruneShareOptions(CLI::App* command, const char* what, PruneShareArguments* args);

// The share for a keyframe of `frame` trained with `options`: the given one, or the selection's
// (with progress on stderr and its table on stdout; `choice` holds its trials).
Status ResolvePruneShare(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                         const PruneShareArguments& args, float* share, PruneShareChoice* choice);

// What a report records of the selection (null when the share was given).
nlohmann::json PruneShareJson(const PruneShareArguments& args, const PruneShareChoice& choice);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_PRUNE_SHARE_ARGUMENTS_H_
