// overlay geometry of the frame builder: colour bar with ticks, header text, gravity arrow,
// test rectangle, force chains (canvas pixels, y up)
#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gs {

namespace detail {

void Painter::triangle(Vec2 a, Vec2 b, Vec2 c, Rgba8 col) {
  for (Vec2 v : {a, b, c}) out.push_back({static_cast<float>(v.x), static_cast<float>(v.y), col});
}

void Painter::quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d, Rgba8 col) {
  triangle(a, b, c, col);
  triangle(a, c, d, col);
}

void Painter::rect(float x0, float y0, float x1, float y1, Rgba8 col) {
  quad({x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, col);
}

void Painter::line(Vec2 a, Vec2 b, float width, Rgba8 col) {
  const double len = norm(b - a);
  if (len <= 0.0) return;
  const Vec2 n = perp(b - a) * (0.5 * width / len);
  quad(a - n, b - n, b + n, a + n, col);
}

void Painter::frame(float x0, float y0, float x1, float y1, float w, Rgba8 col) {
  rect(x0, y0, x1, y0 + w, col);
  rect(x0, y1 - w, x1, y1, col);
  rect(x0, y0 + w, x0 + w, y1 - w, col);
  rect(x1 - w, y0 + w, x1, y1 - w, col);
}

void Painter::disk(Vec2 c, float r, Rgba8 col, int segments) {
  for (int k = 0; k < segments; ++k) {
    const double a0 = 2.0 * M_PI * k / segments, a1 = 2.0 * M_PI * (k + 1) / segments;
    triangle(c, c + Vec2{std::cos(a0), std::sin(a0)} * r, c + Vec2{std::cos(a1), std::sin(a1)} * r,
             col);
  }
}

int utf8_length(const std::string& s) {
  int n = 0;
  for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
  return n;
}

namespace {

// "×10⁻³" for an exponent p, with superscript digits
std::string power_of_ten(int p) {
  static const char* sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string digits;
  for (int a = std::abs(p);; a /= 10) {
    digits = sup[a % 10] + digits;
    if (a < 10) break;
  }
  return std::string("×10") + (p < 0 ? "⁻" : "") + digits;
}

// the colour-bar title for the quantity
std::string bar_label(const FrameSpec& spec) {
  switch (spec.color_by) {
    case ColorBy::speed:
      return "speed (m/s)";
    case ColorBy::speed_rms:
      return "|v| / v_rms";
    case ColorBy::species:
      return "species";
    case ColorBy::vy:
      return "v_y (m/s)";
    case ColorBy::extra:
      return spec.extra_unit.empty() ? spec.extra_label
                                     : spec.extra_label + " (" + spec.extra_unit + ")";
    case ColorBy::uniform:
      break;
  }
  return "";
}

}  // namespace

void add_colorbar(FrameData& f, const FrameSpec& spec, const PageLayout& page, double lo, double hi,
                  int n_species) {
  const Colormap& map = colormap(spec.colormap);
  const float fs = page.font, H = static_cast<float>(f.height);
  Painter paint{f.overlay};

  // the bar: a column in the panel, its top leaving room for the title
  const float x0 = page.plot_x1 + 0.8f * fs, x1 = x0 + 1.0f * fs;
  const float y0 = std::max(1.5f * fs, 0.1f * H), y1 = H - std::max(3.2f * fs, 0.15f * H);
  if (!(y1 > y0 + 4.0f)) return;  // no room on a tiny frame
  ColorBarInfo& info = f.colorbar;
  info.shown = true;
  info.rect = {x0, y0, x1, y1};
  info.label = bar_label(spec);

  // its fill: 256 strips of the map, or one block per species
  const bool discrete = spec.color_by == ColorBy::species;
  const int strips = discrete ? n_species : 256;
  for (int k = 0; k < strips; ++k) {
    const float ya = y0 + (y1 - y0) * k / strips, yb = y0 + (y1 - y0) * (k + 1) / strips;
    const Rgba8 c =
        discrete ? map.at(n_species > 1 ? double(k) / (n_species - 1) : 0.0) : map.lut[k];
    paint.rect(x0, ya, x1, yb, c);
  }
  const float lw = std::max(1.0f, fs / 16.0f);
  paint.frame(x0 - lw, y0 - lw, x1 + lw, y1 + lw, lw, spec.text_color);

  // ticks: nice values of the range, or the species indices at the block centres
  std::vector<double> ticks;
  double t_lo = lo, t_hi = hi;
  if (discrete) {
    t_lo = -0.5, t_hi = n_species - 0.5;
    const int every = std::max(1, n_species / 8);
    for (int s = 0; s < n_species; s += every) ticks.push_back(s);
  } else {
    ticks = nice_ticks(lo, hi, std::clamp(static_cast<int>((y1 - y0) / (2.2f * fs)), 2, 8));
  }
  info.lo = t_lo;
  info.hi = t_hi;
  info.ticks = ticks;

  // very small or large values get a common power of ten in the title
  const double amax = std::max(std::abs(lo), std::abs(hi));
  int p10 = 0;
  if (!discrete && amax > 0.0 && (amax < 1e-2 || amax >= 1e4))
    p10 = static_cast<int>(std::floor(std::log10(amax)));
  std::vector<double> shown = ticks;
  for (double& t : shown) t /= std::pow(10.0, p10);
  const std::vector<std::string> labels = tick_labels(shown);
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    const float y = static_cast<float>(y0 + (y1 - y0) * (ticks[k] - t_lo) / (t_hi - t_lo));
    paint.rect(x1, y - 0.5f * lw, x1 + 0.35f * fs, y + 0.5f * lw, spec.text_color);
    f.text.push_back(
        {labels[k], x1 + 0.55f * fs, y, 0.85f * fs, HAlign::left, VAlign::middle, spec.text_color});
  }

  // the title above the bar, the power of ten under it
  const float tx = page.plot_x1 + 0.4f * fs;
  if (p10 != 0) {
    f.text.push_back(
        {info.label, tx, y1 + 1.9f * fs, fs, HAlign::left, VAlign::baseline, spec.text_color});
    f.text.push_back({power_of_ten(p10), tx, y1 + 0.7f * fs, 0.85f * fs, HAlign::left,
                      VAlign::baseline, spec.text_color});
  } else {
    f.text.push_back(
        {info.label, tx, y1 + 0.8f * fs, fs, HAlign::left, VAlign::baseline, spec.text_color});
  }
}

void add_overlays(FrameData& f, const RenderOverlays& ov, const FrameSpec& spec,
                  const PageLayout& page, float r_typ) {
  const float fs = page.font;
  Painter paint{f.overlay}, world{f.world_overlay};

  // force chains: segments between centres, width proportional to the force
  double fmax = 0.0;
  for (const auto& c : ov.force_chains) fmax = std::max(fmax, c.force);
  const float wmax = std::max(1.0f, 0.5f * r_typ);
  for (const auto& c : ov.force_chains) {
    if (!(c.force > 0.0)) continue;
    const float w = std::max(0.75f, static_cast<float>(wmax * c.force / fmax));
    world.line(f.camera.to_canvas(c.a), f.camera.to_canvas(c.b), w, {170, 20, 20, 220});
  }

  // the test (measurement) rectangle as a red frame
  if (ov.test_rect) {
    const auto& r = *ov.test_rect;
    const Vec2 a = f.camera.to_canvas({r[0], r[1]}), b = f.camera.to_canvas({r[2], r[3]});
    world.frame(static_cast<float>(std::min(a.x, b.x)), static_cast<float>(std::min(a.y, b.y)),
                static_cast<float>(std::max(a.x, b.x)), static_cast<float>(std::max(a.y, b.y)),
                std::max(1.5f, fs / 9.0f), {220, 40, 40, 235});
  }

  // the gravity arrow in an inset at the top right of the view
  if (ov.show_gravity) {
    const float R = 2.2f * fs;
    const Rect box = gravity_rect(page);
    const Vec2 c{box[2] - 1.1f * R, box[3] - 1.1f * R};
    paint.disk(c, R, {255, 255, 255, 200}, 48);
    for (int k = 0; k < 48; ++k) {
      const double a0 = 2 * M_PI * k / 48, a1 = 2 * M_PI * (k + 1) / 48;
      paint.line(c + Vec2{std::cos(a0), std::sin(a0)} * R, c + Vec2{std::cos(a1), std::sin(a1)} * R,
                 std::max(1.0f, fs / 12.0f), spec.text_color);
    }
    const double g = norm(ov.gravity);
    const Rgba8 red{185, 25, 25, 255};
    if (g > 0.0) {
      const Vec2 d = ov.gravity / g, tip = c + d * (0.8 * R), tail = c - d * (0.8 * R);
      const double hl = 0.8 * fs, hw = 0.85 * fs;
      paint.line(tail, tip - d * hl, std::max(2.0f, 0.22f * fs), red);
      paint.triangle(tip, tip - d * hl + perp(d) * (0.5 * hw), tip - d * hl - perp(d) * (0.5 * hw),
                     red);
    } else {
      paint.disk(c, 0.2f * fs, red, 16);
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "g = %.2f m/s²", g);
    f.text.push_back({buf, static_cast<float>(c.x - R - 0.5f * fs), static_cast<float>(c.y),
                      0.85f * fs, HAlign::right, VAlign::middle, spec.text_color});
  }

  // header lines at the top left on a translucent panel
  const std::vector<std::string> lines = header_lines(ov);
  if (lines.empty()) return;
  const Rect panel = header_rect(lines, page);
  paint.rect(panel[0], panel[1], panel[2], panel[3], {255, 255, 255, 190});
  for (std::size_t k = 0; k < lines.size(); ++k)
    f.text.push_back({lines[k], panel[0] + 0.35f * fs, panel[3] - 0.95f * fs - 1.35f * fs * k, fs,
                      HAlign::left, VAlign::baseline, spec.text_color});
}

std::vector<std::string> header_lines(const RenderOverlays& ov) {
  std::vector<std::string> lines;
  if (!ov.title.empty()) lines.push_back(ov.title);
  std::string clock;
  if (ov.show_time) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "t = %.3f s", ov.time);
    clock = buf;
  }
  if (ov.has_tap)
    clock += (clock.empty() ? "" : "    ") + std::string("tap ") + std::to_string(ov.tap);
  if (!clock.empty()) lines.push_back(clock);
  for (const auto& l : ov.lines) lines.push_back(l);
  return lines;
}

Rect header_rect(const std::vector<std::string>& lines, const PageLayout& page) {
  if (lines.empty()) return {};
  // width from an average DejaVu Sans glyph of 0.56 em, 1.35 em per line
  const float fs = page.font;
  int chars = 0;
  for (const auto& l : lines) chars = std::max(chars, utf8_length(l));
  const float x0 = page.plot_x0 + 0.35f * fs, y1 = page.plot_y1 - 0.35f * fs;
  return {x0, y1 - 1.35f * fs * lines.size() - 0.3f * fs, x0 + 0.56f * fs * chars + 0.7f * fs, y1};
}

Rect gravity_rect(const PageLayout& page) {
  // the inset disk (radius 2.2 em) with "g = 9.81 m/s²" (about 6 em) to its left
  const float fs = page.font, R = 2.2f * fs;
  const float x1 = page.plot_x1 - 0.2f * R, y1 = page.plot_y1 - 0.2f * R;
  return {x1 - 2.2f * R - 6.8f * fs, y1 - 2.2f * R, x1, y1};
}

}  // namespace detail

std::vector<double> nice_ticks(double lo, double hi, int max_count) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  max_count = std::max(2, max_count);
  // the smallest step of 1, 2, 2.5, 5 × 10^k giving at most max_count ticks in [lo, hi]
  const double raw = (hi - lo) / (max_count - 1);
  const int e = static_cast<int>(std::floor(std::log10(raw)));
  const double mag = std::pow(10.0, std::abs(e));
  // k·m·10^e, dividing by 10^|e| for negative e so that 3 × 0.1 prints and compares as 0.3
  auto value = [&](double km) { return e < 0 ? km / mag : km * mag; };
  double m = 10.0;
  for (double cand : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    const double s = value(cand);
    const double count = std::floor(hi / s + 1e-9) - std::ceil(lo / s - 1e-9) + 1;
    if (count <= max_count) {
      m = cand;
      break;
    }
  }
  const double step = value(m);
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k <= std::floor(hi / step + 1e-9); k += 1.0)
    ticks.push_back(k == 0.0 ? 0.0 : value(k * m));
  return ticks;
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  // the decimals that show every multiple of the step exactly
  int decimals = 0;
  if (ticks.size() >= 2) {
    const double step = std::abs(ticks[1] - ticks[0]);
    while (decimals < 10) {
      const double s = step * std::pow(10.0, decimals);
      if (std::abs(s - std::round(s)) <= 1e-6 * s) break;
      ++decimals;
    }
  }
  std::vector<std::string> out;
  for (double t : ticks) {
    char buf[64];
    if (ticks.size() >= 2)
      std::snprintf(buf, sizeof buf, "%.*f", decimals, t == 0.0 ? 0.0 : t);
    else
      std::snprintf(buf, sizeof buf, "%g", t);
    out.push_back(buf);
  }
  return out;
}

}  // namespace gs
