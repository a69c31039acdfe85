// ProgressBar: one line on a terminal stream (stderr by default) that training rewrites in
// place: a bar, the iteration, the smoothed loss and PSNR, the Gaussian count and the speed.
// Into a file or a pipe (a log) it appends a whole line at every tenth of the run instead, so
// that a log holds a few readable lines, not thousands of rewrites on one line.
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

// Whether the stream is a terminal (where lines can be rewritten in place).
bool IsTerminal(std::FILE* stream);

// A status line, e.g. "  frame 3: motion": rewritten in place on a terminal, appended as a
// line elsewhere. ClearStatus blanks it on a terminal before other output.
void ShowStatus(std::FILE* stream, const std::string& text);
void ClearStatus(std::FILE* stream);

class ProgressBar {
 public:
  explicit ProgressBar(std::FILE* stream = stderr);
  // Shows the progress, after `label` (e.g. "keyframe 0").
  void Update(const TrainingProgress& progress, const std::string& label = "");
  // Ends the line (once something was written).
  void Finish();

 private:
  std::FILE* stream_;
  bool terminal_;
  bool written_ = false;
  int logged_tenths_ = -1;  // off a terminal: the last tenth of the run written
  int last_iteration_ = 0;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_PROGRESS_BAR_H_
