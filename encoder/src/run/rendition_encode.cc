#include "encoder/src/run/rendition_encode.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/distributed/mpi_ranks.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/pipeline/sequence_report_output.h"
#include "encoder/src/pipeline/stage_options.h"
#include "encoder/src/run/encode_steps.h"
#include "encoder/src/run/peak_memory.h"
#include "encoder/src/run/rendition_manifest.h"
#include "encoder/src/run/stream_check.h"
#include "encoder/src/stream/frame_rate.h"
#include "encoder/src/train/keyframe_stage.h"

namespace m4d {

namespace {

// One rendition's stream and its report.
struct CodedRendition {
  std::vector<uint8_t> stream;
  SequenceReport report;
};

// The arguments at one rendition's rate point.
EncodeArguments RenditionArguments(const EncodeArguments& args, const std::string& id) {
  EncodeArguments point = args;
  point.rate_point = id;
  return point;
}

// What the capture and the automatic choices decided for the first rendition holds for every
// rendition: the frame rate, the up axis, the prune share and an automatic rate weight.
void ShareFirstChoices(const EncodeArguments& args, const AutomaticChoices& choices,
                       std::vector<EncoderOptions>* options) {
  const EncoderOptions& first = (*options)[0];
  for (size_t r = 1; r < options->size(); ++r) {
    EncoderOptions& o = (*options)[r];
    o.fps_num = first.fps_num;
    o.fps_den = first.fps_den;
    o.up_axis = first.up_axis;
    o.keyframe.importance_prune_share = first.keyframe.importance_prune_share;
    if (args.keyframe_rate.automatic && choices.trains_keyframe) {
      o.keyframe_rate_weight = first.keyframe_rate_weight;
    }
  }
}

// Each rendition's encoder options at its rate point, the capture opened. The first rendition's
// settings train the shared keyframe, so the choices made for it are given to the others.
Status ResolveRenditionOptions(const EncodeArguments& args, Capture* capture,
                               std::vector<EncoderOptions>* options) {
  options->resize(args.renditions.size());
  for (size_t r = 0; r < options->size(); ++r) {
    M4D_RETURN_IF_ERROR(
        ResolveEncoderOptions(RenditionArguments(args, args.renditions[r]), &(*options)[r]));
  }
  uint32_t unused_num, unused_den;
  if (!args.fps.empty()) M4D_RETURN_IF_ERROR(ParseFrameRate(args.fps, &unused_num, &unused_den));
  M4D_RETURN_IF_ERROR(OpenCapture(args.capture, capture));
  EncoderOptions& first = (*options)[0];
  M4D_RETURN_IF_ERROR(ChooseFrameRate(args.fps, *capture, &first));
  M4D_RETURN_IF_ERROR(ChooseUpAxis(args.up, *capture, &first));
  M4D_RETURN_IF_ERROR(CheckViewsBeforeTraining(*capture, first.first_frame, first.frame_count));
  AutomaticChoices choices;
  M4D_RETURN_IF_ERROR(ResolveAutomaticChoices(RenditionArguments(args, args.renditions[0]),
                                              *capture, &first, &choices));
  ShareFirstChoices(args, choices, options);
  return Status::Ok();
}

// The first keyframe every rendition starts from: read from --keyframe-ply, else trained once
// with the first rendition's options.
Status TrainSharedKeyframe(const EncodeArguments& args, const Capture& capture,
                           const EncoderOptions& options, EncodeProgress* progress,
                           GaussianModel* first) {
  if (!args.keyframe_ply.empty()) return ReadFirstKeyframe(args, options.sh_degree, first);
  EncoderCallbacks callbacks = progress->Callbacks();
  const int frame = options.first_frame;
  return TrainKeyframe(
      capture, frame, FirstKeyframeTraining(options),
      [&](const TrainingProgress& p) { callbacks.training("keyframe", frame, p); }, first);
}

// Codes rendition r from the shared first keyframe; its frames and summary on stdout.
Status EncodeRendition(const EncodeArguments& args, size_t r, const Capture& capture,
                       const EncoderOptions& options, const GaussianModel& first,
                       EncodeProgress* progress, CodedRendition* coded) {
  std::printf("\nrendition %s%s\n", args.renditions[r].c_str(),
              r == 0 ? " (decides the GOPs)" : "");
  progress->header = true;
  SequenceEncoder encoder(capture, options);
  encoder.SetFirstKeyframe(first);
  M4D_RETURN_IF_ERROR(encoder.Encode(progress->Callbacks(), &coded->report));
  coded->report.peak_memory_bytes = PeakMemoryBytes();
  PrintSummary(stdout, coded->report);
  coded->stream = encoder.stream();
  return Status::Ok();
}

// The GOP starts the first rendition decided (its keyframes after the first frame), imposed on
// the others so that their random-access points are aligned with it.
void ImposeGopStarts(const SequenceReport& decider, std::vector<EncoderOptions>* options) {
  const int first_frame = (*options)[0].first_frame;
  for (const FrameReport& f : decider.frames) {
    const int frame = static_cast<int>(f.frame_index);
    if (f.keyframe && frame != first_frame) {
      for (size_t o = 1; o < options->size(); ++o) (*options)[o].gop.starts.push_back(frame);
    }
  }
}

// Rendition r's stream and JSON report (its options and what it shares), checked by decoding.
Status WriteRendition(const EncodeArguments& args, size_t r, const CodedRendition& coded) {
  const std::string& id = args.renditions[r];
  const std::string path = RenditionPath(args.output, id);
  M4D_RETURN_IF_ERROR(WriteFileAtomically(path, coded.stream.data(), coded.stream.size()));
  const nlohmann::json extra = {
      {"options", EncodeOptionsJson(RenditionArguments(args, id))},
      {"rendition",
       {{"id", id}, {"keyframe_shared_with", args.renditions}, {"gops_from", args.renditions[0]}}}};
  M4D_RETURN_IF_ERROR(WriteReportJson(path + ".json", coded.report, extra.dump()));
  return CheckDecodedHashes(coded.stream, coded.report);
}

// Every rendition's stream and report, then the manifest listing them.
Status WriteRenditionsAndManifest(const EncodeArguments& args,
                                  const std::vector<CodedRendition>& coded) {
  std::vector<RenditionStream> listed;
  for (size_t r = 0; r < coded.size(); ++r) {
    M4D_RETURN_IF_ERROR(WriteRendition(args, r, coded[r]));
    const std::string& id = args.renditions[r];
    const std::string name =
        std::filesystem::path(RenditionPath(args.output, id)).filename().string();
    listed.push_back({id, id, name, &coded[r].stream});
  }
  std::string manifest;
  M4D_RETURN_IF_ERROR(RenditionManifestJson(listed, &manifest));
  return WriteFileAtomically(ManifestPath(args.output),
                             reinterpret_cast<const uint8_t*>(manifest.data()), manifest.size());
}

// The mean PSNR of the held-out views (0 without any).
double MeanHeldOutPsnr(const SequenceReport& report) {
  double psnr = 0;
  int measured = 0;
  for (const FrameReport& f : report.frames) {
    if (f.held_out) psnr += f.psnr, ++measured;
  }
  return measured > 0 ? psnr / measured : 0.0;
}

// Per rendition its bytes, bit rate and held-out PSNR, then where the manifest is.
void PrintRenditionTable(const EncodeArguments& args, const EncoderOptions& first,
                         const std::vector<CodedRendition>& coded) {
  std::printf("\n%-34s %zu renditions, every frame decoded by the SDK to the encoder's hash\n",
              "decoder check", coded.size());
  std::printf("%-10s %12s %10s %8s\n", "rendition", "bytes", "kbit/s", "PSNR");
  for (size_t r = 0; r < coded.size(); ++r) {
    const size_t bytes = coded[r].stream.size();
    const double seconds =
        static_cast<double>(coded[r].report.frames.size()) * first.fps_den / first.fps_num;
    std::printf("%-10s %12zu %10.1f %8.2f\n", args.renditions[r].c_str(), bytes,
                8.0 * static_cast<double>(bytes) / seconds / 1000.0,
                MeanHeldOutPsnr(coded[r].report));
  }
  std::printf("%-34s %s\n", "manifest", ManifestPath(args.output).c_str());
}

}  // namespace

Status CheckRenditionOutputs(const EncodeArguments& args, bool force) {
  if (!args.rate_point.empty()) {
    return Status(M4D_ERR_INVALID_ARG, "--renditions names the rate points: no --rate-point");
  }
  if (args.chunk_frames > 0 || CurrentRanks().size > 1 || !args.views.empty() ||
      !args.json.empty() || args.keyframe_source || args.encoder.independent_frames) {
    return Status(M4D_ERR_INVALID_ARG,
                  "--renditions codes no chunks (--chunk-frames, MPI), no --views, no --json "
                  "(each rendition's report is beside its stream) and no baseline");
  }
  std::vector<std::string> outputs;
  for (size_t r = 0; r < args.renditions.size(); ++r) {
    const std::string& id = args.renditions[r];
    RatePointSettings point;
    M4D_RETURN_IF_ERROR(FindRatePoint(id, &point));
    if (std::find(args.renditions.begin(), args.renditions.begin() + r, id) !=
        args.renditions.begin() + r) {
      return Status(M4D_ERR_INVALID_ARG, "--renditions: " + id + " given twice");
    }
    outputs.push_back(RenditionPath(args.output, id));
    outputs.push_back(RenditionPath(args.output, id) + ".json");
  }
  outputs.push_back(ManifestPath(args.output));
  for (const std::string& path : outputs) {
    std::error_code ec;
    if (!force && std::filesystem::is_regular_file(path, ec)) {
      return Status(M4D_ERR_INVALID_ARG, path + " exists: give --force to replace it");
    }
  }
  for (const std::string& path : outputs) M4D_RETURN_IF_ERROR(CheckOutputPath(path));
  return Status::Ok();
}

Status RunRenditionEncode(const EncodeArguments& args, bool force) {
  M4D_RETURN_IF_ERROR(CheckRenditionOutputs(args, force));
  Capture capture;
  std::vector<EncoderOptions> options;
  M4D_RETURN_IF_ERROR(ResolveRenditionOptions(args, &capture, &options));
  EncodeProgress progress;
  GaussianModel first;
  M4D_RETURN_IF_ERROR(TrainSharedKeyframe(args, capture, options[0], &progress, &first));
  std::vector<CodedRendition> coded(options.size());
  for (size_t r = 0; r < coded.size(); ++r) {
    M4D_RETURN_IF_ERROR(EncodeRendition(args, r, capture, options[r], first, &progress, &coded[r]));
    if (r == 0) ImposeGopStarts(coded[0].report, &options);
  }
  M4D_RETURN_IF_ERROR(WriteRenditionsAndManifest(args, coded));
  PrintRenditionTable(args, options[0], coded);
  return Status::Ok();
}

}  // namespace m4d
