// m4d_packet_times: decode time of each packet of a stream through the public C API, one
// thread, as a table per packet type and per frame kind. web/bench/packet_decode_times.mjs
// measures the WebAssembly decoder the same way, so the two tables compare (scripts/
// bench_web.sh prints them side by side).
//
//   m4d_packet_times STREAM [--repeat N]
//
// Each packet's time is m4d_send_packet plus taking the frame it completes; the best of N
// decodes of the whole stream counts. Output lines: "<row> <count> <median ms> <mean ms>",
// rows: one per packet type, "inter_frame" (an inter frame's packets together) and
// "keyframe" (a keyframe's).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "m4d/m4d.h"

namespace {

struct Packet {
  size_t offset, size;
  uint32_t type, frame_index;
};

const char* TypeName(uint32_t type) {
  static const char* const kNames[] = {"",
                                       "sequence_header",
                                       "keyframe_static",
                                       "keyframe_dynamic",
                                       "mlp_weights",
                                       "motion_grid",
                                       "compensation",
                                       "static_update",
                                       "appearance"};
  return type < sizeof(kNames) / sizeof(kNames[0]) ? kNames[type] : "unknown";
}

std::vector<Packet> Split(const std::vector<uint8_t>& data) {
  std::vector<Packet> packets;
  M4dPacketInfo info;
  for (size_t pos = 0; pos < data.size(); pos += info.packet_size) {
    if (m4d_parse_packet_header(&data[pos], data.size() - pos, &info) != M4D_OK) break;
    packets.push_back({pos, info.packet_size, info.type, info.frame_index});
  }
  return packets;
}

// One decode of the stream; each packet's milliseconds into ms. False on a decode error.
bool DecodeOnce(const std::vector<uint8_t>& data, const std::vector<Packet>& packets,
                std::vector<double>* ms) {
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* context = nullptr;
  if (m4d_open(&context, &settings) < 0) return false;
  bool ok = true;
  for (size_t k = 0; k < packets.size() && ok; ++k) {
    const auto start = std::chrono::steady_clock::now();
    int r = m4d_send_packet(context, &data[packets[k].offset], packets[k].size);
    M4dFrame frame;
    while (m4d_get_frame(context, &frame) == M4D_OK) m4d_frame_unref(&frame);
    if (r == M4D_ERR_AGAIN) r = m4d_send_packet(context, &data[packets[k].offset], packets[k].size);
    (*ms)[k] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ok = r == M4D_OK;
  }
  m4d_close(&context);
  return ok;
}

void PrintRow(const std::string& name, std::vector<double> values) {
  if (values.empty()) return;
  std::sort(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  std::printf("%s %zu %.3f %.3f\n", name.c_str(), values.size(), values[values.size() / 2],
              sum / values.size());
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  if (argc == 4 && std::string(argv[2]) == "--repeat") repeat = std::atoi(argv[3]);
  if ((argc != 2 && argc != 4) || repeat < 1) {
    std::fprintf(stderr, "usage: m4d_packet_times STREAM [--repeat N]\n");
    return 2;
  }
  std::ifstream file(argv[1], std::ios::binary);
  const std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
  const std::vector<Packet> packets = Split(data);
  if (!file.good() && !file.eof()) {
    std::fprintf(stderr, "m4d_packet_times: cannot read %s\n", argv[1]);
    return 2;
  }
  std::vector<double> best(packets.size(), 1e30), ms(packets.size());
  for (int r = 0; r < repeat; ++r) {
    if (!DecodeOnce(data, packets, &ms)) {
      std::fprintf(stderr, "m4d_packet_times: %s does not decode cleanly\n", argv[1]);
      return 1;
    }
    for (size_t k = 0; k < packets.size(); ++k) best[k] = std::min(best[k], ms[k]);
  }
  std::map<std::string, std::vector<double>> rows;
  std::map<uint32_t, double> frame_ms;
  std::map<uint32_t, bool> keyframe;
  for (size_t k = 0; k < packets.size(); ++k) {
    rows[TypeName(packets[k].type)].push_back(best[k]);
    frame_ms[packets[k].frame_index] += best[k];
    if (packets[k].type == M4D_PACKET_KEYFRAME_DYNAMIC) keyframe[packets[k].frame_index] = true;
  }
  for (const auto& [index, total] : frame_ms) {
    rows[keyframe[index] ? "keyframe" : "inter_frame"].push_back(total);
  }
  for (const auto& [name, values] : rows) PrintRow(name, values);
  return 0;
}
