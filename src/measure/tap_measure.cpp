#include "measure/tap_measure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "measure/packing.hpp"

namespace gs {

TapMeasurement measure_tap(const World& w, const ContactSet& cs, const double rect[4]) {
  TapMeasurement m;
  // φ of the test rectangle and of its halves, by exact clipping
  const double x0 = rect[0], y0 = rect[1], x1 = rect[2], y1 = rect[3];
  const double xm = 0.5 * (x0 + x1);
  m.phi = phi_in_rect(w, x0, y0, x1, y1);
  m.phi_left = phi_in_rect(w, x0, y0, xm, y1);
  m.phi_right = phi_in_rect(w, xm, y0, x1, y1);
  // proof of rest
  m.kinetic_energy = w.kinetic_energy();
  m.max_speed = max_speed(w);
  // mean heights, all grains and per species
  const std::size_t ns = w.species.size();
  std::vector<double> sum(ns, 0.0), cnt(ns, 0.0);
  double all = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    sum[w.sp[i]] += w.s.y[i];
    cnt[w.sp[i]] += 1.0;
    all += w.s.y[i];
  }
  m.z_mean = w.size() > 0 ? all / static_cast<double>(w.size()) : 0.0;
  m.z_species.resize(ns);
  for (std::size_t k = 0; k < ns; ++k) m.z_species[k] = cnt[k] > 0 ? sum[k] / cnt[k] : 0.0;
  // contacts and stress (P.41)
  m.coordination = mean_coordination(w, cs);
  m.S = force_moment_tensor(w, cs);
  return m;
}

std::vector<double> height_grid(double top, double dh) {
  std::vector<double> g;
  const long n = static_cast<long>(std::ceil(top / dh - 1e-9));
  for (long k = 1; k <= n; ++k) g.push_back(static_cast<double>(k) * dh);
  return g;
}

std::vector<double> cumulative_counts(const World& w, const std::vector<double>& grid) {
  const std::size_t ns = w.species.size(), nh = grid.size();
  std::vector<double> out(ns * nh, 0.0);
  if (nh == 0) return out;
  // histogram by grid cell, then a running sum: n(h_k) counts centres with y < h_k
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto it = std::upper_bound(grid.begin(), grid.end(), w.s.y[i]);
    if (it == grid.end()) continue;  // above the grid
    out[w.sp[i] * nh + static_cast<std::size_t>(it - grid.begin())] += 1.0;
  }
  for (std::size_t s = 0; s < ns; ++s)
    for (std::size_t k = 1; k < nh; ++k) out[s * nh + k] += out[s * nh + k - 1];
  return out;
}

std::vector<std::string> cumulative_count_names(const World& w, const std::vector<double>& grid) {
  std::vector<std::string> names;
  for (const Species& sp : w.species)
    for (double h : grid) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "@%g", h * 1000.0);
      names.push_back(sp.name + buf);
    }
  return names;
}

}  // namespace gs
