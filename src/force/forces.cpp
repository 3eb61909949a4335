#include "force/forces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contact/narrow.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

namespace gs {
namespace {

// pair parameters: the mean of the two materials' values (identical materials: exact)
law::PolyLawParams poly_params(const MaterialSpec& a, const MaterialSpec& b) {
  return {0.5 * (a.E + b.E), 0.5 * (a.gamma + b.gamma), 0.5 * (a.mu + b.mu)};
}

// position of j's periodic image as seen from i
Vec2 image_pos(const World& w, std::uint32_t j, std::uint32_t image) {
  return {w.s.x[j] + image_sx(image) * w.Lx, w.s.y[j] + image_sy(image) * w.Ly};
}

}  // namespace

ContactSettings contact_settings(const SceneSpec& scene) {
  return {scene.model.hdot_finite_difference, scene.model.rocking_damping,
          scene.model.clip_attractive};
}

ContactModel::ContactModel(const World& w, const ContactSettings& settings)
    : nsp_(w.species.size()) {
  const std::size_t stride = nsp_ + 1;
  poly_.resize(nsp_ * stride);
  poly_pc_.resize(nsp_ * stride);
  disk_.resize(nsp_ * stride);
  // Model P's pair constants stand for every grain of a species: check that they may
  for (std::size_t i = 0; i < (w.polygons() ? w.size() : 0); ++i) {
    const Species& k = w.species[w.sp[i]];
    if (w.radius[i] != k.radius || w.mass[i] != k.mass || w.inv_mass[i] != 1.0 / k.mass ||
        w.inv_inertia[i] != (k.inertia > 0 ? 1.0 / k.inertia : 0.0))
      throw std::logic_error("ContactModel: grain " + std::to_string(i) +
                             " has a radius, mass or inertia other than its species'");
  }
  hdot_fd_ = settings.hdot_finite_difference;
  rocking_ = settings.rocking_damping;
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
      poly_pc_[a * stride + b] = poly_pair_const(w, a, b, poly_[a * stride + b]);
      // Model S: dashpots from the target restitutions (T.2.6, T.2.12)
      law::DiskLawParams d;
      d.ks = 0.5 * (ma.ks + mb.ks);
      const double en = 0.5 * (ma.eps_n + mb.eps_n), et = 0.5 * (ma.eps_t + mb.eps_t);
      d.gn = en < 1.0 ? law::gamma_normal(en, m12, d.ks) : 0.0;
      d.gt = et < 1.0 ? law::gamma_tangential(et, m12, d.ks) : 0.0;
      d.mu = 0.5 * (ma.mu + mb.mu);
      d.clip = settings.clip_attractive;
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
  for (const Species& sp : w.species) {
    max_sides_ = std::max(max_sides_, sp.body.n);
    extent_.push_back(body_extent(sp.body));
  }
}

// the mass and size constants of Model P for species a against species b (b = nsp: a wall),
// by the expressions the per-grain values (World::add_particle) would give
ContactModel::PolyPairConst ContactModel::poly_pair_const(const World& w, std::size_t a,
                                                          std::size_t b,
                                                          const law::PolyLawParams& p) const {
  const bool wall = b == nsp_;
  const Species& si = w.species[a];
  const double ri = si.radius;
  const double inv_ii = si.inertia > 0 ? 1.0 / si.inertia : 0.0;
  PolyPairConst c;
  double inv_m_par = 1.0 / si.mass + ri * ri * inv_ii;
  if (wall) {
    c.l = ri;
    c.m_perp = si.mass;
  } else {
    const Species& sj = w.species[b];
    const double rj = sj.radius;
    const double inv_ij = sj.inertia > 0 ? 1.0 / sj.inertia : 0.0;
    c.l = ri * rj / (ri + rj);
    c.m_perp = si.mass * sj.mass / (si.mass + sj.mass);
    inv_m_par += 1.0 / sj.mass + rj * rj * inv_ij;
  }
  c.m_par = 1.0 / inv_m_par;
  c.damp_n = p.gamma * std::sqrt(p.E * c.m_perp);
  c.damp_t = std::sqrt((2.0 / 7.0) * p.E * c.m_par);
  return c;
}

// Model P (docs/physics.md §2.2): overlap-area normal force with Cundall–Strack friction
bool ContactModel::polygon_pair(const World& w, PairKey key, const ContactSet& cs,
                                std::size_t& hint, double dt, PairForce& pf, PairResult& pr) const {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  const std::size_t stride = nsp_ + 1;
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
  if (!g.touching) return false;

  // the contact's history, if it touched last step: last step's keys are searched forward
  // from the previous hit of this thread (candidates ascend), else by bisection
  ContactState state = cs.history(key, hint);

  // geometry of the pair (P.29–P.33): l, m⊥, m∥
  const std::size_t pk = w.sp[i] * stride + (wall ? nsp_ : w.sp[j]);
  const law::PolyLawParams& p = poly_[pk];
  const PolyPairConst& pc = poly_pc_[pk];
  const double l = pc.l;

  // relative velocity of i against j at the contact point
  const Vec2 ri_s = g.s - xi;
  Vec2 vrel = Vec2{w.s.vx[i], w.s.vy[i]} + cross(w.s.omega[i], ri_s);
  if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]} + cross(w.s.omega[j], g.s - xj);
  const Vec2 t = perp(g.n);
  const double vn = dot(vrel, g.n), vt = dot(vrel, t);

  // normal force (P.34) with ḣ_eff analytic (chord × approach speed / l) or by difference
  const double h = g.overlap / l;
  const double hdot = hdot_fd_ ? (h - state.h_prev) / dt  // h_prev = 0 before first touch
                               : g.chord * vn / l;
  state.h_prev = h;
  const double fn = law::poly_normal_force_damped(p, h, hdot, pc.damp_n);
  // tangential force (P.35–P.36); the force on i opposes its sliding: −F∥·t
  const double ft = law::cundall_strack_damped(p, state.spring, vt, fn, pc.damp_t, dt);

  // the same dashpot spread along the contact line: its moment about s damps relative
  // rotation, ∫ x·(γ√(E m⊥)/l)·ω_rel·x dx = γ√(E m⊥)·L³/(12 l)·ω_rel (only while pressing)
  double couple = 0.0;
  if (rocking_ && fn > 0.0) {
    const double w_rel = w.s.omega[i] - (wall ? 0.0 : w.s.omega[j]);
    couple = pc.damp_n * g.chord * g.chord * g.chord / (12.0 * l) * w_rel;
  }
  // j gets +fn·n + ft·t, i the opposite; torques about each centre
  const Vec2 F = g.n * fn + perp(g.n) * ft;
  pf = {F.x, F.y, cross(g.s - xi, F) + couple, wall ? 0.0 : cross(g.s - xj, F) + couple};
  pr = {g.degenerate, g.s, g.n, fn, ft, g.overlap, h, state};
  return true;
}

// Model S (docs/physics.md §3): linear spring, normal and tangential dashpots, optional friction
[[gnu::always_inline]] inline bool ContactModel::disk_pair(const World& w, PairKey key,
                                                           PairForce& pf, PairResult& pr) const {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  const std::uint32_t i = key_i(key), j = key_j(key);
  const bool wall = j >= N;
  const Vec2 xi{w.s.x[i], w.s.y[i]};
  const BodyView bi{xi, w.radius[i], nullptr};
  const ContactGeom g =
      wall ? disk_wall(bi, w.walls[j - N])
           : disk_disk(bi, BodyView{image_pos(w, j, key_image(key)), w.radius[j], nullptr});
  if (!g.touching) return false;
  Vec2 vrel{w.s.vx[i], w.s.vy[i]};
  if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]};
  const Vec2 t = perp(g.n);
  const law::DiskLawParams& p = disk_[w.sp[i] * (nsp_ + 1) + (wall ? nsp_ : w.sp[j])];
  const law::DiskForce df = law::linear_spring_dashpot(p, g.overlap, dot(vrel, g.n), dot(vrel, t));
  const Vec2 F = g.n * df.fn + t * df.ft;
  pf = {F.x, F.y, 0.0, 0.0};
  pr.degenerate = false;
  pr.s = g.s;
  pr.n = g.n;
  pr.fn = df.fn;
  pr.ft = df.ft;
  pr.overlap = g.overlap;
  pr.h = g.overlap;
  return true;
}

// disk pairs cost a few ns: a parallel region of their own from kParallelMinCheap pairs. But
// where the particle loops run in parallel anyway (n ≥ kParallelMinCheap: the accelerations
// come in the same region), the pairs join it from kParallelMin, so that the first thread does
// not evaluate them alone while the team waits, reading the others' positions
std::size_t ContactModel::parallel_pairs_from(bool polygons, std::size_t n) {
  return polygons || n >= kParallelMinCheap ? kParallelMin : kParallelMinCheap;
}

// Below the thresholds a plain loop over the candidates sums each pair's force into its two
// particles as it goes. Above them: pairs in parallel into per-candidate slots → touching ones
// compacted into the contact set in fixed blocks → each particle's forces summed over its own
// pairs in candidate order, from zero. Each particle's terms are the same in the same order
// either way, so the forces are bitwise the same on any number of threads, serial or parallel.
ForceStats ContactModel::evaluate(const World& w, const std::vector<PairKey>& cand, ContactSet& cs,
                                  ForceBuffer& f, double dt, ThreadTeam& team,
                                  std::uint64_t generation, RangeFn after, StageClock* clock) {
  const std::size_t n = w.size();
  const std::size_t ncand = cand.size();
  const bool poly = w.polygons();
  if (ncand >= (std::size_t{1} << 31))
    throw std::length_error("ContactModel::evaluate: more than 2^31 candidate pairs");
  f.fx.resize(n);
  f.fy.resize(n);
  f.tq.resize(poly ? n : 0);
  ForceStats st;
  const bool placed = poly && placed_ahead_;  // by the last evaluate()'s `after`
  placed_ahead_ = false;
  if (!poly) find_common_radius(w, generation);
  if (run_parallel(ncand, parallel_pairs_from(poly, n))) {
    // disks of which few touched last step: each particle's sum from the few touching pairs
    // themselves, not from its candidates (sums_from_touching); else the per-particle index
    const bool from_touching = !poly && few_touched(cs, ncand);
    const bool reindex = !from_touching && (generation == 0 || generation != indexed_generation_ ||
                                            n != indexed_n_ || ncand != indexed_count_);
    st = evaluate_parallel(w, cand, cs, f, dt, team, reindex, from_touching, placed, after, clock);
    if (reindex) {
      indexed_generation_ = generation;
      indexed_n_ = n;
      indexed_count_ = ncand;
    }
  } else {
    if (poly) {
      place_walls(w);
      shapes_.resize(n, max_sides_);
      if (!placed) place_shapes(w, 0, n);
    }
    st = evaluate_serial(w, cand, cs, f, dt);
    if (clock) clock->lap(Stage::NarrowPhase);  // the serial loop sums each pair as it goes
    if (after) parallel_ranges(team, n, kParallelMinCheap, after);
  }
  cs.replace(next_);
  cs.degenerate += st.degenerate;
  st.contacts = cs.keys.size();
  st.candidates = ncand;
  return st;
}

// the walls' polygons (a handful; set every step, so that a scene may move its walls)
void ContactModel::place_walls(const World& w) {
  int wall_n = 0;
  for (const Wall& wl : w.walls) wall_n = std::max(wall_n, wl.poly.n);
  wall_shapes_.resize(w.walls.size(), wall_n);
  for (std::size_t k = 0; k < w.walls.size(); ++k) wall_shapes_.set(k, w.walls[k].poly);
}

// world-frame polygons [b, e) of this step, with their edges and bounding circles (the store
// sized beforehand)
void ContactModel::place_shapes(const World& w, std::size_t b, std::size_t e) {
  for (std::size_t i = b; i < e; ++i) {
    const int k = w.sp[i];
    shapes_.set_placed(i, w.species[k].body, extent_[k], {w.s.x[i], w.s.y[i]}, w.s.th[i]);
  }
}

// the contact's statistics: h_eff (or δ) and the same over the smaller grain's radius
// (one_radius: disks of one radius, whose max_overlap_rel finish_overlaps makes at the end)
static void note_overlap(ForceStats& st, const World& w, PairKey key, double h, bool degenerate,
                         bool one_radius) {
  const std::uint32_t i = key_i(key), j = key_j(key);
  st.degenerate += degenerate;
  st.max_overlap = std::max(st.max_overlap, h);
  if (one_radius) return;
  const double ri = w.radius[i];
  st.max_overlap_rel =
      std::max(st.max_overlap_rel, h / (j >= w.size() ? ri : std::min(ri, w.radius[j])));
}

ForceStats ContactModel::evaluate_serial(const World& w, const std::vector<PairKey>& cand,
                                         const ContactSet& cs, ForceBuffer& f, double dt) {
  const bool poly = w.polygons();
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  clear_forces(f, N);
  next_.keys.clear();
  next_.state.clear();
  next_.records.clear();
  ForceStats st;
  PairForce pf;
  PairResult r;
  const bool one_radius = one_radius_disks(poly);
  // one loop per model, so that the disk loop is free of polygon branches; `at(q)`: the q-th
  // candidate the loop visits
  auto run = [&](std::size_t count, auto&& at, auto&& pair) {
    for (std::size_t q = 0; q < count; ++q) {
      const PairKey key = at(q);
      if (!pair(key)) continue;
      const std::uint32_t i = key_i(key), j = key_j(key);
      f.fx[i] -= pf.fx;
      f.fy[i] -= pf.fy;
      if (poly) f.tq[i] -= pf.ti;
      if (j < N) {
        f.fx[j] += pf.fx;
        f.fy[j] += pf.fy;
        if (poly) f.tq[j] += pf.tj;
      }
      next_.keys.push_back(key);
      next_.records.push_back({key, r.s, r.n, r.fn, r.ft, r.overlap});
      if (poly) next_.state.push_back(r.state);
      note_overlap(st, w, key, r.h, r.degenerate, one_radius);
    }
  };
  std::size_t hint = 0;
  if (poly) {
    run(
        cand.size(), [&](std::size_t q) { return cand[q]; },
        [&](PairKey key) { return polygon_pair(w, key, cs, hint, dt, pf, r); });
  } else {
    // disks: where few candidates touched last step (a gas, the 1D ring: 6 %), a branch-free
    // pass first keeps the disk pairs that touch (disk_disk's own test) and every wall pair,
    // so that the loop no longer mispredicts at each contact; in a packing, where almost all
    // touch, that pass would only add work. Either way the same pairs are evaluated.
    // Block by block: the selected pairs are evaluated while the lines the selection read
    // are still in the cache
    if (few_touched(cs, cand.size())) {
      constexpr std::size_t kSelectBlock = 1024;
      for (std::size_t k0 = 0; k0 < cand.size(); k0 += kSelectBlock) {
        const std::size_t k1 = std::min(cand.size(), k0 + kSelectBlock);
        const std::size_t m = select_disk_pairs(w, cand, k0, k1);
        prefetch_disk_pairs(w, cand, m, f);
        run(
            m, [&](std::size_t q) { return cand[sel_[q]]; },
            [&](PairKey key) { return disk_pair(w, key, pf, r); });
      }
    } else {
      run(
          cand.size(), [&](std::size_t q) { return cand[q]; },
          [&](PairKey key) { return disk_pair(w, key, pf, r); });
    }
  }
  finish_overlaps(st, one_radius);
  note_touched(f, N);
  return st;
}

// zero the force buffer before the serial sum: only the entries the last serial evaluation
// wrote, where it recorded them (few touching pairs) and the buffer is still the same size
// and otherwise untouched; else every entry. Either way every entry is +0.0 afterwards.
void ContactModel::clear_forces(ForceBuffer& f, std::size_t n) {
  if (f.sparse && f.sparse_n == n && f.fx.size() == n && f.fy.size() == n) {
    const bool tq = f.tq.size() == n;
    for (std::uint32_t p : f.touched) {
      f.fx[p] = 0.0;
      f.fy[p] = 0.0;
      if (tq) f.tq[p] = 0.0;
    }
    if (tq || f.tq.empty()) return;
  }
  std::fill(f.fx.begin(), f.fx.end(), 0.0);
  std::fill(f.fy.begin(), f.fy.end(), 0.0);
  std::fill(f.tq.begin(), f.tq.end(), 0.0);
}

// after a serial sum: where at most 1/8 of the particles can hold a non-zero entry (a random
// write costs about a cache line, eight sequential zeros), remember them for clear_forces
void ContactModel::note_touched(ForceBuffer& f, std::size_t n) {
  f.touched.clear();
  f.sparse = 2 * next_.keys.size() <= n / 8;
  f.sparse_n = n;
  if (!f.sparse) return;
  for (PairKey key : next_.keys) {
    f.touched.push_back(key_i(key));
    if (key_j(key) < n) f.touched.push_back(key_j(key));
  }
}

ForceStats ContactModel::evaluate_parallel(const World& w, const std::vector<PairKey>& cand,
                                           const ContactSet& cs, ForceBuffer& f, double dt,
                                           ThreadTeam& team, bool reindex, bool from_touching,
                                           bool placed, RangeFn after, StageClock* clock) {
  const std::size_t n = w.size();
  const std::size_t ncand = cand.size();
  const bool poly = w.polygons();
  const bool one_radius = one_radius_disks(poly);
  if (reindex) index_candidates(cand, n);
  f.sparse = false;  // every entry is written below
  touch_.resize(ncand);
  pair_f_.resize(ncand);
  pair_r_.resize(ncand);
  // one parallel region: polygons placed → every candidate pair, chunk by chunk (a chunk's
  // history search resumes where its last one ended), each chunk counting its touching pairs
  // → the chunks' first slots (a prefix sum) → each chunk's touching pairs compacted into the
  // contact set, in candidate order whatever the chunking → each particle's forces, its pairs
  // in candidate order, from zero
  const std::size_t chunk = poly ? 16 : 512;
  const std::size_t nchunks = (ncand + chunk - 1) / chunk;
  chunk_first_.resize(nchunks);
  chunk_stats_.assign(nchunks, {});
  PassSchedule& schedule = team.pass();
  schedule.plan(nchunks, poly && !placed ? n : 0);
  if (poly) {
    place_walls(w);
    shapes_.resize(n, max_sides_);
  }
#pragma omp parallel
  {
    const int tid = team_thread(), nt = team_size();
    const auto [p_begin, p_end] = team.particles(n, tid, nt);
    if (poly && !placed) {
      schedule.place(tid, nt, [&](std::size_t b, std::size_t e) { place_shapes(w, b, e); });
#pragma omp barrier
    }
    // the time this thread spends on its own particles (summing, the callback): the next
    // step's particles are split by it
    double t_particles = 0.0;
    auto run_chunk = [&](std::size_t c) {
      const std::size_t k0 = c * chunk, k1 = std::min(ncand, k0 + chunk);
      std::size_t hint = 0, touching = 0;
      for (std::size_t k = k0; k < k1; ++k) {
        const bool t = poly ? polygon_pair(w, cand[k], cs, hint, dt, pair_f_[k], pair_r_[k])
                            : disk_pair(w, cand[k], pair_f_[k], pair_r_[k]);
        touch_[k] = t;
        touching += t;
      }
      chunk_first_[c] = touching;
    };
    schedule.run_chunks(tid, nt, run_chunk);
#pragma omp barrier
#pragma omp single
    {
      std::size_t total = 0;
      for (std::size_t& first : chunk_first_) {
        const std::size_t c = first;
        first = total;
        total += c;
      }
      next_.keys.resize(total);
      next_.records.resize(total);
      next_.state.resize(poly ? total : 0);
      touching_k_.resize(from_touching ? total : 0);
    }
    // the compaction over the same chunks as the pair loop's own ranges
    const ItemRange own_chunks = schedule.chunk_range(tid, nt);
    for (std::size_t c = own_chunks.begin; c < own_chunks.end; ++c) {
      std::size_t out = chunk_first_[c];
      const std::size_t k0 = c * chunk, k1 = std::min(ncand, k0 + chunk);
      for (std::size_t k = k0; k < k1; ++k) {
        if (!touch_[k]) continue;
        const PairKey key = cand[k];
        const PairResult& r = pair_r_[k];
        next_.keys[out] = key;
        if (from_touching) touching_k_[out] = static_cast<std::uint32_t>(k);
        next_.records[out] = {key, r.s, r.n, r.fn, r.ft, r.overlap};
        if (poly) next_.state[out] = r.state;
        ++out;
        note_overlap(chunk_stats_[c], w, key, r.h, r.degenerate, one_radius);
      }
    }
    if (from_touching) {  // the sums read every thread's compacted pairs
#pragma omp barrier
    }
    if (clock && tid == 0) clock->lap(Stage::NarrowPhase);
    const double tp1 = wall_seconds();  // (the barrier's wait is no particle's work)
    if (from_touching) {
      sums_from_touching(w, f, p_begin, p_end);
    } else {
      for (std::size_t p = p_begin; p < p_end; ++p) {
        double fx = 0.0, fy = 0.0, tq = 0.0;
        for (std::uint32_t e = cand_start_[p]; e < cand_start_[p + 1]; ++e) {
          const std::uint32_t k = cand_entry_[e] >> 1;
          if (!touch_[k]) continue;
          const PairForce& r = pair_f_[k];
          if (cand_entry_[e] & 1u) {
            fx += r.fx;
            fy += r.fy;
            tq += r.tj;
          } else {
            fx -= r.fx;
            fy -= r.fy;
            tq -= r.ti;
          }
        }
        f.fx[p] = fx;
        f.fy[p] = fy;
        if (poly) f.tq[p] = tq;
      }
    }
    if (clock && tid == 0) clock->lap(Stage::Laws);
    if (after) after(p_begin, p_end);
    t_particles += wall_seconds() - tp1;
    schedule.record_particles(tid, nt, p_end - p_begin, t_particles);
  }  // omp parallel
  team.update();
  ForceStats st;  // maxima and counts: the same whatever the chunking
  for (const ForceStats& b : chunk_stats_) {
    st.degenerate += b.degenerate;
    st.max_overlap = std::max(st.max_overlap, b.max_overlap);
    st.max_overlap_rel = std::max(st.max_overlap_rel, b.max_overlap_rel);
  }
  finish_overlaps(st, one_radius);
  return st;
}

// counting sort of the candidates' (k, side) entries by particle: ascending k per particle
void ContactModel::index_candidates(const std::vector<PairKey>& cand, std::size_t n) {
  const std::uint32_t N = static_cast<std::uint32_t>(n);
  cand_start_.assign(n + 1, 0);
  for (PairKey key : cand) {
    ++cand_start_[key_i(key) + 1];
    if (key_j(key) < N) ++cand_start_[key_j(key) + 1];
  }
  for (std::size_t p = 0; p < n; ++p) cand_start_[p + 1] += cand_start_[p];
  cand_entry_.resize(cand_start_[n]);
  fill_.assign(cand_start_.begin(), cand_start_.end() - 1);
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const auto e = static_cast<std::uint32_t>(k << 1);
    cand_entry_[fill_[key_i(cand[k])]++] = e;
    if (key_j(cand[k]) < N) cand_entry_[fill_[key_j(cand[k])]++] = e | 1u;
  }
}

}  // namespace gs
