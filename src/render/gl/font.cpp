// FreeType glyph atlases: DejaVu Sans (or $GS_FONT) rasterised once per pixel size
#if defined(GS_HAVE_FREETYPE)
#include <ft2build.h>
#include FT_FREETYPE_H

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include "render/renderer.hpp"

namespace gs {

namespace {

constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// the FreeType library, the face and the atlases made so far
struct FontCache {
  std::string path;
  std::mutex mutex;
  FT_Library lib = nullptr;
  FT_Face face = nullptr;
  bool failed = false;
  std::map<int, std::shared_ptr<const GlyphAtlas>> atlases;

  ~FontCache() {
    if (face) FT_Done_Face(face);
    if (lib) FT_Done_FreeType(lib);
  }

  // open the face once; a failure is reported once and then text is skipped
  bool open() {
    if (face) return true;
    if (failed) return false;
    failed = FT_Init_FreeType(&lib) != 0 || FT_New_Face(lib, path.c_str(), 0, &face) != 0;
    if (failed)
      std::fprintf(stderr, "gransim: cannot load font %s; frames get no text\n", path.c_str());
    return !failed;
  }

  // render every glyph of the charset and pack them on shelves of a 512 px wide atlas
  std::shared_ptr<const GlyphAtlas> build(int size) {
    FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(size));
    auto atlas = std::make_shared<GlyphAtlas>();
    atlas->size_px = size;
    atlas->width = size > 40 ? 1024 : 512;
    atlas->ascender = face->size->metrics.ascender / 64.0f;
    atlas->descender = face->size->metrics.descender / 64.0f;
    struct Bitmap {
      char32_t cp;
      Glyph g;
      std::vector<std::uint8_t> pixels;
    };
    std::vector<Bitmap> bitmaps;
    int pen_x = 1, pen_y = 1, shelf = 0;
    for (char32_t cp : atlas_charset()) {
      if (FT_Load_Char(face, cp, FT_LOAD_RENDER) != 0) continue;
      const FT_GlyphSlot s = face->glyph;
      Bitmap b{cp, {}, {}};
      b.g.w = static_cast<int>(s->bitmap.width);
      b.g.h = static_cast<int>(s->bitmap.rows);
      b.g.left = s->bitmap_left;
      b.g.top = s->bitmap_top;
      b.g.advance = s->advance.x / 64.0f;
      // next shelf when the row is full (1 px gaps keep linear filtering clean)
      if (pen_x + b.g.w + 1 > atlas->width) pen_x = 1, pen_y += shelf + 1, shelf = 0;
      b.g.x = pen_x;
      b.g.y = pen_y;
      pen_x += b.g.w + 1;
      shelf = std::max(shelf, b.g.h);
      for (int r = 0; r < b.g.h; ++r)
        for (int c = 0; c < b.g.w; ++c)
          b.pixels.push_back(s->bitmap.buffer[r * s->bitmap.pitch + c]);
      bitmaps.push_back(std::move(b));
    }
    // copy the bitmaps into the atlas
    atlas->height = pen_y + shelf + 1;
    atlas->alpha.assign(static_cast<std::size_t>(atlas->width) * atlas->height, 0);
    for (const auto& b : bitmaps) {
      for (int r = 0; r < b.g.h; ++r)
        for (int c = 0; c < b.g.w; ++c)
          atlas->alpha[static_cast<std::size_t>(b.g.y + r) * atlas->width + b.g.x + c] =
              b.pixels[static_cast<std::size_t>(r) * b.g.w + c];
      atlas->glyphs[b.cp] = b.g;
    }
    return atlas;
  }
};

}  // namespace

FontProvider freetype_fonts(const std::string& font_path) {
  auto cache = std::make_shared<FontCache>();
  const char* env = std::getenv("GS_FONT");
  cache->path = !font_path.empty() ? font_path : (env && *env) ? env : kDefaultFont;
  return [cache](int size) -> std::shared_ptr<const GlyphAtlas> {
    size = std::max(6, std::min(size, 200));
    std::lock_guard<std::mutex> lock(cache->mutex);
    if (!cache->open()) return nullptr;
    auto& slot = cache->atlases[size];
    if (!slot) slot = cache->build(size);
    return slot;
  };
}

}  // namespace gs
#endif  // GS_HAVE_FREETYPE
