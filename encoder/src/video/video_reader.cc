#include "encoder/src/video/video_reader.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/video/ffmpeg_status.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace m4d {
namespace {

// More frames than any real capture has; a larger declared count is a broken file.
constexpr int64_t kMaxVideoFrames = 1 << 24;

struct CachedFrame {
  int index = -1;
  uint64_t last_use = 0;
  std::vector<uint8_t> rgb;  // width * height * 3
};

// swscale's YUV-to-RGB coefficients for the colour space a frame is tagged with; untagged
// frames get swscale's default (BT.601), as the ffmpeg command line converts them.
const int* YuvCoefficients(AVColorSpace space) {
  switch (space) {
    case AVCOL_SPC_BT709:
      return sws_getCoefficients(SWS_CS_ITU709);
    case AVCOL_SPC_FCC:
      return sws_getCoefficients(SWS_CS_FCC);
    case AVCOL_SPC_SMPTE240M:
      return sws_getCoefficients(SWS_CS_SMPTE240M);
    case AVCOL_SPC_BT2020_NCL:
    case AVCOL_SPC_BT2020_CL:
      return sws_getCoefficients(SWS_CS_BT2020);
    default:
      return sws_getCoefficients(SWS_CS_DEFAULT);
  }
}

bool IsFullRangeFormat(AVPixelFormat format) {
  return format == AV_PIX_FMT_YUVJ420P || format == AV_PIX_FMT_YUVJ422P ||
         format == AV_PIX_FMT_YUVJ444P || format == AV_PIX_FMT_YUVJ440P;
}

}  // namespace

struct VideoReader::State {
  ~State() { Close(); }

  Status OpenDecoder();
  void Close();
  Status CountPackets(int64_t* count);
  // Decodes the next frame into `frame`; *end when the stream has no more.
  Status DecodeNext(bool* end);
  Status ConvertFrame(CachedFrame* slot);
  CachedFrame* Cached(int index);
  CachedFrame* LeastRecentlyUsed();

  std::string path;
  VideoReaderOptions options;
  int width = 0;
  int height = 0;
  double fps = 0;
  int frame_count = 0;

  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* frame = nullptr;
  SwsContext* sws = nullptr;
  int stream_index = -1;
  int next_index = 0;  // index of the frame DecodeNext gives next
  bool flushing = false;
  std::vector<CachedFrame> cache;
  uint64_t use_clock = 0;
};

void VideoReader::State::Close() {
  sws_freeContext(sws);
  sws = nullptr;
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  stream_index = -1;
  next_index = 0;
  flushing = false;
}

Status VideoReader::State::OpenDecoder() {
  Close();
  int err = avformat_open_input(&format, path.c_str(), nullptr, nullptr);
  if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: cannot open '" + path + "'", err);
  err = avformat_find_stream_info(format, nullptr);
  if (err < 0) return FfmpegError(M4D_ERR_BITSTREAM, "video: unreadable '" + path + "'", err);
  const AVCodec* decoder = nullptr;
  stream_index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (stream_index < 0 || !decoder) {
    return Status(M4D_ERR_UNSUPPORTED, "video: no decodable video stream in '" + path + "'");
  }
  codec = avcodec_alloc_context3(decoder);
  packet = av_packet_alloc();
  frame = av_frame_alloc();
  if (!codec || !packet || !frame) return Status(M4D_ERR_NOMEM, "video: out of memory");
  err = avcodec_parameters_to_context(codec, format->streams[stream_index]->codecpar);
  if (err < 0) return FfmpegError(M4D_ERR_BITSTREAM, "video: bad stream in '" + path + "'", err);
  codec->thread_count = options.threads;
  err = avcodec_open2(codec, decoder, nullptr);
  if (err < 0) {
    return FfmpegError(M4D_ERR_UNSUPPORTED, "video: cannot decode '" + path + "'", err);
  }
  return Status::Ok();
}

Status VideoReader::State::CountPackets(int64_t* count) {
  *count = 0;
  while (true) {
    const int err = av_read_frame(format, packet);
    if (err == AVERROR_EOF) return Status::Ok();
    if (err < 0) return FfmpegError(M4D_ERR_BITSTREAM, "video: reading '" + path + "'", err);
    if (packet->stream_index == stream_index) ++*count;
    av_packet_unref(packet);
    if (*count > kMaxVideoFrames) return LimitError("video: too many frames in '" + path + "'");
  }
}

Status VideoReader::State::DecodeNext(bool* end) {
  *end = false;
  while (true) {
    int err = avcodec_receive_frame(codec, frame);
    if (err == 0) return Status::Ok();
    if (err == AVERROR_EOF) {
      *end = true;
      return Status::Ok();
    }
    if (err != AVERROR(EAGAIN)) {
      return FfmpegError(M4D_ERR_BITSTREAM, "video: decoding '" + path + "'", err);
    }
    if (flushing) return BitstreamError("video: decoder stalled on '" + path + "'");
    err = av_read_frame(format, packet);
    if (err == AVERROR_EOF) {
      flushing = true;
      err = avcodec_send_packet(codec, nullptr);
    } else if (err < 0) {
      return FfmpegError(M4D_ERR_BITSTREAM, "video: reading '" + path + "'", err);
    } else {
      if (packet->stream_index == stream_index) err = avcodec_send_packet(codec, packet);
      av_packet_unref(packet);
    }
    if (err < 0) return FfmpegError(M4D_ERR_BITSTREAM, "video: decoding '" + path + "'", err);
  }
}

Status VideoReader::State::ConvertFrame(CachedFrame* slot) {
  if (frame->width != width || frame->height != height) {
    return BitstreamError("video: frame size changes within '" + path + "'");
  }
  const AVPixelFormat source = static_cast<AVPixelFormat>(frame->format);
  sws = sws_getCachedContext(sws, width, height, source, width, height, AV_PIX_FMT_RGB24,
                             SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr,
                             nullptr);
  if (!sws) return Status(M4D_ERR_UNSUPPORTED, "video: cannot convert frames of '" + path + "'");
  const bool full_range = frame->color_range == AVCOL_RANGE_JPEG || IsFullRangeFormat(source);
  sws_setColorspaceDetails(sws, YuvCoefficients(frame->colorspace), full_range ? 1 : 0,
                           sws_getCoefficients(SWS_CS_DEFAULT), 1, 0, 1 << 16, 1 << 16);
  slot->rgb.resize(static_cast<size_t>(width) * height * 3);
  uint8_t* planes[4] = {slot->rgb.data(), nullptr, nullptr, nullptr};
  int strides[4] = {3 * width, 0, 0, 0};
  if (sws_scale(sws, frame->data, frame->linesize, 0, height, planes, strides) != height) {
    return BitstreamError("video: cannot convert a frame of '" + path + "'");
  }
  return Status::Ok();
}

CachedFrame* VideoReader::State::Cached(int index) {
  for (CachedFrame& slot : cache) {
    if (slot.index == index) {
      slot.last_use = ++use_clock;
      return &slot;
    }
  }
  return nullptr;
}

CachedFrame* VideoReader::State::LeastRecentlyUsed() {
  return &*std::min_element(
      cache.begin(), cache.end(),
      [](const CachedFrame& a, const CachedFrame& b) { return a.last_use < b.last_use; });
}

VideoReader::VideoReader(std::unique_ptr<State> state) : state_(std::move(state)) {}
VideoReader::~VideoReader() = default;

Status VideoReader::Open(const std::string& path, const VideoReaderOptions& options,
                         std::unique_ptr<VideoReader>* reader) {
  InitFfmpegLogging();
  if (options.cache_frames < 1 || options.cache_frames > 64 || options.threads < 0) {
    return Status(M4D_ERR_INVALID_ARG, "video: cache_frames must be 1..64, threads >= 0");
  }
  auto state = std::make_unique<State>();
  state->path = path;
  state->options = options;
  M4D_RETURN_IF_ERROR(state->OpenDecoder());
  const AVStream* stream = state->format->streams[state->stream_index];
  state->width = stream->codecpar->width;
  state->height = stream->codecpar->height;
  M4D_RETURN_IF_ERROR(CheckImageShape(state->width, state->height, 3, "video '" + path + "'"));
  const AVRational rate =
      stream->avg_frame_rate.num > 0 ? stream->avg_frame_rate : stream->r_frame_rate;
  state->fps = rate.num > 0 && rate.den > 0 ? av_q2d(rate) : 0.0;
  int64_t count = stream->nb_frames;
  if (count <= 0) {
    M4D_RETURN_IF_ERROR(state->CountPackets(&count));
    M4D_RETURN_IF_ERROR(state->OpenDecoder());  // back to the start
  }
  if (count > kMaxVideoFrames) return LimitError("video: too many frames in '" + path + "'");
  state->frame_count = static_cast<int>(count);
  state->cache.resize(options.cache_frames);
  reader->reset(new VideoReader(std::move(state)));
  return Status::Ok();
}

int VideoReader::width() const { return state_->width; }
int VideoReader::height() const { return state_->height; }
double VideoReader::fps() const { return state_->fps; }
int VideoReader::frame_count() const { return state_->frame_count; }

Status VideoReader::ReadFrame(int index, Image* rgb) {
  State& s = *state_;
  if (index < 0 || index >= s.frame_count) {
    return Status(M4D_ERR_INVALID_ARG,
                  "video: frame " + std::to_string(index) + " out of range in '" + s.path + "'");
  }
  CachedFrame* hit = s.Cached(index);
  if (!hit) {
    if (index < s.next_index || !s.codec) M4D_RETURN_IF_ERROR(s.OpenDecoder());
    const int cache_start = index - static_cast<int>(s.cache.size()) + 1;
    while (s.next_index <= index) {
      bool end = false;
      Status status = s.DecodeNext(&end);
      if (status.ok() && end) {
        status = BitstreamError("video: '" + s.path + "' ends after " +
                                std::to_string(s.next_index) + " frames");
      }
      // Only the frames the cache will keep are converted; the others are just decoded.
      if (status.ok() && s.next_index >= cache_start) {
        CachedFrame* slot = s.LeastRecentlyUsed();
        slot->index = -1;
        slot->last_use = ++s.use_clock;
        status = s.ConvertFrame(slot);
        if (status.ok()) slot->index = s.next_index;
      }
      if (!status.ok()) {
        s.Close();  // the next request starts again from the beginning
        return status;
      }
      ++s.next_index;
    }
    hit = s.Cached(index);
  }
  Reshape(s.width, s.height, 3, rgb);
  const uint8_t* bytes = hit->rgb.data();
  float* out = rgb->pixels.data();
  const size_t n = hit->rgb.size();
  for (size_t i = 0; i < n; ++i) out[i] = ByteToFloat(bytes[i]);
  return Status::Ok();
}

}  // namespace m4d
