// internal to the frame builder: the page layout and the overlay geometry (colour bar, text,
// gravity arrow, test rectangle, force chains). Everything here is in canvas pixels, y up.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "render/frame.hpp"

namespace gs::detail {

/// where things go on the canvas, px
struct PageLayout {
  float plot_x0 = 0, plot_y0 = 0, plot_x1 = 0, plot_y1 = 0;  ///< the world view, px
  float font = 14;                                           ///< text height, px
  bool colorbar = false;                                     ///< a colour-bar panel on the right
};

/// a canvas rectangle x0, y0, x1, y1, px
using Rect = std::array<float, 4>;

/// the header lines: title, "t = … s    tap N", extra lines
std::vector<std::string> header_lines(const RenderOverlays& ov);
/// where the header panel goes (top left of the view); empty (all 0) without lines
Rect header_rect(const std::vector<std::string>& lines, const PageLayout& page);
/// where the gravity inset and its label go (top right of the view)
Rect gravity_rect(const PageLayout& page);

/// append coloured triangles for simple shapes
struct Painter {
  std::vector<ColorVertex>& out;

  void triangle(Vec2 a, Vec2 b, Vec2 c, Rgba8 col);
  void quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d, Rgba8 col);
  void rect(float x0, float y0, float x1, float y1, Rgba8 col);
  /// a segment a→b of the given width, px
  void line(Vec2 a, Vec2 b, float width, Rgba8 col);
  /// the outline of the rectangle, drawn inside it, width px
  void frame(float x0, float y0, float x1, float y1, float width, Rgba8 col);
  /// a filled disk approximated by `segments` triangles
  void disk(Vec2 c, float r, Rgba8 col, int segments = 32);
};

/// number of code points in a UTF-8 string
int utf8_length(const std::string& s);

/// the colour bar: strips of the colour map, frame, ticks, labels; fills frame.colorbar
void add_colorbar(FrameData& frame, const FrameSpec& spec, const PageLayout& page, double lo,
                  double hi, int n_species);

/// text lines, gravity arrow, test rectangle, force chains
void add_overlays(FrameData& frame, const RenderOverlays& ov, const FrameSpec& spec,
                  const PageLayout& page, float typical_radius_px);

}  // namespace gs::detail
