// an offscreen OSMesa GL context (the only place that sees osmesa.h)
#pragma once
#include <string>
#include <vector>

namespace gs::gl {

class OsMesaContext {
 public:
  using Proc = void (*)();

  /// a 3.3 core-profile context, or a compatibility one when core is unavailable (noted on
  /// stderr); throws RenderError when neither can be made
  OsMesaContext();
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  /// bind the context to this thread with a width × height colour buffer
  void make_current(int width, int height);
  /// the default framebuffer's pixels, RGBA8, top row first
  const unsigned char* pixels() const { return buffer_.data(); }
  /// "core" or "compatibility"
  const std::string& profile() const { return profile_; }
  /// an entry point by name (OSMesaGetProcAddress)
  static Proc proc(const char* name);

 private:
  void* ctx_ = nullptr;                ///< OSMesaContext
  std::vector<unsigned char> buffer_;  ///< the default framebuffer, RGBA8
  int width_ = 0, height_ = 0;         ///< its size, px
  std::string profile_;
};

}  // namespace gs::gl
