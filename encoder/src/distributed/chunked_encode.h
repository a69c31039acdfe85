// Chunked encoding: the frames are split into chunks of equal length, each starting at a
// random-access point (a keyframe trained from scratch, the SEQUENCE_HEADER repeated), and
// each chunk is coded alone by the same closed-loop encoder, its frames numbered where they
// sit in the whole stream. The chunks' streams, concatenated in order, are one valid stream.
//
// Chunks are spread over the ranks of an MPI job (mpi_ranks.h) round-robin, or coded in turn
// by a single process; either way each finished chunk is checkpointed (its stream and its
// frames' reports, written atomically) in a directory every rank sees, so a run that failed,
// was killed or stopped resumes with the same command without redoing finished chunks. Rank 0
// then joins the chunks.
#ifndef M4D_ENCODER_DISTRIBUTED_CHUNKED_ENCODE_H_
#define M4D_ENCODER_DISTRIBUTED_CHUNKED_ENCODE_H_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/pipeline/frame_report.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/train/gaussian_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct Chunk {
  int first = 0;  // capture frame
  int count = 0;
};

// Frames [first, first + frames) in chunks of chunk_frames (the last may be shorter).
std::vector<Chunk> PlanChunks(int first, int frames, int chunk_frames);

// The chunks of `options`' frame range in `capture`: of chunk_frames, or under MPI without a
// length one per rank. Empty when the range holds no frame.
std::vector<Chunk> PlanCaptureChunks(const Capture& capture, const EncoderOptions& options,
                                     int chunk_frames);

struct ChunkedEncodeOptions {
  int chunk_frames = 0;
  std::string checkpoint_dir;
  // What decides the stream (options, capture, frames): a checkpoint directory made for other
  // settings is refused rather than mixed in.
  nlohmann::json settings;
  int max_chunks = 0;  // stop after coding this many chunks in this process (0: no limit)
  const GaussianModel* first_keyframe = nullptr;  // the first chunk's, when given
};

struct ChunkedEncodeResult {
  bool complete = false;  // every chunk is done (rank 0 then holds the joined stream)
  size_t chunks = 0, chunks_done = 0, chunks_coded_here = 0;
  std::vector<uint8_t> stream;                           // rank 0, when complete
  SequenceReport report;                                 // rank 0, when complete
  nlohmann::json chunk_table = nlohmann::json::array();  // rank 0: per chunk, who and how long
};

// Codes the chunks of `options`' frame range that are not checkpointed yet; collective over the
// MPI job. Progress and frame lines on stderr/stdout, prefixed with the rank.
Status RunChunkedEncode(const Capture& capture, const EncoderOptions& options,
                        const ChunkedEncodeOptions& chunked, const EncoderCallbacks& callbacks,
                        ChunkedEncodeResult* result);

}  // namespace m4d

#endif  // M4D_ENCODER_DISTRIBUTED_CHUNKED_ENCODE_H_
