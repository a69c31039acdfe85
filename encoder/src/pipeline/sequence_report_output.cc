#include "encoder/src/pipeline/sequence_report_output.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "encoder/src/io/atomic_file.h"

namespace m4d {
namespace {

double Kb(size_t bytes) { return static_cast<double>(bytes) / 1000.0; }

size_t Layer(const FrameReport& f, int type) { return f.bytes.by_type[type]; }

}  // namespace

const std::vector<ReportLayer>& ReportLayers() {
  static const std::vector<ReportLayer> kLayers = {
      {M4D_PACKET_SEQUENCE_HEADER, "sequence_header", "headers"},
      {M4D_PACKET_KEYFRAME_STATIC, "static", "static key"},
      {M4D_PACKET_STATIC_UPDATE, "static_update", "static update"},
      {M4D_PACKET_KEYFRAME_DYNAMIC, "dynamic", "dynamic key"},
      {M4D_PACKET_MLP_WEIGHTS, "mlp", "MLP weights"},
      {M4D_PACKET_MOTION_GRID, "motion_grid", "motion grids"},
      {M4D_PACKET_APPEARANCE, "appearance", "appearance"},
      {M4D_PACKET_COMPENSATION, "compensation", "compensation"}};
  return kLayers;
}

SequenceSummary Summarise(const SequenceReport& report) {
  SequenceSummary s;
  size_t inter_bytes = 0, key_bytes = 0;
  double inter_seconds = 0;
  for (const FrameReport& f : report.frames) {
    ++s.frames;
    s.held_out = s.held_out || f.held_out;
    s.psnr += f.psnr;
    s.ssim += f.ssim;
    s.seconds += f.seconds.total();
    for (size_t type = 0; type < f.bytes.by_type.size(); ++type) {
      s.kb_per_frame_by_type[type] += Kb(f.bytes.by_type[type]);
    }
    if (f.keyframe) {
      ++s.keyframes;
      key_bytes += f.bytes.total();
      s.keyframe_psnr += f.psnr;
    } else {
      inter_bytes += f.bytes.total();
      inter_seconds += f.seconds.total();
    }
  }
  const size_t inter = s.frames - s.keyframes;
  if (s.frames) {
    s.kb_per_frame = Kb(report.stream_bytes) / static_cast<double>(s.frames);
    s.psnr /= static_cast<double>(s.frames);
    s.ssim /= static_cast<double>(s.frames);
    for (double& kb : s.kb_per_frame_by_type) kb /= static_cast<double>(s.frames);
  }
  if (s.keyframes) {
    s.kb_per_keyframe = Kb(key_bytes) / static_cast<double>(s.keyframes);
    s.keyframe_psnr /= static_cast<double>(s.keyframes);
  }
  if (inter) {
    s.kb_per_inter_frame = Kb(inter_bytes) / static_cast<double>(inter);
    s.seconds_per_inter_frame = inter_seconds / static_cast<double>(inter);
  }
  return s;
}

// A held-out measure, or "-" without a held-out camera (not a 0.00 that reads as a result).
std::string Measure(const FrameReport& f, double value, int decimals) {
  if (!f.held_out) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

void PrintFrameLine(std::FILE* out, const FrameReport& f, bool header) {
  if (header) {
    std::fprintf(out, "%5s %4s %9s %9s %7s %8s %7s %8s %9s %8s %8s %6s %6s %7s %6s %7s %7s\n",
                 "frame", "type", "static KB", "dyn KB", "mlp KB", "grid KB", "app KB", "comp KB",
                 "total KB", "static", "dynamic", "+add", "-rem", "PSNR", "SSIM", "train",
                 "time s");
  }
  std::fprintf(
      out,
      "%5u %4s %9.2f %9.2f %7.2f %8.2f %7.2f %8.2f %9.2f %8zu %8zu %6zu %6zu %7s %6s %7.2f %7.1f\n",
      f.frame_index, f.keyframe ? (f.random_access ? "key" : "dkey") : "inter",
      Kb(Layer(f, M4D_PACKET_KEYFRAME_STATIC) + Layer(f, M4D_PACKET_STATIC_UPDATE)),
      Kb(Layer(f, M4D_PACKET_KEYFRAME_DYNAMIC)), Kb(Layer(f, M4D_PACKET_MLP_WEIGHTS)),
      Kb(Layer(f, M4D_PACKET_MOTION_GRID)), Kb(Layer(f, M4D_PACKET_APPEARANCE)),
      Kb(Layer(f, M4D_PACKET_COMPENSATION)), Kb(f.bytes.total()), f.static_count, f.dynamic_count,
      f.added, f.removed, Measure(f, f.psnr, 2).c_str(), Measure(f, f.ssim, 4).c_str(),
      f.training_psnr, f.seconds.total());
  std::fflush(out);
}

void PrintSummary(std::FILE* out, const SequenceReport& report) {
  const SequenceSummary s = Summarise(report);
  std::fprintf(out, "\n%-34s %zu (%zu keyframes)\n", "frames", s.frames, s.keyframes);
  std::fprintf(out, "%-34s %zu bytes\n", "stream", report.stream_bytes);
  std::fprintf(out, "%-34s %.2f KB\n", "per frame (keyframes included)", s.kb_per_frame);
  std::fprintf(out, "%-34s %.2f KB\n", "per inter frame", s.kb_per_inter_frame);
  std::fprintf(out, "%-34s %.2f KB\n", "per keyframe", s.kb_per_keyframe);
  if (s.held_out) {
    std::fprintf(out, "%-34s %.2f dB (keyframes %.2f dB), SSIM %.4f\n", "held-out PSNR", s.psnr,
                 s.keyframe_psnr, s.ssim);
  } else {
    std::fprintf(out, "%-34s none: the capture has no held-out camera\n", "held-out PSNR");
  }
  std::fprintf(out, "%-34s %.1f s (%.1f s per inter frame)\n", "encoding time", s.seconds,
               s.seconds_per_inter_frame);
  if (report.peak_memory_bytes > 0) {
    std::fprintf(out, "%-34s %.1f MB\n", "peak memory",
                 static_cast<double>(report.peak_memory_bytes) / 1e6);
  }
  std::fprintf(out, "%-34s %8s %7s\n", "bytes by layer", "KB/frame", "share");
  for (const ReportLayer& layer : ReportLayers()) {
    const double kb = s.kb_per_frame_by_type[layer.packet_type];
    if (kb == 0) continue;
    std::fprintf(out, "  %-32s %8.2f %6.1f%%\n", layer.label, kb,
                 s.kb_per_frame > 0 ? 100.0 * kb / s.kb_per_frame : 0.0);
  }
}

nlohmann::json FrameReportJson(const FrameReport& f) {
  using nlohmann::json;
  json bytes = {{"total", f.bytes.total()}};
  for (const ReportLayer& layer : ReportLayers()) bytes[layer.key] = Layer(f, layer.packet_type);
  json seconds = {{"keyframe", f.seconds.keyframe}, {"decoupling", f.seconds.decoupling},
                  {"motion", f.seconds.motion},     {"compensation", f.seconds.compensation},
                  {"coding", f.seconds.coding},     {"evaluation", f.seconds.evaluation},
                  {"total", f.seconds.total()}};
  return {{"frame", f.frame_index},
          {"keyframe", f.keyframe},
          {"random_access", f.random_access},
          {"bytes", bytes},
          {"static_gaussians", f.static_count},
          {"dynamic_gaussians", f.dynamic_count},
          {"added", f.added},
          {"removed", f.removed},
          {"gop_ratio", f.ratio},
          {"training_psnr", f.training_psnr},
          {"compensation_gain", f.compensation_gain},
          {"compensation_abandoned", f.compensation_abandoned},
          {"motion_gain", f.motion_gain},
          {"motion_skipped", f.motion_skipped},
          {"appearance_gain", f.appearance_gain},
          {"appearance_skipped", f.appearance_skipped},
          {"psnr_reference", f.psnr_reference},
          {"prediction_psnr", f.prediction_psnr},
          {"seeded", f.seeded},
          {"psnr", f.held_out ? json(f.psnr) : json(nullptr)},
          {"ssim", f.held_out ? json(f.ssim) : json(nullptr)},
          {"hash", f.hash},
          {"seconds", seconds}};
}

Status FrameReportFromJson(const nlohmann::json& j, FrameReport* f) {
  try {
    *f = FrameReport();
    f->frame_index = j.at("frame").get<uint32_t>();
    f->keyframe = j.at("keyframe").get<bool>();
    f->random_access = j.at("random_access").get<bool>();
    for (const ReportLayer& layer : ReportLayers()) {
      f->bytes.by_type[layer.packet_type] = j.at("bytes").at(layer.key).get<size_t>();
    }
    f->static_count = j.at("static_gaussians").get<size_t>();
    f->dynamic_count = j.at("dynamic_gaussians").get<size_t>();
    f->added = j.at("added").get<size_t>();
    f->removed = j.at("removed").get<size_t>();
    f->ratio = j.at("gop_ratio").get<double>();
    f->training_psnr = j.at("training_psnr").get<double>();
    f->compensation_gain = j.at("compensation_gain").get<double>();
    f->compensation_abandoned = j.value("compensation_abandoned", false);  // older reports
    f->motion_gain = j.at("motion_gain").get<double>();
    f->motion_skipped = j.at("motion_skipped").get<bool>();
    f->appearance_gain = j.at("appearance_gain").get<double>();
    f->appearance_skipped = j.at("appearance_skipped").get<bool>();
    f->psnr_reference = j.at("psnr_reference").get<double>();
    f->prediction_psnr = j.at("prediction_psnr").get<double>();
    f->seeded = j.at("seeded").get<size_t>();
    f->held_out = !j.at("psnr").is_null();
    if (f->held_out) {
      f->psnr = j.at("psnr").get<double>();
      f->ssim = j.at("ssim").get<double>();
    }
    f->hash = j.at("hash").get<std::string>();
    const nlohmann::json& s = j.at("seconds");
    f->seconds.keyframe = s.at("keyframe").get<double>();
    f->seconds.decoupling = s.at("decoupling").get<double>();
    f->seconds.motion = s.at("motion").get<double>();
    f->seconds.compensation = s.at("compensation").get<double>();
    f->seconds.coding = s.at("coding").get<double>();
    f->seconds.evaluation = s.at("evaluation").get<double>();
  } catch (const nlohmann::json::exception& e) {
    return Status(M4D_ERR_INVALID_ARG, std::string("frame report: ") + e.what());
  }
  return Status::Ok();
}

Status WriteReportJson(const std::string& path, const SequenceReport& report,
                       const std::string& extra_json_object) {
  using nlohmann::json;
  json frames = json::array();
  for (const FrameReport& f : report.frames) frames.push_back(FrameReportJson(f));
  const SequenceSummary s = Summarise(report);
  json by_layer = json::object();
  for (const ReportLayer& layer : ReportLayers()) {
    by_layer[layer.key] = s.kb_per_frame_by_type[layer.packet_type];
  }
  json doc = {{"frames", frames},
              {"summary",
               {{"frames", s.frames},
                {"keyframes", s.keyframes},
                {"stream_bytes", report.stream_bytes},
                {"kb_per_frame", s.kb_per_frame},
                {"kb_per_inter_frame", s.kb_per_inter_frame},
                {"kb_per_keyframe", s.kb_per_keyframe},
                {"held_out_camera", s.held_out},
                {"psnr", s.held_out ? json(s.psnr) : json(nullptr)},
                {"keyframe_psnr", s.held_out ? json(s.keyframe_psnr) : json(nullptr)},
                {"ssim", s.held_out ? json(s.ssim) : json(nullptr)},
                {"seconds", s.seconds},
                {"seconds_per_inter_frame", s.seconds_per_inter_frame},
                {"peak_memory_bytes", report.peak_memory_bytes},
                {"kb_per_frame_by_layer", by_layer}}}};
  if (!extra_json_object.empty()) {
    json extra = json::parse(extra_json_object, nullptr, false);
    if (extra.is_object()) doc.update(extra);
  }
  M4D_RETURN_IF_ERROR(CheckOutputPath(path));  // creates its directory
  const std::string text = doc.dump(2) + "\n";
  return WriteFileAtomically(path, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

}  // namespace m4d
