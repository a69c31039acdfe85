// m4d_synth: writes a synthetic M4D stream (random Gaussian sets, sparse smooth motion grids,
// compensation every frame; or the decoding edge cases of --edge-cases) with the reference stream
// writer, decodes the file back with the public C API, and checks frame by frame that the decoder
// reproduces the writer's closed-loop reconstruction. Prints per-frame and per-layer sizes.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "encoder/src/io/atomic_file.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "encoder/src/synthetic/synthetic_edge_cases.h"
#include "m4d/m4d.h"
#include "sdk/src/common/md5.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/decode/frame_hash.h"
#include "tools/existing_output.h"
#include "tools/number_checks.h"
#include "tools/usage_exit.h"

namespace {

struct Options {
  std::string output;
  bool force = false;
  int gops = 3;
  int frames_per_gop = 10;
  int static_count = 20000;
  int dynamic_count = 5000;
  int sh_degree = 3;
  float motion_fraction = 0.05f;
  uint64_t seed = 1;
  std::vector<int> grid;  // resolution, channels per level (empty: the paper's)
  int mlp_layers = 1, mlp_width = 64;
  int bits = 0;      // every Gaussian group's bits (0: the writer's defaults)
  int codebook = 0;  // codebook size of log scales, SH DC and higher SH (0: none; 0.6)
  // How every set codes its attributes but the positions (0.8): the smaller, or always one.
  m4d::AttributeCoding attribute_coding = m4d::AttributeCoding::kSmaller;
  // GOPs after the first are dependent (bitstream 0.3): they keep the static set and change
  // this share of it (removed, and replaced or added) with a STATIC_UPDATE (0: none).
  bool dependent_gops = false;
  float static_change = 0.0f;
  int bitstream_minor = M4D_BITSTREAM_VERSION_MINOR;  // 2: a version 0.2 stream
  // Inter frames after the first of a GOP change the colour of this share of the dynamic
  // Gaussians with an APPEARANCE (bitstream 0.3; 0: none).
  float appearance_fraction = 0.0f;
  // The edge-case content of synthetic_edge_cases.h instead of random dynamic sets, MLPs and
  // motion (its own grid and MLP configuration).
  bool edge_cases = false;
};

// Colour changes of a share of the set (APPEARANCE values): small signed steps, zero elsewhere.
std::vector<int32_t> SyntheticAppearance(size_t n, float share, uint64_t seed) {
  m4d::SyntheticRandom rng(seed);
  std::vector<int32_t> values(3 * n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (rng.Uniform() >= share) continue;
    for (int c = 0; c < 3; ++c) values[3 * i + c] = static_cast<int32_t>(rng.Next() % 81) - 40;
  }
  return values;
}

// Not a power of two: a decoder that adds the value before scaling it gets other floats.
constexpr float kSyntheticAppearanceStep = 0.0123f;

// A dependent keyframe's change of the static set: every k-th Gaussian removed, and a few more
// added than removed (so that both the in-place replacement and the append of 6.4 occur).
m4d::SetChange StaticChange(const m4d::GaussianSet& static_set, float share, int sh_degree,
                            uint64_t seed) {
  m4d::SetChange change;
  change.removed.assign(static_set.size(), 0);
  size_t removed = 0;
  if (share > 0.0f) {
    const size_t k = std::max<size_t>(1, static_cast<size_t>(1.0f / share));
    for (size_t i = seed % k; i < static_set.size(); i += k, ++removed) change.removed[i] = 1;
  }
  const float center[3] = {0, 0, 0};
  change.added =
      m4d::SyntheticGaussianSet(share > 0.0f ? removed + 3 : 0, sh_degree, seed, center, 3.0f);
  return change;
}

// The sequence configuration the options ask for; false (with a message) when out of limits.
bool StreamOptions(const Options& opt, m4d::StreamWriterOptions* wo) {
  wo->sequence.sh_degree = opt.sh_degree;
  wo->sequence.version_minor = opt.bitstream_minor;
  if (opt.dependent_gops && opt.bitstream_minor < 3) {
    std::fprintf(stderr, "m4d_synth: dependent GOPs need bitstream 0.3\n");
    return false;
  }
  if (opt.appearance_fraction > 0.0f && opt.bitstream_minor < 3) {
    std::fprintf(stderr, "m4d_synth: appearance updates need bitstream 0.3\n");
    return false;
  }
  wo->sequence.num_frames = static_cast<uint32_t>(opt.gops * opt.frames_per_gop);
  if (!opt.grid.empty()) {
    if (opt.grid.size() % 2 != 0 || opt.grid.size() > 2 * m4d::kMaxGridLevels) {
      std::fprintf(stderr, "m4d_synth: --grid takes 1 to %d resolution,channels pairs\n",
                   m4d::kMaxGridLevels);
      return false;
    }
    m4d::GridConfig& g = wo->sequence.grid;
    g.num_levels = static_cast<int>(opt.grid.size() / 2);
    for (int l = 0; l < g.num_levels; ++l) {
      g.resolution[l] = opt.grid[2 * l];
      g.channels[l] = opt.grid[2 * l + 1];
      if (g.channels[l] > m4d::kMaxGridChannels) {
        std::fprintf(stderr, "m4d_synth: at most %d channels per level\n", m4d::kMaxGridChannels);
        return false;
      }
    }
    if (g.total_values() > m4d::kMaxGridValues) {
      std::fprintf(stderr, "m4d_synth: the grid has more than %u values\n", m4d::kMaxGridValues);
      return false;
    }
  }
  wo->sequence.mlp.hidden_layers = opt.mlp_layers;
  wo->sequence.mlp.hidden_width = opt.mlp_width;
  if (opt.edge_cases) {
    wo->sequence.grid = m4d::EdgeCaseGridConfig();
    wo->sequence.mlp = m4d::EdgeCaseMlpConfig();
  }
  if (opt.bits > 0) {
    m4d::GaussianQuantization q;
    q.position_bits = q.log_scale_bits = q.rotation_bits = opt.bits;
    q.opacity_bits = q.sh_dc_bits = q.sh_rest_bits = opt.bits;
    wo->quantization = wo->compensation_quantization = q;
  }
  if (opt.codebook > 0) {
    if (opt.bitstream_minor < 6) {
      std::fprintf(stderr, "m4d_synth: codebooks need bitstream 0.6\n");
      return false;
    }
    m4d::GaussianQuantization& q = wo->quantization;
    q.log_scale_codebook = q.sh_dc_codebook = q.sh_rest_codebook = opt.codebook;
    q.codebooks_only_where_they_pay = false;
  }
  if (opt.attribute_coding == m4d::AttributeCoding::kAdaptive && opt.bitstream_minor < 8) {
    std::fprintf(stderr, "m4d_synth: adaptive attributes need bitstream 0.8\n");
    return false;
  }
  wo->quantization.attribute_coding = opt.attribute_coding;
  wo->compensation_quantization.attribute_coding = opt.attribute_coding;
  return true;
}

// A set of dynamic Gaussians: a keyframe's or a compensation's.
m4d::GaussianSet DynamicSet(const Options& opt, size_t n, uint64_t seed) {
  const float fg_center[3] = {0.2f, 0.1f, 0};
  return opt.edge_cases ? m4d::EdgeCaseGaussianSet(n, opt.sh_degree, seed)
                        : m4d::SyntheticGaussianSet(n, opt.sh_degree, seed, fg_center, 0.5f);
}

// The motion of an inter frame; `dynamic_set` is the set it moves.
m4d::FloatMotionGrid Motion(const Options& opt, const m4d::GridConfig& config, uint64_t seed,
                            const m4d::GaussianSet& dynamic_set) {
  return opt.edge_cases ? m4d::EdgeCaseMotionGrid(seed, dynamic_set)
                        : m4d::SyntheticMotionGrid(config, seed, -1.0f, 1.0f, opt.motion_fraction);
}

// Writes the stream and returns the writer's reconstructed hash for each frame.
bool WriteStream(const Options& opt, std::vector<uint8_t>* bytes,
                 std::vector<std::string>* hashes) {
  using namespace m4d;
  StreamWriterOptions wo;
  if (!StreamOptions(opt, &wo)) return false;
  StreamWriter writer(wo);
  const float center[3] = {0, 0, 0};
  std::printf("%6s %4s %12s %12s %10s %10s %12s %10s\n", "frame", "type", "static B", "dynamic B",
              "mlp B", "motion B", "appearance B", "comp B");
  for (int g = 0; g < opt.gops; ++g) {
    const uint64_t seed = opt.seed * 1000 + g;
    GaussianSet bg = SyntheticGaussianSet(opt.static_count, opt.sh_degree, seed, center, 3.0f);
    GaussianSet fg = DynamicSet(opt, opt.dynamic_count, seed + 7);
    MlpWeights mlp = opt.edge_cases
                         ? EdgeCaseMlp()
                         : SyntheticMlp(wo.sequence.grid.feature_count(), wo.sequence.mlp, seed);
    DecodedFrame recon;
    for (int f = 0; f < opt.frames_per_gop; ++f) {
      Status status;
      if (f == 0 && g > 0 && opt.dependent_gops) {
        const SetChange change =
            StaticChange(writer.static_set(), opt.static_change, opt.sh_degree, seed * 5);
        status = writer.WriteDependentKeyframe(change, fg, mlp, &recon);
      } else if (f == 0) {
        status = writer.WriteKeyframe(bg, fg, mlp, &recon);
      } else {
        status = writer.WriteMotion(
            Motion(opt, wo.sequence.grid, seed * 31 + f, writer.moved_dynamic_set()));
        if (status.ok() && opt.appearance_fraction > 0.0f && f > 1) {
          status =
              writer.WriteAppearance(kSyntheticAppearanceStep,
                                     SyntheticAppearance(writer.moved_dynamic_set().size(),
                                                         opt.appearance_fraction, seed * 13 + f));
        }
        if (status.ok()) {
          // Replace about 1% of the dynamic Gaussians each frame.
          const size_t n = writer.moved_dynamic_set().size();
          std::vector<uint8_t> removed(n, 0);
          for (size_t i = f; i < n; i += 100) removed[i] = 1;
          GaussianSet added = DynamicSet(opt, n / 100, seed * 77 + f);
          status = writer.WriteCompensation(removed, added, &recon);
        }
      }
      if (!status.ok()) {
        std::fprintf(stderr, "m4d_synth: %s\n", status.message().c_str());
        return false;
      }
      hashes->push_back(FrameHashHex(recon));
      const auto& b = writer.last_frame_bytes().by_type;
      std::printf("%6u %4s %12zu %12zu %10zu %10zu %12zu %10zu\n", recon.frame_index,
                  f == 0 ? "key" : "inter",
                  b[M4D_PACKET_KEYFRAME_STATIC] + b[M4D_PACKET_SEQUENCE_HEADER] +
                      b[M4D_PACKET_STATIC_UPDATE],
                  b[M4D_PACKET_KEYFRAME_DYNAMIC], b[M4D_PACKET_MLP_WEIGHTS],
                  b[M4D_PACKET_MOTION_GRID], b[M4D_PACKET_APPEARANCE], b[M4D_PACKET_COMPENSATION]);
    }
  }
  *bytes = writer.bytes();
  return true;
}

// Decodes the file with the public API and counts frames whose hash matches the writer's.
int CountMatches(const std::vector<uint8_t>& data, const std::vector<std::string>& hashes,
                 double* ms) {
  M4dSettings s;
  m4d_default_settings(&s);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &s) < 0) return -1;
  int matches = 0;
  size_t frame = 0, pos = 0;
  const auto t0 = std::chrono::steady_clock::now();
  M4dPacketInfo info;
  while (pos < data.size() && m4d_parse_packet_header(&data[pos], data.size() - pos, &info) == 0) {
    if (m4d_send_packet(ctx, &data[pos], info.packet_size) < 0) break;
    pos += info.packet_size;
    M4dFrame f;
    while (m4d_get_frame(ctx, &f) == M4D_OK) {
      uint8_t md5[16];
      m4d_frame_hash(&f, md5);
      if (frame < hashes.size() && m4d::HexDigest(md5) == hashes[frame]) ++matches;
      ++frame;
      m4d_frame_unref(&f);
    }
  }
  *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  m4d_close(&ctx);
  return matches;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{"Write a synthetic M4D stream and verify the decoder reproduces it."};
  app.add_option("-o,--output", opt.output, "stream file to write")->required();
  app.add_option("--gops", opt.gops, "number of GOPs")->check(m4d::Within(1, 1000));
  app.add_option("--frames-per-gop", opt.frames_per_gop, "frames per GOP")
      ->check(m4d::Within(1, 10000));
  app.add_option("--static", opt.static_count, "static Gaussians per keyframe")
      ->check(m4d::Within(0, 1 << 22));
  app.add_option("--dynamic", opt.dynamic_count, "dynamic Gaussians per keyframe")
      ->check(m4d::Within(0, 1 << 21));
  app.add_option("--sh-degree", opt.sh_degree, "SH degree")->check(m4d::Within(0, 3));
  app.add_option("--motion-fraction", opt.motion_fraction,
                 "fraction of the motion grid's box covered by motion")
      ->check(m4d::Within(0.0f, 1.0f));
  app.add_option("--seed", opt.seed, "random seed")->check(m4d::AtLeast(0));
  app.add_option("--grid", opt.grid,
                 "motion grid levels as resolution,channels pairs (default: the paper's 32,4,64,4,"
                 "128,2)")
      ->delimiter(',')
      ->check(m4d::Within(1, 256));
  app.add_option("--mlp-layers", opt.mlp_layers, "hidden layers of the motion MLP")
      ->check(m4d::Within(1, 4));
  app.add_option("--mlp-width", opt.mlp_width, "width of its hidden layers")
      ->check(m4d::Within(1, 256));
  app.add_flag("--dependent-gops", opt.dependent_gops,
               "GOPs after the first keep the static set (bitstream 0.3 dependent keyframes)");
  app.add_option("--static-change", opt.static_change,
                 "with --dependent-gops: share of the static set each dependent keyframe "
                 "replaces, plus 3 Gaussians added (0: no STATIC_UPDATE)")
      ->check(m4d::Within(0.0f, 1.0f));
  app.add_option(
         "--bitstream-minor", opt.bitstream_minor,
         "bitstream minor version to write (2: a 0.2 stream, without dependent GOPs; 3: one "
         "rANS state per symbol block; 4: four-component rotations; 5: no codebooks)")
      ->check(m4d::Within(2, M4D_BITSTREAM_VERSION_MINOR));
  app.add_option("--bits", opt.bits, "bits of every Gaussian attribute group (0: defaults)")
      ->check(m4d::Within(0, 24));
  app.add_option("--codebook", opt.codebook,
                 "codebook size of the keyframes' log scales, SH DC and higher SH, used in every "
                 "set of at least 32 Gaussians per entry (0: none; bitstream 0.6)")
      ->check(m4d::Within(0, 4096));
  const std::map<std::string, m4d::AttributeCoding> codings = {
      {"smaller", m4d::AttributeCoding::kSmaller},
      {"draco", m4d::AttributeCoding::kDraco},
      {"adaptive", m4d::AttributeCoding::kAdaptive}};
  app.add_option("--attribute-coding", opt.attribute_coding,
                 "how every set codes its attributes but the positions: the smaller of Draco and "
                 "adaptive attributes (bitstream 0.8), or always one of them")
      ->transform(CLI::CheckedTransformer(codings, CLI::ignore_case));
  app.add_option("--appearance-fraction", opt.appearance_fraction,
                 "share of the dynamic Gaussians whose colour an APPEARANCE changes in each inter "
                 "frame but a GOP's first (0: none; bitstream 0.3)")
      ->check(m4d::Within(0.0f, 1.0f));
  app.add_flag("--edge-cases", opt.edge_cases,
               "dynamic sets, MLPs and motion made of the decoding edge cases of spec 5.4 and "
               "6.3 (its own grid and MLP; --motion-fraction has no effect)")
      ->excludes("--grid", "--mlp-layers", "--mlp-width");
  app.add_flag("-f,--force", opt.force, "replace an existing stream (else refused)");
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  const m4d::Status may_write = m4d::RefuseExistingOutput(opt.output, opt.force);
  if (!may_write.ok()) {
    std::fprintf(stderr, "m4d_synth: %s\n", may_write.message().c_str());
    return 2;
  }

  std::vector<uint8_t> bytes;
  std::vector<std::string> hashes;
  const auto t0 = std::chrono::steady_clock::now();
  if (!WriteStream(opt, &bytes, &hashes)) return 1;
  const double write_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const m4d::Status written = m4d::WriteFileAtomically(opt.output, bytes.data(), bytes.size());
  if (!written.ok()) {
    std::fprintf(stderr, "m4d_synth: %s\n", written.message().c_str());
    return 1;
  }

  double decode_ms = 0;
  const int matches = CountMatches(bytes, hashes, &decode_ms);
  std::printf("\n%-28s %s\n", "stream", opt.output.c_str());
  std::printf("%-28s %zu bytes (%.1f KB/frame)\n", "size", bytes.size(),
              bytes.size() / 1000.0 / static_cast<double>(hashes.size()));
  std::printf("%-28s %.1f ms\n", "write (incl. closed loop)", write_ms);
  std::printf("%-28s %.1f ms (%.2f ms/frame)\n", "decode", decode_ms,
              decode_ms / static_cast<double>(hashes.size()));
  std::printf("%-28s %d / %zu frames\n", "hash match writer/decoder", matches, hashes.size());
  return matches == static_cast<int>(hashes.size()) ? 0 : 1;
}
