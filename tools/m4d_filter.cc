// m4d_filter: writes the foreground-only form of a stream (spec 2): every KEYFRAME_STATIC and
// STATIC_UPDATE removed, the rest copied. It stays a valid stream, and it is all a player that
// composites the foreground over its own background needs to receive. Stops with an error at the
// first packet whose header does not parse.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "encoder/src/io/atomic_file.h"
#include "m4d/m4d.h"
#include "tools/existing_output.h"
#include "tools/usage_exit.h"

int main(int argc, char** argv) {
  std::string input, output;
  bool force = false;
  CLI::App app{
      "Write the foreground-only form of a stream (every KEYFRAME_STATIC and STATIC_UPDATE "
      "removed)."};
  app.add_option("input", input, "stream to read")->required()->check(CLI::ExistingFile);
  app.add_option("output", output, "foreground-only stream to write")->required();
  app.add_flag("-f,--force", force, "replace an existing output (else refused)");
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  const m4d::Status may_write = m4d::RefuseExistingOutput(output, force);
  if (!may_write.ok()) {
    std::fprintf(stderr, "m4d_filter: %s\n", may_write.message().c_str());
    return 2;
  }

  std::ifstream in(input, std::ios::binary);
  const std::vector<uint8_t> data((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  std::vector<uint8_t> kept;
  size_t pos = 0, packets = 0, dropped = 0;
  while (pos < data.size()) {
    M4dPacketInfo info;
    const int r = m4d_parse_packet_header(&data[pos], data.size() - pos, &info);
    if (r != M4D_OK) {
      std::fprintf(
          stderr, "m4d_filter: %s: byte %zu: %s\n", input.c_str(), pos,
          r == M4D_ERR_AGAIN ? "the stream ends inside a packet (truncated)" : m4d_error_string(r));
      return 1;
    }
    if (info.type != M4D_PACKET_KEYFRAME_STATIC && info.type != M4D_PACKET_STATIC_UPDATE) {
      kept.insert(kept.end(), data.begin() + static_cast<std::ptrdiff_t>(pos),
                  data.begin() + static_cast<std::ptrdiff_t>(pos + info.packet_size));
    } else {
      ++dropped;
    }
    ++packets;
    pos += info.packet_size;
  }
  if (packets == 0) {
    std::fprintf(stderr, "m4d_filter: %s holds no packet\n", input.c_str());
    return 1;
  }
  const m4d::Status written = m4d::WriteFileAtomically(output, kept.data(), kept.size());
  if (!written.ok()) {
    std::fprintf(stderr, "m4d_filter: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("%s: %zu of %zu packets kept (%zu bytes)\n", output.c_str(), packets - dropped,
              packets, kept.size());
  return 0;
}
