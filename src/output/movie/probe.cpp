// reading movies back: decode every frame to count them, or one frame to RGBA
#include "output/movie/movie.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <functional>

#include "core/error.hpp"

namespace gs {

namespace {

/// an open movie file with a decoder on its best video stream
struct Decoder {
  std::string path;
  AVFormatContext* fmt = nullptr;
  AVCodecContext* ctx = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* frame = nullptr;
  int stream = -1;

  explicit Decoder(const std::string& p) : path(p) {
    if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_ERROR);
    int rc = avformat_open_input(&fmt, path.c_str(), nullptr, nullptr);
    if (rc < 0) fail("cannot open movie", rc);
    if ((rc = avformat_find_stream_info(fmt, nullptr)) < 0) fail("no stream information", rc);
    const AVCodec* codec = nullptr;
    stream = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (stream < 0 || !codec) fail("no decodable video stream", stream < 0 ? stream : 0);
    ctx = avcodec_alloc_context3(codec);
    packet = av_packet_alloc();
    frame = av_frame_alloc();
    if (!ctx || !packet || !frame) fail("out of memory");
    avcodec_parameters_to_context(ctx, fmt->streams[stream]->codecpar);
    if ((rc = avcodec_open2(ctx, codec, nullptr)) < 0) fail("cannot open the decoder", rc);
  }

  ~Decoder() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&ctx);
    avformat_close_input(&fmt);
  }

  [[noreturn]] void fail(const std::string& what, int code = 0) const {
    std::string msg = what;
    if (code) {
      char buf[AV_ERROR_MAX_STRING_SIZE] = {};
      av_strerror(code, buf, sizeof buf);
      msg += std::string(": ") + buf;
    }
    throw InputError(path, "", msg);
  }

  // decode to the end (or until on_frame returns false), calling on_frame for each frame
  void run(const std::function<bool(const AVFrame*)>& on_frame) {
    auto drain = [&]() {
      int rc;
      while ((rc = avcodec_receive_frame(ctx, frame)) >= 0) {
        const bool more = on_frame(frame);
        av_frame_unref(frame);
        if (!more) return false;
      }
      if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) fail("decoding failed", rc);
      return true;
    };
    while (av_read_frame(fmt, packet) >= 0) {
      const bool ours = packet->stream_index == stream;
      const int rc = ours ? avcodec_send_packet(ctx, packet) : 0;
      av_packet_unref(packet);
      if (rc < 0) fail("decoding failed", rc);
      if (ours && !drain()) return;
    }
    avcodec_send_packet(ctx, nullptr);
    drain();
  }
};

}  // namespace

MovieInfo probe_movie(const std::string& path) {
  Decoder d(path);
  const AVStream* s = d.fmt->streams[d.stream];
  MovieInfo info;
  info.width = s->codecpar->width;
  info.height = s->codecpar->height;
  info.codec = avcodec_get_name(s->codecpar->codec_id);
  const char* pf = av_get_pix_fmt_name(static_cast<AVPixelFormat>(s->codecpar->format));
  info.pixel_format = pf ? pf : "";
  info.fps = s->avg_frame_rate.den ? av_q2d(s->avg_frame_rate) : 0.0;
  // the stream's own duration, else the container's
  if (s->duration > 0)
    info.duration = s->duration * av_q2d(s->time_base);
  else if (d.fmt->duration > 0)
    info.duration = d.fmt->duration / static_cast<double>(AV_TIME_BASE);
  d.run([&](const AVFrame*) {
    ++info.frames;
    return true;
  });
  return info;
}

Image movie_frame(const std::string& path, int index) {
  Decoder d(path);
  Image img;
  int seen = 0;
  // decode up to the wanted frame and convert it to RGBA
  d.run([&](const AVFrame* f) {
    if (seen++ < index) return true;
    img = Image(f->width, f->height);
    SwsContext* sws = sws_getContext(f->width, f->height, static_cast<AVPixelFormat>(f->format),
                                     f->width, f->height, AV_PIX_FMT_RGBA,
                                     SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
    if (!sws) d.fail("cannot convert the decoded frame to RGBA");
    std::uint8_t* dst = img.rgba.data();
    const int stride = f->width * 4;
    sws_scale(sws, f->data, f->linesize, 0, f->height, &dst, &stride);
    sws_freeContext(sws);
    return false;
  });
  if (img.width == 0)
    throw InputError(
        path, "",
        "movie has no frame " + std::to_string(index) + " (only " + std::to_string(seen) + ")");
  return img;
}

}  // namespace gs
