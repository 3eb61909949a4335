// World → RenderParticles / RenderWalls / RenderOverlays / BoxExtent, and the per-particle
// contact quantities (coordination, pressure, force chains) the colouring can show
#include "view/render_world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "broadphase/broadphase.hpp"
#include "drive/schedule.hpp"

namespace gs {

RenderParticles world_particles(const World& w) {
  const std::size_t n = w.size();
  RenderParticles p;
  p.x = w.s.x;
  p.y = w.s.y;
  p.theta = w.s.th;
  p.vx = w.s.vx;
  p.vy = w.s.vy;
  p.radius.resize(n);
  p.sides.resize(n);
  p.species.resize(n);
  // shape from the species: regular n-gon (vertex 0 at θ, as World::shape) or disk
  for (std::size_t i = 0; i < n; ++i) {
    const Species& k = w.species[w.sp[i]];
    p.radius[i] = w.radius[i];
    p.sides[i] = k.shape == ShapeKind::Polygon ? k.sides : 0;
    p.species[i] = w.sp[i];
  }
  return p;
}

RenderWalls world_walls(const World& w) {
  RenderWalls out;
  for (const Wall& wall : w.walls) {
    // walls are rectangles; any other polygon is drawn by its bounding box
    std::array<Vec2, 4> q;
    if (wall.poly.n == 4) {
      for (int k = 0; k < 4; ++k) q[k] = wall.poly[k];
    } else {
      q = {Vec2{wall.lo.x, wall.lo.y}, Vec2{wall.hi.x, wall.lo.y}, Vec2{wall.hi.x, wall.hi.y},
           Vec2{wall.lo.x, wall.hi.y}};
    }
    out.rects.push_back(q);
  }
  return out;
}

BoxExtent world_box(const World& w) {
  BoxExtent b;
  b.x1 = w.Lx;
  b.y1 = w.Ly;
  if (w.box == BoxKind::Periodic) {
    b.periodic_x = b.periodic_y = true;
  } else if (w.box == BoxKind::Ring1D) {
    // the line: a strip around the particles, a few radii high
    b.periodic_x = true;
    double lo = 0.0, hi = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      lo = std::min(lo, w.s.y[i]);
      hi = std::max(hi, w.s.y[i]);
    }
    b.y0 = lo - 3.0 * w.max_radius;
    b.y1 = hi + 3.0 * w.max_radius;
  }
  return b;
}

namespace {

// each touching contact with its two ends: i, j (j >= N for a wall), the force on j
template <class F>
void for_each_contact(const World& w, const ContactSet& c, F&& f) {
  const std::size_t n = w.size();
  for (const ContactRecord& r : c.records) {
    const std::size_t i = key_i(r.key), j = key_j(r.key);
    if (i >= n) continue;
    const Vec2 force = r.n * r.fn + perp(r.n) * r.ft;  // on j, N
    f(i, j, j >= n, r, force);
  }
}

}  // namespace

std::vector<double> contact_counts(const World& w, const ContactSet& c) {
  std::vector<double> z(w.size(), 0.0);
  for_each_contact(w, c, [&](std::size_t i, std::size_t j, bool wall, const ContactRecord&, Vec2) {
    z[i] += 1.0;
    if (!wall) z[j] += 1.0;
  });
  return z;
}

std::vector<double> contact_pressure(const World& w, const ContactSet& c) {
  std::vector<double> p(w.size(), 0.0);
  for_each_contact(w, c,
                   [&](std::size_t i, std::size_t j, bool wall, const ContactRecord& r, Vec2 f) {
                     // −½ tr Σ (s − x) ⊗ f: on i the force is −f, on j it is +f (j's centre in i's
                     // frame)
                     const Vec2 xi{w.s.x[i], w.s.y[i]};
                     p[i] += dot(r.s - xi, f);
                     if (!wall) p[j] -= dot(r.s - (xi + w.separation(i, j)), f);
                   });
  for (std::size_t i = 0; i < p.size(); ++i) p[i] /= 2.0 * w.species[w.sp[i]].area;
  return p;
}

std::vector<ContactLine> force_chain_lines(const World& w, const ContactSet& c) {
  std::vector<ContactLine> out;
  out.reserve(c.records.size());
  for_each_contact(w, c,
                   [&](std::size_t i, std::size_t j, bool wall, const ContactRecord& r, Vec2) {
                     const Vec2 xi{w.s.x[i], w.s.y[i]};
                     out.push_back({xi, wall ? r.s : xi + w.separation(i, j), std::abs(r.fn)});
                   });
  return out;
}

FrameSpec frame_spec(const RenderSpec& r) {
  FrameSpec f;
  f.width = r.width;
  f.height = r.height;
  f.msaa = r.msaa;
  f.colormap = r.colormap;
  f.colorbar = r.colorbar;
  f.camera.margin = r.margin;
  f.camera.region = r.region;
  if (r.range) f.range = std::pair{(*r.range)[0], (*r.range)[1]};
  // contact quantities travel as the builder's "extra" value
  if (r.color_by == "contacts") {
    f.color_by = ColorBy::extra;
    f.extra_label = "contacts";
  } else if (r.color_by == "pressure") {
    f.color_by = ColorBy::extra;
    f.extra_label = "p";
    f.extra_unit = "N/m";
  } else {
    f.color_by = parse_color_by(r.color_by);
  }
  return f;
}

bool needs_contacts(const RenderSpec& r) {
  return r.force_chains || r.color_by == "contacts" || r.color_by == "pressure";
}

ViewSettings ViewSettings::from(const SceneSpec& scene) {
  const double* t = scene.output.test_rect;
  return {scene.drive, {t[0], t[1], t[2], t[3]}};
}

FrameInfo frame_info(const World& w, const ViewSettings& view, Vec2 gravity) {
  FrameInfo info;
  info.time = w.s.t;
  info.gravity = gravity;
  info.test_rect = view.test_rect;
  const DriveSpec& d = view.drive;
  if (is_tapping(d)) {
    const DrivePhase ph = drive_phase(d, w.clock_origin, w.s.t);
    info.settling = ph.settling;
    info.exciting = ph.exciting;
    if (!ph.settling) info.tap = ph.tap + 1;
    char buf[96];
    if (info.settling)
      std::snprintf(buf, sizeof buf, "settling");
    else if (info.exciting && d.kind == DriveKind::NegativeG)
      std::snprintf(buf, sizeof buf, "pulse: g_p = %g for %g s", d.g_p, d.t1);
    else if (info.exciting)
      std::snprintf(buf, sizeof buf, "rotating: f = %g Hz", d.f);
    else
      std::snprintf(buf, sizeof buf, "relaxing");
    info.protocol = buf;
  }
  return info;
}

WorldFrame world_frame(const World& w, const ContactSet* contacts, const FrameInfo& info,
                       const RenderSpec& r) {
  if (needs_contacts(r) && !contacts)
    throw std::invalid_argument("world_frame: this [render] needs the contacts");
  WorldFrame f;
  f.particles = world_particles(w);
  f.walls = world_walls(w);
  f.box = world_box(w);
  f.spec = frame_spec(r);
  if (r.color_by == "contacts") f.particles.value_extra = contact_counts(w, *contacts);
  if (r.color_by == "pressure") f.particles.value_extra = contact_pressure(w, *contacts);

  // overlays: title, clock and tap, protocol phase, gravity, test rectangle, chains
  RenderOverlays& ov = f.overlays;
  ov.title = r.title;
  ov.time = info.time;
  ov.show_time = r.clock;
  // strong slow motion: the time in ms (the header's "t = 0.005 s" would barely move), and
  // the factor
  if (r.clock && r.schedule == RenderSchedule::Time && r.slowmo >= 20.0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "t = %.3f ms    slow motion %g×", 1e3 * info.time, r.slowmo);
    ov.show_time = false;
    ov.lines.push_back(buf);
  }
  if (r.clock && info.tap) {
    ov.has_tap = true;
    ov.tap = static_cast<int>(*info.tap);
  }
  if (r.clock && !info.protocol.empty()) ov.lines.push_back(info.protocol);
  ov.gravity = info.gravity;
  ov.show_gravity = r.gravity_arrow;
  if (r.test_rect && info.test_rect) ov.test_rect = info.test_rect;
  if (r.force_chains) ov.force_chains = force_chain_lines(w, *contacts);
  return f;
}

}  // namespace gs
