#include "tools/m4d/ablate_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/run/rd_sweep.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/encode_command.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

struct AblateArguments {
  EncodeArguments encode;
  SweepOutput out{"out/ablate", false};
  std::vector<double> lambdas = PaperLambdas();
  int fixed_gop = 50;             // the paper's fixed GOP length
  std::vector<std::string> only;  // ablations to run; empty: all of them
};

struct Ablation {
  const char* name;   // file names
  const char* label;  // the table's
  std::function<void(EncoderOptions*)> apply;
};

std::vector<Ablation> Ablations(int fixed_gop) {
  return {{"full", "full method", [](EncoderOptions*) {}},
          {"no_decoupling", "no decoupling (all dynamic)",
           [](EncoderOptions* o) { o->ablation.decoupling = false; }},
          {"no_motion", "no motion estimation",
           [](EncoderOptions* o) { o->ablation.motion_estimation = false; }},
          {"no_compensation", "no compensation",
           [](EncoderOptions* o) { o->ablation.compensation = false; }},
          {"fixed_gop", "fixed GOP",
           [fixed_gop](EncoderOptions* o) {
             o->gop.adaptive = false;
             o->gop.fixed_length = fixed_gop;
           }},
          {"no_rate", "rate term off", [](EncoderOptions* o) { o->ablation.rate_term = false; }}};
}

struct Row {
  std::string label;
  double kb_per_frame = 0, kb_per_inter = 0, psnr = 0, inter_psnr = 0;
};

Row Summarise(const RdCurve& curve) {
  Row row;
  row.label = curve.label;
  for (const RdPoint& p : curve.points) {
    row.kb_per_frame += p.summary.kb_per_frame / curve.points.size();
    row.kb_per_inter += p.summary.kb_per_inter_frame / curve.points.size();
    row.psnr += p.summary.psnr / curve.points.size();
    row.inter_psnr += p.inter_psnr / curve.points.size();
  }
  return row;
}

Status RunAblate(AblateArguments args) {
  std::error_code ec;
  std::filesystem::create_directories(args.out.dir, ec);
  if (ec) return Status(M4D_ERR_INVALID_ARG, "cannot create " + args.out.dir);
  M4D_RETURN_IF_ERROR(PrepareSharedKeyframe(args.out, &args.encode));
  std::vector<RdCurve> curves;
  const std::vector<Ablation> ablations = Ablations(args.fixed_gop);
  for (const Ablation& a : ablations) {
    // The full method is the anchor of every comparison, so it always runs.
    const bool wanted = &a == &ablations[0] || args.only.empty() ||
                        std::find(args.only.begin(), args.only.end(), a.name) != args.only.end();
    if (!wanted) continue;
    EncodeArguments run = args.encode;
    a.apply(&run.encoder);
    curves.emplace_back();
    curves.back().label = a.label;
    M4D_RETURN_IF_ERROR(RunSweep(run, args.lambdas, args.out, a.name, &curves.back()));
  }
  std::printf("\nmeans over lambda_2 = ");
  for (double l : args.lambdas) std::printf("%g ", l);
  std::printf("\n%-30s %10s %10s %9s %11s %18s %18s\n%-30s %10s %10s %9s %11s %9s %8s %9s %8s\n",
              "", "", "", "", "", "all frames", "inter frames", "configuration", "KB/frame",
              "KB/inter", "PSNR", "inter PSNR", "BD-rate", "BD-PSNR", "BD-rate", "BD-PSNR");
  nlohmann::json rows = nlohmann::json::array();
  for (const RdCurve& curve : curves) {
    const Row r = Summarise(curve);
    std::printf("%-30s %10.2f %10.2f %9.2f %11.2f", r.label.c_str(), r.kb_per_frame, r.kb_per_inter,
                r.psnr, r.inter_psnr);
    nlohmann::json row = RdCurveJson(curve);
    if (&curve == &curves[0]) {
      std::printf(" %9s\n", "anchor");
    } else {
      const nlohmann::json bd = CompareCurves(curves[0], curve);
      std::printf(" %s %s\n", BdCells(bd, "all").c_str(), BdCells(bd, "inter").c_str());
      row["bd"] = bd;
    }
    rows.push_back(row);
  }
  const std::filesystem::path dir(args.out.dir);
  std::ofstream((dir / "ablate.json").string()) << rows.dump(2) << "\n";
  for (const Status& plot :
       {PlotRdCurves(curves, (dir / "ablate.png").string(), RateScope::kAllFrames),
        PlotRdCurves(curves, (dir / "ablate_inter.png").string(), RateScope::kInterFrames)}) {
    if (!plot.ok()) std::fprintf(stderr, "m4d ablate: no plot: %s\n", plot.message().c_str());
  }
  std::printf(
      "\nBD against the full method (PCHIP Bjontegaard over each RD envelope; all frames: KB "
      "per frame, keyframes included); n/a: fewer than two points or no common range\nreport "
      "%s, plots %s and ablate_inter.png\n",
      (dir / "ablate.json").c_str(), (dir / "ablate.png").c_str());
  return Status::Ok();
}

}  // namespace

void AddAblateCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<AblateArguments>();
  CLI::App* cmd = app->add_subcommand(
      "ablate", "the paper's ablations swept over lambda_2, with BD-rate against the full method");
  AddCaptureArguments(cmd, &args->encode.capture);
  AddEncoderOptions(cmd, &args->encode);
  AddSweepOutputOptions(cmd, &args->out);
  cmd->add_option("--lambdas", args->lambdas,
                  "rate weights lambda_2, each with the nearest rate point's other settings "
                  "(default: the paper's, r1..r5)")
      ->delimiter(',')
      ->check(m4d::Positive());
  std::vector<std::string> names;  // every ablation but the full method, the anchor
  for (const Ablation& a : Ablations(args->fixed_gop)) names.emplace_back(a.name);
  names.erase(names.begin());
  cmd->add_option("--ablations", args->only,
                  "only these ablations beside the full method (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(names));
  cmd->add_option("--fixed-gop-length", args->fixed_gop, "GOP length of the fixed-GOP ablation")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->callback([args, exit_code]() { *exit_code = ReportStatus("ablate", RunAblate(*args)); });
}

}  // namespace m4d
