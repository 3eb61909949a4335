// text layout on the canvas from a glyph atlas (shared by the GL and software backends)
#include "render/text.hpp"

#include <cmath>

namespace gs {

std::u32string decode_utf8(const std::string& s) {
  std::u32string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    // the lead byte gives the length, continuation bytes carry 6 bits each
    int len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (len == 0 || i + len > s.size()) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    char32_t cp = len == 1 ? c : c & (0x7F >> len);
    bool ok = true;
    for (int k = 1; k < len; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      ok = ok && (cc & 0xC0) == 0x80;
      cp = (cp << 6) | (cc & 0x3F);
    }
    out.push_back(ok ? cp : 0xFFFD);
    i += ok ? len : 1;
  }
  return out;
}

std::u32string atlas_charset() {
  std::u32string cs;
  for (char32_t c = 32; c < 127; ++c) cs.push_back(c);
  // superscripts, Greek letters and signs used in labels (φ, ², ×10⁻³, °, ·, μ, −)
  cs += U"⁰¹²³⁴⁵⁶⁷⁸⁹⁻²³°·×−±μφθωσρΔ";
  return cs;
}

std::vector<GlyphQuad> layout_text(const TextItem& item, const GlyphAtlas& atlas) {
  const std::u32string cps = decode_utf8(item.text);
  // the advance width for horizontal alignment
  float width = 0.0f;
  for (char32_t c : cps)
    if (auto it = atlas.glyphs.find(c); it != atlas.glyphs.end())
      width += std::round(it->second.advance);
  float pen = item.x;
  if (item.halign == HAlign::center) pen -= 0.5f * width;
  if (item.halign == HAlign::right) pen -= width;
  float base = item.y;
  if (item.valign == VAlign::top) base -= atlas.ascender;
  // middle: centre the digit height (cap height ≈ 0.72 em for DejaVu Sans) on the anchor
  if (item.valign == VAlign::middle) base -= 0.36f * static_cast<float>(atlas.size_px);
  // whole pixels keep the glyph bitmaps crisp
  pen = std::round(pen);
  base = std::round(base);

  std::vector<GlyphQuad> quads;
  for (char32_t c : cps) {
    auto it = atlas.glyphs.find(c);
    if (it == atlas.glyphs.end()) it = atlas.glyphs.find(U'?');
    if (it == atlas.glyphs.end()) continue;
    const Glyph& g = it->second;
    if (g.w > 0 && g.h > 0) {
      const float x0 = pen + g.left, y1 = base + g.top;
      quads.push_back({x0, y1 - g.h, x0 + g.w, y1, g.x, g.y, g.w, g.h});
    }
    pen += std::round(g.advance);
  }
  return quads;
}

}  // namespace gs
