#include "pipeline/egofun3d/video.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libswscale/swscale.h>
}

#include <cstring>
#include <filesystem>

namespace efc::egofun3d {
namespace {

std::string av_error(int rc) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(rc, buf, sizeof buf);
  return buf;
}

}  // namespace

struct VideoReader::State {
  AVFormatContext* fmt = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* frame = nullptr;
  SwsContext* sws = nullptr;
  int stream = -1;
  int width = 0, height = 0;
  double fps = 0;
  bool draining = false, done = false;

  ~State() {
    sws_freeContext(sws);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&fmt);
  }
};

VideoReader::VideoReader() = default;
VideoReader::~VideoReader() = default;

double VideoReader::fps() const { return s_ ? s_->fps : 0; }
int VideoReader::width() const { return s_ ? s_->width : 0; }
int VideoReader::height() const { return s_ ? s_->height : 0; }

bool VideoReader::open(const std::string& path, std::string* error) {
  // FFmpeg logs to stderr on its own; the importer reports in efc's format.
  av_log_set_level(AV_LOG_QUIET);
  s_ = std::make_unique<State>();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    *error = "does not exist";
    return false;
  }
  int rc = avformat_open_input(&s_->fmt, path.c_str(), nullptr, nullptr);
  if (rc < 0) {
    *error = "is not a video FFmpeg can open (" + av_error(rc) + ")";
    return false;
  }
  if ((rc = avformat_find_stream_info(s_->fmt, nullptr)) < 0) {
    *error = "has no readable stream information (" + av_error(rc) + ")";
    return false;
  }
  const AVCodec* decoder = nullptr;
  s_->stream = av_find_best_stream(s_->fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (s_->stream < 0 || !decoder) {
    *error = s_->stream == AVERROR_DECODER_NOT_FOUND ? "has a video stream no installed decoder reads"
                                                     : "has no video stream";
    return false;
  }
  AVStream* st = s_->fmt->streams[s_->stream];
  s_->codec = avcodec_alloc_context3(decoder);
  if (!s_->codec || avcodec_parameters_to_context(s_->codec, st->codecpar) < 0 ||
      (rc = avcodec_open2(s_->codec, decoder, nullptr)) < 0) {
    *error = "has a video stream that cannot be decoded";
    return false;
  }
  s_->width = st->codecpar->width;
  s_->height = st->codecpar->height;
  AVRational rate = st->avg_frame_rate;
  if (rate.num <= 0 || rate.den <= 0) rate = st->r_frame_rate;
  if (rate.num <= 0 || rate.den <= 0) {
    *error = "has no frame rate";
    return false;
  }
  s_->fps = av_q2d(rate);
  if (s_->width <= 0 || s_->height <= 0) {
    *error = "has a video stream of unknown size";
    return false;
  }
  s_->packet = av_packet_alloc();
  s_->frame = av_frame_alloc();
  return s_->packet && s_->frame;
}

bool VideoReader::next(seq::Image8* out, std::string* error) {
  error->clear();
  if (!s_ || s_->done) return false;
  for (;;) {
    int rc = avcodec_receive_frame(s_->codec, s_->frame);
    if (rc == 0) break;
    if (rc == AVERROR_EOF) {
      s_->done = true;
      return false;
    }
    if (rc != AVERROR(EAGAIN)) {
      *error = "cannot be decoded (" + av_error(rc) + ")";
      return false;
    }
    if (s_->draining) {  // EAGAIN while draining: nothing more will come
      s_->done = true;
      return false;
    }
    // Feed the decoder the next packet of our stream (or the end).
    for (;;) {
      rc = av_read_frame(s_->fmt, s_->packet);
      if (rc < 0) {
        s_->draining = true;
        avcodec_send_packet(s_->codec, nullptr);
        break;
      }
      if (s_->packet->stream_index != s_->stream) {
        av_packet_unref(s_->packet);
        continue;
      }
      rc = avcodec_send_packet(s_->codec, s_->packet);
      av_packet_unref(s_->packet);
      if (rc < 0 && rc != AVERROR(EAGAIN)) {
        *error = "cannot be decoded (" + av_error(rc) + ")";
        return false;
      }
      break;
    }
  }
  AVFrame* f = s_->frame;
  if (f->width != s_->width || f->height != s_->height) {
    *error = "changes frame size mid-stream (" + std::to_string(f->width) + "x" + std::to_string(f->height) +
             ", the stream says " + std::to_string(s_->width) + "x" + std::to_string(s_->height) + ")";
    av_frame_unref(f);
    return false;
  }
  // Exact conversion flags: for RGB sources (ffv1 bgr0, png) swscale only
  // reorders bytes, so pixels come through unchanged.
  s_->sws = sws_getCachedContext(s_->sws, f->width, f->height, static_cast<AVPixelFormat>(f->format), f->width,
                                 f->height, AV_PIX_FMT_RGB24, SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT,
                                 nullptr, nullptr, nullptr);
  if (!s_->sws) {
    *error = "has a pixel format that cannot be converted to RGB";
    av_frame_unref(f);
    return false;
  }
  out->width = f->width;
  out->height = f->height;
  out->channels = 3;
  out->pixels.assign(static_cast<size_t>(f->width) * f->height * 3, 0);
  uint8_t* dst[4] = {out->pixels.data(), nullptr, nullptr, nullptr};
  int dst_stride[4] = {f->width * 3, 0, 0, 0};
  sws_scale(s_->sws, f->data, f->linesize, 0, f->height, dst, dst_stride);
  av_frame_unref(f);
  return true;
}

}  // namespace efc::egofun3d
