#include "force/forces.hpp"

#include <algorithm>
#include <cmath>

#include "contact/narrow.hpp"

namespace gs {
namespace {

// pair parameters: the mean of the two materials' values (identical materials: exact)
law::PolyLawParams poly_params(const MaterialSpec& a, const MaterialSpec& b) {
  return {0.5 * (a.E + b.E), 0.5 * (a.gamma + b.gamma), 0.5 * (a.mu + b.mu)};
}

// below this many items a parallel region costs more than it saves (and on a busy machine
// far more: waiting threads lose their time slices)
constexpr std::size_t kParallelMin = 1000;

// position of j's periodic image as seen from i
Vec2 image_pos(const World& w, std::uint32_t j, std::uint32_t image) {
  return {w.s.x[j] + image_sx(image) * w.Lx, w.s.y[j] + image_sy(image) * w.Ly};
}

// the first index of ascending `keys` not below `key` (std::lower_bound), found by a short
// forward scan from `hint` when the hint lies at or just before it
std::size_t history_index(const std::vector<PairKey>& keys, PairKey key, std::size_t hint) {
  const std::size_t n = keys.size();
  if (hint <= n && (hint == 0 || keys[hint - 1] < key)) {
    for (int step = 0; step < 4; ++step, ++hint)
      if (hint == n || !(keys[hint] < key)) return hint;
    return static_cast<std::size_t>(std::lower_bound(keys.begin() + hint, keys.end(), key) -
                                    keys.begin());
  }
  return static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), key) -
                                  keys.begin());
}

}  // namespace

ContactModel::ContactModel(const World& w) : nsp_(w.species.size()) {
  const std::size_t stride = nsp_ + 1;
  poly_.resize(nsp_ * stride);
  disk_.resize(nsp_ * stride);
  hdot_fd_ = w.scene.model.hdot_finite_difference;
  rocking_ = w.scene.model.rocking_damping;
  min_contact_time_ = 1e300;
  for (std::size_t a = 0; a < nsp_; ++a) {
    for (std::size_t b = 0; b <= nsp_; ++b) {
      const bool wall = b == nsp_;
      const Species& si = w.species[a];
      const MaterialSpec& ma = w.materials[si.material];
      const MaterialSpec& mb = w.materials[wall ? w.wall_material : w.species[b].material];
      const double mi = si.mass, mj = wall ? 0.0 : w.species[b].mass;
      const double m12 = wall ? mi : mi * mj / (mi + mj);
      poly_[a * stride + b] = poly_params(ma, mb);
      // Model S: dashpots from the target restitutions (T.2.6, T.2.12)
      law::DiskLawParams d;
      d.ks = 0.5 * (ma.ks + mb.ks);
      const double en = 0.5 * (ma.eps_n + mb.eps_n), et = 0.5 * (ma.eps_t + mb.eps_t);
      d.gn = en < 1.0 ? law::gamma_normal(en, m12, d.ks) : 0.0;
      d.gt = et < 1.0 ? law::gamma_tangential(et, m12, d.ks) : 0.0;
      d.mu = 0.5 * (ma.mu + mb.mu);
      d.clip = w.scene.model.clip_attractive;
      disk_[a * stride + b] = d;
      // stiffest contact: Model S exact; Model P linearised for flat faces, k ≈ E·side/l
      double tc;
      if (si.shape == ShapeKind::Disk) {
        tc = law::contact_time(d.ks, m12, d.gn);
      } else {
        const double rj = wall ? si.radius : w.species[b].radius;
        const double l = wall ? si.radius : si.radius * rj / (si.radius + rj);
        const double side = 2.0 * std::min(si.radius, rj) * std::sin(M_PI / si.sides);
        tc = M_PI * std::sqrt(m12 * l / (poly_[a * stride + b].E * side));
      }
      min_contact_time_ = std::min(min_contact_time_, tc);
    }
  }
  for (const Species& sp : w.species) max_sides_ = std::max(max_sides_, sp.body.n);
}

ForceStats ContactModel::evaluate(const World& w, const std::vector<PairKey>& cand,
                                  ContactSet& cs, ForceBuffer& f, double dt) {
  new_keys_.clear();
  new_state_.clear();
  new_records_.clear();
  ForceStats st = w.polygons() ? evaluate_polygons(w, cand, cs, f, dt)
                               : evaluate_disks(w, cand, cs, f);
  cs.keys.swap(new_keys_);
  cs.state.swap(new_state_);
  cs.records.swap(new_records_);
  cs.degenerate += st.degenerate;
  st.contacts = cs.keys.size();
  return st;
}

// Model P (SPEC 2.2): overlap-area normal force with Cundall–Strack friction. The pairs are
// evaluated in parallel into a per-candidate array; forces are then summed serially in key
// order, so the result is bitwise the same for any number of threads.
ForceStats ContactModel::evaluate_polygons(const World& w, const std::vector<PairKey>& cand,
                                           ContactSet& cs, ForceBuffer& f, double dt) {
  ForceStats st;
  const std::size_t n = w.size();
  const std::uint32_t N = static_cast<std::uint32_t>(n);
  const std::size_t stride = nsp_ + 1;
  const std::int64_t ncand = static_cast<std::int64_t>(cand.size());
  // world-frame polygons once per step, with their edges and bounding circles
  shapes_.resize(n, max_sides_);
  int wall_n = 0;
  for (const Wall& wl : w.walls) wall_n = std::max(wall_n, wl.poly.n);
  wall_shapes_.resize(w.walls.size(), wall_n);
  for (std::size_t k = 0; k < w.walls.size(); ++k) wall_shapes_.set(k, w.walls[k].poly);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i)
    shapes_.set_placed(i, w.species[w.sp[i]].body, {w.s.x[i], w.s.y[i]}, w.s.th[i]);
  pair_out_.resize(cand.size());

  const std::vector<PairKey>& old_keys = cs.keys;
#pragma omp parallel if (cand.size() >= kParallelMin)
  {
    std::size_t hint = 0;  // where this thread's last history search ended
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t k = 0; k < ncand; ++k) {
      const PairKey key = cand[k];
      PairResult& out = pair_out_[k];
      out.touching = false;
      const std::uint32_t i = key_i(key), j = key_j(key);
      const bool wall = j >= N;
      const Vec2 xi{w.s.x[i], w.s.y[i]};
      ContactGeom g;
      Vec2 xj;
      if (wall) {
        g = polygon_polygon(shapes_.ref(i), wall_shapes_.ref(j - N), w.walls[j - N].normal);
      } else {
        xj = image_pos(w, j, key_image(key));
        if (key_image(key) == kNoImage) {
          g = polygon_polygon(shapes_.ref(i), shapes_.ref(j), xj - xi);
        } else {  // a periodic image: shift a copy of j's polygon (general routine)
          const Poly pi = shapes_.poly(i);
          Poly pj = shapes_.poly(j);
          for (int v = 0; v < pj.n; ++v) pj.v[v] += xj - Vec2{w.s.x[j], w.s.y[j]};
          g = polygon_polygon(BodyView{xi, w.radius[i], &pi}, BodyView{xj, w.radius[j], &pj});
        }
      }
      if (!g.touching) continue;

      // the contact's history, if it touched last step: last step's keys are searched forward
      // from the previous hit of this thread (candidates ascend), else by bisection
      ContactState state;
      hint = history_index(old_keys, key, hint);
      if (hint < old_keys.size() && old_keys[hint] == key) state = cs.state[hint];

      // geometry of the pair (P.29–P.33): l, m⊥, m∥
      const std::size_t si = w.sp[i];
      const law::PolyLawParams& p = poly_[si * stride + (wall ? nsp_ : w.sp[j])];
      const double ri = w.radius[i];
      double l, m_perp, inv_m_par = w.inv_mass[i] + ri * ri * w.inv_inertia[i];
      if (wall) {
        l = ri;
        m_perp = w.mass[i];
      } else {
        const double rj = w.radius[j];
        l = ri * rj / (ri + rj);
        m_perp = w.mass[i] * w.mass[j] / (w.mass[i] + w.mass[j]);
        inv_m_par += w.inv_mass[j] + rj * rj * w.inv_inertia[j];
      }
      const double m_par = 1.0 / inv_m_par;

      // relative velocity of i against j at the contact point
      const Vec2 ri_s = g.s - xi;
      Vec2 vrel = Vec2{w.s.vx[i], w.s.vy[i]} + cross(w.s.w[i], ri_s);
      if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]} + cross(w.s.w[j], g.s - xj);
      const Vec2 t = perp(g.n);
      const double vn = dot(vrel, g.n), vt = dot(vrel, t);

      // normal force (P.34) with ḣ_eff analytic (chord × approach speed / l) or by difference
      const double h = g.overlap / l;
      const double hdot = hdot_fd_ ? (h - state.h_prev) / dt  // h_prev = 0 before first touch
                                   : g.chord * vn / l;
      state.h_prev = h;
      const double fn = law::poly_normal_force(p, h, hdot, m_perp);
      // tangential force (P.35–P.36); the force on i opposes its sliding: −F∥·t
      const double ft = law::cundall_strack(p, state.spring, vt, fn, m_par, dt);

      // the same dashpot spread along the contact line: its moment about s damps relative
      // rotation, ∫ x·(γ√(E m⊥)/l)·ω_rel·x dx = γ√(E m⊥)·L³/(12 l)·ω_rel (only while pressing)
      double couple = 0.0;
      if (rocking_ && fn > 0.0) {
        const double w_rel = w.s.w[i] - (wall ? 0.0 : w.s.w[j]);
        couple = p.gamma * std::sqrt(p.E * m_perp) * g.chord * g.chord * g.chord / (12.0 * l) *
                 w_rel;
      }
      out = {true, g.degenerate, g.s, g.n, xj, fn, ft, couple, g.overlap, h, state};
    }
  }  // omp parallel

  // accumulate in key order: j gets +fn·n + ft·t, i the opposite; torques about each centre
  for (std::int64_t k = 0; k < ncand; ++k) {
    const PairResult& r = pair_out_[k];
    if (!r.touching) continue;
    const PairKey key = cand[k];
    const std::uint32_t i = key_i(key), j = key_j(key);
    const bool wall = j >= N;
    const Vec2 F = r.n * r.fn + perp(r.n) * r.ft;
    const Vec2 xi{w.s.x[i], w.s.y[i]};
    f.fx[i] -= F.x;
    f.fy[i] -= F.y;
    f.tq[i] -= cross(r.s - xi, F) + r.couple;
    if (!wall) {
      f.fx[j] += F.x;
      f.fy[j] += F.y;
      f.tq[j] += cross(r.s - r.xj, F) + r.couple;
    }
    new_keys_.push_back(key);
    new_state_.push_back(r.state);
    new_records_.push_back({key, r.s, r.n, r.fn, r.ft, r.overlap});
    if (r.degenerate) ++st.degenerate;
    const double ri = w.radius[i];
    st.max_overlap = std::max(st.max_overlap, r.h);
    st.max_overlap_rel = std::max(st.max_overlap_rel, r.h / (wall ? ri : std::min(ri, w.radius[j])));
  }
  return st;
}

// Model S (SPEC 3): linear spring, normal and tangential dashpots, optional friction
ForceStats ContactModel::evaluate_disks(const World& w, const std::vector<PairKey>& cand,
                                        ContactSet&, ForceBuffer& f) {
  ForceStats st;
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  const std::size_t stride = nsp_ + 1;
  for (PairKey key : cand) {
    const std::uint32_t i = key_i(key), j = key_j(key);
    const bool wall = j >= N;
    const Vec2 xi{w.s.x[i], w.s.y[i]};
    const BodyView bi{xi, w.radius[i], nullptr};
    const ContactGeom g = wall ? disk_wall(bi, w.walls[j - N])
                               : disk_disk(bi, BodyView{image_pos(w, j, key_image(key)),
                                                        w.radius[j], nullptr});
    if (!g.touching) continue;
    Vec2 vrel{w.s.vx[i], w.s.vy[i]};
    if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]};
    const Vec2 t = perp(g.n);
    const law::DiskLawParams& p = disk_[w.sp[i] * stride + (wall ? nsp_ : w.sp[j])];
    const law::DiskForce df = law::linear_spring_dashpot(p, g.overlap, dot(vrel, g.n), dot(vrel, t));
    const Vec2 F = g.n * df.fn + t * df.ft;
    f.fx[i] -= F.x;
    f.fy[i] -= F.y;
    if (!wall) {
      f.fx[j] += F.x;
      f.fy[j] += F.y;
    }
    new_keys_.push_back(key);
    new_records_.push_back({key, g.s, g.n, df.fn, df.ft, g.overlap});
    st.max_overlap = std::max(st.max_overlap, g.overlap);
    st.max_overlap_rel = std::max(st.max_overlap_rel,
                                  g.overlap / (wall ? w.radius[i] : std::min(w.radius[i], w.radius[j])));
  }
  return st;
}

}  // namespace gs
