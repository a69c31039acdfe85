#include "tools/m4d/bench_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/run/stream_check.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/encode_command.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

struct BenchArguments {
  EncodeArguments encode;
  std::string dir = "out/bench";
  int decode_runs = 5;
};

constexpr const char* kStages[] = {"keyframe",     "decoupling", "motion",
                                   "compensation", "coding",     "evaluation"};

std::vector<double> Stages(const StageSeconds& s) {
  return {s.keyframe, s.decoupling, s.motion, s.compensation, s.coding, s.evaluation};
}

void PrintStageLine(const char* label, const std::vector<double>& stages) {
  double total = 0;
  std::printf("%-14s", label);
  for (double s : stages) std::printf(" %12.2f", s), total += s;
  std::printf(" %10.2f\n", total);
}

// Encode time per frame by stage, and the mean over inter frames.
nlohmann::json EncodeTable(const SequenceReport& report) {
  std::printf("\nencode: seconds per frame by stage\n%-14s", "frame");
  for (const char* stage : kStages) std::printf(" %12s", stage);
  std::printf(" %10s\n", "total");
  std::vector<double> inter_sum(std::size(kStages), 0.0);
  int inter = 0;
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameReport& f : report.frames) {
    const std::vector<double> stages = Stages(f.seconds);
    const std::string label = std::to_string(f.frame_index) + (f.keyframe ? " key" : " inter");
    PrintStageLine(label.c_str(), stages);
    nlohmann::json row = {{"frame", f.frame_index}, {"keyframe", f.keyframe}};
    for (size_t s = 0; s < stages.size(); ++s) row[kStages[s]] = stages[s];
    frames.push_back(row);
    if (f.keyframe) continue;
    for (size_t s = 0; s < stages.size(); ++s) inter_sum[s] += stages[s];
    ++inter;
  }
  nlohmann::json mean = nlohmann::json::object();
  if (inter > 0) {
    for (double& s : inter_sum) s /= inter;
    PrintStageLine("inter mean", inter_sum);
    for (size_t s = 0; s < inter_sum.size(); ++s) mean[kStages[s]] = inter_sum[s];
  }
  return {{"frames", frames}, {"inter_frame_mean", mean}};
}

// Decodes the stream `runs` times; per frame the fastest run (the least disturbed).
Status DecodeTable(const std::string& path, const SequenceReport& report, int runs,
                   nlohmann::json* out) {
  std::ifstream file(path, std::ios::binary);
  const std::vector<uint8_t> stream((std::istreambuf_iterator<char>(file)),
                                    std::istreambuf_iterator<char>());
  std::vector<double> best;
  for (int r = 0; r < runs; ++r) {
    DecodedStream decoded;
    M4D_RETURN_IF_ERROR(DecodeStream(stream, &decoded));
    if (decoded.seconds.size() != report.frames.size()) {
      return Status(M4D_ERR_BITSTREAM, "bench: the stream decodes to another frame count");
    }
    if (best.empty()) best = decoded.seconds;
    for (size_t f = 0; f < best.size(); ++f) best[f] = std::min(best[f], decoded.seconds[f]);
  }
  std::printf("\ndecode (SDK, m4d.h): ms per frame, best of %d runs\n%-14s %10s %10s\n", runs,
              "frame", "KB", "ms");
  double key_ms = 0, inter_ms = 0;
  int keys = 0;
  nlohmann::json frames = nlohmann::json::array();
  for (size_t f = 0; f < best.size(); ++f) {
    const FrameReport& r = report.frames[f];
    const std::string label = std::to_string(r.frame_index) + (r.keyframe ? " key" : " inter");
    std::printf("%-14s %10.2f %10.2f\n", label.c_str(), r.bytes.total() / 1000.0, 1e3 * best[f]);
    (r.keyframe ? key_ms : inter_ms) += 1e3 * best[f];
    keys += r.keyframe;
    frames.push_back({{"frame", r.frame_index}, {"keyframe", r.keyframe}, {"ms", 1e3 * best[f]}});
  }
  const int inters = static_cast<int>(best.size()) - keys;
  nlohmann::json mean = {{"keyframe_ms", keys ? key_ms / keys : 0.0},
                         {"inter_frame_ms", inters ? inter_ms / inters : 0.0}};
  std::printf("%-14s %10s %10.2f\n%-14s %10s %10.2f\n", "keyframe mean", "",
              mean["keyframe_ms"].get<double>(), "inter mean", "",
              mean["inter_frame_ms"].get<double>());
  *out = {{"runs", runs}, {"frames", frames}, {"mean", mean}};
  return Status::Ok();
}

Status RunBench(BenchArguments args) {
  EncodeArguments& run = args.encode;
  run.output = (std::filesystem::path(args.dir) / "bench.m4d").string();
  SequenceReport report;
  M4D_RETURN_IF_ERROR(RunEncode(run, &report));
  nlohmann::json doc = {{"options", EncodeOptionsJson(run)},
                        {"threads", run.encoder.context.threads},
                        {"encode", EncodeTable(report)}};
  nlohmann::json decode;
  M4D_RETURN_IF_ERROR(DecodeTable(run.output, report, args.decode_runs, &decode));
  doc["decode"] = decode;
  const std::string json_path = (std::filesystem::path(args.dir) / "bench.json").string();
  std::ofstream json(json_path);
  json << doc.dump(2) << "\n";
  if (!json) return Status(M4D_ERR_INVALID_ARG, "cannot write " + json_path);
  std::printf("\nreport %s\n", json_path.c_str());
  return Status::Ok();
}

}  // namespace

void AddBenchCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<BenchArguments>();
  args->encode.capture.capture.max_frames = 4;
  CLI::App* cmd = app->add_subcommand(
      "bench",
      "encode time per frame by stage and SDK decode time per frame (first 4 frames "
      "unless --frames)");
  AddCaptureArguments(cmd, &args->encode.capture);
  AddEncoderOptions(cmd, &args->encode);
  cmd->add_option("-o,--output-dir", args->dir, "stream and bench.json go here")
      ->capture_default_str();
  cmd->add_option("--decode-runs", args->decode_runs, "decode the stream this many times")
      ->check(m4d::Within(1, 1000))
      ->capture_default_str();
  cmd->callback([args, exit_code]() { *exit_code = ReportStatus("bench", RunBench(*args)); });
}

}  // namespace m4d
