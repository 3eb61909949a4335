#include "force/laws/disk_pair.hpp"

#include <limits>
#include <type_traits>

namespace gs {

DiskPairEvaluator::DiskPairEvaluator(const World& w, const ContactSettings& settings)
    : nsp_(w.species.size()) {
  params_.resize(nsp_ * (nsp_ + 1));
  for (std::size_t a = 0; a < nsp_; ++a) {
    for (std::size_t b = 0; b <= nsp_; ++b) {
      const bool wall = b == nsp_;
      const Species& si = w.species[a];
      const MaterialSpec& ma = w.materials[si.material];
      const MaterialSpec& mb = w.materials[wall ? w.wall_material : w.species[b].material];
      const double mi = si.mass, mj = wall ? 0.0 : w.species[b].mass;
      const double m12 = wall ? mi : mi * mj / (mi + mj);
      // dashpots from the target restitutions (T.2.6, T.2.12)
      law::DiskLawParams d;
      d.ks = 0.5 * (ma.ks + mb.ks);
      const double en = 0.5 * (ma.eps_n + mb.eps_n), et = 0.5 * (ma.eps_t + mb.eps_t);
      d.gn = en < 1.0 ? law::gamma_normal(en, m12, d.ks) : 0.0;
      d.gt = et < 1.0 ? law::gamma_tangential(et, m12, d.ks) : 0.0;
      d.mu = 0.5 * (ma.mu + mb.mu);
      d.clip = settings.clip_attractive;
      params_[pair_index(nsp_, a, b)] = d;
    }
  }
}

double DiskPairEvaluator::contact_time(const World& w, std::size_t a, std::size_t b) const {
  const bool wall = b == nsp_;
  const double mi = w.species[a].mass, mj = wall ? 0.0 : w.species[b].mass;
  const double m12 = wall ? mi : mi * mj / (mi + mj);
  const law::DiskLawParams& d = params(a, b);
  return law::contact_time(d.ks, m12, d.gn);
}

void DiskPairEvaluator::find_common_radius(const World& w, std::uint64_t generation) {
  const std::size_t n = w.size();
  if (generation != 0 && generation == common_radius_generation_ && n == common_radius_n_) return;
  common_radius_generation_ = generation;  // an unknown list (0) is looked at every time
  common_radius_n_ = n;
  common_radius_ = n > 0 ? w.radius[0] : 0.0;
  for (std::size_t i = 1; i < n; ++i)
    if (w.radius[i] != common_radius_) {
      common_radius_ = std::numeric_limits<double>::quiet_NaN();
      break;
    }
}

// the same expressions as narrow<Disk, Disk>, so the same decisions, without its branch. Where
// every disk has the same radius r_i + r_j is that radius twice, the same bits without the loads
std::size_t DiskPairEvaluator::select(const World& w, const std::vector<PairKey>& cand,
                                      std::size_t k0, std::size_t k1,
                                      std::vector<std::uint32_t>& sel_out) const {
  const auto N = static_cast<std::uint32_t>(w.size());
  const double* x = w.s.x.data();
  const double* y = w.s.y.data();
  const double* r = w.radius.data();
  sel_out.resize(k1 - k0);
  std::uint32_t* sel = sel_out.data();
  std::size_t m = 0;
  const double rc = common_radius_;
  auto select = [&](auto common) {
    constexpr bool kCommon = decltype(common)::value;
    auto reach = [&](std::uint32_t i, std::uint32_t j) { return kCommon ? rc + rc : r[i] + r[j]; };
    if (w.box == BoxKind::Ring1D) {
      // the ring: no walls, every y is 0 and no image is shifted in y, so d.y is exactly 0
      // and d.x alone gives narrow<Disk, Disk>'s decision (norm2(d) = d.x² + 0 to the last bit)
      for (std::size_t k = k0; k < k1; ++k) {
        const PairKey key = cand[k];
        const std::uint32_t i = key_i(key), j = key_j(key);
        const double dx = x[j] + image_sx(key_image(key)) * w.Lx - x[i];
        const double dist2 = dx * dx, rr = reach(i, j);
        sel[m] = static_cast<std::uint32_t>(k);
        m += static_cast<std::size_t>(!((dist2 >= rr * rr) | (dist2 == 0.0)));
      }
      return;
    }
    for (std::size_t k = k0; k < k1; ++k) {
      const PairKey key = cand[k];
      const std::uint32_t i = key_i(key), j = key_j(key);
      const bool wall = j >= N;
      const std::uint32_t jj = wall ? i : j;  // a wall's index is no particle: read i instead
      const std::uint32_t image = key_image(key);
      const Vec2 d =
          Vec2{x[jj] + image_sx(image) * w.Lx, y[jj] + image_sy(image) * w.Ly} - Vec2{x[i], y[i]};
      const double dist2 = norm2(d), rr = reach(i, jj);
      sel[m] = static_cast<std::uint32_t>(k);
      m += static_cast<std::size_t>(wall | !((dist2 >= rr * rr) | (dist2 == 0.0)));
    }
  };
  if (rc == rc)
    select(std::true_type{});  // not NaN: one radius
  else
    select(std::false_type{});
  return m;
}

// in a large dilute box the selected pairs lie far apart and each line is a cache miss, so the
// misses overlap instead of coming one after another
void DiskPairEvaluator::prefetch(const World& w, const std::vector<PairKey>& cand,
                                 const std::vector<std::uint32_t>& sel, std::size_t m,
                                 const double* fx, const double* fy) {
  const auto N = static_cast<std::uint32_t>(w.size());
  for (std::size_t q = 0; q < m; ++q) {
    const PairKey key = cand[sel[q]];
    for (const std::uint32_t p : {key_i(key), key_j(key)}) {
      if (p >= N) continue;  // a wall
      __builtin_prefetch(&w.s.vx[p]);
      __builtin_prefetch(&w.s.vy[p]);
      __builtin_prefetch(&w.sp[p]);
      __builtin_prefetch(fx + p, 1);
      __builtin_prefetch(fy + p, 1);
    }
  }
}

}  // namespace gs
