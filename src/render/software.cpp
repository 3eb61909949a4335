// the software ("null") backend: a compact CPU rasteriser of FrameData.
// Shapes get analytic anti-aliasing from signed distances (coverage = clamp(0.5 − d, 0, 1)),
// the same formulas the GL shaders use, so both backends draw the same picture.
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "render/renderer.hpp"

namespace gs {

RendererKind parse_renderer_kind(const std::string& name) {
  if (name == "auto" || name.empty()) return RendererKind::automatic;
  if (name == "gl" || name == "osmesa") return RendererKind::gl;
  if (name == "software" || name == "null" || name == "cpu") return RendererKind::software;
  throw InputError("", "renderer", "unknown renderer '" + name + "' (known: auto, gl, software)");
}

std::array<int, 4> clip_pixels(const std::array<float, 4>& r, int width, int height) {
  // pixel i is inside when its centre i + 0.5 lies in [x0, x1)
  auto first = [](float a, int n) {
    return std::clamp(static_cast<int>(std::ceil(a - 0.5f)), 0, n);
  };
  return {first(r[0], width), first(r[1], height), first(r[2], width), first(r[3], height)};
}

namespace {

/// wall hatch: every other diagonal band of 6 px is darker (as shaders/wall.frag)
bool hatched(float cx, float cy) { return static_cast<int>(std::floor((cx + cy) / 6.0f)) & 1; }

class SoftwareRenderer final : public Renderer {
 public:
  explicit SoftwareRenderer(FontProvider fonts) : fonts_(std::move(fonts)) {}

  Image render(const FrameData& f) override {
    Image img(f.width, f.height);
    img_ = &img;
    // background, walls, particles, world overlays (clipped), overlays, text
    for (std::size_t k = 0; k < img.rgba.size(); k += 4) {
      img.rgba[k] = f.background.r;
      img.rgba[k + 1] = f.background.g;
      img.rgba[k + 2] = f.background.b;
      img.rgba[k + 3] = 255;
    }
    const std::array<int, 4> all{0, 0, f.width, f.height};
    const auto view = clip_pixels(f.view_clip, f.width, f.height);
    triangles(f.walls, view, true);
    const auto clip = clip_pixels(f.particle_clip, f.width, f.height);
    for (const auto& s : f.polygons) shape(s, f, clip);
    for (const auto& s : f.disks) shape(s, f, clip);
    triangles(f.world_overlay, view, false);
    triangles(f.overlay, all, false);
    if (fonts_)
      for (const auto& t : f.text) text(t);
    img_ = nullptr;
    return img;
  }

  std::string describe() const override {
    return fonts_ ? "software rasteriser (analytic coverage, FreeType text)"
                  : "software rasteriser (analytic coverage, no text)";
  }

 private:
  // blend a colour with coverage cov into canvas pixel (i, j), j counted from the bottom
  void blend(int i, int j, Rgba8 c, float cov) {
    const float a = cov * (c.a / 255.0f);
    if (a <= 0.0f) return;
    std::uint8_t* px = img_->pixel(i, img_->height - 1 - j);
    const std::uint8_t src[3] = {c.r, c.g, c.b};
    for (int k = 0; k < 3; ++k)
      px[k] = static_cast<std::uint8_t>(std::lround(px[k] + (src[k] - px[k]) * a));
  }

  // triangles by edge functions at pixel centres, colours interpolated, top-left fill rule
  void triangles(const std::vector<ColorVertex>& v, const std::array<int, 4>& clip, bool hatch) {
    for (std::size_t t = 0; t + 2 < v.size(); t += 3) {
      ColorVertex a = v[t], b = v[t + 1], c = v[t + 2];
      double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (area == 0.0) continue;
      if (area < 0.0) std::swap(b, c), area = -area;
      const int i0 = std::max(clip[0], static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
      const int i1 = std::min(clip[2], static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
      const int j0 = std::max(clip[1], static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
      const int j1 = std::min(clip[3], static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
      // edge p→q: value > 0 inside; on the edge only for top or left edges
      auto edge = [](const ColorVertex& p, const ColorVertex& q, double x, double y) {
        const double w = (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
        const bool top_left = (q.y < p.y) || (q.y == p.y && q.x < p.x);
        return (w > 0.0 || (w == 0.0 && top_left)) ? w : -1.0;
      };
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          const double x = i + 0.5, y = j + 0.5;
          const double wa = edge(b, c, x, y), wb = edge(c, a, x, y), wc = edge(a, b, x, y);
          if (wa < 0.0 || wb < 0.0 || wc < 0.0) continue;
          auto mix = [&](std::uint8_t pa, std::uint8_t pb, std::uint8_t pc) {
            return static_cast<std::uint8_t>(std::lround((wa * pa + wb * pb + wc * pc) / area));
          };
          Rgba8 col{mix(a.color.r, b.color.r, c.color.r), mix(a.color.g, b.color.g, c.color.g),
                    mix(a.color.b, b.color.b, c.color.b), mix(a.color.a, b.color.a, c.color.a)};
          if (hatch && hatched(static_cast<float>(x), static_cast<float>(y)))
            col = {static_cast<std::uint8_t>(col.r * 0.8f), static_cast<std::uint8_t>(col.g * 0.8f),
                   static_cast<std::uint8_t>(col.b * 0.8f), col.a};
          blend(i, j, col, 1.0f);
        }
    }
  }

  // a regular polygon or a disk: signed distance d (px, > 0 outside), coverage and outline
  void shape(const ShapeInstance& s, const FrameData& f, const std::array<int, 4>& clip) {
    const int n = s.sides > 64 ? 0 : s.sides;  // (the builder draws finer n-gons as disks)
    // inward distance to the boundary is max over edge normals of dot(p, n_k) − apothem
    float nx[64], ny[64];
    const float apothem = n > 0 ? s.radius * std::cos(static_cast<float>(M_PI) / n) : s.radius;
    for (int k = 0; k < n; ++k) {
      const double a = s.angle + (2 * k + 1) * M_PI / n;
      nx[k] = static_cast<float>(std::cos(a));
      ny[k] = static_cast<float>(std::sin(a));
    }
    const float reach = s.radius + 1.0f;
    const int i0 = std::max(clip[0], static_cast<int>(std::floor(s.cx - reach)));
    const int i1 = std::min(clip[2], static_cast<int>(std::ceil(s.cx + reach)));
    const int j0 = std::max(clip[1], static_cast<int>(std::floor(s.cy - reach)));
    const int j1 = std::min(clip[3], static_cast<int>(std::ceil(s.cy + reach)));
    const float w = f.outline_px;
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const float px = i + 0.5f - s.cx, py = j + 0.5f - s.cy;
        float d;
        if (n == 0) {
          d = std::sqrt(px * px + py * py) - s.radius;
        } else {
          d = -1e30f;
          for (int k = 0; k < n; ++k) d = std::max(d, px * nx[k] + py * ny[k]);
          d -= apothem;
        }
        const float cov = std::clamp(0.5f - d, 0.0f, 1.0f);
        if (cov <= 0.0f) continue;
        // the outline is the band of width w inside the boundary
        const float t = w > 0.0f ? std::clamp(-d - w + 0.5f, 0.0f, 1.0f) : 1.0f;
        const Rgba8& o = f.outline_color;
        const Rgba8 col{static_cast<std::uint8_t>(std::lround(o.r + (s.fill.r - o.r) * t)),
                        static_cast<std::uint8_t>(std::lround(o.g + (s.fill.g - o.g) * t)),
                        static_cast<std::uint8_t>(std::lround(o.b + (s.fill.b - o.b) * t)),
                        s.fill.a};
        blend(i, j, col, cov);
      }
  }

  // glyph coverage bitmaps blended in the text colour
  void text(const TextItem& t) {
    const auto atlas = fonts_(static_cast<int>(std::lround(t.size)));
    if (!atlas) return;
    for (const GlyphQuad& q : layout_text(t, *atlas))
      for (int v = 0; v < q.ah; ++v)
        for (int u = 0; u < q.aw; ++u) {
          const int i = static_cast<int>(q.x0) + u, j = static_cast<int>(q.y1) - 1 - v;
          if (i < 0 || j < 0 || i >= img_->width || j >= img_->height) continue;
          const std::uint8_t a =
              atlas->alpha[static_cast<std::size_t>(q.ay + v) * atlas->width + q.ax + u];
          if (a) blend(i, j, t.color, a / 255.0f);
        }
  }

  FontProvider fonts_;
  Image* img_ = nullptr;
};

}  // namespace

std::unique_ptr<Renderer> make_software_renderer(FontProvider fonts) {
  return std::make_unique<SoftwareRenderer>(std::move(fonts));
}

}  // namespace gs
