// pair correlation g(R) (T.4.10) with minimum image
#include "analysis/rfm_gr.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace gs::rfm {

PairCorrelation2D::PairCorrelation2D(double box, double r_max, int n_bins)
    : box_(box),
      r_max_(r_max),
      n_bins_(n_bins),
      pairs_(static_cast<std::size_t>(std::max(n_bins, 0)), 0.0) {
  if (!(box > 0.0)) throw InputError("PairCorrelation2D", "box", "box side must be positive");
  if (!(r_max > 0.0) || r_max > 0.5 * box)
    throw InputError("PairCorrelation2D", "r_max", "need 0 < R_max ≤ L/2 (minimum image)");
  if (n_bins < 1) throw InputError("PairCorrelation2D", "n_bins", "need at least one bin");
}

// minimum-image separation into its bin
void PairCorrelation2D::add_pair(Vec2 d) {
  d.x -= box_ * std::round(d.x / box_);
  d.y -= box_ * std::round(d.y / box_);
  const double r2 = norm2(d);
  if (r2 >= r_max_ * r_max_) return;
  const int b = static_cast<int>(std::sqrt(r2) / r_max_ * n_bins_);
  if (b < n_bins_) pairs_[static_cast<std::size_t>(b)] += 1.0;
}

void PairCorrelation2D::count_brute(std::span<const Vec2> r) {
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = i + 1; j < r.size(); ++j) add_pair(r[j] - r[i]);
}

void PairCorrelation2D::count_cells(std::span<const Vec2> r) {
  // cells at least R_max wide: every pair closer than R_max is in neighbouring cells
  // (no more than 1024 a side: wider cells only hold more pairs)
  const int nc = static_cast<int>(std::min(box_ / r_max_, 1024.0));
  const double cw = box_ / nc;
  std::vector<std::vector<std::size_t>> cell(static_cast<std::size_t>(nc) *
                                             static_cast<std::size_t>(nc));
  // a coordinate's cell, wrapped into the box in floating point first (any finite x)
  auto wrap = [&](double x) {
    const double u = x / cw - nc * std::floor(x / cw / nc);
    return std::clamp(static_cast<int>(u), 0, nc - 1);
  };
  for (std::size_t i = 0; i < r.size(); ++i)
    cell[static_cast<std::size_t>(wrap(r[i].y) * nc + wrap(r[i].x))].push_back(i);
  // each unordered cell pair once: the cell itself and 4 of its 8 neighbours
  const int nb[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (int cy = 0; cy < nc; ++cy)
    for (int cx = 0; cx < nc; ++cx) {
      const auto& a = cell[static_cast<std::size_t>(cy * nc + cx)];
      for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = i + 1; j < a.size(); ++j) add_pair(r[a[j]] - r[a[i]]);
      for (const auto& o : nb) {
        const int ox = (cx + o[0] + nc) % nc, oy = (cy + o[1] + nc) % nc;
        const auto& b = cell[static_cast<std::size_t>(oy * nc + ox)];
        for (std::size_t i : a)
          for (std::size_t j : b) add_pair(r[j] - r[i]);
      }
    }
}

void PairCorrelation2D::add_snapshot(std::span<const Vec2> r) {
  if (r.size() < 2) throw InputError("PairCorrelation2D::add_snapshot", "", "need two particles");
  // the cell list needs at least three cells per side to avoid double counting
  if (box_ / r_max_ >= 3.0)
    count_cells(r);
  else
    count_brute(r);
  const double n = static_cast<double>(r.size());
  ideal_density_ += n * (n - 1.0) / (2.0 * box_ * box_);
  ++snapshots_;
}

std::vector<GrBin> PairCorrelation2D::bins() const {
  // g = pairs / (ideal pair density × annulus area)
  std::vector<GrBin> out(static_cast<std::size_t>(n_bins_));
  const double dr = r_max_ / n_bins_;
  for (int b = 0; b < n_bins_; ++b) {
    GrBin& g = out[static_cast<std::size_t>(b)];
    g.r_lo = b * dr;
    g.r_hi = (b + 1) * dr;
    g.r = 0.5 * (g.r_lo + g.r_hi);
    g.pairs = pairs_[static_cast<std::size_t>(b)];
    const double ideal = ideal_density_ * std::numbers::pi * (g.r_hi * g.r_hi - g.r_lo * g.r_lo);
    g.g = ideal > 0 ? g.pairs / ideal : 0.0;
    g.g_err = g.pairs > 0 ? g.g / std::sqrt(g.pairs) : 0.0;
  }
  return out;
}

void write_gr_csv(const RecordSink& sink, const std::filesystem::path& path,
                  std::span<const GrBin> bins) {
  const auto w = sink.create(path.string(), {"R", "g", "g_err", "pairs"});
  for (const GrBin& b : bins) w->row({b.r, b.g, b.g_err, b.pairs});
}

}  // namespace gs::rfm
