// The rigid update of a moved Gaussian (bitstream-spec 6.3 steps 5 and 6, paper eq. for
// Trans): position plus the predicted translation, rotation left-multiplied by the predicted
// quaternion increment (1 + o3, o4, o5, o6) and normalised. Float training version with its
// backward pass; the decoder's normative version lives in the SDK.
#ifndef M4D_ENCODER_MOTION_RIGID_UPDATE_H_
#define M4D_ENCODER_MOTION_RIGID_UPDATE_H_

namespace m4d {

// o: the 7 MLP outputs; p, q: position and rotation (w, x, y, z) before; writes after.
void RigidUpdate(const float o[7], const float p[3], const float q[4], float p_out[3],
                 float q_out[4]);

// Given dL/dp_out and dL/dq_out, writes dL/do (7 values). dL/dp = dL/dp_out is not needed
// here: positions before the update are fixed while motion is trained.
void RigidUpdateBackward(const float o[7], const float q[4], const float dp_out[3],
                         const float dq_out[4], float d_o[7]);

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_RIGID_UPDATE_H_
