// RD sweeps for `m4d rd` and `m4d ablate`: the same encode at several rate weights lambda_2,
// all starting from one first keyframe (its training does not depend on lambda_2, so it is
// trained once), and what the reports need from each run.
#ifndef M4D_ENCODER_RUN_RD_SWEEP_H_
#define M4D_ENCODER_RUN_RD_SWEEP_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/metrics/bjontegaard.h"
#include "encoder/src/pipeline/sequence_report_output.h"
#include "encoder/src/run/encode_run.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The paper's lambda_2 set, smallest rate first.
const std::vector<double>& PaperLambdas();

struct RdPoint {
  std::string name;  // the rate point, e.g. "r5 lambda_2 5e-05"
  double lambda = 0;
  SequenceSummary summary;
  double inter_psnr = 0;           // mean over inter frames (0 without any)
  std::vector<double> frame_psnr;  // held-out PSNR per frame
  std::vector<bool> keyframe;      // per frame
  std::string stream;              // the stream written
};

struct RdCurve {
  std::string label;  // e.g. "full method"
  std::vector<RdPoint> points;
};

// Where a sweep writes and whether it may reuse what an earlier sweep wrote there: a run whose
// stream and report exist with the same recorded options, and trained models.
struct SweepOutput {
  std::string dir;
  bool reuse = false;
};

// Trains the first keyframe once into dir/keyframe.ply and points args at it, unless
// args->keyframe_ply is already set; automatic start and prune shares are chosen first and given to
// every rate point (their retraining prunes it too), kept in dir/keyframe.ply.prune_share.
Status PrepareSharedKeyframe(const SweepOutput& out, EncodeArguments* args);

// Encodes with each lambda (and the settings of the rate point nearest it) into
// dir/<name>_lambda<L>.m4d (and its JSON).
Status RunSweep(const EncodeArguments& args, const std::vector<double>& lambdas,
                const SweepOutput& out, const std::string& name, RdCurve* curve);

// The per-frame baseline (every frame trained on its own, coded as a static keyframe) at each
// rate point's keyframe coding, finest first, into dir/static_q<i>.m4d. Each frame is trained
// once (dir/frame_<t>.ply; the first frame's model is the shared keyframe).
Status RunStaticLadder(const EncodeArguments& args, const SweepOutput& out, RdCurve* curve);

// Which frames a rate point's rate and PSNR are means over. Over all frames keyframes dominate
// a short sequence and where each GOP starts moves a point a long way; inter frames alone
// compare what motion coding costs.
enum class RateScope { kAllFrames, kInterFrames };

// (KB per frame, mean held-out PSNR) of the curve's RD envelope (the points no cheaper point
// matches in PSNR), by rate, for Bjontegaard deltas.
std::vector<RatePoint> RatePoints(const RdCurve& curve, RateScope scope);

// Bjontegaard deltas of `test` against `anchor`, over all frames ("all") and over inter frames
// ("inter"), each with bd_rate_percent when the curves share a PSNR range, bd_psnr_db when
// they share a rate range, and error when neither can be computed (too few points, no range).
nlohmann::json CompareCurves(const RdCurve& anchor, const RdCurve& test);
// One scope of a comparison as table cells: "  -12.3%   +0.45", "n/a" for a missing delta.
std::string BdCells(const nlohmann::json& compare, const char* scope);

// The curve as JSON: per point lambda, stream, rates, PSNRs, time, PSNR per frame.
nlohmann::json RdCurveJson(const RdCurve& curve);

// The first curve of an earlier `m4d rd` report (its rd.json), e.g. another encoder
// version's sweep kept as the anchor of a BD-rate; its label names the file.
// M4D_ERR_INVALID_ARG when the file is missing or not such a report.
Status LoadAnchorCurve(const std::string& rd_json, RdCurve* curve);

// PSNR against KB per frame for each curve, with gnuplot; M4D_ERR_UNSUPPORTED when gnuplot
// is missing.
// Points joined by rate; over inter frames, curves without any are left out.
Status PlotRdCurves(const std::vector<RdCurve>& curves, const std::string& png, RateScope scope);
// Held-out PSNR per frame, one line per lambda of the curve.
Status PlotPsnrPerFrame(const RdCurve& curve, const std::string& png);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_RD_SWEEP_H_
