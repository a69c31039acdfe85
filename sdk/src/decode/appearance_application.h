// Appearance application (bitstream-spec 6.7): adds the dequantized colour change of an
// APPEARANCE packet to the SH DC coefficients of the dynamic set.
// Normative float code: built with -ffp-contract=off.
#ifndef M4D_SDK_DECODE_APPEARANCE_APPLICATION_H_
#define M4D_SDK_DECODE_APPEARANCE_APPLICATION_H_

#include "sdk/src/layers/appearance_update.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// update.values must hold 3 values per Gaussian of *set.
void ApplyAppearanceUpdate(const AppearanceUpdate& update, GaussianSet* set);

}  // namespace m4d

#endif  // M4D_SDK_DECODE_APPEARANCE_APPLICATION_H_
