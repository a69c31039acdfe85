// TrainingRandom: the seeded random source of training (view order, Gaussian splitting,
// random initialisation). Built on std::mt19937_64, whose output the standard fixes, with its
// own conversions to uniform and normal values, so that a seed gives the same training on
// every standard library.
#ifndef M4D_ENCODER_TRAIN_TRAINING_RANDOM_H_
#define M4D_ENCODER_TRAIN_TRAINING_RANDOM_H_

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace m4d {

class TrainingRandom {
 public:
  explicit TrainingRandom(uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1), 24 random bits.
  float Uniform() { return static_cast<float>(engine_() >> 40) * (1.0f / 16777216.0f); }

  // Uniform integer in [0, n), n > 0 (multiply-shift of 32 random bits; the bias is below
  // n / 2^32, irrelevant for view orders).
  uint32_t Below(uint32_t n) {
    return static_cast<uint32_t>(((engine_() >> 32) * static_cast<uint64_t>(n)) >> 32);
  }

  // Standard normal (Box-Muller, one value per two uniforms).
  float Normal() {
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
    const double u2 = static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0);
    return static_cast<float>(std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
  }

  // Fisher-Yates shuffle.
  template <typename T>
  void Shuffle(std::vector<T>* values) {
    for (size_t i = values->size(); i > 1; --i) {
      std::swap((*values)[i - 1], (*values)[Below(static_cast<uint32_t>(i))]);
    }
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_TRAINING_RANDOM_H_
