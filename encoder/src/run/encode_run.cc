#include "encoder/src/run/encode_run.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "encoder/src/distributed/chunked_encode.h"
#include "encoder/src/distributed/mpi_ranks.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/pipeline/sequence_report_output.h"
#include "encoder/src/stream/frame_rate.h"
#include "encoder/src/video/video_writer.h"

#include "encoder/src/run/encode_steps.h"
#include "encoder/src/run/peak_memory.h"
#include "encoder/src/run/rendition_encode.h"
#include "encoder/src/run/strategy_arguments.h"
#include "encoder/src/run/stream_check.h"
#include "encoder/src/run/view_strip.h"
namespace m4d {

namespace {

// |truth - render| times gain, clamped: where the decoded frame differs.
Image ErrorImage(const Image& truth, const Image& render, float gain) {
  Image error(truth.width, truth.height, 3);
  for (size_t i = 0; i < error.pixels.size(); ++i) {
    error.pixels[i] = std::min(1.0f, gain * std::fabs(truth.pixels[i] - render.pixels[i]));
  }
  return error;
}

// Appends the strip to dir/views.mp4 (opened on the first frame; sizes cropped to even).
Status AppendToVideo(const std::string& dir, const std::vector<const Image*>& images,
                     std::unique_ptr<VideoWriter>* video) {
  Image strip;
  M4D_RETURN_IF_ERROR(ViewStrip(images, &strip));
  Image even(strip.width & ~1, strip.height & ~1, 3);
  for (int y = 0; y < even.height; ++y) std::copy_n(strip.row(y), even.row_size(), even.row(y));
  if (!*video) {
    VideoWriterOptions options;
    options.fps = 5;  // slow enough to follow the per-frame differences
    M4D_RETURN_IF_ERROR(VideoWriter::Open((std::filesystem::path(dir) / "views.mp4").string(),
                                          even.width, even.height, options, video));
  }
  return (*video)->Write(even);
}

}  // namespace

namespace {

void SetBits(const std::vector<int>& b, GaussianQuantization* q) {
  q->position_bits = b[0];
  q->log_scale_bits = b[1];
  q->rotation_bits = b[2];
  q->opacity_bits = b[3];
  q->sh_dc_bits = b[4];
  q->sh_rest_bits = b[5];
}

std::vector<int> Codebooks(const GaussianQuantization& q) {
  return {q.log_scale_codebook, q.sh_dc_codebook, q.sh_rest_codebook};
}

std::vector<int> QuantizationBits(const GaussianQuantization& q) {
  return {q.position_bits, q.log_scale_bits, q.rotation_bits,
          q.opacity_bits,  q.sh_dc_bits,     q.sh_rest_bits};
}

}  // namespace

Status ResolveEncoderOptions(const EncodeArguments& args, EncoderOptions* options) {
  *options = args.encoder;
  RatePointSettings point = RatePointForLambda(args.lambda);
  if (!args.rate_point.empty()) M4D_RETURN_IF_ERROR(FindRatePoint(args.rate_point, &point));
  ApplyRatePoint(point, options);
  if (args.lambda3 >= 0) options->compensation.sparsity_weight = args.lambda3;
  if (args.tau_g >= 0) options->compensation_thresholds.gradient = static_cast<float>(args.tau_g);
  if (args.keyframe_bits.size() == 6) SetBits(args.keyframe_bits, &options->quantization);
  if (args.compensation_bits.size() == 6) {
    SetBits(args.compensation_bits, &options->compensation_quantization);
  }
  if (args.keyframe_codebooks.size() == 3) {
    const std::vector<int>& k = args.keyframe_codebooks;
    if (k[0] == 1 || k[1] == 1 || k[2] == 1) {
      return Status(M4D_ERR_INVALID_ARG, "--keyframe-codebooks: a size is 0 or 2..4096");
    }
    options->quantization.log_scale_codebook = k[0];
    options->quantization.sh_dc_codebook = k[1];
    options->quantization.sh_rest_codebook = k[2];
  }
  if (args.keyframe_rate.weight >= 0) options->keyframe_rate_weight = args.keyframe_rate.weight;
  if (options->gop.fixed_length > 0) options->gop.adaptive = false;
  options->keyframe = KeyframeSchedule(args);
  return Status::Ok();
}

nlohmann::json EncodeOptionsJson(const EncodeArguments& args) {
  EncoderOptions o;
  ResolveEncoderOptions(args, &o);  // the rate point name was checked before
  const CaptureOptions& c = args.capture.capture;
  return {{"dataset", args.capture.dataset},
          {"capture",
           {{"test_camera", c.test_camera},
            {"downscale", c.downscale},
            {"first_frame", c.first_frame},
            {"max_frames", c.max_frames},
            {"initial_points", c.initial_points}}},
          {"first_frame", o.first_frame},
          {"frame_count", o.frame_count},
          {"keyframe_ply", args.keyframe_ply},
          {"keyframe_iterations", KeyframeSchedule(args).iterations},
          {"max_gaussians", KeyframeSchedule(args).densification.max_gaussians},
          {"gaussians_per_pixel", KeyframeSchedule(args).max_gaussians_per_pixel},
          {"importance_prune_share",
           args.prune.Automatic() ? nlohmann::json("auto")
                                  : nlohmann::json(KeyframeSchedule(args).importance_prune_share)},
          {"start_share", args.prune.StartAutomatic()
                              ? nlohmann::json("auto")
                              : nlohmann::json(KeyframeSchedule(args).sweep_share)},
          {"prune_max_loss_per_halving_db", args.prune.Automatic() || args.prune.StartAutomatic()
                                                ? nlohmann::json(args.prune.max_loss_per_halving_db)
                                                : nlohmann::json()},
          {"min_importance_pixels", KeyframeSchedule(args).min_importance_pixels},
          {"quantization_aware_iterations", KeyframeSchedule(args).quantization_aware_iterations},
          {"random_init", args.random_init},
          {"strategy", StrategyName(KeyframeSchedule(args).strategy)},
          {"retrain_iterations", o.retrain_iterations},
          {"rate_point", args.rate_point},
          {"lambda", o.motion.rate_weight},
          {"lambda3", o.compensation.sparsity_weight},
          {"tau_g", o.compensation_thresholds.gradient},
          {"sh_degree", o.sh_degree},
          {"lookahead", {o.lookahead_frames, o.lookahead_step}},
          {"decoupling_thresholds",
           {o.decoupling.thresholds.displacement, o.decoupling.thresholds.scale_change,
            o.decoupling.thresholds.error}},
          {"motion_iterations", {o.first_motion_iterations, o.motion.iterations}},
          {"motion_views_per_step", o.motion.views_per_step},
          {"motion_rate_decay", o.motion_rate_decay},
          {"compensation_iterations", o.compensation.iterations},
          {"compensation_min_gain", o.compensation_min_gain},
          {"compensation_early_decision", o.compensation_early_decision},
          {"motion_min_gain", o.motion_min_gain},
          {"appearance_step", o.motion.appearance_step},
          {"appearance_min_gain", o.appearance_min_gain},
          {"appearance_check_every", o.motion.appearance_check_every},
          {"appearance_min_views", o.appearance_min_views},
          {"change_support", o.decoupling.thresholds.change_support},
          {"noise_gap", o.gop.noise_gap},
          {"adaptive_gop", o.gop.adaptive && o.gop.fixed_length == 0},
          {"fixed_gop", o.gop.fixed_length},
          {"max_gop", o.gop.max_length},
          {"random_access_seconds", o.gop.random_access_seconds},
          {"gop_threshold", o.gop.threshold},
          {"gop_psnr_drop", o.gop.max_psnr_drop},
          {"decoupling", o.ablation.decoupling},
          {"motion_estimation", o.ablation.motion_estimation},
          {"compensation", o.ablation.compensation},
          {"rate_term", o.ablation.rate_term},
          {"independent_frames", o.independent_frames},
          {"keyframe_bits", QuantizationBits(o.quantization)},
          {"compensation_bits", QuantizationBits(o.compensation_quantization)},
          {"keyframe_codebooks", Codebooks(o.quantization)},
          {"keyframe_rate_weight", args.keyframe_rate.automatic
                                       ? nlohmann::json("auto")
                                       : nlohmann::json(o.keyframe_rate_weight)},
          {"fps", args.fps},
          {"chunk_frames", args.chunk_frames},
          {"seed", o.context.seed}};
}

KeyframeTrainingOptions KeyframeSchedule(const EncodeArguments& args) {
  KeyframeTrainingOptions o = args.keyframe_iterations > 0
                                  ? KeyframeTrainingOptions::Short(args.keyframe_iterations)
                                  : args.encoder.keyframe;
  if (args.max_gaussians > 0) o.densification.max_gaussians = args.max_gaussians;
  if (args.gaussians_per_pixel >= 0) {
    o.max_gaussians_per_pixel = static_cast<float>(args.gaussians_per_pixel);
  }
  if (args.quantization_aware >= 0) o.quantization_aware_iterations = args.quantization_aware;
  if (!args.prune.Automatic()) o.importance_prune_share = static_cast<float>(args.prune.share);
  if (!args.prune.StartAutomatic()) o.sweep_share = static_cast<float>(args.prune.sweep_share);
  if (args.prune_below >= 0) o.min_importance_pixels = static_cast<float>(args.prune_below);
  o.random_initialisation = args.random_init;
  ApplyStrategy(args.strategy, &o);
  return o;
}

std::string ReportPath(const EncodeArguments& args) {
  return args.json.empty() ? args.output + ".json" : args.json;
}

namespace {

Status EncodeWhole(const EncodeArguments& args, const Capture& capture,
                   const EncoderOptions& options, EncodeProgress* progress, SequenceReport* report,
                   std::vector<uint8_t>* stream) {
  EncoderCallbacks callbacks = progress->Callbacks();
  Status view_status = Status::Ok();
  std::unique_ptr<VideoWriter> views_video;
  if (!args.views.empty()) {
    callbacks.held_out_view = [&](int frame, const Image& truth, const Image& render) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05d.png", frame);
      const Image error = ErrorImage(truth, render, 4.0f);
      Status s = WriteViewStrip((std::filesystem::path(args.views) / name).string(),
                                {&truth, &render, &error});
      if (s.ok()) s = AppendToVideo(args.views, {&truth, &render, &error}, &views_video);
      if (view_status.ok()) view_status = s;
    };
  }
  SequenceEncoder encoder(capture, options);
  if (!args.keyframe_ply.empty()) {
    GaussianModel model;
    M4D_RETURN_IF_ERROR(ReadFirstKeyframe(args, options.sh_degree, &model));
    encoder.SetFirstKeyframe(std::move(model));
  }
  if (args.keyframe_source) encoder.SetKeyframeSource(args.keyframe_source);
  M4D_RETURN_IF_ERROR(encoder.Encode(callbacks, report));
  report->peak_memory_bytes = PeakMemoryBytes();
  PrintSummary(stdout, *report);
  M4D_RETURN_IF_ERROR(view_status);
  if (views_video) {
    M4D_RETURN_IF_ERROR(views_video->Finish());
    std::printf("%-34s %s/views.mp4 (%s)\n", "held-out views", args.views.c_str(),
                views_video->codec_name().c_str());
  }
  *stream = encoder.stream();
  return Status::Ok();
}

std::string CheckpointDir(const EncodeArguments& args) {
  return args.checkpoint_dir.empty() ? args.output + ".chunks" : args.checkpoint_dir;
}

void PrintChunkTable(const nlohmann::json& table) {
  std::printf("\n%6s %7s %7s %5s %10s %10s\n", "chunk", "frames", "first", "rank", "seconds", "KB");
  for (const nlohmann::json& c : table) {
    std::printf("%6d %7d %7d %5d %10.1f %10.2f\n", c["chunk"].get<int>(), c["count"].get<int>(),
                c["first"].get<int>(), c["rank"].get<int>(), c["seconds"].get<double>(),
                static_cast<double>(c["bytes"].get<size_t>()) / 1000.0);
  }
}

// Chunked: *done is false when this rank has nothing to write (not rank 0, or chunks remain).
Status EncodeChunked(const EncodeArguments& args, const Capture& capture,
                     const EncoderOptions& options, const nlohmann::json& settings,
                     EncodeProgress* progress, SequenceReport* report, std::vector<uint8_t>* stream,
                     nlohmann::json* chunk_table, bool* done) {
  ChunkedEncodeOptions chunked;
  chunked.chunk_frames = args.chunk_frames;
  chunked.checkpoint_dir = CheckpointDir(args);
  chunked.settings = settings;
  chunked.max_chunks = args.max_chunks;
  GaussianModel first;
  if (!args.keyframe_ply.empty()) {
    M4D_RETURN_IF_ERROR(ReadFirstKeyframe(args, options.sh_degree, &first));
    chunked.first_keyframe = &first;
  }
  ChunkedEncodeResult result;
  M4D_RETURN_IF_ERROR(RunChunkedEncode(capture, options, chunked, progress->Callbacks(), &result));
  *done = result.complete && CurrentRanks().rank == 0;
  if (!result.complete && CurrentRanks().rank == 0) {
    std::printf("%zu of %zu chunks done in %s: the same command goes on with the others\n",
                result.chunks_done, result.chunks, chunked.checkpoint_dir.c_str());
  }
  if (!*done) return Status::Ok();
  *report = std::move(result.report);
  *stream = std::move(result.stream);
  *chunk_table = std::move(result.chunk_table);
  report->peak_memory_bytes = PeakMemoryBytes();
  std::printf("\n");
  for (size_t f = 0; f < report->frames.size(); ++f) {
    PrintFrameLine(stdout, report->frames[f], f == 0);
  }
  PrintChunkTable(*chunk_table);
  std::printf("\n");
  PrintSummary(stdout, *report);
  return Status::Ok();
}

}  // namespace

Status RunEncode(const EncodeArguments& args, SequenceReport* report) {
  EncoderOptions options;
  M4D_RETURN_IF_ERROR(ResolveEncoderOptions(args, &options));
  const bool chunked = args.chunk_frames > 0 || CurrentRanks().size > 1;
  if (chunked && (!args.views.empty() || args.keyframe_source || options.independent_frames)) {
    return Status(M4D_ERR_INVALID_ARG,
                  "chunked encoding (--chunk-frames, MPI) codes no --views and no baseline");
  }
  // Hours of encoding must not end in a path that cannot be written.
  if (CurrentRanks().rank == 0) {
    M4D_RETURN_IF_ERROR(CheckOutputPath(args.output));
    M4D_RETURN_IF_ERROR(CheckOutputPath(ReportPath(args)));
  }
  uint32_t unused_num, unused_den;
  if (!args.fps.empty()) M4D_RETURN_IF_ERROR(ParseFrameRate(args.fps, &unused_num, &unused_den));
  Capture capture;
  M4D_RETURN_IF_ERROR(OpenCapture(args.capture, &capture));
  M4D_RETURN_IF_ERROR(ChooseFrameRate(args.fps, capture, &options));
  M4D_RETURN_IF_ERROR(ChooseUpAxis(args.up, capture, &options));
  M4D_RETURN_IF_ERROR(CheckViewsBeforeTraining(capture, options.first_frame, options.frame_count));
  AutomaticChoices choices;
  M4D_RETURN_IF_ERROR(ResolveAutomaticChoices(args, capture, &options, &choices));

  EncodeProgress progress;
  std::vector<uint8_t> stream;
  nlohmann::json extra = {
      {"options", EncodeOptionsJson(args)},
      {"start_size_selection",
       choices.from_scratch ? StartSizeJson(args.prune, choices.start) : nlohmann::json()},
      {"prune_share_selection",
       choices.trains_keyframe ? PruneShareJson(args.prune, choices.prune) : nlohmann::json()},
      {"keyframe_bits_selection",
       choices.trains_keyframe
           ? KeyframeBitsJson(EncodeKeyframeBits(args), args.prune.bits_max_loss_per_halving_db,
                              choices.bits)
           : nlohmann::json()},
      {"rate_weight_selection", choices.trains_keyframe
                                    ? RateWeightJson(args.keyframe_rate, choices.rate)
                                    : nlohmann::json()}};
  if (chunked) {
    nlohmann::json settings = extra["options"];
    settings["resolved"] = {options.keyframe.importance_prune_share,
                            options.keyframe_rate_weight,
                            options.fps_num,
                            options.fps_den,
                            capture.frame_count,
                            options.keyframe.sweep_share,
                            QuantizationName(options.quantization)};
    bool done = false;
    nlohmann::json chunk_table;
    M4D_RETURN_IF_ERROR(EncodeChunked(args, capture, options, settings, &progress, report, &stream,
                                      &chunk_table, &done));
    if (!done) return Status::Ok();
    extra["chunks"] = chunk_table;
  } else {
    M4D_RETURN_IF_ERROR(EncodeWhole(args, capture, options, &progress, report, &stream));
  }
  M4D_RETURN_IF_ERROR(WriteFileAtomically(args.output, stream.data(), stream.size()));
  const std::string json_path = ReportPath(args);
  M4D_RETURN_IF_ERROR(WriteReportJson(json_path, *report, extra.dump()));
  M4D_RETURN_IF_ERROR(CheckDecodedHashes(stream, *report));
  std::printf("%-34s %zu frames decoded by the SDK, every hash equal to the encoder's\n",
              "decoder check", report->frames.size());
  std::printf("%-34s %s (report %s)\n", "stream", args.output.c_str(), json_path.c_str());
  return Status::Ok();
}

}  // namespace m4d
