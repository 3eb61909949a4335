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

}  // namespace gs
