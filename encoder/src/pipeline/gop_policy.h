// GopPolicy: where the encoder's GOPs start and which kind each one is. A GOP ends before a
// frame either whatever the frame holds (an imposed start, the fixed or the maximum length) or
// on what the coded frame measured (the adaptive rule); a GOP that starts soon after the last
// random-access keyframe keeps its static set, so that only the dynamic layer is re-sent.
#ifndef M4D_ENCODER_PIPELINE_GOP_POLICY_H_
#define M4D_ENCODER_PIPELINE_GOP_POLICY_H_

#include <cstdint>

#include "encoder/src/pipeline/encoder_options.h"

namespace m4d {

class GopPolicy {
 public:
  explicit GopPolicy(const EncoderOptions& options);

  // Whether the GOP that started at `start` ends before `frame`, before anything of the frame is
  // measured: `frame` is one of GopOptions::starts, or the GOP reached its fixed or maximum
  // length (only without imposed starts).
  bool EndsBefore(int start, int frame) const;
  // Whether an inter frame `length` frames after its keyframe starts a new GOP instead of being
  // coded (the adaptive rule, not with imposed starts nor before GopOptions::min_length): its
  // r_t (`ratio`) exceeds tau_GOP, or its training PSNR fell more than
  // GopOptions::max_psnr_drop below `reference` (the keyframe's, less its noise gap).
  bool Restarts(int length, double ratio, double psnr, double reference) const;
  // Whether any GOP but the first may start among `frames` frames from `first`: one of
  // GopOptions::starts lies among them, a fixed or maximum length ends inside them, or the
  // adaptive rule may end a GOP. Its keyframe is then trained, so the automatic keyframe
  // choices are needed even when the first keyframe is given.
  bool MayRestart(int first, int frames) const;
  // Whether a GOP starting at `frame` keeps the static set (GopOptions::random_access_seconds).
  bool Dependent(int frame) const;
  // A GOP starts at `frame`; a random-access one restarts the interval Dependent measures.
  void Started(int frame, bool dependent);

 private:
  GopOptions gop_;
  uint32_t fps_num_, fps_den_;
  bool independent_frames_;
  int random_access_start_ = 0;  // first frame of the last random-access GOP
};

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_GOP_POLICY_H_
