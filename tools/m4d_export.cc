// m4d_export: decoded frames of an M4D stream as files other tools open: the 3DGS PLY layout
// of the reference implementation (SuperSplat and the reference viewers read it), or binary
// glTF with KHR_gaussian_splatting. Each file holds one frame's Gaussians, static layer first.
// Each format gets the orientation its readers expect: the stream's up axis (spec 4.1;
// -y when the stream does not state it) becomes -y in PLY (3DGS' OpenCV axes) and +y in glTF.
//
//   m4d_export STREAM -o DIR [--frames FIRST[:LAST]] [--layers all|static|dynamic]
//              [--format ply|glb] [--force]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "encoder/src/export/axis_rotation.h"
#include "encoder/src/export/frame_gaussians.h"
#include "encoder/src/export/gltf_splat_writer.h"
#include "encoder/src/export/turn_gaussians.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "m4d/m4d.h"
#include "tools/existing_output.h"
#include "tools/usage_exit.h"

namespace {

struct Options {
  std::string input, output_dir, frames, layers = "all", format = "ply";
  uint32_t first = 0, last = UINT32_MAX;
  bool force = false;
};

bool ParseFrames(Options* o) {
  if (o->frames.empty()) return true;
  const size_t colon = o->frames.find(':');
  try {
    o->first = static_cast<uint32_t>(std::stoul(o->frames.substr(0, colon)));
    o->last = colon == std::string::npos ? o->first
              : colon + 1 == o->frames.size()
                  ? UINT32_MAX
                  : static_cast<uint32_t>(std::stoul(o->frames.substr(colon + 1)));
  } catch (const std::exception&) {
    return false;
  }
  return o->first <= o->last;
}

// Writes one decoded frame in the orientation of its format; false (with a message) on
// failure.
bool Export(const Options& o, const M4dFrame& frame, int up_axis, int* written) {
  if (frame.frame_index < o.first || frame.frame_index > o.last) return true;
  const uint32_t layers = o.layers == "static"    ? M4D_LAYER_STATIC
                          : o.layers == "dynamic" ? M4D_LAYER_DYNAMIC
                                                  : M4D_LAYER_ALL;
  m4d::GaussianSet set;
  m4d::Status status = m4d::GaussianSetFromFrame(frame, layers, &set);
  char name[32];
  std::snprintf(name, sizeof(name), "/frame_%05u.%s", frame.frame_index, o.format.c_str());
  const std::string path = o.output_dir + name;
  const bool glb = o.format == "glb";
  if (status.ok() && glb && set.size() == 0) {
    std::fprintf(stderr,
                 "m4d_export: frame %u: no Gaussians in the %s layer%s; a glTF file cannot hold "
                 "an empty point set (PLY can: --format ply)\n",
                 frame.frame_index, o.layers.c_str(), o.layers == "all" ? "s" : "");
    return false;
  }
  // The folder is created with the first file: an export that writes nothing leaves nothing.
  if (status.ok() && *written == 0) status = m4d::CheckOutputPath(path);
  if (status.ok()) {
    m4d::TurnGaussians(glb ? m4d::GltfFrame(up_axis) : m4d::PlyFrame(up_axis), &set);
    status = glb ? m4d::WriteGaussianGlb(path, set) : m4d::WriteGaussianPly(path, set);
  }
  if (!status.ok()) {
    std::fprintf(stderr, "m4d_export: frame %u: %s\n", frame.frame_index, status.message().c_str());
    return false;
  }
  std::printf("%s: %zu Gaussians\n", path.c_str(), set.size());
  ++*written;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Export decoded frames of an M4D stream as 3DGS PLY or glTF (KHR_gaussian_splatting)."};
  app.add_option("stream", o.input, "stream file")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output-dir", o.output_dir, "directory for frame_<index>.ply or .glb")
      ->required();
  app.add_option("--frames", o.frames, "FIRST, FIRST:LAST or FIRST: (default: every frame)");
  app.add_option("--layers", o.layers, "layers in each file")
      ->check(CLI::IsMember({"all", "static", "dynamic"}))
      ->capture_default_str();
  app.add_option("--format", o.format,
                 "ply: the 3DGS PLY layout, the stream's up as -y (OpenCV axes, as the reference "
                 "tools read it); glb: binary glTF, up +y. A stream that does not state its up "
                 "axis (before bitstream 0.9) is taken as -y up")
      ->check(CLI::IsMember({"ply", "glb"}))
      ->capture_default_str();
  app.add_flag("-f,--force", o.force, "replace existing frame files (else refused)");
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  if (!ParseFrames(&o)) {
    std::fprintf(stderr, "m4d_export: --frames %s is not FIRST, FIRST:LAST or FIRST:\n",
                 o.frames.c_str());
    return 2;
  }
  m4d::Status status = m4d::RefuseExistingFrames(o.output_dir, o.format, o.first, o.last, o.force);
  if (!status.ok()) {
    std::fprintf(stderr, "m4d_export: %s\n", status.message().c_str());
    return 2;
  }
  std::vector<uint8_t> data;
  status = m4d::ReadFileBytes(o.input, SIZE_MAX / 2, &data);
  if (!status.ok()) {
    std::fprintf(stderr, "m4d_export: %s\n", status.message().c_str());
    return 1;
  }
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) != M4D_OK) return 1;
  int written = 0, errors = 0;
  bool ok = true;
  auto drain = [&]() {
    M4dFrame frame;
    M4dStreamInfo info;
    const int up_axis =
        m4d_get_stream_info(ctx, &info) == M4D_OK ? static_cast<int>(info.up_axis) : 0;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      ok = Export(o, frame, up_axis, &written) && ok;
      m4d_frame_unref(&frame);
    }
  };
  size_t pos = 0;
  while (ok && pos < data.size()) {
    size_t skip = 0;
    M4dPacketInfo info;
    if (m4d_find_packet(data.data() + pos, data.size() - pos, &skip, &info) != M4D_OK) {
      std::fprintf(stderr, "m4d_export: the stream ends inside a packet at byte %zu\n", pos);
      ++errors;
      break;
    }
    if (skip > 0) m4d_flush(ctx), ++errors;
    pos += skip;
    int r = m4d_send_packet(ctx, data.data() + pos, info.packet_size);
    if (r == M4D_ERR_AGAIN) drain(), r = m4d_send_packet(ctx, data.data() + pos, info.packet_size);
    if (r < 0) {
      std::fprintf(stderr, "m4d_export: byte %zu: %s\n", pos, m4d_last_error(ctx));
      ++errors;
    }
    drain();
    pos += info.packet_size;
  }
  m4d_close(&ctx);
  if (ok && written == 0) {
    std::fprintf(stderr, "m4d_export: no frame of %s in %s\n",
                 o.frames.empty() ? "any index" : o.frames.c_str(), o.input.c_str());
  }
  return ok && written > 0 && errors == 0 ? 0 : 1;
}
