// m4d_render_bench: time per frame of decoding and rendering with the SDK's GL renderer,
// split by stage, on a synthetic stream: 100k Gaussians at SH degree 3 (a shell of static
// ones around the camera, a dynamic ball in front) over a keyframe and inter frames, drawn
// at 1280x720 from inside the shell. Gaussians are sized like a trained scene's, about half
// their spacing, so that surfaces are covered a few times over. Prints one line per frame
// and the means. With --stream, a real stream instead, seen from a camera of its capture
// (--capture, --camera) with the focal length scaled to the output width.
//
//     m4d_render_bench [--gaussians N] [--frames N] [--width W] [--height H] [--threads T]
//                      [--stream FILE --capture DIR [--camera C]]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "encoder/src/dataset/capture_loader.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "m4d/m4d.h"
#include "m4d/m4d_render.h"

namespace {

using Clock = std::chrono::steady_clock;
using Packets = std::vector<std::vector<uint8_t>>;

struct Options {
  size_t gaussians = 100000;
  int frames = 10;
  uint32_t width = 1280, height = 720;
  int threads = 0;
  std::string stream, capture;
  int camera = -1;  // -1: the capture's held-out camera
};

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// n Gaussians on a sphere (a trained surface's density): scales about half the spacing,
// random orientations, mostly opaque.
m4d::GaussianSet Shell(size_t n, const float centre[3], float radius, uint64_t seed) {
  m4d::GaussianSet set = m4d::SyntheticGaussianSet(n, 3, seed, centre, radius);
  const float spacing = std::sqrt(4.0f * 3.14159265f * radius * radius / static_cast<float>(n));
  const float log_scale = std::log(0.5f * spacing);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      // Reuse the generator's spread (uniform over [-5.5, -3]) as a +-0.4 jitter.
      set.log_scales[3 * i + a] = log_scale + 0.32f * (set.log_scales[3 * i + a] + 4.25f);
    }
    set.opacity_logits[i] = 1.0f + 0.5f * set.opacity_logits[i];
  }
  return set;
}

// One GOP: a keyframe with 80% static and 20% dynamic Gaussians, then moving frames.
bool MakeStream(const Options& o, Packets* packets) {
  m4d::StreamWriterOptions options;
  options.sequence.sh_degree = 3;
  m4d::StreamWriter writer(options);
  const float center[3] = {0, 0, 0}, ball[3] = {0.2f, 0.1f, 1.2f};
  const size_t dynamic = o.gaussians / 5;
  m4d::DecodedFrame recon;
  m4d::Status status = writer.WriteKeyframe(
      Shell(o.gaussians - dynamic, center, 3.0f, 1), Shell(dynamic, ball, 0.6f, 2),
      m4d::SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, 3), &recon);
  for (int f = 1; f < o.frames && status.ok(); ++f) {
    status =
        writer.WriteMotion(m4d::SyntheticMotionGrid(options.sequence.grid, 4 + f, -1, 3, 0.05f));
    std::vector<uint8_t> removed(writer.moved_dynamic_set().size(), 0);
    if (status.ok()) {
      status =
          writer.WriteCompensation(removed, m4d::SyntheticGaussianSet(0, 3, 5, ball, 0.6f), &recon);
    }
  }
  if (!status.ok()) {
    std::fprintf(stderr, "m4d_render_bench: %s\n", status.message().c_str());
    return false;
  }
  const std::vector<uint8_t>& bytes = writer.bytes();
  M4dPacketInfo info;
  for (size_t pos = 0; pos < bytes.size(); pos += info.packet_size) {
    if (m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info) != M4D_OK) return false;
    packets->emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
  }
  return true;
}

// At z = -1.5 inside the shell, looking along +z with a 60 degree horizontal field of view.
M4dRenderCamera BenchCamera(const Options& o) {
  M4dRenderCamera c = {};
  c.width = o.width;
  c.height = o.height;
  c.fx = c.fy = 0.5f * static_cast<float>(o.width) / std::tan(0.5f * 60.0f * 3.14159265f / 180);
  c.cx = 0.5f * static_cast<float>(o.width);
  c.cy = 0.5f * static_cast<float>(o.height);
  c.rotation[0] = c.rotation[4] = c.rotation[8] = 1.0f;
  c.translation[2] = 1.5f;
  c.near_plane = 0.2f;
  return c;
}

bool ReadStream(const std::string& path, int frames, Packets* packets) {
  std::vector<uint8_t> bytes;
  if (!m4d::ReadFileBytes(path, size_t{1} << 32, &bytes).ok()) return false;
  M4dPacketInfo info;
  for (size_t pos = 0; pos < bytes.size(); pos += info.packet_size) {
    if (m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info) != M4D_OK) return false;
    if (static_cast<int>(info.frame_index) >= frames) break;
    packets->emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
  }
  return true;
}

// The capture's camera at the output size: same focal length per pixel of width, centred.
bool CaptureCamera(const Options& o, M4dRenderCamera* c) {
  m4d::Capture capture;
  if (!m4d::LoadCapture(o.capture, m4d::CaptureOptions(), &capture).ok()) return false;
  const int index = o.camera >= 0 ? o.camera : std::max(capture.FirstTestCamera(), 0);
  if (capture.cameras.empty() || index >= static_cast<int>(capture.cameras[0].size())) {
    return false;
  }
  const m4d::Camera& from = capture.cameras[0][index];
  const float scale = static_cast<float>(o.width) / static_cast<float>(from.width);
  *c = BenchCamera(o);
  c->fx = from.fx * scale;
  c->fy = from.fy * scale;
  std::copy(from.rotation, from.rotation + 9, c->rotation);
  std::copy(from.translation, from.translation + 3, c->translation);
  return true;
}

struct Row {
  double decode = 0, copy = 0, project = 0, sort = 0, upload = 0, draw = 0;
  double total() const { return decode + copy + project + sort + upload + draw; }
};

void Print(const char* label, const Row& r, uint32_t visible) {
  std::printf("%6s %9.1f %8.1f %9.1f %7.1f %8.1f %7.1f %8.1f %7.1f %9u\n", label, r.decode, r.copy,
              r.project, r.sort, r.upload, r.draw, r.total(), 1000.0 / r.total(), visible);
}

int Run(const Options& o) {
  Packets packets;
  M4dRenderCamera camera = BenchCamera(o);
  if (!o.stream.empty()) {
    if (!ReadStream(o.stream, o.frames, &packets) || !CaptureCamera(o, &camera)) {
      std::fprintf(stderr, "m4d_render_bench: cannot read %s or the camera of %s\n",
                   o.stream.c_str(), o.capture.c_str());
      return 1;
    }
  } else if (!MakeStream(o, &packets)) {
    return 1;
  }
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* decoder = nullptr;
  M4dRendererSettings render_settings;
  m4d_renderer_default_settings(&render_settings);
  render_settings.threads = o.threads;
  M4dRenderer* renderer = nullptr;
  if (m4d_open(&decoder, &settings) < 0 || m4d_renderer_open(&renderer, &render_settings) < 0) {
    std::fprintf(stderr, "m4d_render_bench: cannot open the decoder or the renderer\n");
    return 1;
  }
  if (o.stream.empty()) {
    std::printf("%zu Gaussians (SH 3), ", o.gaussians);
  } else {
    std::printf("%s, ", o.stream.c_str());
  }
  std::printf("%ux%u, %s\n", o.width, o.height, m4d_renderer_description(renderer));
  std::printf("%6s %9s %8s %9s %7s %8s %7s %8s %7s %9s\n", "frame", "decode ms", "copy ms",
              "project", "sort", "upload", "draw", "total", "fps", "splats");
  Row sum;
  int frames = 0;
  Clock::time_point start = Clock::now();
  for (const std::vector<uint8_t>& p : packets) {
    int r = m4d_send_packet(decoder, p.data(), p.size());
    M4dFrame frame;
    while (r == M4D_ERR_AGAIN || m4d_get_frame(decoder, &frame) == M4D_OK) {
      if (r == M4D_ERR_AGAIN) {
        m4d_get_frame(decoder, &frame);
      }
      Row row;
      row.decode = Ms(start);
      Clock::time_point t = Clock::now();
      m4d_renderer_upload(renderer, &frame, M4D_LAYER_ALL);
      row.copy = Ms(t);
      if (m4d_renderer_draw(renderer, &camera) < 0) {
        std::fprintf(stderr, "m4d_render_bench: %s\n", m4d_renderer_last_error(renderer));
        return 1;
      }
      M4dRenderStats stats;
      m4d_renderer_stats(renderer, &stats);
      row.project = stats.project_ms;
      row.sort = stats.sort_ms;
      row.upload = stats.upload_ms;
      row.draw = stats.draw_ms;
      char label[16];
      std::snprintf(label, sizeof(label), "%u", frame.frame_index);
      Print(label, row, stats.visible);
      for (double Row::*f :
           {&Row::decode, &Row::copy, &Row::project, &Row::sort, &Row::upload, &Row::draw}) {
        sum.*f += row.*f;
      }
      ++frames;
      m4d_frame_unref(&frame);
      if (r == M4D_ERR_AGAIN) r = m4d_send_packet(decoder, p.data(), p.size());
      start = Clock::now();
    }
  }
  if (frames > 0) {
    for (double Row::*f :
         {&Row::decode, &Row::copy, &Row::project, &Row::sort, &Row::upload, &Row::draw}) {
      sum.*f /= frames;
    }
    Print("mean", sum, 0);
  }
  m4d_renderer_close(&renderer);
  m4d_close(&decoder);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("Decode and GL render time per frame, by stage");
  app.add_option("--gaussians", o.gaussians, "Gaussians per frame")
      ->check(CLI::Range(size_t{1000}, size_t{4000000}))
      ->capture_default_str();
  app.add_option("--frames", o.frames, "frames (one GOP)")
      ->check(CLI::Range(1, 300))
      ->capture_default_str();
  app.add_option("--width", o.width, "image width")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  app.add_option("--height", o.height, "image height")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "CPU threads of the renderer (0: all cores)")
      ->check(CLI::Range(0, 256));
  app.add_option("--stream", o.stream, "a stream to render instead of the synthetic one");
  app.add_option("--capture", o.capture, "the stream's capture, for its camera")
      ->needs(app.get_option("--stream"));
  app.add_option("--camera", o.camera, "camera index (default: the held-out one)");
  CLI11_PARSE(app, argc, argv);
  if (!o.stream.empty() && o.capture.empty()) {
    std::fprintf(stderr, "m4d_render_bench: --stream needs --capture\n");
    return 2;
  }
  return Run(o);
}
