// helpers for the render tests: the renderers under test and pixel reading in canvas coordinates
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/image.hpp"
#include "render/renderer.hpp"

namespace gs::test {

/// the backends every raster test runs on ("gl" only where OSMesa is compiled in)
inline std::vector<std::string> backends() {
#if defined(GS_HAVE_OSMESA)
  return {"software", "gl"};
#else
  return {"software"};
#endif
}

/// one renderer per backend for the whole test program (GL shader compilation is slow).
/// Deliberately never destroyed: at exit OSMesa tears itself down before static destructors
/// would run, and making its context current then crashes.
inline Renderer& renderer(const std::string& kind) {
  static Renderer* sw = nullptr;
  static Renderer* gl = nullptr;
  Renderer*& slot = kind == "gl" ? gl : sw;
  if (!slot) slot = make_renderer(parse_renderer_kind(kind)).release();
  return *slot;
}

/// the pixel covering canvas point (x, y) (canvas: px, origin bottom-left, y up)
inline Rgba8 at_canvas(const Image& img, double x, double y) {
  const int col = static_cast<int>(std::floor(x));
  const int row = img.height - 1 - static_cast<int>(std::floor(y));
  const std::uint8_t* p = img.pixel(col, row);
  return {p[0], p[1], p[2], p[3]};
}

/// how far a pixel has moved from bg towards fg, measured on the channel where they differ most
inline double blend_fraction(Rgba8 pix, Rgba8 bg, Rgba8 fg) {
  const int d[3] = {fg.r - bg.r, fg.g - bg.g, fg.b - bg.b};
  const int p[3] = {pix.r - bg.r, pix.g - bg.g, pix.b - bg.b};
  int k = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(d[c]) > std::abs(d[k])) k = c;
  return static_cast<double>(p[k]) / d[k];
}

/// largest channel difference
inline int color_distance(Rgba8 a, Rgba8 b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

}  // namespace gs::test
