// OSMesa context: core profile 3.3 first, compatibility profile as the fallback
#include "render/gl/context.hpp"

#include <GL/osmesa.h>

#include <cstdio>

#include "render/renderer.hpp"

namespace gs::gl {

namespace {

// a context of the given profile and minimum version, or nullptr
OSMesaContext create(int profile, int major, int minor) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         profile,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         major,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         minor,
                         0};
  return OSMesaCreateContextAttribs(attribs, nullptr);
}

}  // namespace

OsMesaContext::OsMesaContext() {
  // core 3.3 as asked by the shaders; else whatever compatibility context there is
  OSMesaContext c = create(OSMESA_CORE_PROFILE, 3, 3);
  profile_ = "core";
  if (!c) {
    c = create(OSMESA_COMPAT_PROFILE, 3, 3);
    if (!c) c = create(OSMESA_COMPAT_PROFILE, 1, 0);
    profile_ = "compatibility";
    if (c)
      std::fprintf(stderr, "gransim: OSMesa core profile 3.3 unavailable; using a %s context\n",
                   profile_.c_str());
  }
  if (!c) throw RenderError("OSMesaCreateContextAttribs failed (no core or compatibility context)");
  ctx_ = c;
}

OsMesaContext::~OsMesaContext() {
  if (ctx_) OSMesaDestroyContext(static_cast<OSMesaContext>(ctx_));
}

void OsMesaContext::make_current(int width, int height) {
  // a new buffer only when the size changes; OSMesa keeps drawing into the one we pass
  if (width != width_ || height != height_) {
    buffer_.assign(static_cast<std::size_t>(width) * height * 4, 0);
    width_ = width;
    height_ = height;
  }
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), buffer_.data(), GL_UNSIGNED_BYTE, width,
                         height))
    throw RenderError("OSMesaMakeCurrent failed for a " + std::to_string(width) + "x" +
                      std::to_string(height) + " buffer");
  // rows top first, as gs::Image has them
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

OsMesaContext::Proc OsMesaContext::proc(const char* name) {
  return reinterpret_cast<Proc>(OSMesaGetProcAddress(name));
}

}  // namespace gs::gl
