// MP4 movies from Images through FFmpeg (libavcodec/libavformat/libswscale): H.264 (libx264)
// with an MPEG-4 part 2 fallback; knows nothing of GL
#pragma once
#include <memory>
#include <string>

#include "core/image.hpp"

namespace gs {

struct MovieOptions {
  int fps = 30;                   ///< frames per second
  int crf = 20;                   ///< quality: x264 constant rate factor (0 best … 51 worst)
  std::string preset = "medium";  ///< x264 speed preset (ultrafast … veryslow)
  std::string codec;              ///< "" = libx264 if present, else mpeg4; or "libx264", "mpeg4"
};

/// encodes frames of one size into an .mp4 (yuv420p; an odd width or height is padded by one
/// pixel, repeating the last column or row, since 4:2:0 needs even sizes)
class MovieEncoder {
 public:
  MovieEncoder();
  ~MovieEncoder();  ///< closes the file if still open (errors then are swallowed)
  MovieEncoder(const MovieEncoder&) = delete;
  MovieEncoder& operator=(const MovieEncoder&) = delete;

  /// start a movie of width × height frames; throws InputError naming the path
  void open(const std::string& path, int width, int height, int fps = 30, int crf = 20);
  void open(const std::string& path, int width, int height, const MovieOptions& options);
  /// encode one frame (its size must be the one given to open)
  void add_frame(const Image& frame);
  /// flush the encoder, write the trailer, close the file
  void close();

  bool is_open() const;
  int frames() const;              ///< frames added since the last open (also after close)
  std::string codec_name() const;  ///< "libx264" or "mpeg4"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int frames_ = 0;  ///< frames added since open
};

/// what a movie file holds, by decoding it
struct MovieInfo {
  int width = 0, height = 0;  ///< px
  int frames = 0;             ///< frames decoded
  double duration = 0.0;      ///< container duration, s
  double fps = 0.0;           ///< average frame rate, 1/s
  std::string codec;          ///< codec name, e.g. "h264"
  std::string pixel_format;   ///< e.g. "yuv420p"
};

/// open, decode every frame and count; throws InputError naming the path
MovieInfo probe_movie(const std::string& path);

/// decode frame `index` (0-based) of a movie back to RGBA (for checks and thumbnails)
Image movie_frame(const std::string& path, int index);

}  // namespace gs
