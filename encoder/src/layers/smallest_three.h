// Smallest-three rotation coding (bitstream-spec 5.4), the encoder's half: a quaternion as its
// three smallest components after normalisation, with the largest made positive.
#ifndef M4D_ENCODER_LAYERS_SMALLEST_THREE_H_
#define M4D_ENCODER_LAYERS_SMALLEST_THREE_H_

namespace m4d {

// Writes the components of the unit quaternion q / |q| other than the largest in magnitude
// (the first of equals), in order, negated when that one is negative, to abc[0..2], and
// returns its index (0..3). A zero quaternion is taken as the identity (index 0, abc 0),
// which the renderer draws as a zero one is drawn: unrotated. q must be finite.
int SplitSmallestThree(const float* q, float* abc);

// The same with the dropped component `index` chosen by the caller: abc[0..2] are the other
// components of q / |q|, negated when q[index] is negative.
void SplitAt(const float* q, int index, float* abc);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_SMALLEST_THREE_H_
