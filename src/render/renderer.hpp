// backends that turn a FrameData into an Image: OSMesa (render/gl, when compiled in) or the
// software rasteriser (always there, so machines without GL still get pictures)
#pragma once
#include <array>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/image.hpp"
#include "render/frame.hpp"
#include "render/text.hpp"

namespace gs {

/// the GL backend could not start or failed (no OSMesa, no GL 3.3, shader error)
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  /// draw the frame; the Image is width × height RGBA8, top row first, opaque
  virtual Image render(const FrameData& frame) = 0;
  /// one line saying what draws: "software" or "OSMesa 4.5 core profile, llvmpipe, 4x MSAA"
  virtual std::string describe() const = 0;
};

enum class RendererKind {
  automatic,  ///< OSMesa when compiled in and working, else software
  gl,         ///< OSMesa or RenderError
  software    ///< the CPU rasteriser (the "null" backend)
};
/// "auto", "gl" (or "osmesa"), "software" (or "null", "cpu"); else InputError
RendererKind parse_renderer_kind(const std::string& name);

/// the CPU rasteriser: edge functions for triangles, signed distances for polygons and disks
/// (one sample per pixel with analytic coverage, no MSAA); text when `fonts` gives atlases
std::unique_ptr<Renderer> make_software_renderer(FontProvider fonts = {});

/// pixels whose centres lie in a canvas rectangle x0, y0, x1, y1 (px): first and one-past-last
/// column and row counted from the bottom, clamped to the image (the GL scissor box)
std::array<int, 4> clip_pixels(const std::array<float, 4>& rect, int width, int height);

#if defined(GS_HAVE_OSMESA)
/// the OSMesa backend (render/gl); throws RenderError when no usable context can be made
std::unique_ptr<Renderer> make_gl_renderer();
#endif
#if defined(GS_HAVE_FREETYPE)
/// glyph atlases rasterised by FreeType from a TrueType file (default: DejaVu Sans, or the
/// GS_FONT environment variable), cached per size; gives nullptr when the font cannot be read
FontProvider freetype_fonts(const std::string& font_path = "");
#endif

/// the fonts this build has (FreeType when compiled in, else none)
static inline FontProvider default_fonts() {
#if defined(GS_HAVE_FREETYPE)
  return freetype_fonts();
#else
  return {};
#endif
}

/// the renderer of the given kind; `automatic` falls back to software with a note on stderr.
/// (static inline: each translation unit sees the backends its own target was built with)
static inline std::unique_ptr<Renderer> make_renderer(RendererKind kind = RendererKind::automatic) {
  if (kind == RendererKind::software) return make_software_renderer(default_fonts());
#if defined(GS_HAVE_OSMESA)
  if (kind == RendererKind::gl) return make_gl_renderer();
  try {
    return make_gl_renderer();
  } catch (const RenderError& e) {
    std::fprintf(stderr, "gransim: OpenGL unavailable (%s); using the software renderer\n",
                 e.what());
    return make_software_renderer(default_fonts());
  }
#else
  if (kind == RendererKind::gl)
    throw RenderError("this gransim was built without OSMesa; use the software renderer");
  return make_software_renderer(default_fonts());
#endif
}

}  // namespace gs
