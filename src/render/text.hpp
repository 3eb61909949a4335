// text without GL: a glyph atlas (an 8-bit coverage bitmap plus metrics, filled by a font
// rasteriser such as FreeType in render/gl/font.cpp) and the layout of a TextItem into glyph quads
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "render/frame.hpp"

namespace gs {

/// one glyph in the atlas
struct Glyph {
  int x = 0, y = 0;       ///< top-left corner in the atlas, px (row 0 = top)
  int w = 0, h = 0;       ///< bitmap size, px
  int left = 0, top = 0;  ///< bitmap offset from the pen: right of it, above the baseline, px
  float advance = 0.0f;   ///< pen advance, px
};

/// the glyphs of one font at one pixel size
struct GlyphAtlas {
  int size_px = 0;                             ///< nominal pixel height
  int width = 0, height = 0;                   ///< atlas size, px
  std::vector<std::uint8_t> alpha;             ///< coverage, row 0 at the top
  std::unordered_map<char32_t, Glyph> glyphs;  ///< by code point
  float ascender = 0.0f, descender = 0.0f;     ///< above / below (negative) the baseline, px
};

/// gives the atlas for a pixel size (nullptr: no font, text is skipped)
using FontProvider = std::function<std::shared_ptr<const GlyphAtlas>(int size_px)>;

/// one placed glyph: canvas rectangle (px, y up) and its atlas rectangle (px)
struct GlyphQuad {
  float x0, y0, x1, y1;  ///< canvas, px
  int ax, ay, aw, ah;    ///< atlas x, y (top), width, height, px
};

/// UTF-8 to code points (invalid bytes become U+FFFD)
std::u32string decode_utf8(const std::string& s);

/// the code points every atlas should hold: printable ASCII and the few symbols the overlays use
std::u32string atlas_charset();

/// lay out a text item with the atlas: pixel-aligned glyph quads honouring the anchor
std::vector<GlyphQuad> layout_text(const TextItem& item, const GlyphAtlas& atlas);

}  // namespace gs
