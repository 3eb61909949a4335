// the frame builder: world state → canvas instances (no GL here)
#include "render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "render/overlay.hpp"

namespace gs {

namespace {

/// most sides drawn as a true polygon; finer n-gons are drawn as disks (indistinguishable)
constexpr int kMaxSides = 64;

// the frame size must be drawable
void check_spec(const FrameSpec& spec, const RenderParticles& p) {
  if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384)
    throw InputError("", "render.size",
                     "frame size " + std::to_string(spec.width) + "x" +
                         std::to_string(spec.height) + " is outside 1..16384 px");
  const std::size_t n = p.size();
  if (p.y.size() != n || p.radius.size() != n || p.sides.size() != n)
    throw InputError("", "particles", "x, y, radius and sides must have the same length");
  if ((!p.theta.empty() && p.theta.size() != n) || (!p.vx.empty() && p.vx.size() != n) ||
      (!p.vy.empty() && p.vy.size() != n) || (!p.species.empty() && p.species.size() != n))
    throw InputError("", "particles", "theta, vx, vy and species must be empty or of length n");
  if (spec.color_by == ColorBy::extra && p.value_extra.size() != n)
    throw InputError("", "color_by",
                     "colouring by 'extra' needs one value_extra per particle (have " +
                         std::to_string(p.value_extra.size()) + " for " + std::to_string(n) + ")");
}

// the value range: fixed, or automatic for the quantity
std::pair<double, double> value_range(const FrameSpec& spec, const std::vector<double>& v,
                                      int n_species) {
  if (spec.range) {
    if (!(spec.range->second > spec.range->first))
      throw InputError("", "range", "the colour range needs low < high");
    return *spec.range;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, amax = 0.0;
  for (double x : v) {
    if (!std::isfinite(x)) continue;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    amax = std::max(amax, std::abs(x));
  }
  switch (spec.color_by) {
    case ColorBy::species:
      return {0.0, std::max(1.0, n_species - 1.0)};
    case ColorBy::vy:
      return amax > 0.0 ? std::pair{-amax, amax} : std::pair{-1.0, 1.0};
    case ColorBy::extra:
      if (!(hi >= lo)) return {0.0, 1.0};
      if (hi == lo) return {lo - 0.5, hi + 0.5};
      return {lo, hi};
    default:  // speeds: from rest to the fastest
      return hi > 0.0 ? std::pair{0.0, hi} : std::pair{0.0, 1.0};
  }
}

// fit the world region into the plot area keeping the aspect ratio, centred
Camera fit_camera(const FrameSpec& spec, const RenderWalls& walls, const BoxExtent& box,
                  const detail::PageLayout& page) {
  double x0 = box.x0, y0 = box.y0, x1 = box.x1, y1 = box.y1;
  if (spec.camera.region) {
    const auto& r = *spec.camera.region;
    x0 = r[0], y0 = r[1], x1 = r[2], y1 = r[3];
  } else {
    // the box and the walls around it, then the margin
    for (const auto& q : walls.rects)
      for (const auto& c : q) {
        x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
        y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
      }
    const double m = spec.camera.margin * std::max(x1 - x0, y1 - y0);
    x0 -= m, x1 += m, y0 -= m, y1 += m;
  }
  if (!(x1 > x0) || !(y1 > y0))
    throw InputError("", "camera", "the view region must have positive width and height");
  const double pw = page.plot_x1 - page.plot_x0, ph = page.plot_y1 - page.plot_y0;
  Camera cam;
  cam.scale = std::min(pw / (x1 - x0), ph / (y1 - y0));
  cam.ox = page.plot_x0 + 0.5 * (pw - cam.scale * (x1 - x0)) - cam.scale * x0;
  cam.oy = page.plot_y0 + 0.5 * (ph - cam.scale * (y1 - y0)) - cam.scale * y0;
  return cam;
}

// the periodic images of a particle that reach into the box (including itself)
template <class F>
void for_each_image(const BoxExtent& box, double x, double y, double r, F&& emit) {
  const double lx = box.x1 - box.x0, ly = box.y1 - box.y0;
  if (box.periodic_x) x = box.x0 + (x - box.x0) - lx * std::floor((x - box.x0) / lx);
  if (box.periodic_y) y = box.y0 + (y - box.y0) - ly * std::floor((y - box.y0) / ly);
  for (int sx = -1; sx <= 1; ++sx) {
    if (sx != 0 && !box.periodic_x) continue;
    const double xi = x + sx * lx;
    if (sx != 0 && (xi + r < box.x0 || xi - r > box.x1)) continue;
    for (int sy = -1; sy <= 1; ++sy) {
      if (sy != 0 && !box.periodic_y) continue;
      const double yi = y + sy * ly;
      if (sy != 0 && (yi + r < box.y0 || yi - r > box.y1)) continue;
      emit(xi, yi);
    }
  }
}

}  // namespace

ColorBy parse_color_by(const std::string& name) {
  if (name == "speed" || name.empty()) return ColorBy::speed;
  if (name == "speed_rms" || name == "v/vrms" || name == "speed/vrms") return ColorBy::speed_rms;
  if (name == "species") return ColorBy::species;
  if (name == "vy") return ColorBy::vy;
  if (name == "extra") return ColorBy::extra;
  if (name == "uniform" || name == "none") return ColorBy::uniform;
  throw InputError(
      "", "color_by",
      "unknown colouring '" + name + "' (known: speed, speed_rms, species, vy, extra, uniform)");
}

std::string to_string(ColorBy c) {
  switch (c) {
    case ColorBy::speed:
      return "speed";
    case ColorBy::speed_rms:
      return "speed_rms";
    case ColorBy::species:
      return "species";
    case ColorBy::vy:
      return "vy";
    case ColorBy::extra:
      return "extra";
    case ColorBy::uniform:
      return "uniform";
  }
  return "speed";
}

std::vector<double> particle_values(const RenderParticles& p, ColorBy by) {
  const std::size_t n = p.size();
  std::vector<double> v(n, 0.0);
  auto vx = [&](std::size_t i) { return p.vx.empty() ? 0.0 : p.vx[i]; };
  auto vy = [&](std::size_t i) { return p.vy.empty() ? 0.0 : p.vy[i]; };
  switch (by) {
    case ColorBy::speed:
    case ColorBy::speed_rms: {
      // |v|, then divided by v_rms = sqrt(<|v|²>) when asked
      double sum2 = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        v[i] = std::hypot(vx(i), vy(i));
        sum2 += v[i] * v[i];
      }
      const double vrms = n > 0 ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
      if (by == ColorBy::speed_rms)
        for (double& x : v) x = vrms > 0.0 ? x / vrms : 0.0;
      break;
    }
    case ColorBy::species:
      for (std::size_t i = 0; i < n; ++i) v[i] = p.species.empty() ? 0.0 : p.species[i];
      break;
    case ColorBy::vy:
      for (std::size_t i = 0; i < n; ++i) v[i] = vy(i);
      break;
    case ColorBy::extra:
      for (std::size_t i = 0; i < n && i < p.value_extra.size(); ++i) v[i] = p.value_extra[i];
      break;
    case ColorBy::uniform:
      break;
  }
  return v;
}

FrameData build_frame(const RenderParticles& p, const RenderWalls& walls,
                      const RenderOverlays& overlays, const FrameSpec& spec, const BoxExtent& box) {
  check_spec(spec, p);
  const Colormap& map = colormap(spec.colormap);
  FrameData f;
  f.width = spec.width;
  f.height = spec.height;
  f.msaa = std::max(1, spec.msaa);
  f.background = spec.background;
  f.outline_color = spec.outline_color;
  f.colormap = map.name;

  // page layout: the colour-bar panel on the right, the world view in the rest
  detail::PageLayout page;
  page.font = static_cast<float>(
      spec.font_px > 0.0 ? spec.font_px : std::max(10.0, std::round(spec.height / 40.0)));
  page.colorbar = spec.colorbar && spec.color_by != ColorBy::uniform;
  const float panel = page.colorbar ? std::min(6.5f * page.font, 0.35f * spec.width) : 0.0f;
  page.plot_x0 = 0;
  page.plot_y0 = 0;
  page.plot_x1 = static_cast<float>(spec.width) - panel;
  page.plot_y1 = static_cast<float>(spec.height);
  f.camera = fit_camera(spec, walls, box, page);

  // header and gravity inset must not cover the box: if they would, fit the box below them
  // (not for an explicit camera region, which the user chose)
  if (!spec.camera.region) {
    double bx0 = box.x0, by0 = box.y0, bx1 = box.x1, by1 = box.y1;
    for (const auto& q : walls.rects)
      for (const auto& c : q) {
        bx0 = std::min(bx0, c.x), bx1 = std::max(bx1, c.x);
        by0 = std::min(by0, c.y), by1 = std::max(by1, c.y);
      }
    const Vec2 lo = f.camera.to_canvas({bx0, by0}), hi = f.camera.to_canvas({bx1, by1});
    float band = 0.0f;
    auto reserve = [&](const detail::Rect& r) {
      if (r[2] > r[0] && r[0] < hi.x && r[2] > lo.x && r[1] < hi.y && r[3] > lo.y)
        band = std::max(band, page.plot_y1 - r[1]);
    };
    reserve(detail::header_rect(detail::header_lines(overlays), page));
    if (overlays.show_gravity) reserve(detail::gravity_rect(page));
    if (band > 0.0f && band < 0.5f * spec.height) {
      detail::PageLayout fit = page;
      fit.plot_y1 -= band;
      f.camera = fit_camera(spec, walls, box, fit);
    }
  }

  // particles are clipped to the plot area, and to the box in periodic directions
  const Vec2 b0 = f.camera.to_canvas({box.x0, box.y0}), b1 = f.camera.to_canvas({box.x1, box.y1});
  f.view_clip = {page.plot_x0, page.plot_y0, page.plot_x1, page.plot_y1};
  f.particle_clip = f.view_clip;
  if (box.periodic_x) {
    f.particle_clip[0] = std::max(f.particle_clip[0], static_cast<float>(b0.x));
    f.particle_clip[2] = std::min(f.particle_clip[2], static_cast<float>(b1.x));
  }
  if (box.periodic_y) {
    f.particle_clip[1] = std::max(f.particle_clip[1], static_cast<float>(b0.y));
    f.particle_clip[3] = std::min(f.particle_clip[3], static_cast<float>(b1.y));
  }

  // colour values and their range
  int n_species = 1;
  for (int s : p.species) n_species = std::max(n_species, s + 1);
  const std::vector<double> values = particle_values(p, spec.color_by);
  const auto [lo, hi] = value_range(spec, values, n_species);
  f.value_lo = lo;
  f.value_hi = hi;

  // one instance per particle (and per periodic image), polygons and disks apart
  std::vector<float> radii_px;
  radii_px.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int n = p.sides[i];
    if (n != 0 && n < 3)
      throw InputError("", "sides",
                       "particle " + std::to_string(i) + " has " + std::to_string(n) +
                           " sides (0 = disk, or 3 or more)");
    ShapeInstance s;
    s.radius = static_cast<float>(p.radius[i] * f.camera.scale);
    s.angle = static_cast<float>(p.theta.empty() ? 0.0 : p.theta[i]);
    s.sides = n > kMaxSides ? 0 : n;
    s.fill = spec.color_by == ColorBy::uniform ? spec.uniform_color
                                               : map.at((values[i] - lo) / (hi - lo));
    radii_px.push_back(s.radius);
    auto& dest = s.sides == 0 ? f.disks : f.polygons;
    for_each_image(box, p.x[i], p.y[i], p.radius[i], [&](double x, double y) {
      const Vec2 c = f.camera.to_canvas({x, y});
      s.cx = static_cast<float>(c.x);
      s.cy = static_cast<float>(c.y);
      dest.push_back(s);
    });
  }

  // outline width: thin on small particles, none when they are only a few pixels wide
  float r_typ = 0.0f;
  if (!radii_px.empty()) {
    std::nth_element(radii_px.begin(), radii_px.begin() + radii_px.size() / 2, radii_px.end());
    r_typ = radii_px[radii_px.size() / 2];
  }
  f.outline_px = spec.outline_px >= 0.0
                     ? static_cast<float>(spec.outline_px)
                     : (r_typ < 2.5f ? 0.0f : std::clamp(0.08f * r_typ, 0.5f, 1.5f));

  // walls as two triangles each
  detail::Painter wall_paint{f.walls};
  for (const auto& q : walls.rects) {
    Vec2 c[4];
    for (int k = 0; k < 4; ++k) c[k] = f.camera.to_canvas(q[k]);
    wall_paint.quad(c[0], c[1], c[2], c[3], spec.wall_color);
  }

  // overlays, then the colour bar
  detail::add_overlays(f, overlays, spec, page, r_typ);
  if (page.colorbar) detail::add_colorbar(f, spec, page, lo, hi, n_species);
  return f;
}

}  // namespace gs
