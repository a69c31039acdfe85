// Encoding of gaussian_set() (bitstream-spec 5.4, 5.5).
//
// Draco's sequential method is used at every speed: its kd-tree method codes all attributes
// in one tree with a common bit length and leaves the low bits raw, so with groups of
// different widths (16-bit positions, 5-bit SH) it comes out larger than the raw values,
// while the sequential method entropy-codes each attribute. The Gaussians are put in Morton
// order of their quantized positions first: the order octree_positions() (version 0.7)
// decodes them in, and before it the order in which Draco's delta prediction worked on them.
#include "encoder/src/layers/gaussian_set_writer.h"

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/expert_encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/point_cloud/point_cloud.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "encoder/src/layers/adaptive_attributes_writer.h"
#include "encoder/src/layers/codebook.h"
#include "encoder/src/layers/octree_positions_writer.h"
#include "encoder/src/layers/rotation_symmetry.h"
#include "encoder/src/layers/smallest_three.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/layers/gaussian_set_reader.h"

namespace m4d {
namespace {

// A group's values and how they are coded.
struct GroupPlan {
  int group = 0;
  int components = 0;
  const float* source = nullptr;  // component r of Gaussian i at source[i * stride + r]
  size_t stride = 0;
  int bits = 0;
  bool per_component = false;
  std::vector<float> min, step;  // one pair per component, or one for all
  std::vector<uint32_t> q;       // [i][r] in coding order
  bool delta = false;            // Draco prediction: difference, else none
  std::vector<float> owned;      // the values `source` points to when they are derived
  bool rotation_index = false;   // the index attribute of smallest-three rotations
  uint32_t codebook_size = 0;    // 0: scalar values; else q holds one entry index per Gaussian
  Codebook codebook;             // entries and the index of each Gaussian in set order
};

Status InvalidArg(const std::string& what) {
  return Status(M4D_ERR_INVALID_ARG, "WriteGaussianSet: " + what);
}

// Must match the reader (spec 5.5).
draco::DataType DracoDataType(int bits) {
  return bits <= 8 ? draco::DT_UINT8 : bits <= 16 ? draco::DT_UINT16 : draco::DT_UINT32;
}

int RequestedBits(int group, const GaussianQuantization& quantization) {
  switch (group) {
    case kGroupPosition:
      return quantization.position_bits;
    case kGroupLogScale:
      return quantization.log_scale_bits;
    case kGroupRotation:
      return quantization.rotation_bits;
    case kGroupOpacity:
      return quantization.opacity_bits;
    case kGroupShDc:
      return quantization.sh_dc_bits;
    default:
      return quantization.sh_rest_bits;
  }
}

int RequestedCodebook(int group, const GaussianQuantization& quantization) {
  switch (group) {
    case kGroupLogScale:
      return quantization.log_scale_codebook;
    case kGroupShDc:
      return quantization.sh_dc_codebook;
    case kGroupShRest:
      return quantization.sh_rest_codebook;
    default:
      return 0;
  }
}

// The codebook size a group of a set of n Gaussians is coded with (0: scalar values).
int CodebookSize(int group, size_t n, const GaussianQuantization& quantization) {
  const int size = RequestedCodebook(group, quantization);
  const bool enough = n >= static_cast<size_t>(kCodebookMinGaussiansPerEntry) * size;
  return quantization.syntax.codebooks && size > 0 && enough ? size : 0;
}

// The Draco attribute of a group (spec 5.5): its quantized components, or one entry index.
int AttributeComponents(const GroupPlan& plan) {
  return plan.codebook_size > 0 ? 1 : plan.components;
}

draco::DataType AttributeDataType(const GroupPlan& plan) {
  if (plan.codebook_size > 0) {
    return plan.codebook_size <= 256 ? draco::DT_UINT8 : draco::DT_UINT16;
  }
  return DracoDataType(plan.bits);
}

void SetSource(const GaussianSet& set, GroupPlan* plan) {
  const size_t sh_stride = static_cast<size_t>(set.sh_floats());
  switch (plan->group) {
    case kGroupPosition:
      plan->source = set.positions.data();
      plan->stride = 3;
      break;
    case kGroupLogScale:
      plan->source = set.log_scales.data();
      plan->stride = 3;
      break;
    case kGroupRotation:
      plan->source = set.rotations.data();  // replaced for smallest-three
      plan->stride = 4;
      break;
    case kGroupOpacity:
      plan->source = set.opacity_logits.data();
      plan->stride = 1;
      break;
    case kGroupShDc:
      plan->source = set.sh.data();
      plan->stride = sh_stride;
      break;
    default:
      plan->source = set.sh.data() + 3;
      plan->stride = sh_stride;
      break;
  }
}

// Higher SH coefficients and rotation components cluster at zero (view-independent colour,
// axis-aligned Gaussians): a level at exactly zero keeps them there. Without it, the 3-bit higher
// SH of the default scene's keyframe cost its held-out view several times what they cost with it
// (docs/results/2026-11-30-readme-notebook.md, "A quantization level at zero").
bool HasZeroLevel(int group) { return group == kGroupRotation || group >= kGroupShRest; }

Status CheckFinite(size_t n, const GroupPlan& plan) {
  for (size_t i = 0; i < n; ++i) {
    for (int r = 0; r < plan.components; ++r) {
      if (!std::isfinite(plan.source[i * plan.stride + r])) {
        return InvalidArg("non-finite value in group " + std::to_string(plan.group));
      }
    }
  }
  return Status::Ok();
}

// Smallest-three rotations (spec 5.4): the plan of the three smallest components of each unit
// quaternion, and the plan of the dropped component's index, coded as a value with min 0 and
// step 1 that the header does not carry.
void PlanSmallestThree(const GaussianSet& set, GroupPlan* rotation, GroupPlan* index) {
  const size_t n = set.size();
  rotation->owned.resize(3 * n);
  index->owned.resize(n);
  bool identical = true;
  for (size_t i = 0; i < n; ++i) {
    const float* q = &set.rotations[4 * i];
    index->owned[i] = static_cast<float>(SplitSmallestThree(q, &rotation->owned[3 * i]));
    identical = identical && std::equal(q, q + 4, set.rotations.data());
  }
  // One rotation for all: index 0 makes the group constant (bits 0, nothing in Draco); w is
  // then recovered to within a few f32 ulps of the unit norm, even where it is not the largest.
  if (identical && index->owned[0] != 0.0f) {
    for (size_t i = 0; i < n; ++i) SplitAt(set.rotations.data(), 0, &rotation->owned[3 * i]);
    std::fill(index->owned.begin(), index->owned.end(), 0.0f);
  }
  rotation->components = 3;
  rotation->source = rotation->owned.data();
  rotation->stride = 3;
  index->group = kGroupRotation;
  index->components = 1;
  index->source = index->owned.data();
  index->stride = 1;
  index->rotation_index = true;
  index->per_component = true;
  index->min = {0.0f};
  index->step = {1.0f};
}

// Chooses bits, per_component and (min, step). Positions get their full range per axis; the
// other groups share one step across components, which gives every component the same
// absolute error (the lowest total squared error for the rate), some with a level at zero
// (the largest value may then clamp, by at most half a step more). A group whose components are
// each constant costs nothing: bits 0 and one min per component.
Status PlanQuantization(size_t n, int requested_bits, GroupPlan* plan) {
  M4D_RETURN_IF_ERROR(CheckFinite(n, *plan));
  const int c = plan->components;
  std::vector<float> lo(c), hi(c);
  for (int r = 0; r < c; ++r) {
    float a = plan->source[r], b = plan->source[r];
    for (size_t i = 0; i < n; ++i) {
      const float v = plan->source[i * plan->stride + r];
      a = std::min(a, v);
      b = std::max(b, v);
    }
    lo[r] = a;
    hi[r] = b;
  }
  bool constant = true;
  for (int r = 0; r < c; ++r) constant = constant && lo[r] == hi[r];
  plan->per_component = plan->group == kGroupPosition || constant;
  plan->bits = constant ? 0 : requested_bits;
  if (!plan->per_component) {
    lo.assign(1, *std::min_element(lo.begin(), lo.end()));
    hi.assign(1, *std::max_element(hi.begin(), hi.end()));
  }
  const double levels = std::ldexp(1.0, plan->bits) - 1.0;
  for (size_t p = 0; p < lo.size(); ++p) {
    const float step =
        plan->bits > 0 ? static_cast<float>((static_cast<double>(hi[p]) - lo[p]) / levels) : 0.0f;
    if (!std::isfinite(step)) {
      return InvalidArg("value range too large in group " + std::to_string(plan->group));
    }
    plan->min.push_back(lo[p]);
    plan->step.push_back(step);
  }
  const float step = plan->step[0], top = plan->min[0] + static_cast<float>(levels) * step;
  if (HasZeroLevel(plan->group) && !plan->per_component && plan->min[0] < 0.0f && top > 0.0f) {
    plan->min[0] =
        -static_cast<float>(std::round(-static_cast<double>(plan->min[0]) / step)) * step;
  }
  return Status::Ok();
}

// Replaces the plan's scalar coding by a codebook of `size` entries on its grid.
void PlanCodebook(size_t n, int size, GroupPlan* plan) {
  const size_t c = static_cast<size_t>(plan->components);
  std::vector<float> min(c), step(c);
  for (size_t r = 0; r < c; ++r) {
    min[r] = plan->min[plan->per_component ? r : 0];
    step[r] = plan->step[plan->per_component ? r : 0];
  }
  plan->codebook = FitCodebook(plan->source, n, plan->stride, plan->components, size,
                               CodebookGrid{min.data(), step.data(), plan->bits});
  plan->codebook_size = static_cast<uint32_t>(size);
}

// q = clamp(round((v - min) / step)) in Gaussian order `order`; the step used is the f32
// transmitted, so that the decoder's min + q * step lands within step / 2 of v. A codebook
// group's q is each Gaussian's entry index.
void Quantize(const std::vector<uint32_t>& order, GroupPlan* plan) {
  if (plan->codebook_size > 0) {
    plan->q.resize(order.size());
    for (size_t j = 0; j < order.size(); ++j) plan->q[j] = plan->codebook.index[order[j]];
    return;
  }
  const int c = plan->components;
  const double q_max = std::ldexp(1.0, plan->bits) - 1.0;
  plan->q.resize(order.size() * static_cast<size_t>(c));
  uint32_t* q = plan->q.data();
  for (uint32_t i : order) {
    const float* v = plan->source + i * plan->stride;
    for (int r = 0; r < c; ++r, ++q) {
      const int p = plan->per_component ? r : 0;
      if (plan->step[p] == 0.0f) {
        *q = 0;
        continue;
      }
      const double x = std::round((static_cast<double>(v[r]) - plan->min[p]) / plan->step[p]);
      *q = static_cast<uint32_t>(std::min(std::max(x, 0.0), q_max));
    }
  }
}

// Coding order: Morton order of the quantized positions, Gaussians at the same position in
// set order.
std::vector<uint32_t> CodingOrder(size_t n, const GroupPlan& position) {
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
  if (position.bits == 0) return order;
  GroupPlan quantized = position;
  Quantize(order, &quantized);
  const uint32_t* q = quantized.q.data();
  std::stable_sort(order.begin(), order.end(), [q](uint32_t a, uint32_t b) {
    return MortonLess(q + 3 * static_cast<size_t>(a), q + 3 * static_cast<size_t>(b));
  });
  return order;
}

// Empirical entropy in bits of a histogram.
double Entropy(const std::vector<uint32_t>& histogram, size_t total) {
  double bits = 0;
  for (uint32_t count : histogram) {
    if (count > 0) bits -= count * std::log2(static_cast<double>(count) / total);
  }
  return bits;
}

// Draco codes an attribute's values (prediction none) or its wrapped differences to the
// previous Gaussian (prediction difference) with one entropy table; keep the cheaper one.
// Wide groups are positions in practice, where differences always win.
bool PreferDelta(const GroupPlan& plan) {
  if (plan.bits > 16) return true;
  const auto [lo_it, hi_it] = std::minmax_element(plan.q.begin(), plan.q.end());
  const int64_t lo = *lo_it, span = *hi_it - lo + 1;
  // Draco's wrap transform keeps corrections in [-(span / 2), max_correction].
  const int64_t max_correction = span / 2 - (span % 2 == 0 ? 1 : 0);
  std::vector<uint32_t> plain(static_cast<size_t>(span)), diff(static_cast<size_t>(2 * span));
  const size_t c = static_cast<size_t>(plan.components);
  for (size_t k = 0; k < plan.q.size(); ++k) {
    ++plain[plan.q[k] - lo];
    int64_t d = static_cast<int64_t>(plan.q[k]) - (k >= c ? plan.q[k - c] : lo);
    if (d > max_correction) d -= span;
    if (d < -(span / 2)) d += span;
    ++diff[static_cast<size_t>(d >= 0 ? 2 * d : -2 * d - 1)];
  }
  return Entropy(diff, plan.q.size()) < Entropy(plain, plan.q.size());
}

template <typename T>
void StoreValues(const std::vector<uint32_t>& q, draco::DataBuffer* buffer) {
  std::vector<T> values(q.begin(), q.end());
  buffer->Write(0, values.data(), values.size() * sizeof(T));
}

Status EncodeDraco(size_t n, const std::vector<GroupPlan*>& coded, int speed,
                   draco::EncoderBuffer* out) {
  draco::PointCloud pc;
  pc.set_num_points(static_cast<uint32_t>(n));
  for (const GroupPlan* plan : coded) {
    const draco::DataType type = AttributeDataType(*plan);
    const int components = AttributeComponents(*plan);
    draco::GeometryAttribute attribute;
    attribute.Init(plan->group == kGroupPosition ? draco::GeometryAttribute::POSITION
                                                 : draco::GeometryAttribute::GENERIC,
                   nullptr, static_cast<uint8_t>(components), type, false,
                   draco::DataTypeLength(type) * components, 0);
    const int id = pc.AddAttribute(attribute, true, static_cast<uint32_t>(n));
    draco::DataBuffer* buffer = pc.attribute(id)->buffer();
    if (type == draco::DT_UINT8) {
      StoreValues<uint8_t>(plan->q, buffer);
    } else if (type == draco::DT_UINT16) {
      StoreValues<uint16_t>(plan->q, buffer);
    } else {
      StoreValues<uint32_t>(plan->q, buffer);
    }
  }
  draco::ExpertEncoder encoder(pc);
  encoder.SetSpeedOptions(speed, speed);
  encoder.SetEncodingMethod(draco::POINT_CLOUD_SEQUENTIAL_ENCODING);
  for (size_t j = 0; j < coded.size(); ++j) {
    const draco::Status status = encoder.SetAttributePredictionScheme(
        static_cast<int32_t>(j),
        coded[j]->delta ? draco::PREDICTION_DIFFERENCE : draco::PREDICTION_NONE);
    if (!status.ok()) return InvalidArg(std::string("Draco: ") + status.error_msg());
  }
  const draco::Status status = encoder.EncodeToBuffer(out);
  if (!status.ok()) return InvalidArg(std::string("Draco: ") + status.error_msg());
  return Status::Ok();
}

// Checks the set and the bit depths, and plans every group with components; with
// `fit_codebooks` false, codebook groups keep their scalar bits.
Status PlanGroups(const GaussianSet& set, const GaussianQuantization& quantization,
                  bool fit_codebooks, std::vector<GroupPlan>* plans) {
  if (set.sh_degree < 0 || set.sh_degree > 3) return InvalidArg("SH degree outside 0..3");
  const size_t n = set.size();
  if (set.positions.size() != 3 * n || set.log_scales.size() != 3 * n ||
      set.rotations.size() != 4 * n || set.sh.size() != static_cast<size_t>(set.sh_floats()) * n) {
    return InvalidArg("array sizes do not match the count");
  }
  if (n > kMaxGaussiansPerSet) return InvalidArg("more than 2^22 Gaussians");
  if (quantization.draco_speed < 0 || quantization.draco_speed > 10) {
    return InvalidArg("draco_speed outside 0..10");
  }
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    const int bits = RequestedBits(group, quantization);
    if (bits < 0 || bits > kMaxAttributeBits) return InvalidArg("bits outside 0..24");
    const int size = RequestedCodebook(group, quantization);
    if (size < 0 || size == 1 || size > static_cast<int>(kMaxCodebookSize)) {
      return InvalidArg("codebook size not 0 or 2..4096");
    }
  }
  if (quantization.codebook_bits < 1 || quantization.codebook_bits > kMaxCodebookBits) {
    return InvalidArg("codebook_bits outside 1..12");
  }
  plans->clear();
  if (n == 0) return Status::Ok();
  const bool smallest_three = quantization.syntax.rotation == RotationCoding::kSmallestThree;
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    GroupPlan plan, index;
    plan.group = group;
    plan.components = GaussianGroupComponents(group, set.sh_degree);
    if (plan.components == 0) continue;
    SetSource(set, &plan);
    const int bits = RequestedBits(group, quantization);
    const bool split = group == kGroupRotation && smallest_three;
    if (split) {
      M4D_RETURN_IF_ERROR(CheckFinite(n, plan));
      PlanSmallestThree(set, &plan, &index);
    }
    const int codebook = fit_codebooks ? CodebookSize(group, n, quantization) : 0;
    M4D_RETURN_IF_ERROR(
        PlanQuantization(n, codebook > 0 ? quantization.codebook_bits : bits, &plan));
    if (codebook > 0 && plan.bits > 0) PlanCodebook(n, codebook, &plan);
    plans->push_back(std::move(plan));
    if (split) {
      // With bits 0 every index is 0; constant components with other indices still need them.
      const bool all_zero =
          std::all_of(index.owned.begin(), index.owned.end(), [](float k) { return k == 0.0f; });
      if (plans->back().bits == 0 && !all_zero) plans->back().bits = bits;
      index.bits = plans->back().bits > 0 ? kRotationIndexBits : 0;
      if (index.bits == 0) std::fill(index.owned.begin(), index.owned.end(), 0.0f);
      plans->push_back(std::move(index));
    }
  }
  return Status::Ok();
}

// Squared error of the values the decoder reconstructs from the plan's q (in coding order).
double SquaredError(const std::vector<uint32_t>& order, const GroupPlan& plan) {
  const size_t c = static_cast<size_t>(plan.components);
  double error = 0.0;
  for (size_t j = 0; j < order.size(); ++j) {
    const float* v = plan.source + order[j] * plan.stride;
    for (size_t r = 0; r < c; ++r) {
      const size_t p = plan.per_component ? r : 0;
      const uint32_t q =
          plan.codebook_size > 0 ? plan.codebook.entries[plan.q[j] * c + r] : plan.q[j * c + r];
      const double d =
          static_cast<double>(plan.min[p] + static_cast<float>(q) * plan.step[p]) - v[r];
      error += d * d;
    }
  }
  return error;
}

size_t CodebookBytes(const GroupPlan& plan, RansLayout layout) {
  if (plan.codebook_size == 0) return 0;
  const std::vector<int32_t> entries(plan.codebook.entries.begin(), plan.codebook.entries.end());
  return SymbolBlockSize(entries.data(), entries.size(), layout);
}

// A coded group's bytes (its Draco attribute and codebook entries) and squared error.
struct GroupCost {
  double bytes = 0.0;
  double error = 0.0;
};

Status Cost(size_t n, const std::vector<uint32_t>& order, const GaussianQuantization& quantization,
            GroupPlan* plan, GroupCost* cost) {
  Quantize(order, plan);
  plan->delta = PreferDelta(*plan);
  draco::EncoderBuffer buffer;
  M4D_RETURN_IF_ERROR(EncodeDraco(n, {plan}, quantization.draco_speed, &buffer));
  cost->bytes =
      static_cast<double>(buffer.size() + CodebookBytes(*plan, quantization.syntax.rans_layout));
  cost->error = SquaredError(order, *plan);
  return Status::Ok();
}

Status PlanScalar(size_t n, int bits, const GroupPlan& like, GroupPlan* plan) {
  plan->group = like.group;
  plan->components = like.components;
  plan->source = like.source;
  plan->stride = like.stride;
  return PlanQuantization(n, bits, plan);
}

// Keeps a group's codebook only where it pays on this content: where it lowers the group's squared
// error plus lambda times its bytes below the scalar bits', lambda being the slope of the scalar
// ladder there (error gained per byte saved one bit lower). A threshold on the error alone would be
// wrong both ways: on the default scene's keyframe, colour entries err more in SH space than the
// scalars, yet take fewer bytes and render better; on Panoptic basketball they cost more bytes than
// the scalars (docs/results/2026-11-30-readme-notebook.md, "Codebooks (bitstream 0.6)";
// docs/results/2026-11-30-comment-measurements.md).
Status KeepCodebookIfItPays(size_t n, const std::vector<uint32_t>& order,
                            const GaussianQuantization& quantization, GroupPlan* plan) {
  const int bits = RequestedBits(plan->group, quantization);
  GroupPlan scalar, coarser;
  GroupCost codebook_cost, scalar_cost, coarser_cost;
  M4D_RETURN_IF_ERROR(PlanScalar(n, bits, *plan, &scalar));
  M4D_RETURN_IF_ERROR(Cost(n, order, quantization, &scalar, &scalar_cost));
  M4D_RETURN_IF_ERROR(Cost(n, order, quantization, plan, &codebook_cost));
  double lambda = 0.0;
  if (bits > 1) {
    M4D_RETURN_IF_ERROR(PlanScalar(n, bits - 1, *plan, &coarser));
    M4D_RETURN_IF_ERROR(Cost(n, order, quantization, &coarser, &coarser_cost));
    const double saved = scalar_cost.bytes - coarser_cost.bytes;
    if (saved > 0.0) lambda = std::max(0.0, coarser_cost.error - scalar_cost.error) / saved;
  }
  const double j_codebook = codebook_cost.error + lambda * codebook_cost.bytes;
  const double j_scalar = scalar_cost.error + lambda * scalar_cost.bytes;
  if (!(j_codebook < j_scalar)) *plan = std::move(scalar);
  return Status::Ok();
}

// Codes the positions as octree_positions() (version 0.7, spec 5.6) into `octree` and
// re-encodes the Draco payload without them when that takes fewer bytes than Draco's
// attribute; else leaves both as they are. Octree tables cost up to 255 symbols a level: on
// sets of a few hundred Gaussians (compensation) Draco's deltas win, on keyframes the octree
// (default scene's keyframe at 12 bits: 18.0 bits per Gaussian against 21.2).
Status PreferOctree(size_t n, const GroupPlan& position, const GaussianQuantization& quantization,
                    const std::vector<GroupPlan*>& coded, draco::EncoderBuffer* draco_buffer,
                    std::vector<uint8_t>* octree) {
  std::vector<uint8_t> tree;
  ByteWriter writer(&tree);
  M4D_RETURN_IF_ERROR(WriteOctreePositions(position.q.data(), n, position.bits,
                                           quantization.syntax.rans_layout, &writer));
  const std::vector<GroupPlan*> others(coded.begin() + 1, coded.end());  // positions first
  draco::EncoderBuffer without;
  M4D_RETURN_IF_ERROR(EncodeDraco(n, others, quantization.draco_speed, &without));
  if (tree.size() + without.size() >= draco_buffer->size()) return Status::Ok();
  draco_buffer->Clear();
  draco_buffer->Encode(without.data(), without.size());
  *octree = std::move(tree);
  return Status::Ok();
}

// The fields of adaptive_attributes() (version 0.8, spec 5.7): every coded group but the
// positions.
std::vector<AdaptiveField> AdaptiveFields(const std::vector<GroupPlan*>& coded,
                                          const GaussianSetSyntax& syntax) {
  std::vector<AdaptiveField> fields;
  for (GroupPlan* plan : coded) {
    if (plan->group == kGroupPosition) continue;
    AdaptiveField field;
    field.components = AttributeComponents(*plan);
    const bool codebook = plan->codebook_size > 0;
    field.width = codebook ? CodebookIndexWidth(plan->codebook_size) : plan->bits;
    field.limit = codebook ? plan->codebook_size : 1u << plan->bits;
    field.context = AdaptiveContextOf(plan->group, codebook, plan->rotation_index, syntax);
    field.q = plan->q.data();
    fields.push_back(field);
  }
  return fields;
}

// Binary decisions a decoder makes per Gaussian.
int BinsPerGaussian(const std::vector<AdaptiveField>& fields) {
  int bins = 0;
  for (const AdaptiveField& field : fields) bins += field.components * field.width;
  return bins;
}

size_t VarUintSize(size_t v) {
  size_t bytes = 1;
  for (; v >= 128; v >>= 7) ++bytes;
  return bytes;
}

// Codes the groups other than the positions as adaptive_attributes() (version 0.8) into
// `adaptive`, leaving in the Draco payload only the positions (when not in the octree), when
// that takes fewer bytes or is asked for; else leaves both as they are. The adaptive
// probabilities follow the statistics along the Morton order and condition each value on its
// neighbour's, where Draco codes each attribute with one table (default scene's keyframe at
// r1: 5 % fewer bytes). Its decoding is sequential, about 5 ns per binary decision on one
// core: sets of more decisions per Gaussian than kMaxAdaptiveBinsPerGaussian (higher SH at
// many bits) keep Draco unless asked, so that 100k Gaussians decode within 100 ms.
Status PreferAdaptive(size_t n, const GaussianQuantization& quantization, bool octree,
                      const std::vector<GroupPlan*>& coded, draco::EncoderBuffer* draco_buffer,
                      std::vector<uint8_t>* adaptive) {
  if (quantization.attribute_coding == AttributeCoding::kDraco) return Status::Ok();
  const std::vector<AdaptiveField> fields = AdaptiveFields(coded, quantization.syntax);
  if (quantization.attribute_coding == AttributeCoding::kSmaller &&
      BinsPerGaussian(fields) > kMaxAdaptiveBinsPerGaussian) {
    return Status::Ok();
  }
  std::vector<uint8_t> payload = EncodeAdaptiveAttributes(
      fields.data(), static_cast<int>(fields.size()), static_cast<uint32_t>(n));
  draco::EncoderBuffer positions;
  const bool positions_in_draco = !octree && !coded.empty() && coded[0]->group == kGroupPosition;
  if (positions_in_draco) {
    M4D_RETURN_IF_ERROR(EncodeDraco(n, {coded[0]}, quantization.draco_speed, &positions));
  }
  const size_t draco_size =
      positions_in_draco ? VarUintSize(positions.size()) + positions.size() : 0;
  const size_t adaptive_size = VarUintSize(payload.size()) + payload.size() + draco_size;
  const bool smaller = adaptive_size < VarUintSize(draco_buffer->size()) + draco_buffer->size();
  if (quantization.attribute_coding == AttributeCoding::kSmaller && !smaller) {
    return Status::Ok();
  }
  draco_buffer->Clear();
  draco_buffer->Encode(positions.data(), positions.size());
  *adaptive = std::move(payload);
  return Status::Ok();
}

// codebook_size and the entries (version 0.6, spec 5.4).
Status WriteCodebook(const GroupPlan& plan, RansLayout layout, ByteWriter* out) {
  out->WriteVarUint(plan.codebook_size);
  if (plan.codebook_size == 0) return Status::Ok();
  const std::vector<int32_t> entries(plan.codebook.entries.begin(), plan.codebook.entries.end());
  return WriteSymbolBlock(entries.data(), entries.size(), layout, out);
}

// Whether the set's rotations are coded in their canonical form (a set whose arrays do not
// match its count is left to PlanGroups to refuse).
bool CodesCanonicalRotations(const GaussianSet& set, const GaussianQuantization& quantization) {
  const size_t n = set.size();
  return quantization.canonical_rotations &&
         quantization.syntax.rotation == RotationCoding::kSmallestThree &&
         set.rotations.size() == 4 * n && set.log_scales.size() == 3 * n;
}

Status WriteSet(const GaussianSet& set, const GaussianQuantization& quantization, ByteWriter* out) {
  std::vector<GroupPlan> plans;
  M4D_RETURN_IF_ERROR(PlanGroups(set, quantization, true, &plans));
  const size_t n = set.size();
  if (n == 0) {
    out->WriteVarUint(0);
    return Status::Ok();
  }

  const std::vector<uint32_t> order = CodingOrder(n, plans[kGroupPosition]);
  GroupPlan& position = plans[kGroupPosition];
  std::vector<GroupPlan*> coded;
  for (GroupPlan& plan : plans) {
    if (plan.codebook_size > 0 && quantization.codebooks_only_where_they_pay) {
      M4D_RETURN_IF_ERROR(KeepCodebookIfItPays(n, order, quantization, &plan));
    }
    if (plan.bits == 0) continue;
    Quantize(order, &plan);
    plan.delta = PreferDelta(plan);
    coded.push_back(&plan);
  }
  draco::EncoderBuffer draco_buffer;
  M4D_RETURN_IF_ERROR(EncodeDraco(n, coded, quantization.draco_speed, &draco_buffer));
  std::vector<uint8_t> octree;
  const bool octree_allowed = quantization.syntax.octree_positions && position.bits > 0;
  if (octree_allowed) {
    M4D_RETURN_IF_ERROR(PreferOctree(n, position, quantization, coded, &draco_buffer, &octree));
  }
  std::vector<uint8_t> adaptive;
  if (quantization.syntax.adaptive_attributes) {
    M4D_RETURN_IF_ERROR(
        PreferAdaptive(n, quantization, !octree.empty(), coded, &draco_buffer, &adaptive));
  }

  out->WriteVarUint(static_cast<uint32_t>(n));
  for (const GroupPlan& plan : plans) {
    if (plan.rotation_index) continue;
    out->WriteU8(static_cast<uint8_t>(plan.bits));
    out->WriteU8(plan.per_component ? 1 : 0);
    for (size_t p = 0; p < plan.min.size(); ++p) {
      out->WriteF32(plan.min[p]);
      out->WriteF32(plan.step[p]);
    }
    if (quantization.syntax.codebooks) {
      M4D_RETURN_IF_ERROR(WriteCodebook(plan, quantization.syntax.rans_layout, out));
    }
  }
  if (octree_allowed) {
    out->WriteU8(octree.empty() ? 0 : 1);
    out->WriteBytes(octree.data(), octree.size());
  }
  if (quantization.syntax.adaptive_attributes) {
    out->WriteU8(adaptive.empty() ? 0 : 1);
    if (!adaptive.empty()) {
      out->WriteVarUint(static_cast<uint32_t>(adaptive.size()));
      out->WriteBytes(adaptive.data(), adaptive.size());
    }
  }
  if (adaptive.empty() || draco_buffer.size() > 0) {  // with adaptive attributes, positions only
    out->WriteVarUint(static_cast<uint32_t>(draco_buffer.size()));
    out->WriteBytes(reinterpret_cast<const uint8_t*>(draco_buffer.data()), draco_buffer.size());
  }
  return Status::Ok();
}

// QuantizeGaussianSet on the set's rotations as they are.
Status QuantizeValues(const GaussianQuantization& quantization, GaussianSet* set) {
  std::vector<GroupPlan> plans;
  M4D_RETURN_IF_ERROR(PlanGroups(*set, quantization, false, &plans));
  std::vector<uint32_t> order(set->size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<uint32_t>(i);
  const GroupPlan* rotation_index = nullptr;
  for (GroupPlan& plan : plans) {
    Quantize(order, &plan);
    if (plan.rotation_index) {
      rotation_index = &plan;
      continue;
    }
    // The set's own array; smallest-three rotations go to slots 0..2, composed below.
    size_t stride = plan.stride;
    float* values = const_cast<float*>(plan.source);  // plan.source points into *set
    if (!plan.owned.empty()) {
      values = set->rotations.data();
      stride = 4;
    }
    for (size_t i = 0; i < order.size(); ++i) {
      for (int r = 0; r < plan.components; ++r) {
        const int p = plan.per_component ? r : 0;
        // As the decoder (spec 5.4): one f32 product, one f32 sum.
        const float product = static_cast<float>(plan.q[i * plan.components + r]) * plan.step[p];
        values[i * stride + r] = plan.min[p] + product;
      }
    }
  }
  if (rotation_index != nullptr) {
    for (size_t i = 0; i < order.size(); ++i) {
      ComposeSmallestThree(&set->rotations[4 * i], static_cast<int>(rotation_index->q[i]),
                           &set->rotations[4 * i]);
    }
  }
  return Status::Ok();
}

}  // namespace

Status WriteGaussianSet(const GaussianSet& set, const GaussianQuantization& quantization,
                        ByteWriter* out) {
  if (!CodesCanonicalRotations(set, quantization)) return WriteSet(set, quantization, out);
  GaussianSet canonical = set;
  CanonicalizeRotations(&canonical, nullptr);
  return WriteSet(canonical, quantization, out);
}

Status QuantizeGaussianSet(const GaussianQuantization& quantization, GaussianSet* set) {
  if (!CodesCanonicalRotations(*set, quantization)) return QuantizeValues(quantization, set);
  const std::vector<float> original(set->rotations.begin(), set->rotations.end());
  std::vector<uint8_t> applied;
  CanonicalizeRotations(set, &applied);
  M4D_RETURN_IF_ERROR(QuantizeValues(quantization, set));
  RestoreRotationAxes(applied, original.data(), set);
  return Status::Ok();
}

Status ReconstructGaussianSet(const GaussianSet& set, const GaussianQuantization& quantization,
                              GaussianSet* decoded) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  M4D_RETURN_IF_ERROR(WriteGaussianSet(set, quantization, &writer));
  ByteReader reader(payload.data(), payload.size());
  return ReadGaussianSet(&reader, set.sh_degree, quantization.syntax, kMaxGaussiansPerSet, decoded);
}

}  // namespace m4d
