#include "encoder/src/pipeline/rate_points.h"

#include <cmath>
#include <cstdio>

namespace m4d {
namespace {

GaussianQuantization Bits(int position, int scale, int rotation, int opacity, int color, int sh) {
  GaussianQuantization q;
  q.position_bits = position;
  q.log_scale_bits = scale;
  q.rotation_bits = rotation;
  q.opacity_bits = opacity;
  q.sh_dc_bits = color;
  q.sh_rest_bits = sh;
  return q;
}

// Codebook sizes of the log scales, SH DC and higher SH (bitstream 0.6; 0: scalar values).
GaussianQuantization Codebooks(GaussianQuantization q, int scale, int color, int sh) {
  q.log_scale_codebook = scale;
  q.sh_dc_codebook = color;
  q.sh_rest_codebook = sh;
  return q;
}

// Rotations coded in their canonical form (one bit fewer for the same step).
GaussianQuantization Canonical(GaussianQuantization q) {
  q.canonical_rotations = true;
  return q;
}

RatePointSettings Point(const char* name, double lambda_2, float gradient,
                        const GaussianQuantization& keyframe,
                        const GaussianQuantization& compensation) {
  RatePointSettings p;
  p.name = name;
  p.motion_rate_weight = lambda_2;
  p.replication_gradient = gradient;
  p.keyframe = keyframe;
  p.compensation = compensation;
  return p;
}

}  // namespace

const std::vector<RatePointSettings>& RatePoints() {
  // Each point trades quality for bytes in three places. lambda_2 weighs the motion grid's bits
  // (the paper's set, which at 200 motion steps spends what 400 steps did); tau_g, the replication
  // gradient, makes fewer compensation candidates as it rises, and most replicas only refine what
  // the moved set already shows; the keyframe bits and codebooks size the keyframes. Compensation
  // has bits of its own, coarser than the keyframes' except at r1, whose keyframes are trained for
  // theirs: a compensated Gaussian lives a GOP at most, and the motion moves it by more than a fine
  // step anyway. Each group's keyframe bits sit where one bit less costs more quality than its
  // bytes are worth (the higher SH need enough levels to keep one near zero). Rotations are coded
  // as their three smallest components, one bit below four components for the same error, and
  // canonical only at r1, where the keyframes trained for them gain (at the other points a later
  // GOP of the default scene lost quality). Codebooks are offered where they paid; the writer
  // keeps one only where it pays on the content. Evidence:
  // docs/results/2026-11-30-readme-notebook.md ("A quantization level at zero", "Smallest-three
  // rotations (bitstream 0.5)", "Codebooks (bitstream 0.6)", "r1's keyframe bits", "Canonical
  // rotations", "r1 at 6 bytes per Gaussian", "Faster inter frames") and
  // docs/results/2026-11-30-comment-measurements.md.
  static const std::vector<RatePointSettings> kPoints = {
      Point("r1", 5e-4, 4e-3f, Canonical(Codebooks(Bits(10, 5, 4, 5, 5, 3), 0, 1024, 2)),
            Canonical(Bits(11, 5, 5, 5, 5, 3))),
      Point("r2", 3e-4, 2e-3f, Codebooks(Bits(13, 6, 7, 6, 6, 3), 0, 0, 64),
            Bits(12, 6, 7, 6, 6, 3)),
      Point("r3", 2e-4, 1e-3f, Codebooks(Bits(14, 7, 7, 7, 7, 3), 0, 0, 64),
            Bits(12, 6, 7, 6, 6, 3)),
      Point("r4", 1e-4, 7e-4f, Codebooks(Bits(14, 7, 7, 7, 7, 4), 0, 0, 256),
            Bits(13, 7, 8, 7, 7, 3)),
      Point("r5", 5e-5, 5e-4f, Bits(16, 8, 9, 8, 8, 5), Bits(14, 7, 8, 7, 7, 4)),
  };
  return kPoints;
}

Status FindRatePoint(const std::string& name, RatePointSettings* point) {
  for (const RatePointSettings& p : RatePoints()) {
    if (p.name == name) {
      *point = p;
      return Status::Ok();
    }
  }
  return Status(M4D_ERR_INVALID_ARG, "unknown rate point '" + name + "' (r1..r5)");
}

RatePointSettings RatePointForLambda(double lambda_2) {
  const std::vector<RatePointSettings>& points = RatePoints();
  RatePointSettings nearest = points.front();
  if (!(lambda_2 > 0)) {
    nearest = points.back();  // no rate term: the finest point
  } else {
    double best = INFINITY;
    for (const RatePointSettings& p : points) {
      const double distance = std::fabs(std::log(lambda_2 / p.motion_rate_weight));
      if (distance < best) {
        best = distance;
        nearest = p;
      }
    }
  }
  nearest.motion_rate_weight = lambda_2;
  return nearest;
}

void ApplyRatePoint(const RatePointSettings& point, EncoderOptions* options) {
  options->motion.rate_weight = point.motion_rate_weight;
  options->compensation_thresholds.gradient = point.replication_gradient;
  options->quantization = point.keyframe;
  options->keyframe_rate_weight = point.keyframe_rate_weight;
  options->compensation_quantization = point.compensation;
}

std::vector<KeyframeBitsCandidate> KeyframeBitsCandidates(const std::string& name) {
  const std::vector<RatePointSettings>& points = RatePoints();
  std::vector<KeyframeBitsCandidate> candidates;
  for (auto p = points.rbegin(); p != points.rend(); ++p) {
    if (p->name == name || !candidates.empty()) candidates.push_back({p->name, p->keyframe});
  }
  return candidates;
}

std::string QuantizationName(const GaussianQuantization& q) {
  char name[64];
  std::snprintf(name, sizeof(name), "%d/%d/%d/%d/%d/%d", q.position_bits, q.log_scale_bits,
                q.rotation_bits, q.opacity_bits, q.sh_dc_bits, q.sh_rest_bits);
  if (q.log_scale_codebook == 0 && q.sh_dc_codebook == 0 && q.sh_rest_codebook == 0) return name;
  char codebooks[48];
  std::snprintf(codebooks, sizeof(codebooks), " codebooks %d/%d/%d", q.log_scale_codebook,
                q.sh_dc_codebook, q.sh_rest_codebook);
  return name + std::string(codebooks);
}

}  // namespace m4d
