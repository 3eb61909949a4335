// histograms for the RFM analyses: linear bins of fixed width (velocities, T.A.3) or
// logarithmic bins (free paths, gaps over many decades). Counts carry Poisson errors
// √X (T.A.4) and densities are X/(N_s·Δ) with N_s every sample added (T.A.5), so a
// density integrates to the fraction of samples that fell inside the range.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "core/bytes.hpp"
#include "core/error.hpp"

namespace gs::rfm {

/// bins on [lo, hi): equal widths (linear) or equal ratios (log)
struct Binning {
  enum class Scale { linear, log };
  Scale scale = Scale::linear;
  double lo = 0.0;  ///< lower edge of the first bin, data units
  double hi = 1.0;  ///< upper edge of the last bin, data units
  int n = 1;        ///< number of bins

  static Binning linear(double lo, double hi, int n) { return make(Scale::linear, lo, hi, n); }
  static Binning log(double lo, double hi, int n) { return make(Scale::log, lo, hi, n); }

  /// the bin holding x, or −1 outside [lo, hi)
  int index(double x) const {
    if (!(x >= lo) || !(x < hi)) return -1;
    const double u =
        scale == Scale::linear ? (x - lo) / (hi - lo) : std::log(x / lo) / std::log(hi / lo);
    const int i = static_cast<int>(u * n);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
  }
  /// lower edge of bin i (edge(n) = hi)
  double edge(int i) const {
    if (i >= n) return hi;
    const double u = static_cast<double>(i) / n;
    return scale == Scale::linear ? lo + u * (hi - lo) : lo * std::pow(hi / lo, u);
  }
  /// arithmetic centre (linear) or geometric centre (log) of bin i
  double centre(int i) const {
    return scale == Scale::linear ? 0.5 * (edge(i) + edge(i + 1))
                                  : std::sqrt(edge(i) * edge(i + 1));
  }
  double width(int i) const { return edge(i + 1) - edge(i); }

 private:
  static Binning make(Scale s, double lo, double hi, int n) {
    if (n < 1) throw InputError("Binning", "n", "need at least one bin, got " + std::to_string(n));
    if (!(hi > lo)) throw InputError("Binning", "hi", "upper edge must exceed lower edge");
    if (s == Scale::log && !(lo > 0.0))
      throw InputError("Binning", "lo", "logarithmic bins need a positive lower edge");
    Binning b;
    b.scale = s;
    b.lo = lo;
    b.hi = hi;
    b.n = n;
    return b;
  }
};

/// one bin of a normalised histogram
struct HistBin {
  double lo = 0.0;     ///< lower edge, data units
  double hi = 0.0;     ///< upper edge, data units
  double x = 0.0;      ///< centre (geometric for log bins), data units
  double count = 0.0;  ///< samples in the bin, X
  double p = 0.0;      ///< probability density X/(N_s Δ), 1/data units
  double p_err = 0.0;  ///< Poisson error √X/(N_s Δ), 1/data units
};

/// counts in bins with under/overflow, normalised by every sample added
class Histogram {
 public:
  Histogram() = default;
  explicit Histogram(Binning b) : bins_(b), counts_(static_cast<std::size_t>(b.n), 0.0) {}

  void add(double x) {
    ++total_;
    const int i = bins_.index(x);
    if (i >= 0)
      counts_[static_cast<std::size_t>(i)] += 1.0;
    else if (x < bins_.lo)
      ++under_;
    else
      ++over_;
  }
  /// merge another histogram with identical binning
  void merge(const Histogram& o) {
    if (o.bins_.n != bins_.n || o.bins_.lo != bins_.lo || o.bins_.hi != bins_.hi)
      throw InputError("Histogram::merge", "", "binnings differ");
    for (std::size_t i = 0; i < counts_.size(); ++i) counts_[i] += o.counts_[i];
    total_ += o.total_;
    under_ += o.under_;
    over_ += o.over_;
  }

  const Binning& binning() const { return bins_; }
  const std::vector<double>& counts() const { return counts_; }
  double total() const { return total_; }      ///< N_s, every sample added
  double underflow() const { return under_; }  ///< samples below lo
  double overflow() const { return over_; }    ///< samples at or above hi

  /// the bins with densities and Poisson errors scaled by s (T.A.5, s = 1 → 68 %)
  std::vector<HistBin> bins(double s = 1.0) const {
    std::vector<HistBin> out(counts_.size());
    for (int i = 0; i < bins_.n; ++i) {
      HistBin& b = out[static_cast<std::size_t>(i)];
      b.lo = bins_.edge(i);
      b.hi = bins_.edge(i + 1);
      b.x = bins_.centre(i);
      b.count = counts_[static_cast<std::size_t>(i)];
      const double norm = total_ > 0 ? total_ * (b.hi - b.lo) : 1.0;
      b.p = b.count / norm;
      b.p_err = s * std::sqrt(b.count) / norm;
    }
    return out;
  }

  /// checkpoint: the counts (the binning comes from the scene and must match)
  void save(ByteWriter& out) const {
    out.vec(counts_);
    out.f64(total_);
    out.f64(under_);
    out.f64(over_);
  }
  void load(ByteReader& in) {
    in.vec_sized(counts_, counts_.size(), "histogram counts");
    total_ = in.f64("histogram total");
    under_ = in.f64("histogram underflow");
    over_ = in.f64("histogram overflow");
  }

 private:
  Binning bins_;
  std::vector<double> counts_;
  double total_ = 0.0;
  double under_ = 0.0;
  double over_ = 0.0;
};

}  // namespace gs::rfm
