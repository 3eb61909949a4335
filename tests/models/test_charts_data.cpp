// writes every CSV that gransim.charts.rfm draws, from models and synthetic data, and reads
// them back. The directory is $GS_RFM_CSV_DIR, or gs_rfm_charts in the temporary directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <vector>

#include "analysis/rfm_csv.hpp"
#include "analysis/rfm_freepath.hpp"
#include "analysis/rfm_gaps.hpp"
#include "analysis/rfm_gr.hpp"
#include "analysis/rfm_moments.hpp"
#include "analysis/rfm_sk.hpp"
#include "analysis/rfm_tails.hpp"
#include "models/bisection.hpp"
#include "models/cascade.hpp"
#include "models/walks.hpp"
#include "output/csv.hpp"

namespace gs::models {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() {
  const char* e = std::getenv("GS_RFM_CSV_DIR");
  fs::path d = e && *e ? fs::path(e) : fs::temp_directory_path() / "gs_rfm_charts";
  fs::create_directories(d);
  return d;
}

// N points drawn from a UCP cascade measure: a cell by its mass, then uniform inside it
std::vector<Vec2> cascade_points(int levels, int n, RngStream& rng) {
  const auto m = cascade_field(CascadeKind::ucp, levels, rng);
  std::vector<double> cdf(m.size());
  double s = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i) cdf[i] = (s += m[i]);
  const int side = 1 << levels;
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    const auto c =
        static_cast<int>(std::lower_bound(cdf.begin(), cdf.end(), rng.uniform() * s) - cdf.begin());
    p.push_back({((c % side) + rng.uniform()) / side, ((c / side) + rng.uniform()) / side});
  }
  return p;
}

TEST(ChartsData, WritesEveryCsv) {
  const fs::path dir = out_dir();
  RngStream rng(2024, 0);

  // T(t): 500 particles with noise and a linear drag relax to T = 2 D_v/γ (/(1 − γΔt/2))
  {
    const double dt = 1e-3, gamma = 2.0, kick = std::sqrt(2.0 * dt);
    std::vector<Vec2> v(500);
    for (Vec2& u : v) u = {0.1 * rng.uniform(-0.5, 0.5), 0.1 * rng.uniform(-0.5, 0.5)};
    std::vector<double> t, temp;
    for (int rec = 0; rec < 2000; ++rec) {
      for (int s = 0; s < 10; ++s)
        for (Vec2& u : v) {
          double z0, z1;
          rng.normal_pair(z0, z1);
          u = u * (1.0 - gamma * dt) + Vec2{z0, z1} * kick;
        }
      t.push_back((rec + 1) * 10 * dt);
      temp.push_back(rfm::granular_temperature(v));
    }
    const rfm::BlockAverage b = rfm::block_average(temp, 100);
    rfm::write_temperature_csv(csv_records(), dir / "temperature.csv", t, temp, &b);
    // the second half is in the steady state: mean within 3 % of 2/γ·(1 − 1/N)/(1 − γΔt/2)
    const std::vector<double> late(b.block_means.begin() + 10, b.block_means.end());
    double m = 0.0;
    for (double x : late) m += x;
    EXPECT_NEAR(m / late.size(), (2.0 / gamma) * (1.0 - 1.0 / 500) / (1.0 - gamma * dt / 2), 0.03);
  }

  // P(v): a crossover distribution (T.5.32, v_r = 1, v_c = 1.5) with its fits and ln–ln plots
  {
    const double vr = 1.0, vc = 1.5;
    std::vector<double> grid, cdf{0.0};
    const double dv = 1e-3;
    for (double a = -40.0; a < 40.0; a += dv) {
      grid.push_back(a);
      cdf.push_back(cdf.back() + rfm::crossover_density(a + 0.5 * dv, 1.0, vr, vc, 1.0) * dv);
    }
    grid.push_back(40.0);
    rfm::Histogram h = rfm::velocity_histogram(20.0, 800);
    for (int k = 0; k < 2'000'000; ++k) {
      const double u = rng.uniform() * cdf.back();
      const auto i =
          static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1;
      h.add(grid[i] + dv * (u - cdf[i]) / (cdf[i + 1] - cdf[i]));
    }
    rfm::TailFitOptions opt;
    opt.v_abs_min = 2.0;
    const rfm::TailFit tail = rfm::fit_tail(h, opt);
    const rfm::CrossoverFit cross = rfm::fit_crossover(h);
    rfm::write_velocity_csv(csv_records(), dir / "velocity.csv", h, &tail, &cross);
    rfm::write_tail_scan_csv(csv_records(), dir / "tail_scan.csv", tail);
    // ln–ln with the asymptotic amplitude A₀ = D exp(v_c²/v_r²) (§5.3.3) and with P(0)
    const double a0 = cross.d * std::exp(cross.v_c * cross.v_c / (cross.v_r * cross.v_r));
    double v2 = 0.0;
    for (const auto& b : h.bins()) v2 += b.count * b.x * b.x;
    const double vrms = std::sqrt(v2 / h.total());
    rfm::write_lnln_csv(csv_records(), dir / "lnln_A0.csv", rfm::lnln_tail(h, a0, vrms, 50.0), a0,
                        vrms);
    rfm::write_lnln_csv(csv_records(), dir / "lnln_P0.csv", rfm::lnln_tail(h, cross.d, vrms, 50.0),
                        cross.d, vrms);
    const rfm::CsvTable t = rfm::read_csv(dir / "velocity.csv");
    EXPECT_EQ(t.meta.at("cross_v_c"), cross.v_c);
    EXPECT_EQ(t.column.at("P").size(), 800u);
  }

  // S(k) and g(R) of points on a UCP cascade measure, with an RFM-style D_f fit below k_D
  {
    rfm::StructureFactor2D sk(1.0, 48);
    rfm::PairCorrelation2D gr(1.0, 0.5, 100);
    for (int s = 0; s < 10; ++s) {
      const auto pts = cascade_points(8, 4000, rng);
      sk.add_snapshot(pts);
      gr.add_snapshot(pts);
    }
    rfm::RfmSystem sys;  // d = 0.05 puts k_D near |n| = 16 for N = 4000, L = 1
    sys.box = 1.0;
    sys.n = 4000;
    sys.diameter = 0.05;
    sys.eps_n = sys.eps_t = 0.1;
    const auto shells = sk.shells();
    const rfm::DfFit f = rfm::fit_df_rfm(shells, sys);
    rfm::write_sk_csv(csv_records(), dir / "sk.csv", shells, &f);
    rfm::write_gr_csv(csv_records(), dir / "gr.csv", gr.bins());
    EXPECT_GT(f.d_f, 1.3);
    EXPECT_LT(f.d_f, 1.9);
  }

  // G_h(R) of bisection boundaries (N = 2¹⁰) and the bisection histogram against T.3.36
  {
    rfm::GapStatistics g(rfm::Binning::log(1e-9, 1.0, 60));
    for (int s = 0; s < 200; ++s) {
      const auto seg = bisect(10, rng);
      std::vector<double> r{0.0};
      for (std::size_t i = 0; i + 1 < seg.size(); ++i) r.push_back(r.back() + seg[i]);
      g.add_snapshot(r, 1.0);
    }
    rfm::write_gh_csv(csv_records(), dir / "gh.csv", g);
    BisectionParams bp;
    bp.realisations = 1000;
    write_bisection_csv(csv_records(), dir / "bisection.csv", run_bisection(bp));
  }

  // P_l(l): Weibull free paths with the thesis' D_f = 1.63 and its fit (T.4.25)
  {
    rfm::Histogram h = rfm::free_path_histogram(1e-7, 1e-1, 60);
    for (int i = 0; i < 500'000; ++i) h.add(std::pow(-std::log(rng.uniform()) / 121.0, 1.0 / 0.63));
    const rfm::FreePathFit f = rfm::fit_free_paths(h);
    rfm::write_freepath_csv(csv_records(), dir / "freepath.csv", h, &f);
  }

  // single-particle walks: Q(v, l) for two radii (collapse in v/l^(1/3)) and free heating
  {
    WalkParams p;
    p.noise = 1.0;
    p.mass = 1.0;
    p.dt = 2e-3;
    p.walks = 4000;
    for (double l : {1.0, 8.0}) {
      p.v_max = 8.0 * walk_velocity_scale(p, l);
      write_walk_csv(csv_records(), dir / (l == 1.0 ? "walk_l1.csv" : "walk_l8.csv"),
                     disc_walk(p, l), p, l);
    }
    p.dt = 1e-3;
    write_heating_csv(csv_records(), dir / "heating.csv", free_heating(p, 2, 1000, 2000, 50), p);
    // appendix B: arrivals at x = L against B.32 (thesis Fig. B.1)
    p.walks = 20000;
    p.v_max = 5.0;
    p.bins = 100;
    write_interval_csv(csv_records(), dir / "interval.csv",
                       interval_walk(p, 1.0, IntervalStart::uniform), p, 1.0);
  }

  // cascade S(k): UCP, 8 levels, with the exact expectation and the mid-range fit
  {
    CascadeParams cp;
    cp.levels = 8;
    cp.realisations = 40;
    const CascadeResult r = cascade_structure_factor(cp);
    const auto exact = cascade_expected_sk(cp.kind, 8, 128);
    const double two_pi = 2.0 * std::numbers::pi;
    const rfm::DfFit f = rfm::fit_df(r.shells, two_pi * 4.0 - 1e-9, two_pi * 32.0 + 1e-9);
    write_cascade_csv(csv_records(), dir / "cascade_ucp.csv", r, exact, cp.kind, &f);
  }

  // every file is there and parses
  for (const char* name :
       {"temperature.csv", "velocity.csv", "tail_scan.csv", "lnln_A0.csv", "lnln_P0.csv", "sk.csv",
        "gr.csv", "gh.csv", "bisection.csv", "freepath.csv", "walk_l1.csv", "walk_l8.csv",
        "heating.csv", "interval.csv", "cascade_ucp.csv"}) {
    const rfm::CsvTable t = rfm::read_csv(dir / name);
    EXPECT_FALSE(t.names.empty()) << name;
    EXPECT_FALSE(t.column.at(t.names[0]).empty()) << name;
  }
}

}  // namespace
}  // namespace gs::models
