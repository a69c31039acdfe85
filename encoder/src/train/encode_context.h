// EncodeContext: what every stage of an encode shares, held once by the encoder's options and
// handed to each stage's options: the colour behind the splats, the worker threads and the
// random seed. A stage's seed is the encode's, offset per stage and frame (Reseeded), so that
// stages and frames draw independent random numbers and a run is the same at any thread count.
#ifndef M4D_ENCODER_TRAIN_ENCODE_CONTEXT_H_
#define M4D_ENCODER_TRAIN_ENCODE_CONTEXT_H_

#include <algorithm>
#include <cstdint>

#include "encoder/src/raster/render_settings.h"

namespace m4d {

struct EncodeContext {
  float background[3] = {0.0f, 0.0f, 0.0f};
  int threads = 0;  // 0: the hardware's concurrency
  uint64_t seed = 0;

  // The same context with another seed.
  EncodeContext Reseeded(uint64_t new_seed) const {
    EncodeContext c = *this;
    c.seed = new_seed;
    return c;
  }
  // Renders with this context's threads and background.
  void ApplyTo(RenderSettings* settings) const {
    settings->threads = threads;
    std::copy(background, background + 3, settings->background);
  }
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_ENCODE_CONTEXT_H_
