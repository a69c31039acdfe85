#include "tools/m4d/rd_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/run/rd_sweep.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/encode_command.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

struct RdArguments {
  EncodeArguments encode;
  SweepOutput out{"out/rd", false};
  std::vector<double> lambdas = PaperLambdas();
  std::vector<std::string> baselines = {"static", "dynamic"};
  std::vector<std::string> anchors;  // earlier sweeps' rd.json
};

// A per-inter-frame figure, or "-" for a point without inter frames (the static baseline).
std::string InterCell(const RdPoint& p, double value, int decimals) {
  if (p.summary.frames == p.summary.keyframes) return "-";
  char cell[32];
  std::snprintf(cell, sizeof(cell), "%.*f", decimals, value);
  return cell;
}

void PrintCurve(const RdCurve& curve) {
  std::printf("\n%s\n%-26s %11s %10s %8s %10s %7s %5s %8s\n", curve.label.c_str(), "rate point",
              "KB/frame", "KB/inter", "PSNR", "inter PSNR", "SSIM", "keys", "s/inter");
  for (const RdPoint& p : curve.points) {
    std::printf("%-26s %11.2f %10s %8.2f %10s %7.4f %5zu %8s\n", p.name.c_str(),
                p.summary.kb_per_frame, InterCell(p, p.summary.kb_per_inter_frame, 2).c_str(),
                p.summary.psnr, InterCell(p, p.inter_psnr, 2).c_str(), p.summary.ssim,
                p.summary.keyframes, InterCell(p, p.summary.seconds_per_inter_frame, 1).c_str());
  }
}

// KB per frame by layer at each rate point: where the bytes go along the curve.
void PrintLayerTable(const RdCurve& curve) {
  std::printf("\n%s: KB per frame by layer\n%-26s", curve.label.c_str(), "rate point");
  for (const ReportLayer& layer : ReportLayers()) std::printf(" %13.13s", layer.label);
  std::printf("\n");
  for (const RdPoint& p : curve.points) {
    std::printf("%-26s", p.name.c_str());
    for (const ReportLayer& layer : ReportLayers()) {
      std::printf(" %13.2f", p.summary.kb_per_frame_by_type[layer.packet_type]);
    }
    std::printf("\n");
  }
}

// Ours against a baseline: BD-rate (negative: we need fewer bytes) and BD-PSNR.
nlohmann::json CompareWith(const RdCurve& ours, const RdCurve& baseline) {
  nlohmann::json c = CompareCurves(baseline, ours);
  std::printf("%-30s %s %s\n", baseline.label.c_str(), BdCells(c, "all").c_str(),
              BdCells(c, "inter").c_str());
  c["baseline"] = baseline.label;
  return c;
}

Status RunBaselines(const RdArguments& args, std::vector<RdCurve>* curves) {
  for (const std::string& b : args.baselines) {
    curves->emplace_back();
    RdCurve& curve = curves->back();
    if (b == "static") {
      curve.label = "static per frame";
      M4D_RETURN_IF_ERROR(RunStaticLadder(args.encode, args.out, &curve));
    } else {
      curve.label = "all dynamic (3DGStream-like)";
      EncodeArguments run = args.encode;
      run.encoder.ablation.decoupling = false;
      M4D_RETURN_IF_ERROR(RunSweep(run, args.lambdas, args.out, "no_decoupling", &curve));
    }
  }
  return Status::Ok();
}

Status RunRd(RdArguments args) {
  // The anchors are read before any encoding, so that a wrong path costs no hours.
  std::vector<RdCurve> anchors(args.anchors.size());
  for (size_t i = 0; i < anchors.size(); ++i) {
    M4D_RETURN_IF_ERROR(LoadAnchorCurve(args.anchors[i], &anchors[i]));
  }
  std::error_code ec;
  std::filesystem::create_directories(args.out.dir, ec);
  if (ec) return Status(M4D_ERR_INVALID_ARG, "cannot create " + args.out.dir);
  M4D_RETURN_IF_ERROR(PrepareSharedKeyframe(args.out, &args.encode));
  std::vector<RdCurve> curves(1);
  curves[0].label = "m4d";
  M4D_RETURN_IF_ERROR(RunSweep(args.encode, args.lambdas, args.out, "full", &curves[0]));
  M4D_RETURN_IF_ERROR(RunBaselines(args, &curves));
  curves.insert(curves.end(), anchors.begin(), anchors.end());
  nlohmann::json doc = {{"curves", nlohmann::json::array()}, {"bd", nlohmann::json::array()}};
  for (const RdCurve& curve : curves) {
    PrintCurve(curve);
    doc["curves"].push_back(RdCurveJson(curve));
  }
  PrintLayerTable(curves[0]);
  if (curves.size() > 1) {
    std::printf(
        "\nm4d against the baselines (PCHIP Bjontegaard over each RD envelope)\n%-30s %18s "
        "%18s\n%-30s %9s %8s %9s %8s\n",
        "", "all frames", "inter frames", "baseline", "BD-rate", "BD-PSNR", "BD-rate", "BD-PSNR");
  }
  for (size_t c = 1; c < curves.size(); ++c) doc["bd"].push_back(CompareWith(curves[0], curves[c]));
  const std::filesystem::path dir(args.out.dir);
  std::ofstream((dir / "rd.json").string()) << doc.dump(2) << "\n";
  for (const Status& plot :
       {PlotRdCurves(curves, (dir / "rd.png").string(), RateScope::kAllFrames),
        PlotRdCurves(curves, (dir / "rd_inter.png").string(), RateScope::kInterFrames),
        PlotPsnrPerFrame(curves[0], (dir / "psnr_per_frame.png").string())}) {
    if (!plot.ok()) std::fprintf(stderr, "m4d rd: no plot: %s\n", plot.message().c_str());
  }
  std::printf("\nreport %s; plots rd.png, rd_inter.png and psnr_per_frame.png in %s\n",
              (dir / "rd.json").c_str(), args.out.dir.c_str());
  return Status::Ok();
}

}  // namespace

void AddRdCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<RdArguments>();
  CLI::App* cmd = app->add_subcommand(
      "rd",
      "RD sweep over lambda_2 against the baselines: one stream per rate point, table, JSON "
      "and PNG plots");
  AddCaptureArguments(cmd, &args->encode.capture);
  AddEncoderOptions(cmd, &args->encode);
  AddSweepOutputOptions(cmd, &args->out);
  cmd->add_option("--lambdas", args->lambdas,
                  "rate weights lambda_2, each with the nearest rate point's other settings "
                  "(default: the paper's, r1..r5)")
      ->delimiter(',')
      ->check(m4d::Positive());
  cmd->add_option("--baselines", args->baselines,
                  "static: every frame trained and coded on its own, at each rate point's "
                  "keyframe bits; dynamic: every Gaussian dynamic, over the lambdas; none")
      ->delimiter(',')
      ->check(CLI::IsMember({"static", "dynamic", "none"}))
      ->capture_default_str();
  cmd->add_option("--anchor", args->anchors,
                  "an earlier sweep's rd.json (e.g. another encoder version's): its first curve "
                  "is plotted and compared like a baseline (BD-rate); repeatable")
      ->check(CLI::ExistingFile);
  cmd->callback([args, exit_code]() {
    if (args->baselines == std::vector<std::string>{"none"}) args->baselines.clear();
    *exit_code = ReportStatus("rd", RunRd(*args));
  });
}

}  // namespace m4d
