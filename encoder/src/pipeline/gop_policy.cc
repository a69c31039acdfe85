#include "encoder/src/pipeline/gop_policy.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace m4d {

GopPolicy::GopPolicy(const EncoderOptions& options)
    : gop_(options.gop),
      fps_num_(options.fps_num),
      fps_den_(options.fps_den),
      independent_frames_(options.independent_frames) {}

bool GopPolicy::EndsBefore(int start, int frame) const {
  const int length = frame - start;  // frames in the GOP so far
  const std::vector<int>& starts = gop_.starts;
  const bool fixed = !gop_.adaptive && gop_.fixed_length > 0;
  const bool imposed = std::binary_search(starts.begin(), starts.end(), frame);
  return imposed ||
         (starts.empty() && (length >= gop_.max_length || (fixed && length >= gop_.fixed_length)));
}

bool GopPolicy::Restarts(int length, double ratio, double psnr, double reference) const {
  const double drop = reference - psnr;
  return gop_.adaptive && gop_.starts.empty() && length >= gop_.min_length &&
         (ratio > gop_.threshold || (gop_.max_psnr_drop > 0 && drop > gop_.max_psnr_drop));
}

bool GopPolicy::MayRestart(int first, int frames) const {
  if (independent_frames_) return frames > 1;
  const std::vector<int>& starts = gop_.starts;
  if (!starts.empty()) {
    return std::upper_bound(starts.begin(), starts.end(), first) !=
           std::lower_bound(starts.begin(), starts.end(), first + frames);
  }
  const bool fixed = !gop_.adaptive && gop_.fixed_length > 0;
  return (gop_.adaptive && frames > gop_.min_length) || frames > gop_.max_length ||
         (fixed && frames > gop_.fixed_length);
}

bool GopPolicy::Dependent(int frame) const {
  const double seconds = gop_.random_access_seconds;
  if (seconds <= 0.0 || independent_frames_) return false;
  const double frames = seconds * fps_num_ / fps_den_;
  return frame - random_access_start_ < static_cast<int>(std::lround(std::max(1.0, frames)));
}

void GopPolicy::Started(int frame, bool dependent) {
  if (!dependent) random_access_start_ = frame;
}

}  // namespace m4d
