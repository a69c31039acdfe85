// m4d encode --renditions: several rate points coded as renditions from one first keyframe
// trained once, with aligned GOPs, each stream with its JSON report, and the manifest listing
// them (rendition_manifest.h).
#ifndef M4D_ENCODER_RUN_RENDITION_ENCODE_H_
#define M4D_ENCODER_RUN_RENDITION_ENCODE_H_

#include "encoder/src/run/encode_run.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The renditions' names checked and their outputs writable, before any work. Outputs that
// exist are refused unless `force`.
Status CheckRenditionOutputs(const EncodeArguments& args, bool force);

// Encodes args.renditions: the first keyframe trained once (or read from args.keyframe_ply),
// then each rendition's sequence from it; the first rendition's GOP starts are imposed on the
// others (so random-access points are aligned too). Writes every stream with its JSON report,
// then the manifest. Outputs that exist are refused unless `force`.
Status RunRenditionEncode(const EncodeArguments& args, bool force);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_RENDITION_ENCODE_H_
