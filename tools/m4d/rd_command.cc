#include "rd_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command_status.h"
#include "rd_sweep.h"

namespace m4d {
namespace {

struct RdArguments {
  EncodeArguments encode;
  std::string dir = "out/rd";
  std::vector<double> lambdas = PaperLambdas();
};

void PrintTable(const RdCurve& curve) {
  std::printf("\n%-10s %12s %12s %10s %10s %8s %10s\n", "lambda_2", "KB/frame", "KB/inter", "PSNR",
              "inter PSNR", "SSIM", "s/inter");
  for (const RdPoint& p : curve.points) {
    std::printf("%-10g %12.2f %12.2f %10.2f %10.2f %8.4f %10.1f\n", p.lambda,
                p.summary.kb_per_frame, p.summary.kb_per_inter_frame, p.summary.psnr, p.inter_psnr,
                p.summary.ssim, p.summary.seconds_per_inter_frame);
  }
}

Status RunRd(RdArguments args) {
  std::error_code ec;
  std::filesystem::create_directories(args.dir, ec);
  if (ec) return Status(M4D_ERR_INVALID_ARG, "cannot create " + args.dir);
  M4D_RETURN_IF_ERROR(PrepareSharedKeyframe(args.dir, &args.encode));
  RdCurve curve;
  curve.label = "m4d";
  M4D_RETURN_IF_ERROR(RunSweep(args.encode, args.lambdas, args.dir, "rd", &curve));
  PrintTable(curve);
  const std::string json_path = (std::filesystem::path(args.dir) / "rd.json").string();
  std::ofstream(json_path) << RdCurveJson(curve).dump(2) << "\n";
  for (const Status& plot :
       {PlotRdCurves({curve}, (std::filesystem::path(args.dir) / "rd.png").string()),
        PlotPsnrPerFrame(curve,
                         (std::filesystem::path(args.dir) / "psnr_per_frame.png").string())}) {
    if (!plot.ok()) std::fprintf(stderr, "m4d rd: no plot: %s\n", plot.message().c_str());
  }
  std::printf("\nreport %s; plots rd.png and psnr_per_frame.png in %s\n", json_path.c_str(),
              args.dir.c_str());
  return Status::Ok();
}

}  // namespace

void AddRdCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<RdArguments>();
  CLI::App* cmd = app->add_subcommand(
      "rd", "RD sweep over lambda_2: one stream per rate point, table, JSON and PNG plots");
  AddCaptureArguments(cmd, &args->encode.capture);
  AddEncoderOptions(cmd, &args->encode);
  cmd->add_option("-o,--output-dir", args->dir, "streams, reports and plots go here")
      ->capture_default_str();
  cmd->add_option("--lambdas", args->lambdas, "rate weights lambda_2 (default: the paper's)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  cmd->callback([args, exit_code]() { *exit_code = ReportStatus("rd", RunRd(*args)); });
}

}  // namespace m4d
