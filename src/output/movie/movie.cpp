// the MP4 encoder: RGBA → yuv420p (swscale) → H.264 / MPEG-4 (libavcodec) → mp4 (libavformat)
#include "output/movie/movie.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/error.hpp"

namespace gs {

namespace {

// FFmpeg's message for an error code
std::string av_error(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

}  // namespace

struct MovieEncoder::Impl {
  std::string path;
  int width = 0, height = 0;  ///< frame size given to open, px
  int ew = 0, eh = 0;         ///< encoded (even) size, px
  int count = 0;              ///< frames sent
  AVFormatContext* fmt = nullptr;
  AVCodecContext* ctx = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  std::vector<std::uint8_t> padded;  ///< the RGBA frame grown to even size when needed
  std::string codec;
  bool created = false;  ///< the file at `path` is this encoder's (opened for writing)

  ~Impl() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&ctx);
    if (fmt && fmt->pb) avio_closep(&fmt->pb);
    avformat_free_context(fmt);
  }

  [[noreturn]] void fail(const std::string& what, int code = 0) const {
    throw InputError(path, "", what + (code ? ": " + av_error(code) : std::string()));
  }
  // the file could not be written (a full disk): no partial movie is left behind
  [[noreturn]] void fail_write(const std::string& what, int code) {
    if (fmt && fmt->pb) avio_closep(&fmt->pb);
    if (created) std::remove(path.c_str());
    throw OutputError(path + ": " + what + ": " + av_error(code) +
                      (created ? " (the partial movie is removed)" : ""));
  }

  // send one frame (or nullptr to flush) and write every packet that comes out
  void encode(AVFrame* f) {
    int rc = avcodec_send_frame(ctx, f);
    if (rc < 0) fail("cannot encode a frame", rc);
    while ((rc = avcodec_receive_packet(ctx, packet)) >= 0) {
      av_packet_rescale_ts(packet, ctx->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_interleaved_write_frame(fmt, packet);
      if (rc < 0) fail_write("cannot write a packet", rc);
    }
    if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) fail("encoder failed", rc);
  }
};

MovieEncoder::MovieEncoder() = default;

MovieEncoder::~MovieEncoder() {
  try {
    close();
  } catch (...) {
  }
}

void MovieEncoder::open(const std::string& path, int width, int height, int fps, int crf) {
  MovieOptions o;
  o.fps = fps;
  o.crf = crf;
  open(path, width, height, o);
}

void MovieEncoder::open(const std::string& path, int width, int height, const MovieOptions& o) {
  close();
  auto im = std::make_unique<Impl>();
  im->path = path;
  if (width < 2 || height < 2 || width > 8192 || height > 8192)
    im->fail("movie size " + std::to_string(width) + "x" + std::to_string(height) +
             " is outside 2..8192 px");
  if (o.fps < 1 || o.fps > 1000) im->fail("movie frame rate must be 1..1000 frames/s");
  if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_ERROR);
  im->width = width;
  im->height = height;
  im->ew = width + (width & 1);
  im->eh = height + (height & 1);

  // the container, then the codec: H.264 by x264 first, MPEG-4 part 2 when it is missing
  int rc = avformat_alloc_output_context2(&im->fmt, nullptr, "mp4", path.c_str());
  if (rc < 0 || !im->fmt) im->fail("cannot create an mp4 container", rc);
  const AVCodec* codec = nullptr;
  if (o.codec.empty() || o.codec == "libx264") codec = avcodec_find_encoder_by_name("libx264");
  if (!codec && (o.codec.empty() || o.codec == "mpeg4"))
    codec = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (!codec) im->fail("no encoder '" + (o.codec.empty() ? "libx264/mpeg4" : o.codec) + "'");
  im->codec = codec->name;
  im->stream = avformat_new_stream(im->fmt, nullptr);
  im->ctx = avcodec_alloc_context3(codec);
  if (!im->stream || !im->ctx) im->fail("out of memory");

  // yuv420p at the even size, one tick per frame, BT.601 limited range as swscale makes it
  AVCodecContext* c = im->ctx;
  c->width = im->ew;
  c->height = im->eh;
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->time_base = AVRational{1, o.fps};
  c->framerate = AVRational{o.fps, 1};
  c->gop_size = 2 * o.fps;
  c->colorspace = AVCOL_SPC_SMPTE170M;
  c->color_range = AVCOL_RANGE_MPEG;
  if (im->codec == "libx264") {
    av_opt_set(c->priv_data, "preset", o.preset.c_str(), 0);
    av_opt_set(c->priv_data, "crf", std::to_string(std::clamp(o.crf, 0, 51)).c_str(), 0);
  } else {
    // MPEG-4 part 2 has no CRF: a fixed quantiser of comparable quality
    c->flags |= AV_CODEC_FLAG_QSCALE;
    c->global_quality = FF_QP2LAMBDA * std::clamp(1 + o.crf / 6, 2, 31);
  }
  if (im->fmt->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if ((rc = avcodec_open2(c, codec, nullptr)) < 0) im->fail("cannot open encoder " + im->codec, rc);
  if ((rc = avcodec_parameters_from_context(im->stream->codecpar, c)) < 0)
    im->fail("cannot set stream parameters", rc);
  im->stream->time_base = c->time_base;
  im->stream->avg_frame_rate = c->framerate;

  // the file, with the index moved to the front for streaming
  if ((rc = avio_open(&im->fmt->pb, path.c_str(), AVIO_FLAG_WRITE)) < 0)
    im->fail("cannot open for writing", rc);  // a path the user named: nothing written yet
  im->created = true;
  AVDictionary* opts = nullptr;
  av_dict_set(&opts, "movflags", "+faststart", 0);
  rc = avformat_write_header(im->fmt, &opts);
  av_dict_free(&opts);
  if (rc < 0) im->fail_write("cannot write the mp4 header", rc);

  // a reusable frame, packet and RGBA → YUV converter
  im->frame = av_frame_alloc();
  im->packet = av_packet_alloc();
  if (!im->frame || !im->packet) im->fail("out of memory");
  im->frame->format = c->pix_fmt;
  im->frame->width = c->width;
  im->frame->height = c->height;
  if ((rc = av_frame_get_buffer(im->frame, 0)) < 0) im->fail("cannot allocate a frame", rc);
  im->sws = sws_getContext(im->ew, im->eh, AV_PIX_FMT_RGBA, im->ew, im->eh, AV_PIX_FMT_YUV420P,
                           SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
  if (!im->sws) im->fail("cannot create the RGBA to yuv420p converter");
  impl_ = std::move(im);
  frames_ = 0;
}

void MovieEncoder::add_frame(const Image& img) {
  if (!impl_) throw InputError("", "", "MovieEncoder::add_frame before open");
  Impl& im = *impl_;
  if (img.width != im.width || img.height != im.height)
    im.fail("frame of " + std::to_string(img.width) + "x" + std::to_string(img.height) +
            " px added to a " + std::to_string(im.width) + "x" + std::to_string(im.height) +
            " movie");
  // odd sizes: repeat the last column and row into the even-sized buffer
  const std::uint8_t* src = img.rgba.data();
  if (im.ew != im.width || im.eh != im.height) {
    im.padded.resize(static_cast<std::size_t>(im.ew) * im.eh * 4);
    for (int y = 0; y < im.eh; ++y) {
      const int sy = std::min(y, im.height - 1);
      std::uint8_t* row = &im.padded[static_cast<std::size_t>(y) * im.ew * 4];
      std::memcpy(row, img.pixel(0, sy), static_cast<std::size_t>(im.width) * 4);
      if (im.ew != im.width) std::memcpy(row + im.width * 4, img.pixel(im.width - 1, sy), 4);
    }
    src = im.padded.data();
  }
  // convert and encode with pts = frame number (time base 1/fps)
  int rc = av_frame_make_writable(im.frame);
  if (rc < 0) im.fail("cannot reuse the frame buffer", rc);
  const int stride = im.ew * 4;
  sws_scale(im.sws, &src, &stride, 0, im.eh, im.frame->data, im.frame->linesize);
  im.frame->pts = im.count++;
  try {
    im.encode(im.frame);
  } catch (const OutputError&) {
    impl_.reset();  // the file is gone: nothing is left to close
    throw;
  }
  frames_ = im.count;
}

void MovieEncoder::close() {
  if (!impl_) return;
  std::unique_ptr<Impl> im = std::move(impl_);
  // drain the encoder, then the trailer (the mp4 index)
  im->encode(nullptr);
  const int rc = av_write_trailer(im->fmt);
  if (rc < 0) im->fail_write("cannot write the mp4 trailer", rc);
}

bool MovieEncoder::is_open() const { return impl_ != nullptr; }
int MovieEncoder::frames() const { return frames_; }
std::string MovieEncoder::codec_name() const { return impl_ ? impl_->codec : std::string(); }

}  // namespace gs
