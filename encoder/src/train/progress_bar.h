// ProgressBar: one line on a terminal stream (stderr by default) that training rewrites in
// place: a bar, the iteration, the smoothed loss and PSNR, the Gaussian count and the speed.
#ifndef M4D_ENCODER_TRAIN_PROGRESS_BAR_H_
#define M4D_ENCODER_TRAIN_PROGRESS_BAR_H_

#include <cstddef>
#include <cstdio>
#include <string>

namespace m4d {

struct TrainingProgress {
  int iteration = 0;   // iterations done
  int iterations = 0;  // of the run
  double loss = 0;     // exponential moving average of the training loss
  double psnr = 0;     // exponential moving average of the training views' PSNR (dB)
  size_t gaussians = 0;
  double iterations_per_second = 0;
};

// The line without carriage return or newline, e.g.
// "[#####---------------]  1200/5000  loss 0.0312  PSNR 28.41 dB  123456 Gaussians  9.8 it/s".
std::string FormatProgress(const TrainingProgress& progress);

class ProgressBar {
 public:
  explicit ProgressBar(std::FILE* stream = stderr) : stream_(stream) {}
  // Rewrites the line.
  void Update(const TrainingProgress& progress);
  // Ends the line (once something was written).
  void Finish();

 private:
  std::FILE* stream_;
  bool written_ = false;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_PROGRESS_BAR_H_
