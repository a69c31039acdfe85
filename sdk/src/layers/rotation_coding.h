// How gaussian_set() codes rotations (bitstream-spec 5.4): four quantized components, or, from
// version 0.5, the three smallest components of the unit quaternion with its largest made
// positive, plus that component's index; the largest is recovered from the unit norm.
#ifndef M4D_SDK_LAYERS_ROTATION_CODING_H_
#define M4D_SDK_LAYERS_ROTATION_CODING_H_

namespace m4d {

enum class RotationCoding { kFourComponents, kSmallestThree };

// Bits of the index of the dropped component (0..3).
constexpr int kRotationIndexBits = 2;

// Writes the quaternion (w, x, y, z) whose components other than `index` are abc[0..2], in
// order, and whose component `index` is sqrt(max(0, 1 - (a * a + b * b + c * c))), each
// operation one f32 rounding in that order (spec 5.4). `abc` may alias q[0..2].
void ComposeSmallestThree(const float* abc, int index, float* q);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_ROTATION_CODING_H_
