// Whole-packet decode through the public API, single thread:
//   InterFrame: one inter frame (MOTION_GRID with the paper's grid 4x32^3 + 4x64^3 + 2x128^3,
//               mostly zero, an APPEARANCE change of every moved Gaussian's colour and a
//               COMPENSATION of 1% of the set) moving 100k dynamic Gaussians with the
//               paper's MLP (10 -> 64 -> 7). Target: <= 10 ms.
//   Keyframe:   a keyframe whose static layer holds 100k Gaussians at SH degree 3.
//               Target: <= 100 ms.
#include <benchmark/benchmark.h>

#include <vector>

#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "m4d/m4d.h"

namespace m4d {
namespace {

using Packets = std::vector<std::vector<uint8_t>>;

Packets Split(const std::vector<uint8_t>& bytes) {
  Packets packets;
  size_t pos = 0;
  M4dPacketInfo info;
  while (pos < bytes.size() &&
         m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info) == M4D_OK) {
    packets.emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
    pos += info.packet_size;
  }
  return packets;
}

// A keyframe (static_count static, dynamic_count dynamic Gaussians) and one inter frame.
Packets MakeStream(size_t static_count, size_t dynamic_count, int sh_degree, bool inter) {
  StreamWriterOptions options;  // the paper's grid and MLP configuration by default
  options.sequence.sh_degree = sh_degree;
  StreamWriter writer(options);
  const float center[3] = {0, 0, 0}, fg_center[3] = {0.1f, 0, 0};
  DecodedFrame recon;
  Status status = writer.WriteKeyframe(
      SyntheticGaussianSet(static_count, sh_degree, 1, center, 3.0f),
      SyntheticGaussianSet(dynamic_count, sh_degree, 2, fg_center, 0.6f),
      SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, 3), &recon);
  if (status.ok() && inter) {
    status = writer.WriteMotion(SyntheticMotionGrid(options.sequence.grid, 4, -1, 1, 0.05f));
    const size_t n = writer.moved_dynamic_set().size();
    std::vector<int32_t> appearance(3 * n);
    for (size_t k = 0; k < appearance.size(); ++k) appearance[k] = static_cast<int32_t>(k % 7) - 3;
    if (status.ok()) status = writer.WriteAppearance(1.0f / 64, appearance);
    std::vector<uint8_t> removed(n, 0);
    for (size_t i = 0; i < n; i += 100) removed[i] = 1;
    const GaussianSet added = SyntheticGaussianSet((n + 99) / 100, sh_degree, 5, fg_center, 0.6f);
    if (status.ok()) status = writer.WriteCompensation(removed, added, &recon);
  }
  if (!status.ok()) return {};
  return Split(writer.bytes());
}

void Send(M4dContext* ctx, const std::vector<uint8_t>& p) {
  m4d_send_packet(ctx, p.data(), p.size());
  M4dFrame frame;
  while (m4d_get_frame(ctx, &frame) == M4D_OK) m4d_frame_unref(&frame);
}

void BM_InterFrameDecode(benchmark::State& state) {
  static const Packets packets = MakeStream(1000, 100000, 3, true);
  if (packets.size() != 7) {
    state.SkipWithError("stream setup failed");
    return;
  }
  M4dSettings s;
  m4d_default_settings(&s);
  M4dContext* ctx = nullptr;
  m4d_open(&ctx, &s);
  for (auto _ : state) {
    state.PauseTiming();
    for (size_t i = 0; i < 4; ++i) Send(ctx, packets[i]);  // back to the keyframe's state
    state.ResumeTiming();
    for (size_t i = 4; i < 7; ++i) Send(ctx, packets[i]);
  }
  state.counters["motion_bytes"] = static_cast<double>(packets[4].size());
  state.counters["appearance_bytes"] = static_cast<double>(packets[5].size());
  state.counters["compensation_bytes"] = static_cast<double>(packets[6].size());
  m4d_close(&ctx);
}
BENCHMARK(BM_InterFrameDecode)->Unit(benchmark::kMillisecond)->Iterations(30);

void BM_KeyframeDecode(benchmark::State& state) {
  const int sh_degree = static_cast<int>(state.range(0));
  const Packets packets = MakeStream(100000, 0, sh_degree, false);
  if (packets.size() != 4) {
    state.SkipWithError("stream setup failed");
    return;
  }
  M4dSettings s;
  m4d_default_settings(&s);
  M4dContext* ctx = nullptr;
  m4d_open(&ctx, &s);
  for (auto _ : state) {
    for (const auto& p : packets) Send(ctx, p);
  }
  state.counters["static_layer_bytes"] = static_cast<double>(packets[1].size());
  m4d_close(&ctx);
}
BENCHMARK(BM_KeyframeDecode)->Arg(3)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace
}  // namespace m4d
