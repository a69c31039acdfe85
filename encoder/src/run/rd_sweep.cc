#include "encoder/src/run/rd_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "encoder/src/io/atomic_file.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/run/capture_arguments.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/progress_bar.h"

namespace m4d {
namespace {

std::string LambdaName(double lambda) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", lambda);
  return text;
}

// Runs gnuplot on a script (data inline); the PNG is written by the script.
Status RunGnuplot(const std::string& script) {
  std::FILE* pipe = popen("gnuplot 2>&1", "w");
  if (!pipe) return Status(M4D_ERR_UNSUPPORTED, "cannot start gnuplot");
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  if (status != 0) {
    return Status(M4D_ERR_UNSUPPORTED, "gnuplot failed (is it installed? scripts/setup.sh)");
  }
  return Status::Ok();
}

std::string PlotHeader(const std::string& png, const char* title, const char* x, const char* y) {
  std::ostringstream s;
  s << "set terminal pngcairo size 900,600 noenhanced\n"
    << "set output '" << png << "'\n"
    << "set title '" << title << "'\nset xlabel '" << x << "'\nset ylabel '" << y << "'\n"
    << "set grid\nset key bottom right\n";
  return s.str();
}

// The sweep's keyframe schedule with the stream's SH degree, threads, seed and background.
KeyframeTrainingOptions SweepKeyframeTraining(const EncodeArguments& args) {
  KeyframeTrainingOptions o = KeyframeSchedule(args);
  o.sh_degree = args.encoder.sh_degree;
  o.context = args.encoder.context;
  o.rate_weight = std::max(0.0, args.keyframe_rate.weight);
  return o;
}

// Trains one frame with the sweep's keyframe schedule into a 3DGS PLY, showing progress.
Status TrainToPly(const Capture& capture, int frame, const EncodeArguments& args,
                  const std::string& path) {
  const KeyframeTrainingOptions o = SweepKeyframeTraining(args);
  ProgressBar bar;
  GaussianModel model;
  M4D_RETURN_IF_ERROR(TrainKeyframe(
      capture, frame, o,
      [&](const TrainingProgress& p) {
        if (p.iteration == 0) return;
        bar.Update(p, "keyframe " + std::to_string(frame));
        if (p.iteration == p.iterations) bar.Finish();
      },
      &model));
  GaussianSet set;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(model, model.sh_degree, &set));
  return WriteGaussianPly(path, set);
}

// A rate point from the report `m4d encode` wrote beside its stream.
Status ReadPoint(const std::string& json_path, RdPoint* point) {
  std::ifstream file(json_path);
  const nlohmann::json doc = nlohmann::json::parse(file, nullptr, false);
  try {
    const nlohmann::json& s = doc.at("summary");
    if (s.at("psnr").is_null()) {
      return Status(M4D_ERR_INVALID_ARG,
                    json_path + ": no held-out camera, and an RD curve needs one (--test-camera)");
    }
    SequenceSummary& m = point->summary;
    m.frames = s.at("frames");
    m.keyframes = s.at("keyframes");
    m.kb_per_frame = s.at("kb_per_frame");
    m.kb_per_inter_frame = s.at("kb_per_inter_frame");
    m.kb_per_keyframe = s.at("kb_per_keyframe");
    m.psnr = s.at("psnr");
    m.keyframe_psnr = s.at("keyframe_psnr");
    m.ssim = s.at("ssim");
    m.seconds = s.at("seconds");
    m.seconds_per_inter_frame = s.at("seconds_per_inter_frame");
    double inter_sum = 0;
    int inter = 0;
    for (const nlohmann::json& f : doc.at("frames")) {
      point->frame_psnr.push_back(f.at("psnr"));
      point->keyframe.push_back(f.at("keyframe"));
      if (!point->keyframe.back()) inter_sum += point->frame_psnr.back(), ++inter;
      // Reports of bitstream 0.2 encoders have no static_update.
      for (const ReportLayer& layer : ReportLayers()) {
        m.kb_per_frame_by_type[layer.packet_type] +=
            f.at("bytes").value(layer.key, 0.0) / 1000.0 / static_cast<double>(m.frames);
      }
    }
    point->inter_psnr = inter ? inter_sum / inter : 0.0;
  } catch (const nlohmann::json::exception&) {
    return Status(M4D_ERR_INVALID_ARG, json_path + ": not an encoder report");
  }
  return Status::Ok();
}

// The share an earlier sweep chose (PrepareSharedKeyframe).
Status ReadPruneShare(const std::string& path, double* share, double* sweep_share) {
  std::ifstream file(path);
  double value = -1;
  if (!(file >> value) || !(value >= 0.0 && value < 1.0)) {
    return Status(M4D_ERR_INVALID_ARG, path + ": not a prune share");
  }
  *share = value;
  // Files of sweeps before the start share hold the prune share alone: those started full.
  double sweep = 1.0;
  if (file >> sweep && !(sweep > 0.0 && sweep <= 1.0)) {
    return Status(M4D_ERR_INVALID_ARG, path + ": not a start share");
  }
  *sweep_share = sweep;
  return Status::Ok();
}

// Whether an earlier run wrote this stream and its report with these options.
bool EarlierRun(const EncodeArguments& run) {
  std::ifstream file(run.output + ".json");
  if (!file || !std::filesystem::exists(run.output)) return false;
  const nlohmann::json doc = nlohmann::json::parse(file, nullptr, false);
  return doc.is_object() && doc.contains("options") && doc["options"] == EncodeOptionsJson(run);
}

// Encodes one rate point (or, with reuse, takes an earlier run's) and reads its report.
Status RunPoint(EncodeArguments run, const SweepOutput& out, RdPoint* point) {
  run.json.clear();
  run.views.clear();
  if (out.reuse && EarlierRun(run)) {
    std::printf("reusing %s (same options)\n", run.output.c_str());
  } else {
    SequenceReport report;
    M4D_RETURN_IF_ERROR(RunEncode(run, &report));
  }
  point->stream = run.output;
  return ReadPoint(run.output + ".json", point);
}

}  // namespace

const std::vector<double>& PaperLambdas() {
  static const std::vector<double> kLambdas = [] {
    std::vector<double> lambdas;
    for (const RatePointSettings& p : RatePoints()) lambdas.push_back(p.motion_rate_weight);
    return lambdas;
  }();
  return kLambdas;
}

// Chooses the automatic shares once, on the first frame, for every rate point alike.
Status ResolveSweepShares(const Capture& capture, EncodeArguments* args) {
  KeyframeTrainingOptions options = SweepKeyframeTraining(*args);
  KeyframeShareChoice choice;
  M4D_RETURN_IF_ERROR(
      ResolveKeyframeShares(capture, args->encoder.first_frame, args->prune, &options, &choice));
  args->prune.share = options.importance_prune_share;
  args->prune.sweep_share = options.sweep_share;
  return Status::Ok();
}

Status PrepareSharedKeyframe(const SweepOutput& out, EncodeArguments* args) {
  if (args->keyframe_rate.automatic) {
    return Status(M4D_ERR_INVALID_ARG,
                  "--keyframe-rate-weight auto: a sweep shares one keyframe among its rate "
                  "points; give the weight (m4d train DATASET --keyframe-rate-weight auto prints "
                  "the one it chooses)");
  }
  const bool automatic = args->prune.Automatic() || args->prune.StartAutomatic();
  Capture capture;
  if (!args->keyframe_ply.empty()) {
    // A given keyframe still has its GOPs' keyframes retrained with the prune share; none is
    // trained from scratch, so the start share goes unused.
    if (!args->prune.Automatic()) return Status::Ok();
    args->prune.sweep_share = SweepKeyframeTraining(*args).sweep_share;
    M4D_RETURN_IF_ERROR(OpenCapture(args->capture, &capture));
    return ResolveSweepShares(capture, args);
  }
  const std::string path = (std::filesystem::path(out.dir) / "keyframe.ply").string();
  // Automatic shares are chosen once, with the keyframe, and kept beside it for --reuse.
  const std::string share_path = path + ".prune_share";
  if (out.reuse && std::filesystem::exists(path) &&
      (!automatic || std::filesystem::exists(share_path))) {
    if (automatic) {
      M4D_RETURN_IF_ERROR(ReadPruneShare(share_path, &args->prune.share, &args->prune.sweep_share));
    }
  } else {
    M4D_RETURN_IF_ERROR(OpenCapture(args->capture, &capture));
    M4D_RETURN_IF_ERROR(ResolveSweepShares(capture, args));
    M4D_RETURN_IF_ERROR(TrainToPly(capture, args->encoder.first_frame, *args, path));
    if (automatic) {
      const std::string text =
          std::to_string(args->prune.share) + "\n" + std::to_string(args->prune.sweep_share) + "\n";
      M4D_RETURN_IF_ERROR(WriteFileAtomically(
          share_path, reinterpret_cast<const uint8_t*>(text.data()), text.size()));
    }
  }
  args->keyframe_ply = path;
  return Status::Ok();
}

Status RunSweep(const EncodeArguments& args, const std::vector<double>& lambdas,
                const SweepOutput& out, const std::string& name, RdCurve* curve) {
  for (size_t i = 0; i < lambdas.size(); ++i) {
    std::printf("\n== %s: lambda_2 %g (%zu of %zu) ==\n", curve->label.c_str(), lambdas[i], i + 1,
                lambdas.size());
    EncodeArguments run = args;
    run.rate_point.clear();
    run.lambda = lambdas[i];
    run.output =
        (std::filesystem::path(out.dir) / (name + "_lambda" + LambdaName(lambdas[i]) + ".m4d"))
            .string();
    RdPoint point;
    M4D_RETURN_IF_ERROR(RunPoint(run, out, &point));
    // --lambda takes the nearest rate point's other settings: name both.
    point.name = RatePointForLambda(lambdas[i]).name + " lambda_2 " + LambdaName(lambdas[i]);
    point.lambda = lambdas[i];
    curve->points.push_back(std::move(point));
  }
  return Status::Ok();
}

Status RunStaticLadder(const EncodeArguments& args, const SweepOutput& out, RdCurve* curve) {
  Capture capture;
  M4D_RETURN_IF_ERROR(OpenCapture(args.capture, &capture));
  const int first = args.encoder.first_frame;
  const int available = capture.frame_count - first;
  const int frames =
      args.encoder.frame_count > 0 ? std::min(args.encoder.frame_count, available) : available;
  if (frames <= 0) return Status(M4D_ERR_INVALID_ARG, "first frame beyond the capture");
  std::printf("\n== %s: every frame trained on its own (%d iterations) ==\n", curve->label.c_str(),
              KeyframeSchedule(args).iterations);
  std::vector<std::string> paths;
  for (int t = first; t < first + frames; ++t) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.ply", t);
    paths.push_back((std::filesystem::path(out.dir) / name).string());
    if (t == first && !args.keyframe_ply.empty()) {
      paths.back() = args.keyframe_ply;  // the shared keyframe is this frame's own training
    } else if (!out.reuse || !std::filesystem::exists(paths.back())) {
      M4D_RETURN_IF_ERROR(TrainToPly(capture, t, args, paths.back()));
    }
  }
  EncodeArguments run = args;
  run.encoder.independent_frames = true;
  const int sh_degree = args.encoder.sh_degree;
  run.keyframe_source = [paths, first, sh_degree](int frame, GaussianModel* model) {
    GaussianSet set;
    M4D_RETURN_IF_ERROR(ReadGaussianPly(paths[frame - first], &set));
    return ModelFromGaussianSet(set, sh_degree, model);
  };
  // The rate points' keyframe coding, finest first: the same Gaussian coding as our keyframes.
  const std::vector<RatePointSettings>& ladder = RatePoints();
  for (size_t i = 0; i < ladder.size(); ++i) {
    const RatePointSettings& rate_point = ladder[ladder.size() - 1 - i];
    const std::string name = rate_point.name + " bits " + QuantizationName(rate_point.keyframe);
    std::printf("\n== %s: %s (%zu of %zu) ==\n", curve->label.c_str(), name.c_str(), i + 1,
                ladder.size());
    run.rate_point = rate_point.name;
    run.output =
        (std::filesystem::path(out.dir) / ("static_q" + std::to_string(i) + ".m4d")).string();
    RdPoint point;
    M4D_RETURN_IF_ERROR(RunPoint(run, out, &point));
    point.name = name;
    curve->points.push_back(std::move(point));
  }
  return Status::Ok();
}

std::vector<RatePoint> RatePoints(const RdCurve& curve, RateScope scope) {
  std::vector<RatePoint> points;
  for (const RdPoint& p : curve.points) {
    if (scope == RateScope::kAllFrames) {
      points.push_back({p.summary.kb_per_frame, p.summary.psnr});
    } else if (p.summary.kb_per_inter_frame > 0) {
      points.push_back({p.summary.kb_per_inter_frame, p.inter_psnr});
    }
  }
  std::sort(points.begin(), points.end(),
            [](const RatePoint& a, const RatePoint& b) { return a.rate < b.rate; });
  // The RD envelope: a point that a cheaper one matches in PSNR is never the one to pick
  // (and Bjontegaard needs PSNR rising with rate). Fine quantization steps can cost bytes
  // without gaining anything measurable.
  std::vector<RatePoint> envelope;
  for (const RatePoint& p : points) {
    if (envelope.empty() || p.psnr > envelope.back().psnr) envelope.push_back(p);
  }
  return envelope;
}

nlohmann::json CompareCurves(const RdCurve& anchor, const RdCurve& test) {
  nlohmann::json out = nlohmann::json::object();
  for (RateScope scope : {RateScope::kAllFrames, RateScope::kInterFrames}) {
    BjontegaardDelta bd;
    const Status s = ComputeBjontegaard(RatePoints(anchor, scope), RatePoints(test, scope), &bd);
    nlohmann::json& cell = out[scope == RateScope::kAllFrames ? "all" : "inter"];
    cell = nlohmann::json::object();
    if (!s.ok()) cell["error"] = s.message();
    if (bd.has_rate) cell["bd_rate_percent"] = bd.rate_percent;
    if (bd.has_psnr) cell["bd_psnr_db"] = bd.psnr_db;
  }
  return out;
}

std::string BdCells(const nlohmann::json& compare, const char* scope) {
  char rate[32] = "      n/a", psnr[32] = "     n/a";
  const nlohmann::json& c = compare.at(scope);
  if (c.contains("bd_rate_percent")) {
    std::snprintf(rate, sizeof(rate), "%+8.1f%%", c["bd_rate_percent"].get<double>());
  }
  if (c.contains("bd_psnr_db")) {
    std::snprintf(psnr, sizeof(psnr), "%+8.2f", c["bd_psnr_db"].get<double>());
  }
  return std::string(rate) + " " + psnr;
}

nlohmann::json RdCurveJson(const RdCurve& curve) {
  nlohmann::json points = nlohmann::json::array();
  for (const RdPoint& p : curve.points) {
    nlohmann::json by_layer = nlohmann::json::object();
    for (const ReportLayer& layer : ReportLayers()) {
      by_layer[layer.key] = p.summary.kb_per_frame_by_type[layer.packet_type];
    }
    points.push_back({{"name", p.name},
                      {"lambda", p.lambda},
                      {"stream", p.stream},
                      {"kb_per_frame", p.summary.kb_per_frame},
                      {"kb_per_inter_frame", p.summary.kb_per_inter_frame},
                      {"psnr", p.summary.psnr},
                      {"inter_psnr", p.inter_psnr},
                      {"ssim", p.summary.ssim},
                      {"keyframes", p.summary.keyframes},
                      {"seconds_per_inter_frame", p.summary.seconds_per_inter_frame},
                      {"kb_per_frame_by_layer", by_layer},
                      {"frame_psnr", p.frame_psnr}});
  }
  return {{"label", curve.label}, {"points", points}};
}

Status LoadAnchorCurve(const std::string& rd_json, RdCurve* curve) {
  const auto invalid = [&](const std::string& why) {
    return Status(M4D_ERR_INVALID_ARG, "anchor " + rd_json + ": " + why);
  };
  std::ifstream file(rd_json);
  if (!file) return invalid("cannot read it");
  const nlohmann::json doc = nlohmann::json::parse(file, nullptr, false);
  try {
    const nlohmann::json& first = doc.at("curves").at(0);
    curve->label = first.at("label").get<std::string>() + " (" + rd_json + ")";
    curve->points.clear();
    for (const nlohmann::json& j : first.at("points")) {
      RdPoint p;
      p.name = j.at("name");
      p.lambda = j.at("lambda");
      p.stream = j.at("stream");
      p.summary.kb_per_frame = j.at("kb_per_frame");
      p.summary.kb_per_inter_frame = j.at("kb_per_inter_frame");
      p.summary.psnr = j.at("psnr");
      p.inter_psnr = j.at("inter_psnr");
      p.summary.ssim = j.at("ssim");
      p.summary.keyframes = j.at("keyframes");
      p.summary.seconds_per_inter_frame = j.at("seconds_per_inter_frame");
      p.frame_psnr = j.at("frame_psnr").get<std::vector<double>>();
      p.summary.frames = p.frame_psnr.size();
      // rd reports before the layer tables have none.
      const nlohmann::json by_layer = j.value("kb_per_frame_by_layer", nlohmann::json::object());
      for (const ReportLayer& layer : ReportLayers()) {
        p.summary.kb_per_frame_by_type[layer.packet_type] = by_layer.value(layer.key, 0.0);
      }
      if (!(p.summary.kb_per_frame > 0) || !std::isfinite(p.summary.psnr)) {
        return invalid("point " + p.name + " has no rate or PSNR");
      }
      curve->points.push_back(std::move(p));
    }
  } catch (const nlohmann::json::exception&) {
    return invalid("not an m4d rd report (rd.json)");
  }
  if (curve->points.empty()) return invalid("its first curve has no points");
  return Status::Ok();
}

Status PlotRdCurves(const std::vector<RdCurve>& curves, const std::string& png, RateScope scope) {
  const bool all = scope == RateScope::kAllFrames;
  std::ostringstream s;
  s << PlotHeader(png, all ? "Rate-distortion (held-out camera)" : "Inter frames (held-out camera)",
                  all ? "KB per frame (keyframes included)" : "KB per inter frame",
                  all ? "PSNR (dB)" : "inter-frame PSNR (dB)");
  std::vector<std::vector<std::pair<double, double>>> data;  // per curve, by rate
  std::string plot;
  for (const RdCurve& curve : curves) {
    std::vector<std::pair<double, double>> points;
    for (const RdPoint& p : curve.points) {
      if (all) points.emplace_back(p.summary.kb_per_frame, p.summary.psnr);
      if (!all && p.summary.kb_per_inter_frame > 0) {
        points.emplace_back(p.summary.kb_per_inter_frame, p.inter_psnr);
      }
    }
    if (points.empty()) continue;
    std::sort(points.begin(), points.end());
    plot += (plot.empty() ? "plot " : ", ") +
            std::string("'-' using 1:2 with linespoints lw 2 title '") + curve.label + "'";
    data.push_back(std::move(points));
  }
  if (data.empty()) return Status::Ok();
  s << plot << "\n";
  for (const auto& points : data) {
    for (const auto& [rate, psnr] : points) s << rate << " " << psnr << "\n";
    s << "e\n";
  }
  return RunGnuplot(s.str());
}

Status PlotPsnrPerFrame(const RdCurve& curve, const std::string& png) {
  std::ostringstream s;
  s << PlotHeader(png, "Held-out PSNR per frame", "frame", "PSNR (dB)");
  s << "plot ";
  for (size_t c = 0; c < curve.points.size(); ++c) {
    s << (c ? ", " : "") << "'-' using 1:2 with linespoints title '" << curve.points[c].name << "'";
  }
  s << "\n";
  for (const RdPoint& p : curve.points) {
    for (size_t f = 0; f < p.frame_psnr.size(); ++f) s << f << " " << p.frame_psnr[f] << "\n";
    s << "e\n";
  }
  return RunGnuplot(s.str());
}

}  // namespace m4d
