// 1D reduced coordinates (T.3.16), neighbour gaps (T.3.17, T.3.23) and G_h(R) (T.3.24)
#include "analysis/rfm_gaps.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace gs::rfm {

double reduced_length(double box, long n, double diameter) {
  const double lr = box - static_cast<double>(n) * diameter;
  if (!(lr > 0.0))
    throw InputError("reduced_length", "box", "L − N d must be positive (particles do not fit)");
  return lr;
}

std::vector<double> reduced_coordinates(std::span<const double> r, double box, double diameter) {
  if (r.empty()) throw InputError("reduced_coordinates", "", "no particles");
  if (!(box > 0.0)) throw InputError("reduced_coordinates", "box", "must be positive");
  std::vector<double> out(r.size());
  out[0] = 0.0;
  // distance travelled from particle 0 in the positive direction, minus the particles' widths
  for (std::size_t i = 1; i < r.size(); ++i) {
    double dx = r[i] - r[0];
    dx -= box * std::floor(dx / box);  // into [0, L): the "otherwise" branch of T.3.16
    out[i] = dx - static_cast<double>(i) * diameter;
  }
  return out;
}

std::vector<double> neighbour_gaps(std::span<const double> reduced, double l_reduced, int h) {
  const std::size_t n = reduced.size();
  if (n == 0) throw InputError("neighbour_gaps", "", "no particles");
  if (h < 1) throw InputError("neighbour_gaps", "h", "need h ≥ 1");
  std::vector<double> g(n);
  // R_{i,i+h} with the periodic continuation r′_{i+N} = r′_i + L′
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(h);
    const double rj = reduced[j % n] + static_cast<double>(j / n) * l_reduced;
    g[i] = std::abs(rj - reduced[i]);
  }
  return g;
}

GapStatistics::GapStatistics(Binning bins, std::vector<int> orders, int m_max)
    : bins_(bins), orders_(std::move(orders)), moments_(m_max) {
  if (orders_.empty()) throw InputError("GapStatistics", "orders", "need at least one h");
  for (int h : orders_)
    if (h < 1) throw InputError("GapStatistics", "orders", "every h must be ≥ 1");
  hist_.assign(orders_.size(), Histogram(bins_));
}

void GapStatistics::add_snapshot(std::span<const double> reduced, double l_reduced) {
  // G_h: every R_{i,i+h} of the snapshot into its histogram (T.3.24)
  for (std::size_t k = 0; k < orders_.size(); ++k)
    for (double r : neighbour_gaps(reduced, l_reduced, orders_[k])) hist_[k].add(r);
  // ⟨R^m⟩ of the nearest neighbours (T.3.18)
  moments_.add_snapshot(neighbour_gaps(reduced, l_reduced, 1));
}

void write_gh_csv(const RecordSink& sink, const std::filesystem::path& path,
                  const GapStatistics& g) {
  std::vector<std::string> cols = {"R"};
  for (int h : g.orders()) {
    cols.push_back("G" + std::to_string(h));
    cols.push_back("G" + std::to_string(h) + "_err");
  }
  std::vector<std::vector<HistBin>> bins;
  for (std::size_t k = 0; k < g.orders().size(); ++k) bins.push_back(g.g(k));
  const auto w = sink.create(path.string(), cols);
  for (int i = 0; i < g.binning().n; ++i) {
    std::vector<double> row = {g.binning().centre(i)};
    for (const auto& b : bins) {
      row.push_back(b[static_cast<std::size_t>(i)].p);
      row.push_back(b[static_cast<std::size_t>(i)].p_err);
    }
    w->row(row);
  }
}

}  // namespace gs::rfm
