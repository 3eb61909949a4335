// T(t) in blocks of fixed duration: the block means and spreads against a direct computation on
// a known series, exact means and variances of periods made of whole blocks, the split at the
// steady start, and the table's metadata (τ_int and the error of the steady mean)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "analysis/rfm_blocks.hpp"
#include "analysis/rfm_csv.hpp"
#include "analysis/stats.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "output/csv.hpp"

namespace gs::rfm {
namespace {

// mean and sample standard deviation of x[a, b)
std::pair<double, double> direct(const std::vector<double>& x, std::size_t a, std::size_t b) {
  double m = 0.0;
  for (std::size_t i = a; i < b; ++i) m += x[i];
  m /= static_cast<double>(b - a);
  double ss = 0.0;
  for (std::size_t i = a; i < b; ++i) ss += (x[i] - m) * (x[i] - m);
  return {m, b - a > 1 ? std::sqrt(ss / static_cast<double>(b - a - 1)) : 0.0};
}

// samples every 1 ms (t = step·Δt, as a run writes them) of x_i = 3 + i²/1000 for
// i = 0…300, steady from i = 125: blocks of 50 ms hold 50 samples, the block holding the steady
// start is split 25 + 25, and the last sample (t = 0.3 s) opens a block of its own
struct Known {
  std::vector<double> t, x, steady;
  Known() {
    for (int i = 0; i <= 300; ++i) {
      t.push_back(static_cast<double>(i * 1000) * 1e-6);
      x.push_back(3.0 + i * i / 1000.0);
      steady.push_back(i >= 125 ? 1.0 : 0.0);
    }
  }
};

TEST(RfmBlocks, BlockMeansAndSpreadsMatchADirectComputation) {
  const Known k;
  const std::vector<TimeBlock> b = time_blocks(k.t, k.x, k.steady, 0.05);
  // first sample index of each block and whether it is steady
  const std::vector<std::size_t> start = {0, 50, 100, 125, 150, 200, 250, 300, 301};
  ASSERT_EQ(b.size(), start.size() - 1);
  for (std::size_t j = 0; j + 1 < start.size(); ++j) {
    const auto [m, sd] = direct(k.x, start[j], start[j + 1]);
    EXPECT_EQ(b[j].n, static_cast<double>(start[j + 1] - start[j])) << j;
    EXPECT_DOUBLE_EQ(b[j].t, k.t[start[j]]) << j;
    EXPECT_NEAR(b[j].mean, m, 1e-13 * m) << j;
    EXPECT_NEAR(b[j].sd, sd, 1e-11 * (sd + 1.0)) << j;
    EXPECT_EQ(b[j].steady, start[j] >= 125) << j;
  }
  EXPECT_EQ(b.back().sd, 0.0);  // one sample
}

TEST(RfmBlocks, PeriodsOfWholeBlocksHaveTheirExactMeanAndVariance) {
  // a noisy series: the steady part [0.125, 0.3] s from its blocks, as a report pools them
  const Known k;
  RngStream rng(7, 0);
  std::vector<double> x = k.x;
  for (double& v : x) v += rng.normal();
  const std::vector<TimeBlock> b = time_blocks(k.t, x, k.steady, 0.05);
  double n = 0.0, s = 0.0;
  for (const TimeBlock& q : b)
    if (q.steady) {
      n += q.n;
      s += q.n * q.mean;
    }
  const double m = s / n;
  double ss = 0.0;  // within the blocks and between them
  for (const TimeBlock& q : b)
    if (q.steady) ss += (q.n - 1.0) * q.sd * q.sd + q.n * (q.mean - m) * (q.mean - m);
  const auto [dm, dsd] = direct(x, 125, 301);
  EXPECT_EQ(n, 176.0);
  EXPECT_NEAR(m, dm, 1e-13 * dm);
  EXPECT_NEAR(std::sqrt(ss / (n - 1.0)), dsd, 1e-11 * dsd);
}

TEST(RfmBlocks, NoSteadyFlagsMeansAllSteadyAndBadInputIsNamed) {
  const Known k;
  const std::vector<TimeBlock> b = time_blocks(k.t, k.x, {}, 0.1);
  ASSERT_EQ(b.size(), 4u);  // 100 + 100 + 100 + the sample at 0.3 s
  for (const TimeBlock& q : b) EXPECT_TRUE(q.steady);
  EXPECT_EQ(b[2].n, 100.0);
  EXPECT_THROW(time_blocks(k.t, k.x, {}, 0.0), InputError);
  EXPECT_THROW(time_blocks(k.t, std::vector<double>(3, 1.0), {}, 0.1), InputError);
  std::vector<double> back = k.t;
  back[10] = 0.0;
  EXPECT_THROW(time_blocks(back, k.x, {}, 0.1), InputError);
}

TEST(RfmBlocks, TableCarriesTheSteadyMeanWithItsAutocorrelationError) {
  // an AR(1) steady series, x_i = a x_{i−1} + noise, a = 0.9: τ_int = (1 + a)/(2(1 − a)) = 9.5
  const std::size_t n = 20'000;
  RngStream rng(11, 0);
  std::vector<double> t(n), x(n);
  double v = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    v = 0.9 * v + rng.normal();
    t[i] = static_cast<double>(i) * 1e-3;
    x[i] = 1.0 + 0.1 * v;
  }
  const auto dir = std::filesystem::temp_directory_path() / "gs_rfm_blocks_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "temperature_blocks.csv";
  write_temperature_blocks_csv(csv_records(), path, time_blocks(t, x, {}, 0.05), 0.05, 1e-3, t, x);
  const CsvTable c = read_csv(path);
  std::filesystem::remove_all(dir);
  ASSERT_EQ(c.col("n").size(), n / 50);
  const double tau = autocorr_time(x).tau_int;
  const auto [m, sd] = direct(x, 0, n);
  EXPECT_EQ(c.meta.at("block"), 0.05);
  EXPECT_EQ(c.meta.at("samples"), static_cast<double>(n));
  EXPECT_EQ(c.meta.at("tau_int"), tau);
  // Sokal's window estimate over 20 000 samples: σ_τ ≈ τ√(2(2M + 1)/n) ≈ 1, within 3σ
  EXPECT_NEAR(tau, 9.5, 3.0);
  EXPECT_NEAR(c.meta.at("T_mean"), m, 1e-14);
  EXPECT_NEAR(c.meta.at("T_err"), sd * std::sqrt(2.0 * tau / static_cast<double>(n)), 1e-15);
  EXPECT_NEAR(c.col("T")[3], direct(x, 150, 200).first, 1e-13);
  // the halves: before and from the middle time (t_first + t_last)/2 = 9.9995 s, i.e. the
  // samples 0…9999 and 10 000…19 999
  const std::vector<double> a(x.begin(), x.begin() + 10'000), z(x.begin() + 10'000, x.end());
  EXPECT_EQ(c.meta.at("tau_int_first"), autocorr_time(a).tau_int);
  EXPECT_EQ(c.meta.at("tau_int_second"), autocorr_time(z).tau_int);
}

}  // namespace
}  // namespace gs::rfm
