#include "encoder/src/video/video_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/video/ffmpeg_status.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace m4d {
namespace {

const AVCodec* FindEncoder(const std::string& name) {
  if (!name.empty()) return avcodec_find_encoder_by_name(name.c_str());
  const AVCodec* x264 = avcodec_find_encoder_by_name("libx264");
  return x264 ? x264 : avcodec_find_encoder_by_name("mpeg4");
}

Status CheckOptions(int width, int height, const VideoWriterOptions& options) {
  M4D_RETURN_IF_ERROR(CheckImageShape(width, height, 3, "video frame"));
  if (width % 2 != 0 || height % 2 != 0) {
    return Status(M4D_ERR_INVALID_ARG, "video: width and height must be even for 4:2:0");
  }
  if (!(options.fps > 0 && options.fps <= 1000)) {
    return Status(M4D_ERR_INVALID_ARG, "video: fps must be in (0, 1000]");
  }
  if (options.crf < 0 || options.crf > 51 || options.threads < 0) {
    return Status(M4D_ERR_INVALID_ARG, "video: crf must be 0..51 and threads >= 0");
  }
  return Status::Ok();
}

}  // namespace

struct VideoWriter::State {
  ~State();
  Status Configure(const AVCodec* encoder, int width, int height,
                   const VideoWriterOptions& options);
  // Sends `input` (nullptr: flush) and writes every packet the encoder has ready.
  Status Encode(const AVFrame* input);

  std::string path;
  std::string codec_name;
  int width = 0;
  int height = 0;
  int frames_written = 0;
  bool finished = false;

  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  std::vector<uint8_t> rgb;  // the frame being written as 8-bit RGB
};

VideoWriter::State::~State() {
  if (format && !(format->oformat->flags & AVFMT_NOFILE)) avio_closep(&format->pb);
  avformat_free_context(format);
  avcodec_free_context(&codec);
  av_frame_free(&frame);
  av_packet_free(&packet);
  sws_freeContext(sws);
}

Status VideoWriter::State::Configure(const AVCodec* encoder, int w, int h,
                                     const VideoWriterOptions& options) {
  codec->width = w;
  codec->height = h;
  codec->pix_fmt = AV_PIX_FMT_YUV420P;
  codec->framerate = av_d2q(options.fps, 65535);
  codec->time_base = av_inv_q(codec->framerate);
  codec->thread_count = options.threads;
  codec->color_range = AVCOL_RANGE_MPEG;
  codec->colorspace = AVCOL_SPC_BT709;
  codec->color_primaries = AVCOL_PRI_BT709;
  codec->color_trc = AVCOL_TRC_BT709;
  if (format->oformat->flags & AVFMT_GLOBALHEADER) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (codec_name == "libx264") {
    if (av_opt_set_int(codec->priv_data, "crf", options.crf, 0) < 0 ||
        av_opt_set(codec->priv_data, "preset", options.preset.c_str(), 0) < 0) {
      return Status(M4D_ERR_INVALID_ARG, "video: x264 rejects preset '" + options.preset + "'");
    }
  } else {
    const double q = std::clamp(std::exp2((options.crf - 12) / 6.0), 1.0, 31.0);
    codec->flags |= AV_CODEC_FLAG_QSCALE;
    codec->global_quality = static_cast<int>(std::lround(FF_QP2LAMBDA * q));
  }
  const int err = avcodec_open2(codec, encoder, nullptr);
  if (err < 0) return FfmpegError(M4D_ERR_UNSUPPORTED, "video: cannot open " + codec_name, err);
  return Status::Ok();
}

Status VideoWriter::State::Encode(const AVFrame* input) {
  int err = avcodec_send_frame(codec, input);
  if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: encoding '" + path + "'", err);
  while (true) {
    err = avcodec_receive_packet(codec, packet);
    if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return Status::Ok();
    if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: encoding '" + path + "'", err);
    av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
    packet->stream_index = stream->index;
    err = av_interleaved_write_frame(format, packet);  // takes the packet's reference
    if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: writing '" + path + "'", err);
  }
}

VideoWriter::VideoWriter(std::unique_ptr<State> state) : state_(std::move(state)) {}
VideoWriter::~VideoWriter() = default;

Status VideoWriter::Open(const std::string& path, int width, int height,
                         const VideoWriterOptions& options, std::unique_ptr<VideoWriter>* writer) {
  InitFfmpegLogging();
  M4D_RETURN_IF_ERROR(CheckOptions(width, height, options));
  const AVCodec* encoder = FindEncoder(options.codec);
  if (!encoder) {
    return Status(M4D_ERR_UNSUPPORTED,
                  "video: no encoder '" + (options.codec.empty() ? "mpeg4" : options.codec) + "'");
  }
  auto s = std::make_unique<State>();
  s->path = path;
  s->codec_name = encoder->name;
  s->width = width;
  s->height = height;
  int err = avformat_alloc_output_context2(&s->format, nullptr, nullptr, path.c_str());
  if (err < 0 || !s->format) {
    return FfmpegError(M4D_ERR_UNSUPPORTED, "video: no container for '" + path + "'", err);
  }
  s->codec = avcodec_alloc_context3(encoder);
  s->stream = avformat_new_stream(s->format, nullptr);
  s->frame = av_frame_alloc();
  s->packet = av_packet_alloc();
  if (!s->codec || !s->stream || !s->frame || !s->packet) {
    return Status(M4D_ERR_NOMEM, "video: out of memory");
  }
  M4D_RETURN_IF_ERROR(s->Configure(encoder, width, height, options));
  err = avcodec_parameters_from_context(s->stream->codecpar, s->codec);
  if (err < 0) return FfmpegError(M4D_ERR_UNSUPPORTED, "video: stream parameters", err);
  s->stream->time_base = s->codec->time_base;
  s->stream->avg_frame_rate = s->codec->framerate;
  if (!(s->format->oformat->flags & AVFMT_NOFILE)) {
    err = avio_open(&s->format->pb, path.c_str(), AVIO_FLAG_WRITE);
    if (err < 0)
      return FfmpegError(M4D_ERR_INVALID_ARG, "video: cannot create '" + path + "'", err);
  }
  err = avformat_write_header(s->format, nullptr);
  if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: writing '" + path + "'", err);
  s->frame->format = AV_PIX_FMT_YUV420P;
  s->frame->width = width;
  s->frame->height = height;
  s->frame->color_range = AVCOL_RANGE_MPEG;
  s->frame->colorspace = AVCOL_SPC_BT709;
  err = av_frame_get_buffer(s->frame, 0);
  if (err < 0) return FfmpegError(M4D_ERR_NOMEM, "video: frame buffer", err);
  s->sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P,
                          SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INP, nullptr, nullptr,
                          nullptr);
  if (!s->sws) return Status(M4D_ERR_UNSUPPORTED, "video: no RGB to YUV conversion");
  sws_setColorspaceDetails(s->sws, sws_getCoefficients(SWS_CS_DEFAULT), 1,
                           sws_getCoefficients(SWS_CS_ITU709), 0, 0, 1 << 16, 1 << 16);
  writer->reset(new VideoWriter(std::move(s)));
  return Status::Ok();
}

Status VideoWriter::Write(const Image& rgb) {
  State& s = *state_;
  if (s.finished) return Status(M4D_ERR_INVALID_ARG, "video: write after finish");
  M4D_RETURN_IF_ERROR(CheckImage(rgb, "video frame"));
  if (rgb.width != s.width || rgb.height != s.height || rgb.channels != 3) {
    return Status(M4D_ERR_INVALID_ARG, "video: frame must be " + std::to_string(s.width) + "x" +
                                           std::to_string(s.height) + " RGB");
  }
  s.rgb.resize(rgb.pixels.size());
  for (size_t i = 0; i < rgb.pixels.size(); ++i) s.rgb[i] = FloatToByte(rgb.pixels[i]);
  // The encoder may still hold the previous frame's buffer.
  int err = av_frame_make_writable(s.frame);
  if (err < 0) return FfmpegError(M4D_ERR_NOMEM, "video: frame buffer", err);
  const uint8_t* planes[4] = {s.rgb.data(), nullptr, nullptr, nullptr};
  const int strides[4] = {3 * s.width, 0, 0, 0};
  sws_scale(s.sws, planes, strides, 0, s.height, s.frame->data, s.frame->linesize);
  s.frame->pts = s.frames_written;
  M4D_RETURN_IF_ERROR(s.Encode(s.frame));
  ++s.frames_written;
  return Status::Ok();
}

Status VideoWriter::Finish() {
  State& s = *state_;
  if (s.finished) return Status::Ok();
  s.finished = true;
  M4D_RETURN_IF_ERROR(s.Encode(nullptr));
  const int err = av_write_trailer(s.format);
  if (err < 0) return FfmpegError(M4D_ERR_INVALID_ARG, "video: finishing '" + s.path + "'", err);
  if (!(s.format->oformat->flags & AVFMT_NOFILE)) {
    const int close_err = avio_closep(&s.format->pb);
    if (close_err < 0) {
      return FfmpegError(M4D_ERR_INVALID_ARG, "video: closing '" + s.path + "'", close_err);
    }
  }
  return Status::Ok();
}

const std::string& VideoWriter::codec_name() const { return state_->codec_name; }
int VideoWriter::frames_written() const { return state_->frames_written; }

}  // namespace m4d
