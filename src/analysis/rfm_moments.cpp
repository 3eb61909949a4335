// velocity and gap moments (T.3.11, T.3.18), scaling exponents (T.3.13, T.3.20),
// granular temperature (T.2.19) and block averages (T.2.20)
#include "analysis/rfm_moments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"

namespace gs::rfm {

std::vector<double> abs_moments(std::span<const double> x, int m_max) {
  if (m_max < 1) throw InputError("abs_moments", "m_max", "need m_max ≥ 1");
  if (x.empty()) throw InputError("abs_moments", "", "no values");
  // Σ|x|^m by repeated multiplication, m = 1…m_max
  std::vector<double> s(static_cast<std::size_t>(m_max), 0.0);
  for (double v : x) {
    const double a = std::abs(v);
    double p = 1.0;
    for (int m = 0; m < m_max; ++m) {
      p *= a;
      s[static_cast<std::size_t>(m)] += p;
    }
  }
  for (double& v : s) v /= static_cast<double>(x.size());
  return s;
}

MomentSeries::MomentSeries(int m_max) : m_max_(m_max) {
  if (m_max < 1) throw InputError("MomentSeries", "m_max", "need m_max ≥ 1");
}

void MomentSeries::add_snapshot(std::span<const double> x) {
  per_snapshot_.push_back(abs_moments(x, m_max_));
  weights_.push_back(static_cast<double>(x.size()));
}

void MomentSeries::add_components(std::span<const Vec2> v) {
  std::vector<double> c;
  c.reserve(2 * v.size());
  for (const Vec2& u : v) {
    c.push_back(u.x);
    c.push_back(u.y);
  }
  add_snapshot(c);
}

void MomentSeries::add_speeds(std::span<const Vec2> v) {
  std::vector<double> c;
  c.reserve(v.size());
  for (const Vec2& u : v) c.push_back(norm(u));
  add_snapshot(c);
}

std::vector<double> MomentSeries::mean() const {
  // sample-weighted, so equal to pooling every value of every snapshot (T.3.11)
  std::vector<double> m(static_cast<std::size_t>(m_max_), 0.0);
  double w = 0.0;
  for (std::size_t s = 0; s < per_snapshot_.size(); ++s) {
    for (std::size_t k = 0; k < m.size(); ++k) m[k] += weights_[s] * per_snapshot_[s][k];
    w += weights_[s];
  }
  for (double& v : m) v = w > 0 ? v / w : std::numeric_limits<double>::quiet_NaN();
  return m;
}

std::vector<double> MomentSeries::error() const {
  // scatter of the snapshot means about their plain mean, over √n_snapshots
  const std::size_t n = per_snapshot_.size();
  std::vector<double> e(static_cast<std::size_t>(m_max_), std::numeric_limits<double>::quiet_NaN());
  if (n < 2) return e;
  for (std::size_t k = 0; k < e.size(); ++k) {
    double s = 0.0, s2 = 0.0;
    for (const auto& snap : per_snapshot_) {
      s += snap[k];
      s2 += snap[k] * snap[k];
    }
    const double mu = s / static_cast<double>(n);
    const double var =
        std::max(0.0, (s2 - static_cast<double>(n) * mu * mu) / static_cast<double>(n - 1));
    e[k] = std::sqrt(var / static_cast<double>(n));
  }
  return e;
}

ExponentFit fit_scaling_exponent(std::span<const double> n, std::span<const double> y,
                                 std::span<const double> y_err) {
  // ln y = ln c − exponent·ln N (T.3.13, T.3.20)
  const PowerLawFit p = fit_power_law(n, y, y_err);
  ExponentFit f;
  f.exponent = -p.exponent;
  f.exponent_err = p.exponent_err;
  f.amplitude = p.amplitude;
  f.chi2_r = p.chi2_r;
  return f;
}

std::vector<ExponentFit> fit_scaling_exponents(std::span<const double> n,
                                               const std::vector<std::vector<double>>& moments,
                                               const std::vector<std::vector<double>>& errors) {
  if (moments.size() != n.size() || (!errors.empty() && errors.size() != n.size()))
    throw InputError("fit_scaling_exponents", "", "one row of moments per system size");
  if (moments.empty()) throw InputError("fit_scaling_exponents", "", "no systems");
  const std::size_t m_max = moments.front().size();
  std::vector<ExponentFit> out;
  // one fit per order m across the system sizes
  for (std::size_t k = 0; k < m_max; ++k) {
    std::vector<double> y, e;
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (moments[i].size() != m_max)
        throw InputError("fit_scaling_exponents", "", "rows have different numbers of moments");
      y.push_back(moments[i][k]);
      if (!errors.empty()) e.push_back(errors[i][k]);
    }
    ExponentFit f = fit_scaling_exponent(n, y, e);
    f.m = static_cast<int>(k + 1);
    out.push_back(f);
  }
  return out;
}

double granular_temperature(std::span<const Vec2> v) {
  if (v.empty()) throw InputError("granular_temperature", "", "no particles");
  Vec2 mean{};
  for (const Vec2& u : v) mean += u;
  mean = mean / static_cast<double>(v.size());
  // T = (1/N) Σ|v_i − ⟨v⟩|² (T.2.19)
  double t = 0.0;
  for (const Vec2& u : v) t += norm2(u - mean);
  return t / static_cast<double>(v.size());
}

double granular_temperature(std::span<const double> v) {
  if (v.empty()) throw InputError("granular_temperature", "", "no particles");
  double mean = 0.0;
  for (double u : v) mean += u;
  mean /= static_cast<double>(v.size());
  double t = 0.0;
  for (double u : v) t += (u - mean) * (u - mean);
  return t / static_cast<double>(v.size());
}

BlockAverage block_average(std::span<const double> series, std::size_t block_len) {
  if (block_len < 1) throw InputError("block_average", "block_len", "need block_len ≥ 1");
  BlockAverage b;
  b.block_len = block_len;
  const std::size_t nb = series.size() / block_len;
  if (nb < 1) throw InputError("block_average", "block_len", "series shorter than one block");
  // the complete blocks (T.2.20 per block)
  for (std::size_t i = 0; i < nb; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < block_len; ++j) s += series[i * block_len + j];
    b.block_means.push_back(s / static_cast<double>(block_len));
  }
  double s = 0.0, s2 = 0.0;
  for (double m : b.block_means) {
    s += m;
    s2 += m * m;
  }
  b.mean = s / static_cast<double>(nb);
  // the standard error treats the blocks as independent (blocks ≫ correlation time)
  if (nb > 1) {
    const double var = std::max(
        0.0, (s2 - static_cast<double>(nb) * b.mean * b.mean) / static_cast<double>(nb - 1));
    b.error = std::sqrt(var / static_cast<double>(nb));
  }
  return b;
}

void write_temperature_csv(const RecordSink& sink, const std::filesystem::path& path,
                           std::span<const double> t, std::span<const double> temp,
                           const BlockAverage* blocks) {
  if (t.size() != temp.size())
    throw InputError(path.string(), "", "time and temperature series differ in length");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RecordMeta meta;
  if (blocks)
    meta = {{"T_mean", blocks->mean},
            {"T_err", blocks->error},
            {"block_len", static_cast<double>(blocks->block_len)}};
  std::vector<std::string> cols = {"t", "T"};
  if (blocks) cols.push_back("T_block");
  const auto w = sink.create(path.string(), cols, meta);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!blocks) {
      w->row({t[i], temp[i]});
      continue;
    }
    const std::size_t b = i / blocks->block_len;
    w->row({t[i], temp[i], b < blocks->block_means.size() ? blocks->block_means[b] : nan});
  }
}

void write_moments_csv(const RecordSink& sink, const std::filesystem::path& path,
                       std::span<const double> mean, std::span<const double> err) {
  const auto w = sink.create(path.string(), {"m", "moment", "error"});
  for (std::size_t k = 0; k < mean.size(); ++k)
    w->row({static_cast<double>(k + 1), mean[k], k < err.size() ? err[k] : 0.0});
}

void MomentSeries::save(ByteWriter& out) const {
  out.u64(per_snapshot_.size());
  for (const auto& snap : per_snapshot_) out.vec(snap);
  out.vec(weights_);
}

void MomentSeries::load(ByteReader& in) {
  per_snapshot_.resize(in.count(8, "moment snapshots"));
  for (auto& snap : per_snapshot_)
    in.vec_sized(snap, static_cast<std::size_t>(m_max_), "moment snapshot");
  in.vec(weights_, "moment weights");
  if (weights_.size() != per_snapshot_.size())
    in.fail(in.pos, "moment weights do not match the snapshots");
}

}  // namespace gs::rfm
