#include "force/laws/polygon_pair.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gs {
namespace {

// pair parameters: the mean of the two materials' values (identical materials: exact)
law::PolyLawParams poly_params(const MaterialSpec& a, const MaterialSpec& b) {
  return {0.5 * (a.E + b.E), 0.5 * (a.gamma + b.gamma), 0.5 * (a.mu + b.mu)};
}

}  // namespace

PolygonPairEvaluator::PolygonPairEvaluator(const World& w, const ContactSettings& settings)
    : nsp_(w.species.size()),
      hdot_fd_(settings.hdot_finite_difference),
      rocking_(settings.rocking_damping),
      placed_(w) {
  // the pair constants stand for every grain of a species: check that they may
  for (std::size_t i = 0; i < (w.polygons() ? w.size() : 0); ++i) {
    const Species& k = w.species[w.sp[i]];
    if (w.radius[i] != k.radius || w.mass[i] != k.mass || w.inv_mass[i] != 1.0 / k.mass ||
        w.inv_inertia[i] != (k.inertia > 0 ? 1.0 / k.inertia : 0.0))
      throw std::logic_error("ContactModel: grain " + std::to_string(i) +
                             " has a radius, mass or inertia other than its species'");
  }
  params_.resize(nsp_ * (nsp_ + 1));
  const_.resize(params_.size());
  for (std::size_t a = 0; a < nsp_; ++a) {
    for (std::size_t b = 0; b <= nsp_; ++b) {
      const Species& si = w.species[a];
      const bool wall = b == nsp_;
      const MaterialSpec& mb = w.materials[wall ? w.wall_material : w.species[b].material];
      const std::size_t k = pair_index(nsp_, a, b);
      params_[k] = poly_params(w.materials[si.material], mb);
      const_[k] = pair_const(w, a, b, params_[k]);
    }
  }
}

// the mass and size constants of species a against species b (b = nsp: a wall), by the
// expressions the per-grain values (World::add_particle) would give
PolygonPairEvaluator::PairConst PolygonPairEvaluator::pair_const(
    const World& w, std::size_t a, std::size_t b, const law::PolyLawParams& p) const {
  const bool wall = b == nsp_;
  const Species& si = w.species[a];
  const double ri = si.radius;
  const double inv_ii = si.inertia > 0 ? 1.0 / si.inertia : 0.0;
  PairConst c;
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

double PolygonPairEvaluator::contact_time(const World& w, std::size_t a, std::size_t b) const {
  const bool wall = b == nsp_;
  const Species& si = w.species[a];
  const double mi = si.mass, mj = wall ? 0.0 : w.species[b].mass;
  const double m12 = wall ? mi : mi * mj / (mi + mj);
  const double rj = wall ? si.radius : w.species[b].radius;
  const double l = wall ? si.radius : si.radius * rj / (si.radius + rj);
  const double side = 2.0 * std::min(si.radius, rj) * std::sin(M_PI / si.sides);
  return M_PI * std::sqrt(m12 * l / (params(a, b).E * side));
}

bool PolygonPairEvaluator::pair(const World& w, PairKey key, const ContactSet& cs,
                                std::size_t& hint, double dt, PairForce& pf, PairResult& pr) const {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  const std::uint32_t i = key_i(key), j = key_j(key);
  const bool wall = j >= N;
  const Vec2 xi{w.s.x[i], w.s.y[i]};
  const PolyRef pi = placed_.grain(i);
  const PlacedBody a{xi, 0.0, &pi, {}, nullptr};
  ContactGeom g;
  Vec2 xj;
  if (wall) {
    const PolyRef pw = placed_.wall(j - N);
    g = narrow<kShape, BodyKind::Wall>(a, PlacedBody{{}, 0.0, &pw, {}, &w.walls[j - N]});
  } else {
    xj = image_pos(w, j, key_image(key));
    const PolyRef pj = placed_.grain(j);
    // a periodic image: the shift from j's polygon to the image (else none)
    const Vec2 shift = key_image(key) == kNoImage ? Vec2{} : xj - Vec2{w.s.x[j], w.s.y[j]};
    g = narrow<kShape, kShape>(a, PlacedBody{xj, 0.0, &pj, shift, nullptr});
  }
  if (!g.touching) return false;

  // the contact's history, if it touched last step: last step's keys are searched forward
  // from the previous hit of this thread (candidates ascend), else by bisection
  ContactState state = cs.history(key, hint);

  // geometry of the pair (P.29–P.33): l, m⊥, m∥
  const std::size_t pk = pair_index(nsp_, w.sp[i], wall ? nsp_ : w.sp[j]);
  const law::PolyLawParams& p = params_[pk];
  const PairConst& pc = const_[pk];
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

}  // namespace gs
