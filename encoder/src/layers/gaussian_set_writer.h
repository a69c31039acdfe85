// Encoding of gaussian_set() (bitstream-spec 5.4, 5.5): our own uniform quantization per
// attribute group, integer attributes coded losslessly by Draco.
#ifndef M4D_ENCODER_LAYERS_GAUSSIAN_SET_WRITER_H_
#define M4D_ENCODER_LAYERS_GAUSSIAN_SET_WRITER_H_

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_set_syntax.h"

namespace m4d {

// How the attribute groups other than the positions are coded from version 0.8 (spec 5.4):
// whichever of Draco and adaptive_attributes() takes fewer bytes, or always one of them (for
// streams and tests that must exercise it).
enum class AttributeCoding { kSmaller, kDraco, kAdaptive };

// Bits per attribute group (0..24). Defaults keep rendering quality (peers: SPZ uses 24-bit
// positions, 8-bit scales, opacity and colour, 4-5 bit higher SH).
struct GaussianQuantization {
  int position_bits = 16;
  int log_scale_bits = 8;
  int rotation_bits = 10;
  int opacity_bits = 8;
  int sh_dc_bits = 8;
  int sh_rest_bits = 5;
  // Draco encoder speed 0 (best) .. 10 (fastest); always the sequential method (spec 5.5).
  int draco_speed = 5;
  // Codebook sizes (0: scalar values; spec 5.4, version 0.6). A group with a size K > 0 is
  // coded as K entries fitted by k-means, with codebook_bits per component, and one index per
  // Gaussian, when the set has at least kCodebookMinGaussiansPerEntry * K Gaussians (smaller
  // sets, such as compensation, keep their scalar bits).
  int log_scale_codebook = 0;
  int sh_dc_codebook = 0;
  int sh_rest_codebook = 0;
  int codebook_bits = 10;
  // Keep a codebook only where it lowers error plus bytes against the scalar bits (false: always,
  // for streams that must exercise codebooks).
  bool codebooks_only_where_they_pay = true;
  AttributeCoding attribute_coding = AttributeCoding::kSmaller;
  // Smallest-three rotations: code each Gaussian's rotation as the equivalent one nearest the
  // identity, its scales permuted to match (layers/rotation_symmetry.h); the decoder then
  // draws the same Gaussian from a narrower range of rotations, so one bit fewer gives about
  // the same step. Off by default (the rotations as given); rate point r1 turns it on.
  bool canonical_rotations = false;
  // The stream version's (SequenceHeader::gaussian_set_syntax): the newest by default.
  GaussianSetSyntax syntax;
};

// Adaptive attributes take about 5 ns per binary decision to decode on one core; above this
// many per Gaussian (SH degree 3 at 3 bits and more) a set keeps Draco's faster decoding,
// unless attribute_coding asks for them (100k Gaussians of SH degree 1 at rate point r1's bits
// make 54).
constexpr int kMaxAdaptiveBinsPerGaussian = 128;

// Fewer Gaussians per entry and the entries cost more than the indices save.
constexpr int kCodebookMinGaussiansPerEntry = 32;

// Writes gaussian_set() for `set` (its sh_degree must be the sequence's).
Status WriteGaussianSet(const GaussianSet& set, const GaussianQuantization& quantization,
                        ByteWriter* out);

// What a decoder reconstructs from WriteGaussianSet's output (the set coded, then decoded by
// the SDK's reader), for stages that must continue from it before the packet is written.
Status ReconstructGaussianSet(const GaussianSet& set, const GaussianQuantization& quantization,
                              GaussianSet* decoded);

// Replaces every value of `set` by the one a decoder reconstructs from WriteGaussianSet's
// output (same ranges and rounding; the set keeps its order), without coding it: the
// forward pass of quantization-aware training. With canonical rotations, each Gaussian keeps its
// own axis order and quaternion sign (the decoder's rotation and scales, brought back to them),
// so that the training's gradients stay those of its own parameters. Codebook groups are quantized
// with their scalar bits instead: a k-means per training step would cost more than the step.
Status QuantizeGaussianSet(const GaussianQuantization& quantization, GaussianSet* set);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_GAUSSIAN_SET_WRITER_H_
