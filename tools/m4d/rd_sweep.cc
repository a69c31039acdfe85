#include "rd_sweep.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "capture_arguments.h"
#include "ply/gaussian_ply.h"
#include "train/gaussian_model.h"
#include "train/keyframe_trainer.h"
#include "train/progress_bar.h"

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

}  // namespace

const std::vector<double>& PaperLambdas() {
  static const std::vector<double> kLambdas = {5e-4, 3e-4, 2e-4, 1e-4, 5e-5};
  return kLambdas;
}

Status PrepareSharedKeyframe(const std::string& dir, EncodeArguments* args) {
  if (!args->keyframe_ply.empty()) return Status::Ok();
  Capture capture;
  M4D_RETURN_IF_ERROR(OpenCapture(args->capture, &capture));
  KeyframeTrainingOptions o = args->keyframe_iterations > 0
                                  ? KeyframeTrainingOptions::Short(args->keyframe_iterations)
                                  : args->encoder.keyframe;
  o.sh_degree = args->encoder.sh_degree;
  o.threads = args->encoder.threads;
  o.seed = args->encoder.seed;
  std::copy(args->encoder.background, args->encoder.background + 3, o.background);
  ProgressBar bar;
  GaussianModel model;
  M4D_RETURN_IF_ERROR(TrainKeyframe(
      capture, args->encoder.first_frame, o,
      [&](const TrainingProgress& p) {
        if (p.iteration == 0) return;
        std::fprintf(stderr, "\rshared keyframe ");
        bar.Update(p);
        if (p.iteration == p.iterations) bar.Finish();
      },
      &model));
  GaussianSet set;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(model, model.sh_degree, &set));
  args->keyframe_ply = (std::filesystem::path(dir) / "keyframe.ply").string();
  return WriteGaussianPly(args->keyframe_ply, set);
}

Status RunSweep(const EncodeArguments& args, const std::vector<double>& lambdas,
                const std::string& dir, const std::string& name, RdCurve* curve) {
  for (size_t i = 0; i < lambdas.size(); ++i) {
    std::printf("\n== %s: lambda_2 %g (%zu of %zu) ==\n", curve->label.c_str(), lambdas[i], i + 1,
                lambdas.size());
    EncodeArguments run = args;
    run.rate_point.clear();
    run.encoder.motion.rate_weight = lambdas[i];
    run.output = (std::filesystem::path(dir) / (name + "_lambda" + LambdaName(lambdas[i]) + ".m4d"))
                     .string();
    run.json.clear();
    run.views.clear();
    SequenceReport report;
    M4D_RETURN_IF_ERROR(RunEncode(run, &report));
    RdPoint point;
    point.lambda = lambdas[i];
    point.summary = Summarise(report);
    point.stream = run.output;
    double inter_sum = 0;
    int inter = 0;
    for (const FrameReport& f : report.frames) {
      point.frame_psnr.push_back(f.psnr);
      point.keyframe.push_back(f.keyframe);
      if (!f.keyframe) {
        inter_sum += f.psnr;
        ++inter;
      }
    }
    point.inter_psnr = inter ? inter_sum / inter : 0.0;
    curve->points.push_back(std::move(point));
  }
  return Status::Ok();
}

std::vector<RatePoint> RatePoints(const RdCurve& curve) {
  std::vector<RatePoint> points;
  for (const RdPoint& p : curve.points) points.push_back({p.summary.kb_per_frame, p.summary.psnr});
  return points;
}

nlohmann::json RdCurveJson(const RdCurve& curve) {
  nlohmann::json points = nlohmann::json::array();
  for (const RdPoint& p : curve.points) {
    points.push_back({{"lambda", p.lambda},
                      {"stream", p.stream},
                      {"kb_per_frame", p.summary.kb_per_frame},
                      {"kb_per_inter_frame", p.summary.kb_per_inter_frame},
                      {"psnr", p.summary.psnr},
                      {"inter_psnr", p.inter_psnr},
                      {"ssim", p.summary.ssim},
                      {"keyframes", p.summary.keyframes},
                      {"seconds_per_inter_frame", p.summary.seconds_per_inter_frame},
                      {"frame_psnr", p.frame_psnr}});
  }
  return {{"label", curve.label}, {"points", points}};
}

Status PlotRdCurves(const std::vector<RdCurve>& curves, const std::string& png) {
  std::ostringstream s;
  s << PlotHeader(png, "Rate-distortion (held-out camera)", "KB per frame (keyframes included)",
                  "PSNR (dB)");
  s << "plot ";
  for (size_t c = 0; c < curves.size(); ++c) {
    s << (c ? ", " : "") << "'-' using 1:2 with linespoints lw 2 title '" << curves[c].label << "'";
  }
  s << "\n";
  for (const RdCurve& curve : curves) {
    for (const RdPoint& p : curve.points)
      s << p.summary.kb_per_frame << " " << p.summary.psnr << "\n";
    s << "e\n";
  }
  return RunGnuplot(s.str());
}

Status PlotPsnrPerFrame(const RdCurve& curve, const std::string& png) {
  std::ostringstream s;
  s << PlotHeader(png, "Held-out PSNR per frame", "frame", "PSNR (dB)");
  s << "plot ";
  for (size_t c = 0; c < curve.points.size(); ++c) {
    s << (c ? ", " : "") << "'-' using 1:2 with linespoints title 'lambda_2 "
      << LambdaName(curve.points[c].lambda) << "'";
  }
  s << "\n";
  for (const RdPoint& p : curve.points) {
    for (size_t f = 0; f < p.frame_psnr.size(); ++f) s << f << " " << p.frame_psnr[f] << "\n";
    s << "e\n";
  }
  return RunGnuplot(s.str());
}

}  // namespace m4d
