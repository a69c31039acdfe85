#include "encoder/src/distributed/chunked_encode.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "encoder/src/distributed/mpi_ranks.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/pipeline/sequence_report_output.h"

namespace m4d {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxCheckpointBytes = size_t{1} << 32;

std::string ChunkPath(const std::string& dir, size_t c, const char* extension) {
  char name[32];
  std::snprintf(name, sizeof(name), "chunk_%05zu.%s", c, extension);
  return (std::filesystem::path(dir) / name).string();
}

std::string SettingsPath(const std::string& dir) {
  return (std::filesystem::path(dir) / "settings.json").string();
}

Status ReadJson(const std::string& path, nlohmann::json* json) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(ReadFileBytes(path, kMaxCheckpointBytes, &bytes));
  *json = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
  if (json->is_discarded()) return Status(M4D_ERR_INVALID_ARG, path + ": not JSON");
  return Status::Ok();
}

Status WriteJson(const std::string& path, const nlohmann::json& json) {
  const std::string text = json.dump(1) + "\n";
  return WriteFileAtomically(path, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

// Rank 0: the directory holds this encoding's settings (written when new).
Status CheckSettings(const std::string& dir, const nlohmann::json& settings) {
  const std::string path = SettingsPath(dir);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    M4D_RETURN_IF_ERROR(CheckOutputPath(path));  // creates the directory
    return WriteJson(path, settings);
  }
  nlohmann::json stored;
  M4D_RETURN_IF_ERROR(ReadJson(path, &stored));
  if (stored != settings) {
    return Status(M4D_ERR_INVALID_ARG,
                  dir +
                      " holds the chunks of an encoding with other settings: remove it, or "
                      "give another --checkpoint-dir");
  }
  return Status::Ok();
}

// A chunk is done when its report (written after its stream) names it and its stream's size.
bool ChunkDone(const std::string& dir, size_t c, const Chunk& chunk) {
  nlohmann::json json;
  if (!ReadJson(ChunkPath(dir, c, "json"), &json).ok()) return false;
  std::error_code ec;
  const auto size = std::filesystem::file_size(ChunkPath(dir, c, "m4d"), ec);
  try {
    return !ec && json.value("first", -1) == chunk.first &&
           json.value("count", -1) == chunk.count &&
           json.value("stream_bytes", size_t{0}) == size && json.at("frames").is_array();
  } catch (const nlohmann::json::exception&) {
    return false;  // not a report this code wrote: the chunk is coded again
  }
}

Status EncodeChunk(const Capture& capture, const EncoderOptions& options, size_t c,
                   const Chunk& chunk, uint32_t stream_frames, const ChunkedEncodeOptions& chunked,
                   const EncoderCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  EncoderOptions o = options;
  o.first_frame = chunk.first;
  o.frame_count = chunk.count;
  o.stream_first_index = static_cast<uint32_t>(chunk.first - options.first_frame);
  o.stream_frame_count = stream_frames;
  SequenceEncoder encoder(capture, o);
  if (c == 0 && chunked.first_keyframe) encoder.SetFirstKeyframe(*chunked.first_keyframe);
  SequenceReport report;
  M4D_RETURN_IF_ERROR(encoder.Encode(callbacks, &report));
  const std::vector<uint8_t>& stream = encoder.stream();
  M4D_RETURN_IF_ERROR(WriteFileAtomically(ChunkPath(chunked.checkpoint_dir, c, "m4d"),
                                          stream.data(), stream.size()));
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameReport& f : report.frames) frames.push_back(FrameReportJson(f));
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const nlohmann::json json = {{"first", chunk.first},          {"count", chunk.count},
                               {"rank", CurrentRanks().rank},   {"seconds", seconds},
                               {"stream_bytes", stream.size()}, {"frames", frames}};
  M4D_RETURN_IF_ERROR(WriteJson(ChunkPath(chunked.checkpoint_dir, c, "json"), json));
  std::printf("%schunk %zu (frames %d-%d) coded in %.1f s, %.2f KB\n", RankPrefix().c_str(), c,
              chunk.first, chunk.first + chunk.count - 1, seconds,
              static_cast<double>(stream.size()) / 1000.0);
  return Status::Ok();
}

// Rank 0: chunk c's stream appended to the joined one, its frames' reports and its table row.
Status JoinChunk(const std::string& dir, size_t c, const Chunk& chunk,
                 ChunkedEncodeResult* result) {
  nlohmann::json json;
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(ReadJson(ChunkPath(dir, c, "json"), &json));
  M4D_RETURN_IF_ERROR(ReadFileBytes(ChunkPath(dir, c, "m4d"), kMaxCheckpointBytes, &bytes));
  const Status bad(M4D_ERR_INVALID_ARG, ChunkPath(dir, c, "json") + ": not this chunk's report");
  try {
    const nlohmann::json& frames = json.at("frames");
    if (!frames.is_array() || frames.size() != static_cast<size_t>(chunk.count) ||
        json.at("stream_bytes").get<size_t>() != bytes.size()) {
      return bad;
    }
    for (const nlohmann::json& f : frames) {
      result->report.frames.emplace_back();
      M4D_RETURN_IF_ERROR(FrameReportFromJson(f, &result->report.frames.back()));
    }
    result->chunk_table.push_back({{"chunk", c},
                                   {"first", chunk.first},
                                   {"count", chunk.count},
                                   {"rank", json.at("rank").get<int>()},
                                   {"seconds", json.at("seconds").get<double>()},
                                   {"bytes", bytes.size()}});
  } catch (const nlohmann::json::exception&) {
    return bad;
  }
  result->stream.insert(result->stream.end(), bytes.begin(), bytes.end());
  return Status::Ok();
}

// Rank 0: the chunks' streams in order, one stream, and their frames' reports.
Status JoinChunks(const std::string& dir, const std::vector<Chunk>& chunks,
                  ChunkedEncodeResult* result) {
  for (size_t c = 0; c < chunks.size(); ++c) {
    M4D_RETURN_IF_ERROR(JoinChunk(dir, c, chunks[c], result));
  }
  result->report.stream_bytes = result->stream.size();
  return Status::Ok();
}

// Frames of `options`' range that the capture holds (at most 0 when none).
int FramesToCode(const Capture& capture, const EncoderOptions& options) {
  const int left = capture.frame_count - options.first_frame;
  return options.frame_count > 0 ? std::min(options.frame_count, left) : left;
}

}  // namespace

std::vector<Chunk> PlanChunks(int first, int frames, int chunk_frames) {
  std::vector<Chunk> chunks;
  const int length = chunk_frames > 0 ? chunk_frames : std::max(1, frames);
  for (int f = 0; f < frames; f += length)
    chunks.push_back({first + f, std::min(length, frames - f)});
  return chunks;
}

std::vector<Chunk> PlanCaptureChunks(const Capture& capture, const EncoderOptions& options,
                                     int chunk_frames) {
  const int frames = FramesToCode(capture, options);
  if (frames <= 0) return {};
  // Under MPI without a chunk length: one chunk per rank.
  const int ranks = CurrentRanks().size;
  const int length = chunk_frames > 0 ? chunk_frames : (frames + ranks - 1) / ranks;
  return PlanChunks(options.first_frame, frames, length);
}

Status RunChunkedEncode(const Capture& capture, const EncoderOptions& options,
                        const ChunkedEncodeOptions& chunked, const EncoderCallbacks& callbacks,
                        ChunkedEncodeResult* result) {
  *result = ChunkedEncodeResult();
  const Ranks& ranks = CurrentRanks();
  const int frames = FramesToCode(capture, options);
  if (frames <= 0) return Status(M4D_ERR_INVALID_ARG, "encoder: first frame beyond the capture");
  const std::vector<Chunk> chunks = PlanCaptureChunks(capture, options, chunked.chunk_frames);
  result->chunks = chunks.size();
  const std::string& dir = chunked.checkpoint_dir;
  Status status = ranks.rank == 0 ? CheckSettings(dir, chunked.settings) : Status::Ok();
  if (!AllRanksOk(status.ok())) {
    return status.ok() ? Status(M4D_ERR_INVALID_ARG, "rank 0 refused the checkpoint directory")
                       : status;
  }
  // Every rank lists the unfinished chunks before any rank codes one: they agree on the list.
  std::vector<size_t> todo;
  for (size_t c = 0; c < chunks.size(); ++c) {
    if (!ChunkDone(dir, c, chunks[c])) todo.push_back(c);
  }
  AllRanksOk(true);
  if (ranks.rank == 0 && todo.size() < chunks.size()) {
    std::printf("%zu of %zu chunks already done in %s\n", chunks.size() - todo.size(),
                chunks.size(), dir.c_str());
  }
  for (size_t k = static_cast<size_t>(ranks.rank); k < todo.size() && status.ok();
       k += static_cast<size_t>(ranks.size)) {
    if (chunked.max_chunks > 0 &&
        result->chunks_coded_here >= static_cast<size_t>(chunked.max_chunks)) {
      break;
    }
    status = EncodeChunk(capture, options, todo[k], chunks[todo[k]], static_cast<uint32_t>(frames),
                         chunked, callbacks);
    if (status.ok()) ++result->chunks_coded_here;
  }
  if (!status.ok()) {
    std::fprintf(stderr, "%s%s\n", RankPrefix().c_str(), status.message().c_str());
  }
  const bool all_ok = AllRanksOk(status.ok());
  for (size_t c = 0; c < chunks.size(); ++c) result->chunks_done += ChunkDone(dir, c, chunks[c]);
  if (!all_ok) {
    return status.ok() ? Status(M4D_ERR_INVALID_ARG, "another rank failed (its message above)")
                       : status;
  }
  result->complete = result->chunks_done == chunks.size();
  if (!result->complete || ranks.rank != 0) return Status::Ok();
  return JoinChunks(dir, chunks, result);
}

}  // namespace m4d
