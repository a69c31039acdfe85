// The keyframe bits `m4d encode` and `m4d train` train and code keyframes with: the rate
// point's, or those the keyframe bits selection takes on the prune share's held-out views
// (keyframe_bits_selection.h). Bits given on the command line are kept as given.
#ifndef M4D_ENCODER_RUN_KEYFRAME_BITS_CHOICE_H_
#define M4D_ENCODER_RUN_KEYFRAME_BITS_CHOICE_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "encoder/src/train/keyframe_bits_selection.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The candidates offered at `rate_point`: its own and the coarser points' keyframe
// quantizations, or none when `bits_given` (the command line fixed them).
std::vector<KeyframeBitsCandidate> OfferedKeyframeBits(const std::string& rate_point,
                                                       bool bits_given);

// Runs the selection on `branch` with the bound per halving (its table on stdout); chooses 0
// when nothing is offered.
Status ChooseKeyframeBits(const std::vector<KeyframeBitsCandidate>& offered, double bound,
                          const HeldOutModel& branch, KeyframeBitsChoice* choice);

// What a report records of the selection (null when it made no trial).
nlohmann::json KeyframeBitsJson(const std::vector<KeyframeBitsCandidate>& offered, double bound,
                                const KeyframeBitsChoice& choice);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_KEYFRAME_BITS_CHOICE_H_
