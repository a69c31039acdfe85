#include "sdk/src/layers/rotation_coding.h"

#include <cmath>

namespace m4d {

void ComposeSmallestThree(const float* abc, int index, float* q) {
  const float a = abc[0], b = abc[1], c = abc[2];
  float sum = a * a;
  sum = sum + b * b;
  sum = sum + c * c;
  const float rest = 1.0f - sum;
  const float largest = rest > 0.0f ? std::sqrt(rest) : 0.0f;
  const float coded[3] = {a, b, c};
  int k = 0;
  for (int r = 0; r < 4; ++r) q[r] = r == index ? largest : coded[k++];
}

}  // namespace m4d
