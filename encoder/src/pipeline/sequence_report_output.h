// The encoder's report as a person reads it (a table per frame and a summary) and as
// programs read it (JSON with the same fields).
#ifndef M4D_ENCODER_PIPELINE_SEQUENCE_REPORT_OUTPUT_H_
#define M4D_ENCODER_PIPELINE_SEQUENCE_REPORT_OUTPUT_H_

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "encoder/src/pipeline/frame_report.h"
#include "sdk/src/common/status.h"

namespace m4d {

// A layer of the stream as the reports name it: its packet type, its key in the JSON reports
// and its label in the tables.
struct ReportLayer {
  int packet_type;
  const char* key;
  const char* label;  // at most 13 characters, a table column
};
// Every packet type, in the order of the stream's syntax.
const std::vector<ReportLayer>& ReportLayers();

struct SequenceSummary {
  size_t frames = 0, keyframes = 0;
  double kb_per_frame = 0;        // all frames, keyframes included (the papers' KB/frame)
  double kb_per_inter_frame = 0;  // inter frames only
  double kb_per_keyframe = 0;
  bool held_out = false;               // the frames were measured on a held-out camera
  double psnr = 0, ssim = 0;           // mean over frames
  double keyframe_psnr = 0;            // mean over keyframes
  double seconds = 0;                  // all stages, all frames
  double seconds_per_inter_frame = 0;  // motion + compensation + coding + evaluation
  // Where the bytes go: KB per frame (all frames) by packet type, headers included.
  std::array<double, 9> kb_per_frame_by_type{};
};

SequenceSummary Summarise(const SequenceReport& report);

// One line per frame; the header line first when `header`.
void PrintFrameLine(std::FILE* out, const FrameReport& frame, bool header);
void PrintSummary(std::FILE* out, const SequenceReport& report);

// A frame's report as JSON (the reports' "frames" entries) and back.
nlohmann::json FrameReportJson(const FrameReport& frame);
Status FrameReportFromJson(const nlohmann::json& json, FrameReport* frame);

// The report as JSON (frames, summary, and `extra` fields such as the options used).
Status WriteReportJson(const std::string& path, const SequenceReport& report,
                       const std::string& extra_json_object);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_SEQUENCE_REPORT_OUTPUT_H_
