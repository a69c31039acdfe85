#include "train/progress_bar.h"

#include <algorithm>

namespace m4d {

std::string FormatProgress(const TrainingProgress& p) {
  constexpr int kBarWidth = 20;
  const double done = p.iterations > 0 ? static_cast<double>(p.iteration) / p.iterations : 0.0;
  const int filled = std::clamp(static_cast<int>(done * kBarWidth), 0, kBarWidth);
  std::string line = "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '-') + "]";
  char text[160];
  std::snprintf(text, sizeof(text), " %6d/%d  loss %.4f  PSNR %.2f dB  %zu Gaussians  %.1f it/s",
                p.iteration, p.iterations, p.loss, p.psnr, p.gaussians, p.iterations_per_second);
  return line + text;
}

void ProgressBar::Update(const TrainingProgress& progress) {
  // Trailing spaces clear what a longer previous line left.
  std::fprintf(stream_, "\r%s   ", FormatProgress(progress).c_str());
  std::fflush(stream_);
  written_ = true;
}

void ProgressBar::Finish() {
  if (written_) std::fputc('\n', stream_);
  written_ = false;
}

}  // namespace m4d
