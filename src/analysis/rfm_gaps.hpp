// structure of the 1D RFM (thesis §3.3): reduced coordinates of point-like particles
//   r′_i = r_i − r_1 − (i−1)d        if r_i − r_1 > 0,
//   r′_i = r_i − r_1 + L − (i−1)d    otherwise            (T.3.16, r′_1 = 0),
// neighbour separations R_{i,i+h} = |r′_{i+h} − r′_i| with r′_{i+N} = r′_i + L′ (T.3.17, T.3.23),
// moments ⟨R^m⟩ (T.3.18) and the h-th neighbour distributions
//   G_h(R; N) = (1/N) ⟨Σ_i δ(R − R_{i,i+h})⟩   (T.3.21, T.3.24), normalised to ∫G_h dR = 1.
// Indices here are 0-based: particle 0 is the reference; positions are given in ring order
// (index i+1 is the next particle in the positive direction), wrapped or not.
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "analysis/rfm_hist.hpp"
#include "analysis/rfm_moments.hpp"
#include "core/records.hpp"

namespace gs::rfm {

/// L′ = L − N d, m
double reduced_length(double box, long n, double diameter);
/// reduced coordinates r′ (T.3.16); r′[0] = 0
std::vector<double> reduced_coordinates(std::span<const double> r, double box, double diameter);
/// R_{i,i+h} for i = 0…N−1 with the periodic continuation r′_{i+N} = r′_i + L′ (T.3.17, T.3.23)
std::vector<double> neighbour_gaps(std::span<const double> reduced, double l_reduced, int h = 1);

/// accumulates G_h(R) for several h and the moments of the nearest-neighbour gaps
class GapStatistics {
 public:
  /// bins of R (linear on [0, L′] or logarithmic for the −ln R view of §3.3.2)
  explicit GapStatistics(Binning bins, std::vector<int> orders = {1, 2, 4, 8}, int m_max = 12);
  /// one snapshot of reduced coordinates (T.3.16) with its reduced length L′
  void add_snapshot(std::span<const double> reduced, double l_reduced);

  const std::vector<int>& orders() const { return orders_; }
  const Binning& binning() const { return bins_; }
  /// G_h as densities with Poisson errors, for h = orders()[k]
  std::vector<HistBin> g(std::size_t k) const { return hist_[k].bins(); }
  const Histogram& histogram(std::size_t k) const { return hist_[k]; }
  /// ⟨R^m⟩ of the nearest-neighbour gaps R_{i,i+1}, per snapshot and averaged (T.3.18)
  const MomentSeries& moments() const { return moments_; }

  /// checkpoint: histograms and moments
  void save(ByteWriter& out) const {
    for (const Histogram& h : hist_) h.save(out);
    moments_.save(out);
  }
  void load(ByteReader& in) {
    for (Histogram& h : hist_) h.load(in);
    moments_.load(in);
  }

 private:
  Binning bins_;
  std::vector<int> orders_;
  std::vector<Histogram> hist_;
  MomentSeries moments_;
};

/// columns R, then G<h>, G<h>_err for every order
void write_gh_csv(const RecordSink& sink, const std::filesystem::path& path,
                  const GapStatistics& g);

}  // namespace gs::rfm
