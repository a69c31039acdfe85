#include "encoder/src/train/progress_bar.h"

#include <unistd.h>

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

bool IsTerminal(std::FILE* stream) { return isatty(fileno(stream)) == 1; }

void ShowStatus(std::FILE* stream, const std::string& text) {
  if (IsTerminal(stream)) {
    std::fprintf(stream, "\r%-40s", text.c_str());
  } else {
    std::fprintf(stream, "%s\n", text.c_str());
  }
  std::fflush(stream);
}

void ClearStatus(std::FILE* stream) {
  if (IsTerminal(stream)) std::fprintf(stream, "\r%40s\r", "");
}

ProgressBar::ProgressBar(std::FILE* stream) : stream_(stream), terminal_(IsTerminal(stream)) {}

void ProgressBar::Update(const TrainingProgress& progress, const std::string& label) {
  const std::string prefix = label.empty() ? "" : label + " ";
  if (terminal_) {
    // Trailing spaces clear what a longer previous line left.
    std::fprintf(stream_, "\r%s%s   ", prefix.c_str(), FormatProgress(progress).c_str());
    written_ = true;
  } else {
    const int tenths = progress.iterations > 0 ? 10 * progress.iteration / progress.iterations : 10;
    if (progress.iteration < last_iteration_) logged_tenths_ = -1;  // a new run
    last_iteration_ = progress.iteration;
    if (tenths <= logged_tenths_) return;
    logged_tenths_ = tenths;
    std::fprintf(stream_, "%s%s\n", prefix.c_str(), FormatProgress(progress).c_str());
  }
  std::fflush(stream_);
}

void ProgressBar::Finish() {
  if (written_) std::fputc('\n', stream_);
  written_ = false;
  logged_tenths_ = -1;
  last_iteration_ = 0;
}

}  // namespace m4d
