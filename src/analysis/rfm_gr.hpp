// pair correlation g(R) of points in a periodic L×L box (thesis §4.2, T.4.10):
//   g(R) = L²/(2πR N(N−1)/2) ⟨Σ_{i<j} δ(R − R_ij)⟩,  R_ij by minimum image, R < L/2.
// The thesis normalises by N²/2; N(N−1)/2 is used here so that an ideal gas gives exactly
// g = 1 (the two differ by 1/N). Each bin divides by its exact annulus area π(R₂² − R₁²)
// rather than 2πR dR. Pairs are found by brute force, or through a cell list when
// R_max ≤ L/3.
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "core/bytes.hpp"
#include "core/records.hpp"
#include "core/vec.hpp"

namespace gs::rfm {

/// one bin of g(R)
struct GrBin {
  double r_lo = 0.0;   ///< inner radius, m
  double r_hi = 0.0;   ///< outer radius, m
  double r = 0.0;      ///< bin centre, m
  double g = 0.0;      ///< pair correlation, dimensionless
  double g_err = 0.0;  ///< Poisson error g/√pairs, dimensionless
  double pairs = 0.0;  ///< pair count over all snapshots
};

/// accumulates g(R) over snapshots
class PairCorrelation2D {
 public:
  /// r_max ≤ L/2 (minimum image); n_bins equal-width bins on [0, r_max)
  PairCorrelation2D(double box, double r_max, int n_bins);
  void add_snapshot(std::span<const Vec2> r);
  std::vector<GrBin> bins() const;
  long snapshots() const { return snapshots_; }

  /// checkpoint: the pair counts
  void save(ByteWriter& out) const {
    out.vec(pairs_);
    out.f64(ideal_density_);
    out.i64(snapshots_);
  }
  void load(ByteReader& in) {
    in.vec_sized(pairs_, pairs_.size(), "g(R) pair counts");
    ideal_density_ = in.f64("g(R) density");
    snapshots_ = static_cast<long>(in.i64("g(R) snapshots"));
  }

 private:
  void count_brute(std::span<const Vec2> r);
  void count_cells(std::span<const Vec2> r);
  void add_pair(Vec2 d);
  double box_, r_max_;
  int n_bins_;
  std::vector<double> pairs_;
  double ideal_density_ = 0.0;  // Σ over snapshots of N(N−1)/(2L²), pairs per m²
  long snapshots_ = 0;
};

/// columns R, g, g_err, pairs
void write_gr_csv(const RecordSink& sink, const std::filesystem::path& path,
                  std::span<const GrBin> bins);

}  // namespace gs::rfm
