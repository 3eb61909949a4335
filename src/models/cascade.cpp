// multiplicative cascades (T.6.1–T.6.5): weights, fields, S(k) by FFT, exact E[S(k)], D₂
#include "models/cascade.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>

#include "core/error.hpp"

#if defined(GS_HAVE_FFTW)
#include <fftw3.h>
#endif

namespace gs::models {

namespace {

// Meakin's four numbers (Table 6.1), before normalisation
constexpr std::array<std::array<double, 4>, 4> kMeakin = {{{0.001, 0.15, 0.32, 0.53},
                                                           {0.02, 0.32, 0.32, 0.34},
                                                           {0.18, 0.21, 0.29, 0.31},
                                                           {0.07, 0.26, 0.32, 0.36}}};

std::array<double, 4> meakin_p(CascadeKind k) {
  std::array<double, 4> p =
      kMeakin[static_cast<std::size_t>(k) - static_cast<std::size_t>(CascadeKind::meakin1)];
  const double s = p[0] + p[1] + p[2] + p[3];
  for (double& v : p) v /= s;  // Meakin 3 and 4 do not sum to 1 as printed
  return p;
}

// E[Σ W²] of UCP: 4 ∫ f₃(t) g(t) dt with g(t) = ∫₀¹ a²/(a+t)² da and f₃ the Irwin–Hall density
// of the sum of the other three uniforms; composite Simpson on each polynomial piece of f₃
double ucp_sum_w2() {
  auto g = [](double t) {
    if (t <= 0.0) return 1.0;
    return 1.0 - 2.0 * t * std::log1p(1.0 / t) + t - t * t / (1.0 + t);
  };
  auto f3 = [](double t) {
    if (t < 1.0) return 0.5 * t * t;
    if (t < 2.0) return 0.5 * (-2.0 * t * t + 6.0 * t - 3.0);
    return 0.5 * (3.0 - t) * (3.0 - t);
  };
  double total = 0.0;
  const int m = 4000;  // even
  for (int piece = 0; piece < 3; ++piece) {
    const double a = piece, h = 1.0 / m;
    double s = f3(a + 1e-15) * g(a) + f3(a + 1.0 - 1e-15) * g(a + 1.0);
    for (int i = 1; i < m; ++i) s += (i % 2 ? 4.0 : 2.0) * f3(a + i * h) * g(a + i * h);
    total += s * h / 3.0;
  }
  return 4.0 * total;
}

}  // namespace

std::string_view cascade_name(CascadeKind k) {
  switch (k) {
    case CascadeKind::ucp:
      return "ucp";
    case CascadeKind::unoncp:
      return "unoncp";
    case CascadeKind::symmetrised:
      return "symmetrised";
    case CascadeKind::meakin1:
      return "meakin1";
    case CascadeKind::meakin2:
      return "meakin2";
    case CascadeKind::meakin3:
      return "meakin3";
    case CascadeKind::meakin4:
      return "meakin4";
  }
  return "?";
}

CascadeKind cascade_from_name(std::string_view name) {
  for (int i = 0; i <= static_cast<int>(CascadeKind::meakin4); ++i)
    if (cascade_name(static_cast<CascadeKind>(i)) == name) return static_cast<CascadeKind>(i);
  throw InputError(
      "cascade", "kind",
      "unknown cascade '" + std::string(name) + "' (ucp, unoncp, symmetrised, meakin1…meakin4)");
}

std::array<double, 4> cascade_weights(CascadeKind kind, RngStream& rng) {
  std::array<double, 4> w{};
  switch (kind) {
    case CascadeKind::ucp: {
      // four uniforms normalised by their sum A (T.6.2–6.3)
      double s = 0.0;
      for (double& v : w) s += (v = rng.uniform());
      for (double& v : w) v /= s;
      return w;
    }
    case CascadeKind::unoncp:
      // A = 1; the factor ½ makes E[ΣW] = 1
      for (double& v : w) v = 0.5 * rng.uniform();
      return w;
    case CascadeKind::symmetrised: {
      // a on the diagonal, 1 − a off it (T.6.4), a uniform on (0, ½)
      const double a = 0.5 * rng.uniform();
      return {0.5 * a, 0.5 * (1.0 - a), 0.5 * (1.0 - a), 0.5 * a};
    }
    default: {
      // Meakin: the fixed numbers in a random order (Fisher–Yates)
      w = meakin_p(kind);
      for (int i = 3; i > 0; --i) {
        const int j = std::min(i, static_cast<int>(rng.uniform() * (i + 1)));
        std::swap(w[static_cast<std::size_t>(i)], w[static_cast<std::size_t>(j)]);
      }
      return w;
    }
  }
}

WeightMoments cascade_weight_moments(CascadeKind kind) {
  WeightMoments m;
  auto fill = [&m](double mean, double diag, double off) {
    for (std::size_t q = 0; q < 4; ++q) {
      m.mean[q] = mean;
      for (std::size_t p = 0; p < 4; ++p) m.second[q][p] = q == p ? diag : off;
    }
  };
  if (kind == CascadeKind::ucp) {
    // exchangeable with ΣW = 1: E[W_q W_p] = (1 − E[ΣW²])/12 for q ≠ p
    const double e = ucp_sum_w2();
    fill(0.25, e / 4.0, (1.0 - e) / 12.0);
  } else if (kind == CascadeKind::unoncp) {
    fill(0.25, 1.0 / 12.0, 1.0 / 16.0);  // E[(a/2)²] = 1/12, E[a a′]/4 = 1/16
  } else if (kind == CascadeKind::symmetrised) {
    // x = (a, 1−a, 1−a, a), a ~ U(0, ½): E a = ¼, E a² = 1/12, E(1−a)² = 7/12, E a(1−a) = 1/6
    const std::array<bool, 4> diag = {true, false, false, true};
    for (std::size_t q = 0; q < 4; ++q) {
      m.mean[q] = 0.5 * (diag[q] ? 0.25 : 0.75);
      for (std::size_t p = 0; p < 4; ++p) {
        const double e =
            diag[q] && diag[p] ? 1.0 / 12.0 : (!diag[q] && !diag[p] ? 7.0 / 12.0 : 1.0 / 6.0);
        m.second[q][p] = 0.25 * e;
      }
    }
  } else {
    // a random permutation of fixed p: E[W²] = Σp²/4, E[W_q W_p] = (1 − Σp²)/12
    const auto p = meakin_p(kind);
    const double s2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    fill(0.25, s2 / 4.0, (1.0 - s2) / 12.0);
  }
  return m;
}

double correlation_dimension(CascadeKind kind) {
  const WeightMoments m = cascade_weight_moments(kind);
  double s = 0.0;
  for (std::size_t q = 0; q < 4; ++q) s += m.second[q][q];
  return -std::log2(s);
}

std::string cascade_no_power_law_reason(CascadeKind kind) {
  if (kind != CascadeKind::symmetrised) return "";
  return "S(k) vanishes on the k_x and k_y axes (every row and every column of a split gets the "
         "same mass, a + (1 − a)), so the shell-averaged S(k) is not A k^−D_f";
}

std::vector<double> cascade_field(CascadeKind kind, int levels, RngStream& rng) {
  if (levels < 0 || levels > 13) throw InputError("cascade", "levels", "need 0 ≤ levels ≤ 13");
  std::vector<double> m{1.0}, next;
  // each level: every cell (i, j) hands m·W_(g+2h) to its child (2i+g, 2j+h)
  for (int lev = 0; lev < levels; ++lev) {
    const std::size_t n = std::size_t{1} << lev, n2 = 2 * n;
    next.assign(n2 * n2, 0.0);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const auto w = cascade_weights(kind, rng);
        const double mass = m[j * n + i];
        for (std::size_t h = 0; h < 2; ++h)
          for (std::size_t g = 0; g < 2; ++g)
            next[(2 * j + h) * n2 + 2 * i + g] = mass * w[g + 2 * h];
      }
    m.swap(next);
  }
  return m;
}

void CascadeParams::validate() const {
  if (levels < 1 || levels > 12) throw InputError("cascade", "levels", "need 1 ≤ levels ≤ 12");
  if (realisations < 2) throw InputError("cascade", "realisations", "need at least 2");
  // each realisation fills and transforms a 2^levels × 2^levels field
  const double cells = static_cast<double>(realisations) * std::ldexp(1.0, 2 * levels);
  if (cells > 1e11)
    throw InputError("cascade", "realisations",
                     "realisations × 4^levels = " + std::to_string(cells) +
                         " field cells (hours of work); the limit is 10^11");
  if (n_max < 0 || n_max > (1 << (levels - 1)))
    throw InputError("cascade", "n_max", "need 0 ≤ n_max ≤ 2^(levels−1) (Nyquist)");
  if (!(box > 0.0)) throw InputError("cascade", "box", "must be positive");
}

namespace {

// |F(k)|² of one field on every half-plane mode, F = Σ m exp(−i k·r) (the sign is irrelevant)
class FieldTransform {
 public:
  FieldTransform(int levels, int n_max) : n_(1 << levels), modes_(rfm::half_plane_modes(n_max)) {
#if defined(GS_HAVE_FFTW)
    const std::size_t nc = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_ / 2 + 1);
    in_ = fftw_alloc_real(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_));
    out_ = fftw_alloc_complex(nc);
    std::lock_guard<std::mutex> lock(planner_mutex());  // the FFTW planner is not thread-safe
    plan_ = fftw_plan_dft_r2c_2d(n_, n_, in_, out_, FFTW_ESTIMATE);
#endif
  }
  ~FieldTransform() {
#if defined(GS_HAVE_FFTW)
    std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(plan_);
    fftw_free(in_);
    fftw_free(out_);
#endif
  }
  FieldTransform(const FieldTransform&) = delete;
  FieldTransform& operator=(const FieldTransform&) = delete;

  const std::vector<rfm::SkMode>& modes() const { return modes_; }

  /// S of every mode for the field m (row-major, y rows)
  std::vector<double> power(const std::vector<double>& m) {
    std::vector<double> s(modes_.size());
#if defined(GS_HAVE_FFTW)
    std::copy(m.begin(), m.end(), in_);
    fftw_execute(plan_);
    // r2c keeps k_x ≥ 0; a mode with n_x < 0 is the conjugate of (−n_x, −n_y)
    const int nh = n_ / 2 + 1;
    for (std::size_t i = 0; i < modes_.size(); ++i) {
      int kx = modes_[i].nx, ky = modes_[i].ny;
      if (kx < 0) {
        kx = -kx;
        ky = -ky;
      }
      const int row = (ky % n_ + n_) % n_;
      const fftw_complex& c = out_[static_cast<std::size_t>(row) * static_cast<std::size_t>(nh) +
                                   static_cast<std::size_t>(kx)];
      s[i] = c[0] * c[0] + c[1] * c[1];
    }
#else
    // separable direct transform: rows along x for every n_x, then columns along y
    const double w = 2.0 * std::numbers::pi / n_;
    int nm = 0;
    for (const auto& md : modes_) nm = std::max(nm, std::abs(md.nx));
    std::vector<std::complex<double> > rows(static_cast<std::size_t>(n_) * (2 * nm + 1));
    for (int y = 0; y < n_; ++y)
      for (int kx = -nm; kx <= nm; ++kx) {
        std::complex<double> acc = 0.0;
        for (int x = 0; x < n_; ++x)
          acc += m[static_cast<std::size_t>(y * n_ + x)] * std::polar(1.0, -w * kx * x);
        rows[static_cast<std::size_t>(y * (2 * nm + 1) + kx + nm)] = acc;
      }
    for (std::size_t i = 0; i < modes_.size(); ++i) {
      std::complex<double> acc = 0.0;
      for (int y = 0; y < n_; ++y)
        acc += rows[static_cast<std::size_t>(y * (2 * nm + 1) + modes_[i].nx + nm)] *
               std::polar(1.0, -w * modes_[i].ny * y);
      s[i] = std::norm(acc);
    }
#endif
    return s;
  }

 private:
  static std::mutex& planner_mutex() {
    static std::mutex m;
    return m;
  }
  int n_;
  std::vector<rfm::SkMode> modes_;
#if defined(GS_HAVE_FFTW)
  double* in_ = nullptr;
  fftw_complex* out_ = nullptr;
  fftw_plan plan_ = nullptr;
#endif
};

}  // namespace

CascadeResult cascade_structure_factor(const CascadeParams& p) {
  p.validate();
  const int n_max = p.n_max > 0 ? p.n_max : 1 << (p.levels - 1);
  FieldTransform ft(p.levels, n_max);
  std::vector<double> shell_sum, shell_sum2;
  std::vector<rfm::SkShell> layout;
  double ms = 0.0, ms2 = 0.0;
  for (long r = 0; r < p.realisations; ++r) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(r));
    const std::vector<double> m = cascade_field(p.kind, p.levels, rng);
    double mass = 0.0;
    for (double v : m) mass += v;
    ms += mass;
    ms2 += mass * mass;
    // this realisation's shell means (T.6.5, shell-averaged as in §4.1)
    rfm::ShellAccumulator acc(p.box, n_max);
    const std::vector<double> s = ft.power(m);
    for (std::size_t i = 0; i < s.size(); ++i) acc.add(ft.modes()[i].nx, ft.modes()[i].ny, s[i]);
    const auto shells = acc.shells();
    if (layout.empty()) {
      layout = shells;
      shell_sum.assign(shells.size(), 0.0);
      shell_sum2 = shell_sum;
    }
    for (std::size_t k = 0; k < shells.size(); ++k) {
      shell_sum[k] += shells[k].s;
      shell_sum2[k] += shells[k].s * shells[k].s;
    }
  }
  // the average over realisations, errors from their scatter
  const double nr = static_cast<double>(p.realisations);
  CascadeResult out;
  for (std::size_t k = 0; k < layout.size(); ++k) {
    rfm::SkShell sh = layout[k];
    sh.s = shell_sum[k] / nr;
    sh.s_err = std::sqrt(std::max(0.0, (shell_sum2[k] / nr - sh.s * sh.s) / (nr - 1.0)));
    sh.samples = sh.modes * p.realisations;
    out.shells.push_back(sh);
  }
  out.mass_mean = ms / nr;
  out.mass_err = std::sqrt(std::max(0.0, (ms2 / nr - out.mass_mean * out.mass_mean) / (nr - 1.0)));
  return out;
}

std::vector<rfm::SkShell> cascade_expected_sk(CascadeKind kind, int levels, int n_max, double box) {
  if (levels < 1 || n_max < 1) throw InputError("cascade_expected_sk", "levels", "need ≥ 1");
  const WeightMoments wm = cascade_weight_moments(kind);
  rfm::ShellAccumulator acc(box, n_max);
  // E|F|² by recursion from the finest cells up: F_c = Σ_q W_q e^(i k·δ_q) F_q with independent
  // children of mean μ and mean square s; δ_q the child's offset from its parent's centre
  for (const rfm::SkMode& md : rfm::half_plane_modes(n_max)) {
    const double kx = 2.0 * std::numbers::pi * md.nx / box,
                 ky = 2.0 * std::numbers::pi * md.ny / box;
    double s = 1.0;
    std::complex<double> mu = 1.0;
    for (int lev = levels; lev >= 1; --lev) {
      const double h = box / std::ldexp(1.0, lev);
      std::array<std::complex<double>, 4> ph;
      for (int q = 0; q < 4; ++q)
        ph[static_cast<std::size_t>(q)] =
            std::polar(1.0, kx * ((q % 2) - 0.5) * h + ky * ((q / 2) - 0.5) * h);
      double sn = 0.0;
      std::complex<double> mn = 0.0;
      for (std::size_t q = 0; q < 4; ++q) {
        mn += wm.mean[q] * ph[q] * mu;
        for (std::size_t p = 0; p < 4; ++p)
          sn += q == p ? wm.second[q][q] * s
                       : wm.second[q][p] * std::real(ph[q] * std::conj(ph[p])) * std::norm(mu);
      }
      s = sn;
      mu = mn;
    }
    acc.add(md.nx, md.ny, s);
  }
  auto shells = acc.shells();
  for (auto& sh : shells) sh.s_err = 0.0;  // exact: the spread within a shell is anisotropy
  return shells;
}

void write_cascade_csv(const RecordSink& sink, const std::filesystem::path& path,
                       const CascadeResult& r, const std::vector<rfm::SkShell>& exact,
                       CascadeKind kind, const rfm::DfFit* fit) {
  RecordMeta meta = {{"D2", correlation_dimension(kind)}, {"mass_mean", r.mass_mean}};
  if (fit) {
    meta.insert(meta.end(), {{"D_f", fit->d_f},
                             {"D_f_err", fit->d_f_err},
                             {"A", fit->amplitude},
                             {"k_lo", fit->k_lo},
                             {"k_hi", fit->k_hi},
                             {"chi2_r", fit->chi2_r}});
  }
  const auto w = sink.create(path.string(), {"k", "n", "S", "S_err", "S_exact"}, meta);
  for (std::size_t i = 0; i < r.shells.size(); ++i) {
    const double e = i < exact.size() ? exact[i].s : std::numeric_limits<double>::quiet_NaN();
    w->row({r.shells[i].k, r.shells[i].n, r.shells[i].s, r.shells[i].s_err, e});
  }
}

}  // namespace gs::models
