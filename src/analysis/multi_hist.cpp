#include "analysis/multi_hist.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "analysis/stats.hpp"
#include "core/error.hpp"
#include "core/numbers.hpp"

namespace gs {

namespace {

// the pooled values of x in cells, and each run's count in each cell. A cell spans at most a
// hundredth of the narrowest run's standard deviation (and a 20000th of the pooled range), and
// sits at the mean of its values: the tilt of any run across it is then far below its
// statistical error (the bias of b is ≈ (cell/σ)²/12 relative), while the cells, not the taps,
// set the cost of every step of the joint fit. Values farther apart are cells of their own.
struct Pooled {
  std::vector<double> x;      ///< each cell's mean value
  std::vector<double> start;  ///< each cell's smallest value, increasing
  std::vector<std::vector<double>> counts;
  int cell(double v) const {
    return static_cast<int>(std::upper_bound(start.begin(), start.end(), v) - start.begin()) - 1;
  }
};

Pooled pool(const std::vector<std::vector<double>>& xs) {
  Pooled p;
  std::vector<double> all;
  double narrowest = std::numeric_limits<double>::infinity();
  for (const auto& v : xs) {
    all.insert(all.end(), v.begin(), v.end());
    const double s = stddev(v);
    if (s > 0.0) narrowest = std::min(narrowest, s);
  }
  std::sort(all.begin(), all.end());
  const double range = all.back() - all.front();
  const double width =
      std::max(std::isfinite(narrowest) ? narrowest / 100.0 : 0.0, range / 20000.0);
  double sum = 0.0;
  std::size_t in_cell = 0;
  for (double v : all) {
    if (in_cell > 0 && v > p.start.back() + width) {
      p.x.push_back(sum / static_cast<double>(in_cell));
      sum = 0.0;
      in_cell = 0;
    }
    if (in_cell == 0) p.start.push_back(v);
    sum += v;
    ++in_cell;
  }
  p.x.push_back(sum / static_cast<double>(in_cell));
  p.counts.assign(xs.size(), std::vector<double>(p.x.size(), 0.0));
  for (std::size_t k = 0; k < xs.size(); ++k)
    for (double v : xs[k]) p.counts[k][static_cast<std::size_t>(p.cell(v))] += 1.0;
  return p;
}

// runs linked to the reference through pairs that each hold ≥ 3 values in the other's range
std::vector<bool> linked_runs(const std::vector<std::vector<double>>& xs, int ref) {
  const int K = static_cast<int>(xs.size());
  // sorted copies: a count inside a range is then two binary searches
  std::vector<std::vector<double>> sorted(xs);
  for (auto& v : sorted) std::sort(v.begin(), v.end());
  auto inside = [&](int k, int l) {
    const auto& a = sorted[k];
    const double lo = sorted[l].front(), hi = sorted[l].back();
    return std::upper_bound(a.begin(), a.end(), hi) - std::lower_bound(a.begin(), a.end(), lo) >= 3;
  };
  std::vector<bool> c(K, false);
  c[ref] = true;
  // outwards from the reference, each run visited once
  std::vector<int> todo = {ref};
  while (!todo.empty()) {
    const int l = todo.back();
    todo.pop_back();
    for (int k = 0; k < K; ++k)
      if (!c[k] && inside(k, l) && inside(l, k)) {
        c[k] = true;
        todo.push_back(k);
      }
  }
  return c;
}

std::vector<double> inverse(const std::vector<double>& phi) {
  std::vector<double> x(phi.size());
  for (std::size_t i = 0; i < phi.size(); ++i) x[i] = 1.0 / phi[i];
  return x;
}

// the chain of neighbour fits summed from the reference outwards (input order)
std::vector<MultiBeta> sum_chain(const std::vector<int>& order,
                                 const std::vector<BetaEstimate>& links, int ref) {
  std::vector<MultiBeta> out(order.size());
  const int p_ref = static_cast<int>(std::find(order.begin(), order.end(), ref) - order.begin());
  out[ref].valid = true;
  for (int p = p_ref + 1; p < static_cast<int>(order.size()); ++p) {
    const MultiBeta& prev = out[order[p - 1]];
    const BetaEstimate& l = links[p - 1];
    MultiBeta& m = out[order[p]];
    m.valid = prev.valid && l.valid;
    m.dbeta = prev.dbeta + l.dbeta;
    m.dlnz = prev.dlnz + l.dlnz;
    m.dbeta_err = std::hypot(prev.dbeta_err, l.dbeta_err);
    m.dlnz_err = std::hypot(prev.dlnz_err, l.dlnz_err);
  }
  for (int p = p_ref - 1; p >= 0; --p) {
    const MultiBeta& next = out[order[p + 1]];
    const BetaEstimate& l = links[p];  // run order[p+1] against run order[p]
    MultiBeta& m = out[order[p]];
    m.valid = next.valid && l.valid;
    m.dbeta = next.dbeta - l.dbeta;
    m.dlnz = next.dlnz - l.dlnz;
    m.dbeta_err = std::hypot(next.dbeta_err, l.dbeta_err);
    m.dlnz_err = std::hypot(next.dlnz_err, l.dlnz_err);
  }
  return out;
}

std::vector<BetaEstimate> chain_links(const std::vector<std::vector<double>>& phi,
                                      const std::vector<int>& order, double v_g,
                                      const MultiHistOptions& opts) {
  std::vector<BetaEstimate> links;
  for (std::size_t p = 0; p + 1 < order.size(); ++p) {
    const auto& a = phi[order[p]];
    const auto& b = phi[order[p + 1]];
    OverlapOptions o = opts.overlap;
    if (o.bins == 0 && opts.chain_bins_per_scott > 1) {
      // Scott's width of the pair, as q_fit takes it, divided
      const double w = 3.49 * std::min(stddev(a) * std::pow(double(a.size()), -1.0 / 3.0),
                                       stddev(b) * std::pow(double(b.size()), -1.0 / 3.0));
      const auto [lo_a, hi_a] = std::minmax_element(a.begin(), a.end());
      const auto [lo_b, hi_b] = std::minmax_element(b.begin(), b.end());
      const double range = std::max(*hi_a, *hi_b) - std::min(*lo_a, *lo_b);
      if (w > 0.0)
        o.bins =
            std::clamp(static_cast<int>(std::ceil(range / w)) * opts.chain_bins_per_scott, 5, 2000);
    }
    BetaEstimate l = beta_from_phi(a, b, v_g, o);
    if (opts.tau_int.size() == phi.size())
      l = with_variance_factor(l, opts.tau_int[order[p]] + opts.tau_int[order[p + 1]]);
    links.push_back(std::move(l));
  }
  return links;
}

// a moving-block bootstrap resample of a series of n values: the indices it takes
std::vector<int> resample(int n, int block, std::mt19937_64& rng) {
  block = std::clamp(block, 1, n);
  std::uniform_int_distribution<int> start(0, n - block);
  std::vector<int> out;
  out.reserve(static_cast<std::size_t>(n + block));
  while (static_cast<int>(out.size()) < n) {
    const int s = start(rng);
    for (int i = s; i < s + block; ++i) out.push_back(i);
  }
  out.resize(static_cast<std::size_t>(n));
  return out;
}

// the covariance of the replicas' columns, each pair over the replicas that reached both
// (n − 1 in the denominator, as stddev); NaN where fewer than `need` did
std::vector<std::vector<double>> replica_covariance(const std::vector<std::vector<double>>& rows,
                                                    std::size_t need) {
  const std::size_t Q = rows.empty() ? 0 : rows.front().size();
  std::vector<std::vector<double>> c(Q, std::vector<double>(Q, kNaN));
  for (std::size_t a = 0; a < Q; ++a)
    for (std::size_t b = a; b < Q; ++b) {
      double n = 0.0, ma = 0.0, mb = 0.0;
      for (const auto& w : rows)
        if (std::isfinite(w[a]) && std::isfinite(w[b])) n += 1.0, ma += w[a], mb += w[b];
      if (n < static_cast<double>(need) || n < 2.0) continue;
      ma /= n, mb /= n;
      double s = 0.0;
      for (const auto& w : rows)
        if (std::isfinite(w[a]) && std::isfinite(w[b])) s += (w[a] - ma) * (w[b] - mb);
      c[a][b] = c[b][a] = s / (n - 1.0);
    }
  return c;
}

}  // namespace

JointFit joint_histogram_fit(const std::vector<std::vector<double>>& counts,
                             const std::vector<double>& x, int ref,
                             const std::vector<double>& b_start, int max_iterations,
                             double tolerance, const std::vector<bool>& connected,
                             const std::vector<double>& dlnz_start) {
  const int K = static_cast<int>(counts.size());
  const int B = static_cast<int>(x.size());
  JointFit f;
  f.b.assign(K, kNaN);
  f.dlnz.assign(K, kNaN);
  f.connected.assign(K, false);

  // which runs reach the reference through bins that two runs share (unless given)
  f.connected[ref] = true;
  if (connected.size() == static_cast<std::size_t>(K)) f.connected = connected;
  for (bool grew = connected.empty(); grew;) {
    grew = false;
    for (int k = 0; k < K; ++k) {
      if (f.connected[k]) continue;
      for (int l = 0; l < K && !f.connected[k]; ++l)
        if (f.connected[l])
          for (int j = 0; j < B; ++j)
            if (counts[k][j] > 0.0 && counts[l][j] > 0.0) {
              f.connected[k] = grew = true;
              break;
            }
    }
  }
  std::vector<int> use;  // the reference first: its f and b are fixed at 0 (the gauge)
  use.push_back(ref);
  for (int k = 0; k < K; ++k)
    if (f.connected[k] && k != ref) use.push_back(k);
  const int U = static_cast<int>(use.size());
  std::vector<int> bins;
  std::vector<double> total(B, 0.0), n_run(U, 0.0);
  for (int j = 0; j < B; ++j) {
    for (int u = 0; u < U; ++u) total[j] += counts[use[u]][j];
    if (total[j] > 0.0) bins.push_back(j);
  }
  for (int u = 0; u < U; ++u)
    for (int j : bins) n_run[u] += counts[use[u]][j];
  std::vector<double> ln_n(U);
  for (int u = 0; u < U; ++u) ln_n[u] = std::log(n_run[u]);

  // the convex objective of the multiple-histogram likelihood (as MBAR's), with
  // a_kj = f_k − b_k x_j: F = Σ_j T_j ln Σ_k N_k e^{a_kj} − Σ_kj c_kj a_kj; its minimum has
  // f_k = −ln Z_k and every run's model mean of x equal to its sample mean
  const int P = 2 * (U - 1);  // (f_k, b_k) of every run but the reference
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(P);
  const double x0 = x.empty() ? 0.0 : x[bins.empty() ? 0 : bins[bins.size() / 2]];
  // a warm start (a bootstrap replica starts from the full sample's answer): f_k = −ln Z_k − b_k x0
  for (int u = 1; u < U; ++u) {
    const int k = use[u];
    if (b_start.size() == static_cast<std::size_t>(K) && std::isfinite(b_start[k])) {
      theta[2 * (u - 1) + 1] = b_start[k];
      if (dlnz_start.size() == static_cast<std::size_t>(K) && std::isfinite(dlnz_start[k]))
        theta[2 * (u - 1)] = -dlnz_start[k] - b_start[k] * x0;
    }
  }
  auto exponent = [&](const Eigen::VectorXd& t, int u, int j) {
    if (u == 0) return 0.0;
    return t[2 * (u - 1)] - t[2 * (u - 1) + 1] * (x[j] - x0);  // x centred: f stays O(1)
  };
  std::vector<double> p(U);
  // the Hessian's sums Σ_j T_j p_uj p_vj dx_j^k (k = 0, 1, 2) as three matrix products over
  // the cells (vectorised), where a loop per cell over every pair of runs is not
  Eigen::MatrixXd pw(U, static_cast<Eigen::Index>(bins.size()));
  Eigen::VectorXd w0(static_cast<Eigen::Index>(bins.size())), w1(w0.size()), w2(w0.size());
  auto objective = [&](const Eigen::VectorXd& t, Eigen::VectorXd* grad, Eigen::MatrixXd* hess) {
    double F = 0.0;
    f.terms += static_cast<std::int64_t>(bins.size()) * U;
    if (grad) grad->setZero(P);
    if (hess) hess->setZero(P, P);
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const int j = bins[i];
      double m = -std::numeric_limits<double>::infinity();
      for (int u = 0; u < U; ++u) {
        p[u] = ln_n[u] + exponent(t, u, j);
        m = std::max(m, p[u]);
      }
      double s = 0.0;
      // a run e⁻⁴⁵ below the cell's largest weighs nothing next to it (10⁻¹⁹)
      for (int u = 0; u < U; ++u) s += (p[u] = p[u] - m > -45.0 ? std::exp(p[u] - m) : 0.0);
      F += total[j] * (m + std::log(s));
      for (int u = 0; u < U; ++u) {
        p[u] /= s;
        F -= counts[use[u]][j] * exponent(t, u, j);
      }
      if (!grad) continue;
      const double dx = x[j] - x0;
      for (int u = 1; u < U; ++u) {
        const double r = total[j] * p[u] - counts[use[u]][j];
        (*grad)[2 * (u - 1)] += r;
        (*grad)[2 * (u - 1) + 1] -= r * dx;
      }
      if (!hess) continue;
      for (int u = 0; u < U; ++u) pw(u, static_cast<Eigen::Index>(i)) = p[u];
      w0[static_cast<Eigen::Index>(i)] = total[j];
      w1[static_cast<Eigen::Index>(i)] = total[j] * dx;
      w2[static_cast<Eigen::Index>(i)] = total[j] * dx * dx;
    }
    if (hess && U > 1) {
      // h_uv^(k) = Σ_j w_k,j (δ_uv p_uj − p_uj p_vj)
      const Eigen::MatrixXd h0 =
          (pw * w0).asDiagonal().toDenseMatrix() - pw * w0.asDiagonal() * pw.transpose();
      const Eigen::MatrixXd h1 =
          (pw * w1).asDiagonal().toDenseMatrix() - pw * w1.asDiagonal() * pw.transpose();
      const Eigen::MatrixXd h2 =
          (pw * w2).asDiagonal().toDenseMatrix() - pw * w2.asDiagonal() * pw.transpose();
      for (int u = 1; u < U; ++u)
        for (int v = 1; v < U; ++v) {
          const int a = 2 * (u - 1), c = 2 * (v - 1);
          (*hess)(a, c) += h0(u, v);
          (*hess)(a, c + 1) -= h1(u, v);
          (*hess)(a + 1, c) -= h1(u, v);
          (*hess)(a + 1, c + 1) += h2(u, v);
        }
    }
    return F;
  };

  // Newton's method with a backtracking line search (the objective is convex)
  const double x_range = bins.empty() ? 1.0 : std::max(x[bins.back()] - x[bins.front()], 1e-300);
  Eigen::VectorXd grad(P), step(P);
  Eigen::MatrixXd hess(P, P);
  f.converged = P == 0;
  for (f.iterations = 0; f.iterations < max_iterations && !f.converged; ++f.iterations) {
    const double F = objective(theta, &grad, &hess);
    // a tiny ridge keeps the step defined for a run whose bins carry no information on b
    hess.diagonal().array() += 1e-12 * (1.0 + hess.diagonal().array().abs());
    step = hess.ldlt().solve(-grad);
    double t = 1.0;
    Eigen::VectorXd next = theta + step;
    while (t > 1e-10 && !(objective(next, nullptr, nullptr) <= F + 1e-4 * t * grad.dot(step))) {
      t *= 0.5;
      next = theta + t * step;
    }
    double moved = 0.0;
    for (int u = 1; u < U; ++u)
      moved = std::max(moved, std::abs(t * step[2 * (u - 1) + 1]) * x_range);
    theta = next;
    if (moved < tolerance) f.converged = true;
  }
  // b_k, and ln Z_k − ln Z_ref with the centring undone: ln Z_k = −f_k − b_k x0
  for (int u = 0; u < U; ++u) {
    const int k = use[u];
    const double fk = u == 0 ? 0.0 : theta[2 * (u - 1)];
    f.b[k] = u == 0 ? 0.0 : theta[2 * (u - 1) + 1];
    f.dlnz[k] = -fk - f.b[k] * x0;
  }
  return f;
}

MultiHistResult multi_histogram_beta(const std::vector<std::vector<double>>& phi, int ref,
                                     double v_g, const MultiHistOptions& opts) {
  const int K = static_cast<int>(phi.size());
  if (K < 2) throw InputError("", "runs", "the multiple-histogram estimate needs two runs or more");
  if (ref < 0 || ref >= K) throw InputError("", "reference", "no such run");
  if (!(v_g > 0.0)) throw InputError("", "v_g", "must be > 0 (m²)");
  for (int k = 0; k < K; ++k) {
    if (phi[k].size() < 3)
      throw InputError("", "runs", "run " + std::to_string(k) + " has fewer than 3 taps");
    for (double v : phi[k])
      if (!(v > 0.0 && v <= 1.0))
        throw InputError(
            "", "phi",
            "run " + std::to_string(k) + ": φ = " + std::to_string(v) + " is not in (0, 1]");
  }
  MultiHistResult r;

  // the chain: runs by φ̄, each fitted against its neighbour below
  std::vector<double> means(K);
  for (int k = 0; k < K; ++k) means[k] = mean(phi[k]);
  r.order.resize(K);
  std::iota(r.order.begin(), r.order.end(), 0);
  std::stable_sort(r.order.begin(), r.order.end(),
                   [&](int a, int b) { return means[a] < means[b]; });
  r.links = chain_links(phi, r.order, v_g, opts);
  r.chain = sum_chain(r.order, r.links, ref);
  for (std::size_t p = 0; p < r.links.size(); ++p)
    if (!r.links[p].valid)
      r.notes.push_back("chain: runs " + std::to_string(r.order[p]) + " and " +
                        std::to_string(r.order[p + 1]) + " do not overlap (" + r.links[p].fit.note +
                        ")");

  // the joint fit on the pooled values of x = 1/φ (cells far finer than any run's spread)
  std::vector<std::vector<double>> xs(K);
  for (int k = 0; k < K; ++k) xs[k] = inverse(phi[k]);
  const std::vector<bool> linked = linked_runs(xs, ref);
  const Pooled pooled = pool(xs);
  r.values = static_cast<int>(pooled.x.size());
  r.joint.assign(K, MultiBeta{});
  const JointFit jf = joint_histogram_fit(pooled.counts, pooled.x, ref, {}, opts.max_iterations,
                                          opts.tolerance, linked);
  r.joint_converged = jf.converged;
  r.terms = jf.terms;
  r.joint_iterations = jf.iterations;
  for (int k = 0; k < K; ++k) {
    r.joint[k].valid = jf.connected[k] && jf.converged;
    r.joint[k].dbeta = jf.b[k] / v_g;
    r.joint[k].dlnz = jf.dlnz[k];
    if (!jf.connected[k])
      r.notes.push_back("joint fit: run " + std::to_string(k) +
                        " does not overlap the runs linked to the reference");
  }
  if (opts.step) opts.step();
  if (!jf.converged)
    r.notes.push_back("joint fit: not converged after " + std::to_string(jf.iterations) +
                      " Newton steps");

  // errors: a moving-block bootstrap over taps, the binning held fixed
  // (without a bootstrap the chain keeps the links' own errors added in quadrature, which
  // ignore that neighbouring links share a run; the joint fit has none)
  for (MultiBeta& m : r.joint) m.dbeta_err = m.dlnz_err = kNaN;
  if (opts.bootstrap > 0)
    for (MultiBeta& m : r.chain) m.dbeta_err = m.dlnz_err = kNaN;
  if (opts.bootstrap > 0) {
    std::mt19937_64 rng(opts.seed);
    std::vector<std::vector<double>> cb(K), cz(K), jb(K), jz(K);
    std::vector<std::vector<double>> sample(K);
    // each value's cell, found once: a replica's counts are then tallied in O(n) on the
    // pooled cells (the cells it lacks have no count, and the joint fit skips them), where
    // pooling each replica again would sort it
    std::vector<std::vector<int>> place(K);
    for (int k = 0; k < K; ++k)
      for (double v : xs[k]) place[k].push_back(pooled.cell(v));
    std::vector<std::vector<double>> counts(K, std::vector<double>(pooled.x.size(), 0.0));
    // every replica's β̂ of each block (joint, then direct per reference), for the covariance
    const int D = static_cast<int>(opts.direct_refs.size());
    for (int d : opts.direct_refs)
      if (d < 0 || d >= K) throw InputError("", "direct_refs", "no such run");
    std::vector<std::vector<double>> rows;
    for (int rep = 0; rep < opts.bootstrap; ++rep) {
      for (int k = 0; k < K; ++k) {
        const double tau =
            opts.tau_int.size() == static_cast<std::size_t>(K) ? opts.tau_int[k] : 0.5;
        const std::vector<int> take = resample(static_cast<int>(phi[k].size()),
                                               static_cast<int>(std::lround(2.0 * tau)), rng);
        sample[k].resize(take.size());
        std::fill(counts[k].begin(), counts[k].end(), 0.0);
        for (std::size_t i = 0; i < take.size(); ++i) {
          sample[k][i] = phi[k][static_cast<std::size_t>(take[i])];
          counts[k][static_cast<std::size_t>(place[k][static_cast<std::size_t>(take[i])])] += 1.0;
        }
      }
      MultiHistOptions o = opts;
      const auto links = chain_links(sample, r.order, v_g, o);
      const auto chain = sum_chain(r.order, links, ref);
      for (int k = 0; k < K; ++k)
        if (chain[k].valid) cb[k].push_back(chain[k].dbeta), cz[k].push_back(chain[k].dlnz);
      std::vector<double> row(static_cast<std::size_t>((1 + D) * K), kNaN);
      {
        const JointFit f = joint_histogram_fit(counts, pooled.x, ref, jf.b, opts.max_iterations,
                                               opts.tolerance, linked, jf.dlnz);
        r.terms += f.terms;
        if (f.converged)
          for (int k = 0; k < K; ++k)
            if (f.connected[k]) {
              jb[k].push_back(f.b[k] / v_g), jz[k].push_back(f.dlnz[k]);
              row[static_cast<std::size_t>(k)] = f.b[k] / v_g;
            }
      }
      for (int i = 0; i < D; ++i) {
        const int d = opts.direct_refs[static_cast<std::size_t>(i)];
        const auto direct = betas_from_phi(sample[d], sample, v_g, opts.overlap);
        for (int k = 0; k < K; ++k)
          if (k == d || direct[k].valid)
            row[static_cast<std::size_t>((1 + i) * K + k)] = k == d ? 0.0 : direct[k].dbeta;
      }
      rows.push_back(std::move(row));
      if (opts.step) opts.step();
    }
    // a run's error needs most replicas to have reached it
    const std::size_t need = static_cast<std::size_t>(opts.bootstrap) / 2 + 1;
    for (int k = 0; k < K; ++k) {
      if (cb[k].size() >= need)
        r.chain[k].dbeta_err = stddev(cb[k]), r.chain[k].dlnz_err = stddev(cz[k]);
      if (jb[k].size() >= need)
        r.joint[k].dbeta_err = stddev(jb[k]), r.joint[k].dlnz_err = stddev(jz[k]);
    }
    r.cov = replica_covariance(rows, need);
    r.chain[ref].dbeta_err = r.chain[ref].dlnz_err = 0.0;
    r.joint[ref].dbeta_err = r.joint[ref].dlnz_err = 0.0;
    r.replicas = opts.bootstrap;
  }
  return r;
}

}  // namespace gs
