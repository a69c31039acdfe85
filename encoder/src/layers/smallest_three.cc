#include "encoder/src/layers/smallest_three.h"

#include <cmath>

namespace m4d {

void SplitAt(const float* q, int index, float* abc) {
  double norm = 0.0;
  for (int r = 0; r < 4; ++r) norm += static_cast<double>(q[r]) * q[r];
  norm = std::sqrt(norm);
  if (!(norm > 0.0)) {
    abc[0] = abc[1] = abc[2] = 0.0f;
    return;
  }
  const double scale = (q[index] < 0.0f ? -1.0 : 1.0) / norm;
  int k = 0;
  for (int r = 0; r < 4; ++r) {
    if (r != index) abc[k++] = static_cast<float>(q[r] * scale);
  }
}

int SplitSmallestThree(const float* q, float* abc) {
  int largest = 0;
  for (int r = 1; r < 4; ++r) {
    if (std::fabs(q[r]) > std::fabs(q[largest])) largest = r;
  }
  if (q[largest] == 0.0f) largest = 0;  // the zero quaternion: the identity
  SplitAt(q, largest, abc);
  return largest;
}

}  // namespace m4d
