// m4d_play: decodes an M4D stream and renders it with the SDK's OpenGL ES renderer along a
// camera path, into PNG frames and/or an MP4, printing decode and render time per frame.
//
// Camera paths: a camera of the stream's capture (--capture DIR [--camera N]), an orbit around
// the dynamic layer (--orbit), or a file of poses (--poses FILE: per output frame one line
// "fx fy cx cy r00 r01 r02 r10 r11 r12 r20 r21 r22 tx ty tz", world to camera, OpenCV axes;
// the last pose repeats). Layers: --layers all|static|dynamic (foreground only, background
// only); --background-ply FILE or --background-stream FILE replaces the static layer by a
// Gaussian PLY or by another stream's first static layer.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "encoder/src/dataset/capture_loader.h"
#include "encoder/src/image/image.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/png_io.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/video/video_writer.h"
#include "m4d/m4d.h"
#include "m4d/m4d_render.h"
#include "sdk/src/layers/gaussian_views.h"
#include "tools/existing_output.h"
#include "tools/number_checks.h"
#include "tools/usage_exit.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string stream;
  std::string png_dir, mp4;
  std::string capture;
  int camera = -1;
  bool orbit = false;
  float orbit_degrees = 2.0f;   // per frame
  float orbit_distance = 0.0f;  // 0: three times the dynamic layer's spread
  // The world's up direction; empty: the stream's up_axis, or -y (OpenCV's camera axes, which
  // COLMAP worlds often follow) when the stream does not state one.
  std::vector<float> orbit_up;
  std::string poses;
  int width = 0, height = 0;  // 0: the capture camera's size, else 1280x720
  std::string layers = "all";
  std::string background_ply, background_stream;
  std::vector<float> background = {0, 0, 0};
  int frames = 0;  // 0: all
  double fps = 0;  // 0: the stream's own frame rate
  int sh_degree = 3;
  bool force = false;  // replace existing PNG frames and MP4
};

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

int Fail(const std::string& message) {
  std::fprintf(stderr, "m4d_play: %s\n", message.c_str());
  return 1;
}

void LogToStderr(void*, int level, const char* message) {
  if (level <= M4D_LOG_WARNING) std::fprintf(stderr, "m4d: %s\n", message);
}

// Splits a file into packets. A damaged header is skipped to the next header (the decoder,
// flushed by nothing here, then waits for its next SEQUENCE_HEADER); the first damage is
// reported in *error, and a file with no packet at all fails.
bool ReadPackets(const std::string& path, std::vector<std::vector<uint8_t>>* packets,
                 std::string* error) {
  std::vector<uint8_t> bytes;
  const m4d::Status status = m4d::ReadFileBytes(path, size_t{1} << 34, &bytes);
  if (!status.ok()) {
    *error = status.message();
    return false;
  }
  M4dPacketInfo info;
  size_t pos = 0;
  while (pos < bytes.size()) {
    const int r = m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info);
    if (r == M4D_OK) {
      packets->emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
      pos += info.packet_size;
      continue;
    }
    if (error->empty()) {
      *error = path +
               (r == M4D_ERR_AGAIN ? ": truncated: the stream ends inside a packet at byte "
                                   : ": damaged packet header at byte ") +
               std::to_string(pos);
    }
    if (r == M4D_ERR_AGAIN) break;
    size_t skip = 0;
    const int found = m4d_find_packet(&bytes[pos + 1], bytes.size() - pos - 1, &skip, &info);
    pos = (found == M4D_OK || info.packet_size > 0) ? pos + 1 + skip : bytes.size();
  }
  return packets->size() > 0;  // play what survives the damage
}

// The first static layer of another stream.
bool StreamBackground(const std::string& path, m4d::GaussianSet* set, std::string* error) {
  std::vector<std::vector<uint8_t>> packets;
  if (!ReadPackets(path, &packets, error)) return false;
  M4dSettings settings;
  m4d_default_settings(&settings);
  settings.layers = M4D_LAYER_STATIC;
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) != M4D_OK) return false;
  bool found = false;
  for (const auto& p : packets) {
    const int r = m4d_send_packet(ctx, p.data(), p.size());
    M4dFrame frame;
    if ((r == M4D_OK || r == M4D_ERR_AGAIN) && m4d_get_frame(ctx, &frame) == M4D_OK) {
      *set = m4d::GaussianSet();
      set->sh_degree = static_cast<int>(frame.static_layer.sh_degree);
      found = m4d::AppendLayer(frame.static_layer, set).ok();
      m4d_frame_unref(&frame);
      break;
    }
  }
  m4d_close(&ctx);
  if (!found) *error = path + ": no frame decoded";
  return found;
}

// A pinhole camera of the output size looking from `eye` at `target` (y down in the image).
M4dRenderCamera LookAt(int width, int height, float focal, const float eye[3],
                       const float target[3], const float world_up[3]) {
  M4dRenderCamera c = {};
  c.width = static_cast<uint32_t>(width);
  c.height = static_cast<uint32_t>(height);
  c.fx = c.fy = focal;
  c.cx = 0.5f * width;
  c.cy = 0.5f * height;
  float z[3], len = 0;
  for (int a = 0; a < 3; ++a) {
    z[a] = target[a] - eye[a];
    len += z[a] * z[a];
  }
  len = std::sqrt(len);
  for (float& v : z) v /= len;
  // x = z cross up, then y = z cross x = (z.up) z - up: image y (down) is the world's down.
  const float* up = world_up;
  float x[3] = {z[1] * up[2] - z[2] * up[1], z[2] * up[0] - z[0] * up[2],
                z[0] * up[1] - z[1] * up[0]};
  float xl = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (float& v : x) v /= xl;
  const float y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2],
                      z[0] * x[1] - z[1] * x[0]};
  for (int a = 0; a < 3; ++a) {
    c.rotation[a] = x[a];
    c.rotation[3 + a] = y[a];
    c.rotation[6 + a] = z[a];
  }
  for (int r = 0; r < 3; ++r) {
    c.translation[r] = -(c.rotation[3 * r] * eye[0] + c.rotation[3 * r + 1] * eye[1] +
                         c.rotation[3 * r + 2] * eye[2]);
  }
  c.near_plane = 0.05f;
  return c;
}

// The camera path: one camera per output frame (computed lazily for the orbit).
class CameraPath {
 public:
  bool Init(const Options& o, std::string* error) {
    options_ = o;
    width_ = o.width > 0 ? o.width : 1280;
    height_ = o.height > 0 ? o.height : 720;
    if (!o.capture.empty()) return InitCapture(o, error);
    if (!o.poses.empty()) return InitPoses(o, error);
    return true;  // orbit, set up from the first frame
  }

  // up_axis: the stream's (M4dUpAxis), used when --orbit-up did not say.
  M4dRenderCamera At(int index, const M4dFrame& frame, int up_axis) {
    if (!fixed_.empty()) return fixed_[std::min<size_t>(index, fixed_.size() - 1)];
    if (options_.orbit_up.empty()) options_.orbit_up = StreamUp(up_axis);
    if (!orbit_ready_) SetUpOrbit(frame);
    const float angle = options_.orbit_degrees * 3.14159265f / 180.0f * index;
    // A circle in the plane through the centre perpendicular to `up`, lifted by 0.3 distance.
    const float* up = options_.orbit_up.data();
    float a[3], b[3];
    Perpendiculars(up, a, b);
    float eye[3];
    for (int k = 0; k < 3; ++k) {
      eye[k] =
          centre_[k] + distance_ * (std::sin(angle) * a[k] - std::cos(angle) * b[k] + 0.3f * up[k]);
    }
    return LookAt(width_, height_, 0.9f * width_, eye, centre_, up);
  }

 private:
  bool InitCapture(const Options& o, std::string* error) {
    m4d::Capture capture;
    const m4d::Status status = m4d::LoadCapture(o.capture, m4d::CaptureOptions(), &capture);
    if (!status.ok()) {
      *error = status.message();
      return false;
    }
    const int index = o.camera >= 0 ? o.camera : std::max(capture.FirstTestCamera(), 0);
    if (capture.cameras.empty() || index >= static_cast<int>(capture.cameras[0].size())) {
      *error = "camera " + std::to_string(index) + " not in " + o.capture;
      return false;
    }
    for (const std::vector<m4d::Camera>& row : capture.cameras) {
      const m4d::Camera& from = row[index];
      const float scale = o.width > 0 ? static_cast<float>(o.width) / from.width : 1.0f;
      M4dRenderCamera c = {};
      c.width = static_cast<uint32_t>(o.width > 0 ? o.width : from.width);
      c.height = static_cast<uint32_t>(o.height > 0 ? o.height : from.height);
      c.fx = from.fx * scale;
      c.fy = from.fy * scale;
      c.cx = from.cx * scale + 0.5f * (c.width - from.width * scale);
      c.cy = from.cy * scale + 0.5f * (c.height - from.height * scale);
      std::copy(from.rotation, from.rotation + 9, c.rotation);
      std::copy(from.translation, from.translation + 3, c.translation);
      c.near_plane = from.near_plane;
      fixed_.push_back(c);
    }
    return true;
  }

  bool InitPoses(const Options& o, std::string* error) {
    std::ifstream file(o.poses);
    if (!file) {
      *error = "cannot read " + o.poses + ": " + std::strerror(errno);
      return false;
    }
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream in(line);
      M4dRenderCamera c = {};
      c.width = static_cast<uint32_t>(width_);
      c.height = static_cast<uint32_t>(height_);
      c.near_plane = 0.05f;
      in >> c.fx >> c.fy >> c.cx >> c.cy;
      for (float& r : c.rotation) in >> r;
      for (float& t : c.translation) in >> t;
      if (!in) {
        *error = o.poses + ":" + std::to_string(number) + ": expected 16 numbers";
        return false;
      }
      fixed_.push_back(c);
    }
    if (fixed_.empty()) *error = o.poses + ": no poses";
    return !fixed_.empty();
  }

  // Two unit vectors perpendicular to n (unit) and to each other.
  static void Perpendiculars(const float* n, float a[3], float b[3]) {
    const float helper[3] = {std::fabs(n[0]) < 0.9f ? 1.0f : 0.0f,
                             std::fabs(n[0]) < 0.9f ? 0.0f : 1.0f, 0.0f};
    a[0] = n[1] * helper[2] - n[2] * helper[1];
    a[1] = n[2] * helper[0] - n[0] * helper[2];
    a[2] = n[0] * helper[1] - n[1] * helper[0];
    const float len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) a[k] /= len;
    b[0] = n[1] * a[2] - n[2] * a[1];
    b[1] = n[2] * a[0] - n[0] * a[2];
    b[2] = n[0] * a[1] - n[1] * a[0];
  }

  static std::vector<float> StreamUp(int up_axis) {
    std::vector<float> up = {0, -1, 0};  // not stated: OpenCV's axes
    if (up_axis >= M4D_UP_POS_X && up_axis <= M4D_UP_NEG_Z) {
      up = {0, 0, 0};
      up[(up_axis - 1) / 2] = up_axis % 2 == 1 ? 1.0f : -1.0f;
    }
    return up;
  }

  // The orbit circles the mean of the dynamic layer (or of everything) at three times its
  // spread.
  void SetUpOrbit(const M4dFrame& frame) {
    const M4dGaussians& g = frame.dynamic_layer.count ? frame.dynamic_layer : frame.static_layer;
    double sum[3] = {0, 0, 0}, sq = 0;
    for (uint32_t i = 0; i < g.count; ++i) {
      for (int a = 0; a < 3; ++a) sum[a] += g.positions[3 * i + a];
    }
    for (int a = 0; a < 3; ++a) centre_[a] = g.count ? static_cast<float>(sum[a] / g.count) : 0;
    for (uint32_t i = 0; i < g.count; ++i) {
      for (int a = 0; a < 3; ++a) {
        const double d = g.positions[3 * i + a] - centre_[a];
        sq += d * d;
      }
    }
    const float spread = g.count ? static_cast<float>(std::sqrt(sq / g.count)) : 1.0f;
    distance_ = options_.orbit_distance > 0 ? options_.orbit_distance : 3.0f * spread;
    orbit_ready_ = true;
  }

  Options options_;
  int width_ = 1280, height_ = 720;
  std::vector<M4dRenderCamera> fixed_;
  bool orbit_ready_ = false;
  float centre_[3] = {0, 0, 0};
  float distance_ = 1.0f;
};

struct Totals {
  double decode = 0, render = 0;
  int frames = 0;
};

class Player {
 public:
  int Run(const Options& o) {
    std::string error;
    std::vector<std::vector<uint8_t>> packets;
    if (!ReadPackets(o.stream, &packets, &error)) return Fail(error);
    // Damage is reported and played through (the decoder resumes at the next GOP), and the
    // exit status says it happened.
    bool damaged = !error.empty();
    if (damaged) std::fprintf(stderr, "m4d_play: %s\n", error.c_str());
    options_ = o;
    if (!path_.Init(o, &error)) return Fail(error);
    if (!OpenDecoder(o, &error) || !OpenRenderer(o, &error)) return Fail(error);
    std::printf("%6s %10s %10s %10s %8s %8s %8s %9s\n", "frame", "decode ms", "render ms",
                "project", "sort", "upload", "draw", "splats");
    Clock::time_point start = Clock::now();
    for (const std::vector<uint8_t>& p : packets) {
      int r = m4d_send_packet(decoder_, p.data(), p.size());
      if (r == M4D_ERR_AGAIN) {
        if (!TakeFrames(&start, &error)) return Fail(error);
        r = m4d_send_packet(decoder_, p.data(), p.size());
      }
      if (r < 0 && r != M4D_ERR_AGAIN) {
        std::fprintf(stderr, "m4d_play: packet rejected: %s\n", m4d_last_error(decoder_));
        damaged = true;
      }
      if (!TakeFrames(&start, &error)) return Fail(error);
      if (Done()) break;
    }
    if (!Finish(&error)) return Fail(error);
    if (totals_.frames == 0) return Fail("no frame decoded");
    return damaged ? 1 : 0;
  }

  ~Player() {
    m4d_renderer_close(&renderer_);
    m4d_close(&decoder_);
    video_.reset();
    // An MP4 is renamed into place only once finished: a failed run leaves none.
    if (!options_.mp4.empty()) std::remove(PartialMp4().c_str());
  }

 private:
  // Beside the MP4, with its extension (FFmpeg picks the container by it).
  std::string PartialMp4() const {
    const std::filesystem::path mp4(options_.mp4);
    return (mp4.parent_path() / (".partial." + mp4.filename().string())).string();
  }

  bool Done() const { return options_.frames > 0 && totals_.frames >= options_.frames; }

  bool OpenDecoder(const Options& o, std::string* error) {
    M4dSettings settings;
    m4d_default_settings(&settings);
    settings.layers = o.layers == "static"    ? M4D_LAYER_STATIC
                      : o.layers == "dynamic" ? M4D_LAYER_DYNAMIC
                                              : M4D_LAYER_ALL;
    settings.logger.callback = LogToStderr;
    if (m4d_open(&decoder_, &settings) != M4D_OK) {
      *error = "cannot open the decoder";
      return false;
    }
    if (!o.background_ply.empty()) {
      const m4d::Status status = m4d::ReadGaussianPly(o.background_ply, &background_);
      if (!status.ok()) {
        *error = status.message();
        return false;
      }
    } else if (!o.background_stream.empty()) {
      if (!StreamBackground(o.background_stream, &background_, error)) return false;
    } else {
      return true;
    }
    const M4dGaussians view = m4d::GaussianView(background_);
    if (m4d_set_background(decoder_, &view) != M4D_OK) {
      *error = std::string("background rejected: ") + m4d_last_error(decoder_);
      return false;
    }
    return true;
  }

  bool OpenRenderer(const Options& o, std::string* error) {
    M4dRendererSettings settings;
    m4d_renderer_default_settings(&settings);
    settings.sh_degree = o.sh_degree;
    std::copy_n(o.background.begin(), 3, settings.background);
    settings.logger.callback = LogToStderr;
    if (m4d_renderer_open(&renderer_, &settings) != M4D_OK) {
      *error = "no OpenGL ES renderer (EGL or OSMesa) on this machine";
      return false;
    }
    std::printf("%s: rendering with %s\n", options_.stream.c_str(),
                m4d_renderer_description(renderer_));
    return true;
  }

  bool TakeFrames(Clock::time_point* start, std::string* error) {
    M4dFrame frame;
    while (!Done() && m4d_get_frame(decoder_, &frame) == M4D_OK) {
      const double decode_ms = Ms(*start);
      const bool ok = RenderFrame(frame, decode_ms, error);
      m4d_frame_unref(&frame);
      if (!ok) return false;
      *start = Clock::now();
    }
    return true;
  }

  bool RenderFrame(const M4dFrame& frame, double decode_ms, std::string* error) {
    const Clock::time_point start = Clock::now();
    const M4dRenderCamera camera = path_.At(totals_.frames, frame, StreamUpAxis());
    std::vector<uint8_t> rgb(static_cast<size_t>(camera.width) * camera.height * 3);
    if (m4d_renderer_upload(renderer_, &frame, M4D_LAYER_ALL) != M4D_OK ||
        m4d_renderer_draw(renderer_, &camera) != M4D_OK ||
        m4d_renderer_read_rgb(renderer_, rgb.data(), rgb.size()) != M4D_OK) {
      *error = m4d_renderer_last_error(renderer_);
      return false;
    }
    const double render_ms = Ms(start);
    M4dRenderStats stats;
    m4d_renderer_stats(renderer_, &stats);
    std::printf("%6u %10.1f %10.1f %10.1f %8.1f %8.1f %8.1f %9u\n", frame.frame_index, decode_ms,
                render_ms, stats.project_ms, stats.sort_ms, stats.upload_ms, stats.draw_ms,
                stats.visible);
    totals_.decode += decode_ms;
    totals_.render += render_ms;
    ++totals_.frames;
    return Write(frame.frame_index, camera, rgb, error);
  }

  bool Write(uint32_t index, const M4dRenderCamera& camera, const std::vector<uint8_t>& rgb,
             std::string* error) {
    m4d::Image image(static_cast<int>(camera.width), static_cast<int>(camera.height), 3);
    for (size_t i = 0; i < rgb.size(); ++i) image.pixels[i] = rgb[i] / 255.0f;
    m4d::Status status;
    if (!options_.png_dir.empty()) {
      char name[32];
      std::snprintf(name, sizeof(name), "/frame_%05u.png", index);
      const std::string path = options_.png_dir + name;
      // The folder is created with the first frame: a run that renders nothing leaves nothing.
      if (totals_.frames == 1) status = m4d::CheckOutputPath(path);
      if (status.ok()) status = m4d::WritePng(path, image);
    }
    if (status.ok() && !options_.mp4.empty()) {
      if (!video_) {
        m4d::VideoWriterOptions video;
        video.fps = options_.fps > 0 ? options_.fps : StreamFps();
        status = m4d::VideoWriter::Open(PartialMp4(), image.width & ~1, image.height & ~1, video,
                                        &video_);
      }
      if (status.ok()) status = video_->Write(EvenCrop(image));
    }
    if (!status.ok()) *error = status.message();
    return status.ok();
  }

  // 4:2:0 video needs even sizes.
  static m4d::Image EvenCrop(const m4d::Image& image) {
    if (image.width % 2 == 0 && image.height % 2 == 0) return image;
    m4d::Image out(image.width & ~1, image.height & ~1, 3);
    for (int y = 0; y < out.height; ++y) std::copy_n(image.row(y), out.row_size(), out.row(y));
    return out;
  }

  bool Finish(std::string* error) {
    if (video_) {
      m4d::Status status = video_->Finish();
      if (status.ok() && std::rename(PartialMp4().c_str(), options_.mp4.c_str()) != 0) {
        status = m4d::Status(M4D_ERR_INVALID_ARG,
                             "cannot write " + options_.mp4 + ": " + std::strerror(errno));
      }
      if (!status.ok()) {
        *error = status.message();
        return false;
      }
    }
    if (totals_.frames == 0) {
      *error = "no frame decoded";
      return false;
    }
    std::printf("\n%d frames: decode %.1f ms, render %.1f ms per frame (%.1f frames/s)\n",
                totals_.frames, totals_.decode / totals_.frames, totals_.render / totals_.frames,
                1000.0 * totals_.frames / (totals_.decode + totals_.render));
    if (!options_.png_dir.empty()) std::printf("PNG frames in %s\n", options_.png_dir.c_str());
    if (video_) std::printf("video %s (%s)\n", options_.mp4.c_str(), video_->codec_name().c_str());
    return true;
  }

  // The up axis the stream states (M4D_UP_UNKNOWN before 0.9), read once a frame is decoded.
  int StreamUpAxis() const {
    M4dStreamInfo info;
    return m4d_get_stream_info(decoder_, &info) == M4D_OK ? static_cast<int>(info.up_axis) : 0;
  }

  // The frame rate the stream declares (its SEQUENCE_HEADER), read once a frame is decoded.
  double StreamFps() const {
    M4dStreamInfo info;
    if (m4d_get_stream_info(decoder_, &info) != M4D_OK || info.fps_den == 0) return 30;
    return static_cast<double>(info.fps_num) / info.fps_den;
  }

  Options options_;
  CameraPath path_;
  M4dContext* decoder_ = nullptr;
  M4dRenderer* renderer_ = nullptr;
  m4d::GaussianSet background_;
  std::unique_ptr<m4d::VideoWriter> video_;
  Totals totals_;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("Decode an M4D stream and render it along a camera path (PNG frames, MP4)");
  app.add_option("stream", o.stream, "the stream")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--png-dir", o.png_dir, "write frame_NNNNN.png here (created if missing)");
  app.add_option("--mp4", o.mp4, "write an MP4 (H.264 when FFmpeg has it)");
  auto* capture = app.add_option("--capture", o.capture, "camera path: a camera of this capture");
  app.add_option("--camera", o.camera, "the capture's camera (default: its held-out one)")
      ->needs(capture);
  auto* orbit = app.add_flag("--orbit", o.orbit, "camera path: an orbit around the foreground");
  app.add_option("--orbit-degrees", o.orbit_degrees, "orbit step per frame")->capture_default_str();
  app.add_option("--orbit-distance", o.orbit_distance, "orbit radius (0: 3x the spread)")
      ->check(m4d::AtLeast(0));
  app.add_option("--orbit-up", o.orbit_up,
                 "the world's up direction, x y z (default: the axis the stream states, else "
                 "0 -1 0, OpenCV's y down)")
      ->expected(3);
  auto* poses = app.add_option("--poses", o.poses, "camera path: a file of poses, one per line")
                    ->check(CLI::ExistingFile);
  capture->excludes(orbit)->excludes(poses);
  orbit->excludes(poses);
  app.add_option("--width", o.width, "output width (default: the capture's, else 1280)")
      ->check(m4d::Within(16, 8192));
  app.add_option("--height", o.height, "output height (default: the capture's, else 720)")
      ->check(m4d::Within(16, 8192));
  app.add_option("--layers", o.layers, "all, static (background only), dynamic (foreground only)")
      ->check(CLI::IsMember({"all", "static", "dynamic"}))
      ->capture_default_str();
  auto* ply = app.add_option("--background-ply", o.background_ply,
                             "replace the static layer by this Gaussian PLY")
                  ->check(CLI::ExistingFile);
  app.add_option("--background-stream", o.background_stream,
                 "replace the static layer by another stream's first one")
      ->check(CLI::ExistingFile)
      ->excludes(ply);
  app.add_option("--background-colour", o.background, "colour behind the splats, r g b in 0..1")
      ->expected(3)
      ->check(m4d::Within(0.0f, 1.0f));
  app.add_option("--frames", o.frames, "frames to play (0: all)")->check(m4d::AtLeast(0));
  app.add_option("--fps", o.fps, "frame rate of the MP4 (default: the stream's)")
      ->check(m4d::Within(1.0, 240.0));
  app.add_option("--sh-degree", o.sh_degree, "largest SH degree evaluated")
      ->check(m4d::Within(0, 3))
      ->capture_default_str();
  app.add_flag("-f,--force", o.force, "replace existing PNG frames and MP4 (else refused)");
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  if (o.png_dir.empty() && o.mp4.empty()) {
    std::fprintf(stderr, "m4d_play: nothing to write: give --png-dir and/or --mp4\n");
    return 2;
  }
  m4d::Status may_write = m4d::RefuseExistingOutput(o.mp4, o.force || o.mp4.empty());
  if (may_write.ok() && !o.png_dir.empty()) {
    may_write = m4d::RefuseExistingFrames(o.png_dir, "png", 0, UINT32_MAX, o.force);
  }
  if (!may_write.ok()) {
    std::fprintf(stderr, "m4d_play: %s\n", may_write.message().c_str());
    return 2;
  }
  if (!o.orbit_up.empty()) {
    const float up_length =
        std::sqrt(o.orbit_up[0] * o.orbit_up[0] + o.orbit_up[1] * o.orbit_up[1] +
                  o.orbit_up[2] * o.orbit_up[2]);
    if (!(up_length > 1e-6f)) {
      std::fprintf(stderr, "m4d_play: --orbit-up must not be zero\n");
      return 2;
    }
    for (float& v : o.orbit_up) v /= up_length;
  }
  if ((o.width > 0) != (o.height > 0)) {
    std::fprintf(stderr, "m4d_play: give both --width and --height\n");
    return 2;
  }
  Player player;
  return player.Run(o);
}
