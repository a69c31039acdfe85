// Learning rates of Gaussian training, with the reference 3DGS implementation's values: the
// position rate decays exponentially (log-linearly) from 1.6e-4 to 1.6e-6 over the run and
// is multiplied by the scene extent; the others are constant.
//
// Opacity: the original release used 0.05, later versions 0.025. We keep 0.05, the value of
// the release that the streaming works 4D-MoDe builds on were tuned with; it also moves
// opacities faster in the shorter CPU schedules.
#ifndef M4D_ENCODER_TRAIN_LEARNING_RATE_SCHEDULE_H_
#define M4D_ENCODER_TRAIN_LEARNING_RATE_SCHEDULE_H_

namespace m4d {

// lr(step) = exp((1 - t) log(initial) + t log(final)), t = clamp(step / max_steps, 0, 1),
// times an optional warm-up factor over the first delay_steps:
// delay_multiplier + (1 - delay_multiplier) sin(pi / 2 clamp(step / delay_steps, 0, 1)).
// Zero for a negative step or when both rates are zero (the reference's conventions).
struct ExponentialDecay {
  float initial = 0;
  float final = 0;
  int max_steps = 1;
  int delay_steps = 0;  // 0: no warm-up (the reference's positions)
  float delay_multiplier = 1.0f;

  float At(int step) const;
};

struct GaussianLearningRates {
  ExponentialDecay position{1.6e-4f, 1.6e-6f, 30000};  // times the scene extent
  float sh_dc = 2.5e-3f;
  float sh_rest = 2.5e-3f / 20.0f;
  float opacity = 0.05f;
  float scaling = 5e-3f;
  float rotation = 1e-3f;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_LEARNING_RATE_SCHEDULE_H_
