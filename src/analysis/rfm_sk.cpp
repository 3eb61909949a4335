// structure factor S(k) of periodic point sets (T.4.2) and the D_f fit (T.4.4–T.4.9)
#include "analysis/rfm_sk.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"

namespace gs::rfm {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

void check_grid(double box, int n_max, const char* who) {
  if (!(box > 0.0)) throw InputError(who, "box", "box side must be positive");
  if (n_max < 1) throw InputError(who, "n_max", "cutoff must be at least 1");
}
}  // namespace

std::vector<SkMode> half_plane_modes(int n_max) {
  std::vector<SkMode> m;
  const int n2max = n_max * n_max;
  // row n_y = 0 holds only n_x > 0; rows n_y > 0 hold every n_x within the disc
  for (int ny = 0; ny <= n_max; ++ny)
    for (int nx = -n_max; nx <= n_max; ++nx) {
      if (ny == 0 && nx <= 0) continue;
      if (nx * nx + ny * ny > n2max) continue;
      m.push_back({nx, ny, 0.0});
    }
  return m;
}

// ---- shells ------------------------------------------------------------------------------

ShellAccumulator::ShellAccumulator(double box, int n_max, ShellGrouping g)
    : box_(box), n_max_(n_max), grouping_(g) {
  check_grid(box, n_max, "ShellAccumulator");
  // one shell per n² (exact) or per rounded |n|, numbered in increasing |k|
  const int n2max = n_max * n_max;
  shell_of_key_.assign(static_cast<std::size_t>(n2max + 1), -1);
  std::vector<int> shell_of_group(static_cast<std::size_t>(n2max + 1), -1);
  int shells = 0;
  for (int q = 1; q <= n2max; ++q) {
    // is q a sum of two squares? (only those n² occur)
    bool occurs = false;
    for (int a = 0; a * a <= q && !occurs; ++a) {
      const int b2 = q - a * a;
      const int b = static_cast<int>(std::lround(std::sqrt(static_cast<double>(b2))));
      occurs = b * b == b2;
    }
    if (!occurs) continue;
    const int group = grouping_ == ShellGrouping::exact
                          ? q
                          : static_cast<int>(std::lround(std::sqrt(static_cast<double>(q))));
    if (shell_of_group[static_cast<std::size_t>(group)] < 0)
      shell_of_group[static_cast<std::size_t>(group)] = shells++;
    shell_of_key_[static_cast<std::size_t>(q)] = shell_of_group[static_cast<std::size_t>(group)];
  }
  sum_.assign(static_cast<std::size_t>(shells), 0.0);
  sum2_ = sum_;
  ksum_ = sum_;
  count_.assign(static_cast<std::size_t>(shells), 0);
  modes_ = count_;
  // the mode count of each shell (half plane)
  for (const SkMode& m : half_plane_modes(n_max)) {
    const int s = shell_of_key_[static_cast<std::size_t>(key(m.nx, m.ny))];
    modes_[static_cast<std::size_t>(s)] += 1;
  }
}

int ShellAccumulator::key(int nx, int ny) const { return nx * nx + ny * ny; }

void ShellAccumulator::add(int nx, int ny, double s) {
  const int q = key(nx, ny);
  if (q <= 0 || q > n_max_ * n_max_) return;
  const int i = shell_of_key_[static_cast<std::size_t>(q)];
  const auto u = static_cast<std::size_t>(i);
  sum_[u] += s;
  sum2_[u] += s * s;
  ksum_[u] += std::sqrt(static_cast<double>(q));
  count_[u] += 1;
}

std::vector<SkShell> ShellAccumulator::shells() const {
  std::vector<SkShell> out;
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    if (count_[i] == 0) continue;
    SkShell sh;
    const double c = static_cast<double>(count_[i]);
    sh.n = ksum_[i] / c;
    sh.k = kTwoPi * sh.n / box_;
    sh.s = sum_[i] / c;
    // standard error of the mean from the sample scatter
    if (count_[i] > 1) {
      const double var = std::max(0.0, (sum2_[i] / c - sh.s * sh.s) * c / (c - 1.0));
      sh.s_err = std::sqrt(var / c);
    }
    sh.modes = modes_[i];
    sh.samples = count_[i];
    out.push_back(sh);
  }
  return out;
}

// ---- point sets --------------------------------------------------------------------------

StructureFactor2D::StructureFactor2D(double box, int n_max, ShellGrouping g)
    : box_(box), n_max_(n_max), modes_(half_plane_modes(n_max)), shells_(box, n_max, g) {
  check_grid(box, n_max, "StructureFactor2D");
  mode_sum_.assign(modes_.size(), 0.0);
  // where each n_y row starts in the mode list
  row_begin_.assign(static_cast<std::size_t>(n_max + 2), 0);
  for (std::size_t i = 0, row = 0; row <= static_cast<std::size_t>(n_max) + 1; ++row) {
    while (i < modes_.size() && static_cast<std::size_t>(modes_[i].ny) < row) ++i;
    row_begin_[row] = static_cast<int>(i);
  }
}

void StructureFactor2D::add_snapshot(std::span<const Vec2> r) {
  if (r.empty()) throw InputError("StructureFactor2D::add_snapshot", "", "no particles");
  const int nm = n_max_;
  const std::size_t w = static_cast<std::size_t>(2 * nm + 1);
  std::vector<double> re(modes_.size(), 0.0), im(modes_.size(), 0.0);
  std::vector<double> pxr(w), pxi(w), pyr(static_cast<std::size_t>(nm + 1)),
      pyi(static_cast<std::size_t>(nm + 1));

  for (const Vec2& p : r) {
    // phases exp(i 2π n x/L) for n = −n_max…n_max by recurrence from one exponential
    const double ax = kTwoPi * p.x / box_, ay = kTwoPi * p.y / box_;
    const double cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay);
    pxr[static_cast<std::size_t>(nm)] = 1.0;
    pxi[static_cast<std::size_t>(nm)] = 0.0;
    for (int j = 1; j <= nm; ++j) {
      const auto u = static_cast<std::size_t>(nm + j);
      pxr[u] = pxr[u - 1] * cx - pxi[u - 1] * sx;
      pxi[u] = pxr[u - 1] * sx + pxi[u - 1] * cx;
      pxr[static_cast<std::size_t>(nm - j)] = pxr[u];  // exp(−iθ) = conj(exp(iθ))
      pxi[static_cast<std::size_t>(nm - j)] = -pxi[u];
    }
    pyr[0] = 1.0;
    pyi[0] = 0.0;
    for (std::size_t j = 1; j <= static_cast<std::size_t>(nm); ++j) {
      pyr[j] = pyr[j - 1] * cy - pyi[j - 1] * sy;
      pyi[j] = pyr[j - 1] * sy + pyi[j - 1] * cy;
    }
    // ρ(k) += exp(i k_x x) exp(i k_y y), row by row
    for (int ny = 0; ny <= nm; ++ny) {
      const int b = row_begin_[static_cast<std::size_t>(ny)];
      const int e = row_begin_[static_cast<std::size_t>(ny) + 1];
      if (b == e) continue;
      const double yr = pyr[static_cast<std::size_t>(ny)], yi = pyi[static_cast<std::size_t>(ny)];
      const int off = nm + modes_[static_cast<std::size_t>(b)].nx;  // n_x runs consecutively
      for (int i = b; i < e; ++i) {
        const auto u = static_cast<std::size_t>(i);
        const auto v = static_cast<std::size_t>(off + (i - b));
        re[u] += pxr[v] * yr - pxi[v] * yi;
        im[u] += pxr[v] * yi + pxi[v] * yr;
      }
    }
  }

  // S(k) = |ρ(k)|²/N per mode, into the per-mode sums and the shells
  const double inv_n = 1.0 / static_cast<double>(r.size());
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    const double s = (re[i] * re[i] + im[i] * im[i]) * inv_n;
    mode_sum_[i] += s;
    shells_.add(modes_[i].nx, modes_[i].ny, s);
  }
  ++snapshots_;
}

std::vector<SkMode> StructureFactor2D::modes() const {
  std::vector<SkMode> out = modes_;
  const double inv = snapshots_ > 0 ? 1.0 / static_cast<double>(snapshots_) : 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) out[i].s = mode_sum_[i] * inv;
  return out;
}

// ---- D_f ---------------------------------------------------------------------------------

double mean_free_path(double box, double diameter, long n) {
  if (!(diameter > 0.0) || n < 1) throw InputError("mean_free_path", "", "need d > 0 and N ≥ 1");
  return box * box / (2.0 * diameter * static_cast<double>(n));
}

double dissipative_wavenumber(double eps_n, double eps_t, double l0) {
  return (2.0 - eps_n * eps_n - eps_t * eps_t) / (8.0 * l0);
}

double effective_box_size(double k_d) { return 2.0 * std::numbers::sqrt2 * kTwoPi / k_d; }

DfFit fit_df(std::span<const SkShell> shells, double k_lo, double k_hi) {
  // the shells inside the window with a positive S
  std::vector<double> k, s, e;
  bool all_err = true;
  for (const SkShell& sh : shells) {
    if (sh.k < k_lo || sh.k > k_hi || !(sh.s > 0.0)) continue;
    k.push_back(sh.k);
    s.push_back(sh.s);
    e.push_back(sh.s_err);
    all_err = all_err && sh.s_err > 0.0;
  }
  if (k.size() < 2)
    throw InputError("fit_df", "k_hi",
                     "fewer than two shells with S > 0 in [" + std::to_string(k_lo) + ", " +
                         std::to_string(k_hi) + "]; enlarge the box or the window");
  // S = A k^(−D_f) as a line on logarithms (T.4.4)
  const PowerLawFit p =
      fit_power_law(k, s, all_err ? std::span<const double>(e) : std::span<const double>());
  DfFit f;
  f.d_f = -p.exponent;
  f.d_f_err = p.exponent_err;
  f.amplitude = p.amplitude;
  f.chi2_r = p.chi2_r;
  f.points = p.points;
  f.k_lo = k_lo;
  f.k_hi = k_hi;
  return f;
}

DfFit fit_df_rfm(std::span<const SkShell> shells, const RfmSystem& sys) {
  // k′ = k_D if L > L_Eff, else 2 k_D (thesis §4.1.2)
  const double l0 = mean_free_path(sys.box, sys.diameter, sys.n);
  const double kd = dissipative_wavenumber(sys.eps_n, sys.eps_t, l0);
  const double leff = effective_box_size(kd);
  const double kprime = sys.box > leff ? kd : 2.0 * kd;
  DfFit f = fit_df(shells, 0.0, kprime);
  f.k_d = kd;
  f.l_eff = leff;
  return f;
}

void write_sk_csv(const RecordSink& sink, const std::filesystem::path& path,
                  std::span<const SkShell> shells, const DfFit* fit) {
  RecordMeta meta;
  if (fit) {
    meta = {{"D_f", fit->d_f},     {"D_f_err", fit->d_f_err}, {"A", fit->amplitude},
            {"k_lo", fit->k_lo},   {"k_hi", fit->k_hi},       {"k_D", fit->k_d},
            {"L_eff", fit->l_eff}, {"chi2_r", fit->chi2_r}};
  }
  const auto w = sink.create(path.string(), {"k", "n", "S", "S_err", "modes"}, meta);
  for (const SkShell& s : shells) w->row({s.k, s.n, s.s, s.s_err, static_cast<double>(s.modes)});
}

void ShellAccumulator::save(ByteWriter& out) const {
  out.vec(sum_);
  out.vec(sum2_);
  out.vec(ksum_);
  out.vec(count_);
  out.vec(modes_);
}

void ShellAccumulator::load(ByteReader& in) {
  const std::size_t n = sum_.size();
  in.vec_sized(sum_, n, "S(k) shell sums");
  in.vec_sized(sum2_, n, "S(k) shell sums");
  in.vec_sized(ksum_, n, "S(k) shell sums");
  const std::size_t c = count_.size(), m = modes_.size();
  in.vec(count_, "S(k) shell counts");
  in.vec(modes_, "S(k) shell modes");
  if (count_.size() != c || modes_.size() != m)
    in.fail(in.pos, "S(k) shells do not match the scene");
}

void StructureFactor2D::save(ByteWriter& out) const {
  out.vec(mode_sum_);
  shells_.save(out);
  out.i64(snapshots_);
}

void StructureFactor2D::load(ByteReader& in) {
  in.vec_sized(mode_sum_, mode_sum_.size(), "S(k) mode sums");
  shells_.load(in);
  snapshots_ = static_cast<long>(in.i64("S(k) snapshots"));
}

}  // namespace gs::rfm
