// the RFM observer on a tiny 2D run through `gransim run` (run_command): every file is
// written, and the values are sane and consistent with each other — the moments agree with
// the temperature series (⟨|v|²⟩ in the centre-of-mass frame is T, T.2.19), histograms are
// normalised, S(k) tends to 1 at large k, g(R) is empty inside a diameter and peaks at contact,
// free paths are of the order of the mean free path, post-collision samples match the contacts
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "analysis/rfm_csv.hpp"
#include "app/run/run.hpp"
#include "app/run/run_info.hpp"
#include "measure/rfm_io.hpp"
#include "measure/rfm_observer.hpp"
#include "output/csv.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "sim/step_inspector.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// 200 beads in a 6 cm box (φ = 0.39), ε = 0.6; 0.01 s transient, then 0.03 s sampled every
// 200 steps (150 samples)
constexpr const char* kTiny2D = R"(
[scene]
name = "rfm_tiny"
duration = 0.04
[model]
kind = "S"
rotation = false
[[material]]
name = "glass"
eps_n = 0.6
eps_t = 0.6
mu = 0.0
[[species]]
name = "bead"
radius = 0.0015
mass = 3.53e-5
count = 200
[box]
kind = "periodic"
width = 0.06
[preparation]
placement = "uniform"
seed = 4
velocity_amplitude = 0.5
[drive]
kind = "random_force"
[rfm]
sample_every = 200
discard_time = 0.01
blocks = 5
)";

struct TinyRun {
  fs::path dir;
  // `edit`: replacements in the scene text, and text appended to it
  explicit TinyRun(const std::vector<std::pair<std::string, std::string>>& edit = {},
                   const std::string& append = "", const std::string& tag = "") {
    dir = fs::temp_directory_path() / ("gs_rfm_obs_" + std::to_string(::getpid()) + tag);
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string text = kTiny2D;
    for (const auto& [from, to] : edit) {
      const std::size_t at = text.find(from);
      if (at != std::string::npos) text.replace(at, from.size(), to);
    }
    std::ofstream(dir / "tiny.toml") << text << append;
    RunOptions o;
    o.scene = (dir / "tiny.toml").string();
    o.out = (dir / "run").string();
    o.quiet = true;
    code = run_command(o);
  }
  ~TinyRun() { fs::remove_all(dir); }
  double json(const std::string& key) const {
    const auto text = read_text_file((dir / "run" / "rfm.json").string());
    const auto v = text ? json_number_field(*text, key) : std::nullopt;
    return v ? *v : NAN;
  }
  rfm::CsvTable csv(const std::string& name) const { return rfm::read_csv(dir / "run" / name); }
  int code = -1;
};

TEST(RfmObserver, TinyRunWritesSaneFiles) {
  TinyRun r;
  ASSERT_EQ(r.code, 0);
  for (const char* f : {"rfm.json", "rfm_series.csv", "temperature.csv", "moments.csv",
                        "moments_components.csv", "hist_velocity.csv", "hist_postcollision.csv",
                        "hist_freepath.csv", "velocity.csv", "freepath.csv", "sk.csv", "gr.csv"})
    EXPECT_TRUE(fs::exists(r.dir / "run" / f)) << f;
  EXPECT_EQ(r.json("dimension"), 2.0);
  EXPECT_EQ(r.json("particles"), 200.0);
  EXPECT_NEAR(r.json("phi"), 200 * M_PI * 1.5e-3 * 1.5e-3 / (0.06 * 0.06), 1e-12);

  // temperature: 151 steady samples (t = 0.01 … 0.04), positive; the mean of rfm.json is the
  // mean of the file's samples (5 equal blocks of 30 and one dropped sample)
  const rfm::CsvTable t = r.csv("temperature.csv");
  const auto& T = t.column.at("T");
  ASSERT_EQ(T.size(), 151u);
  EXPECT_EQ(r.json("samples"), 151.0);
  for (double x : T) EXPECT_GT(x, 0.0);
  const double t_mean = std::accumulate(T.begin(), T.begin() + 150, 0.0) / 150.0;
  EXPECT_NEAR(r.json("T_mean"), t_mean, 1e-12 * t_mean);
  // a driven dissipative fluid: between the ε = 0.6 steady value ~0.1–0.3 m²/s² (docs/physics.md
  // §8.5) and the noise-only bound (initial + 4D/M²·t = 0.04 + 1.3 m²/s²)
  EXPECT_GT(t_mean, 0.01);
  EXPECT_LT(t_mean, 1.4);

  // the end-of-run tables come through the writer of the series (the one CSV writer): the text
  // of each steady sample's t and T in temperature.csv is, character for character, that of
  // the same sample in rfm_series.csv
  {
    auto lines = [&](const char* name) {
      std::ifstream in(r.dir / "run" / name);
      std::vector<std::string> out;
      for (std::string l; std::getline(in, l);) out.push_back(l);
      return out;
    };
    auto cells = [](const std::string& line) {
      std::vector<std::string> c;
      std::size_t at = 0;
      for (std::size_t k; (k = line.find(',', at)) != std::string::npos; at = k + 1)
        c.push_back(line.substr(at, k - at));
      c.push_back(line.substr(at));
      return c;
    };
    const auto temp = lines("temperature.csv"), series = lines("rfm_series.csv");
    ASSERT_EQ(cells(series.at(0)).at(2), "T");
    std::map<std::string, std::string> t_of_series;  // t → T, as written
    for (std::size_t i = 1; i < series.size(); ++i) {
      const auto c = cells(series[i]);
      if (c.at(8) == "1") t_of_series[c.at(0)] = c.at(2);
    }
    ASSERT_EQ(temp.size(), 152u);
    for (std::size_t i = 1; i < temp.size(); ++i) {
      const auto c = cells(temp[i]);
      ASSERT_EQ(t_of_series.count(c.at(0)), 1u) << temp[i];
      EXPECT_EQ(t_of_series[c.at(0)], c.at(1)) << "t = " << c.at(0);
      // and in the writer's form: 17 significant digits, read back to the same double
      for (const std::string& x : c) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.17g", std::strtod(x.c_str(), nullptr));
        EXPECT_EQ(x, buf);
      }
    }
  }

  // moments: ⟨|v|²⟩ over the samples equals the mean T exactly (same velocities, COM frame),
  // and the pooled components give half of it
  const rfm::CsvTable mt = r.csv("moments.csv");
  const auto& ms = mt.column.at("moment");
  ASSERT_EQ(ms.size(), 12u);
  const double t_all = std::accumulate(T.begin(), T.end(), 0.0) / static_cast<double>(T.size());
  EXPECT_NEAR(ms[1], t_all, 1e-12 * t_all);
  EXPECT_NEAR(r.csv("moments_components.csv").column.at("moment")[1], 0.5 * t_all, 1e-12 * t_all);
  // Jensen: ⟨|v|⟩² ≤ ⟨|v|²⟩, and every moment finite and positive
  EXPECT_LE(ms[0] * ms[0], ms[1]);
  for (double m : ms) EXPECT_TRUE(std::isfinite(m) && m > 0);

  // the velocity histogram holds 2 components × 200 particles × 151 samples, normalised
  const rfm::Histogram hv = rfm::read_histogram_raw(r.dir / "run" / "hist_velocity.csv");
  EXPECT_EQ(hv.total(), 2.0 * 200 * 151);
  double integral = 0.0;
  for (const auto& b : hv.bins()) integral += b.p * (b.hi - b.lo);
  EXPECT_NEAR(integral, 1.0 - (hv.underflow() + hv.overflow()) / hv.total(), 1e-12);
  EXPECT_LT(hv.overflow() + hv.underflow(), 1e-3 * hv.total());

  // post-collision velocities: two components per particle leaving its last contact
  const rfm::Histogram hp = rfm::read_histogram_raw(r.dir / "run" / "hist_postcollision.csv");
  EXPECT_EQ(hp.total(), 2.0 * r.json("leave_events"));
  EXPECT_GT(hp.total(), 1000.0);

  // free paths: about one per collision, of the order of l₀ = L²/(2dN) = 3 mm (T.4.7)
  const rfm::Histogram hl = rfm::read_histogram_raw(r.dir / "run" / "hist_freepath.csv");
  EXPECT_GT(hl.total(), 0.5 * r.json("leave_events"));
  EXPECT_LE(hl.total(), r.json("leave_events"));
  double lsum = 0.0;
  for (const auto& b : hl.bins()) lsum += b.count * b.x;
  const double l_mean = lsum / hl.total();
  EXPECT_GT(l_mean, 0.1 * 3e-3);
  EXPECT_LT(l_mean, 3.0 * 3e-3);

  // S(k): shells up to |n| = 1.2 L/d = 24; beyond the first peak (k d ≳ 2π·1.3) S ≈ 1
  const rfm::CsvTable sk = r.csv("sk.csv");
  const auto& k = sk.column.at("k");
  const auto& S = sk.column.at("S");
  ASSERT_FALSE(k.empty());
  double s_hi = 0.0;
  int n_hi = 0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    EXPECT_TRUE(std::isfinite(S[i]) && S[i] >= 0.0);
    if (k[i] * 3e-3 > 2 * M_PI * 1.05) {
      s_hi += S[i];
      ++n_hi;
    }
  }
  ASSERT_GT(n_hi, 5);
  EXPECT_NEAR(s_hi / n_hi, 1.0, 0.35);

  // g(R): no pairs closer than 0.98 d (overlaps are ~1e-5 m), a contact peak above 1
  const rfm::CsvTable gr = r.csv("gr.csv");
  const auto& R = gr.column.at("R");
  const auto& g = gr.column.at("g");
  double g_peak = 0.0;
  for (std::size_t i = 0; i < R.size(); ++i) {
    if (R[i] < 0.97 * 3e-3) {
      EXPECT_EQ(g[i], 0.0) << R[i];
    }
    if (R[i] > 3e-3 && R[i] < 3.3e-3) g_peak = std::max(g_peak, g[i]);
  }
  EXPECT_GT(g_peak, 1.2);
}

// the observer's per-particle bookkeeping follows the spatial sort: sorted every 37 steps, a
// short run (over which the dynamics agree to round-off) counts the same leave events, the
// same free paths and the same post-collision velocities as the unsorted run. (Left on the
// old slots, the free paths would start at other particles' leave points.)
TEST(RfmObserver, FollowsTheSpatialSort) {
  const std::vector<std::pair<std::string, std::string>> shorter = {
      {"duration = 0.04", "duration = 0.012"}, {"discard_time = 0.01", "discard_time = 0.002"}};
  TinyRun plain(shorter, "", "_plain");
  TinyRun sorted(shorter, "[integrator]\nsort_every = 37\n", "_sorted");
  ASSERT_EQ(plain.code, 0);
  ASSERT_EQ(sorted.code, 0);
  EXPECT_GT(plain.json("leave_events"), 100.0);
  EXPECT_EQ(sorted.json("leave_events"), plain.json("leave_events"));
  const rfm::Histogram lp = rfm::read_histogram_raw(plain.dir / "run" / "hist_freepath.csv");
  const rfm::Histogram ls = rfm::read_histogram_raw(sorted.dir / "run" / "hist_freepath.csv");
  ASSERT_GT(lp.total(), 30.0);
  EXPECT_EQ(ls.total(), lp.total());
  ASSERT_EQ(ls.bins().size(), lp.bins().size());
  for (std::size_t b = 0; b < lp.bins().size(); ++b)
    EXPECT_EQ(ls.bins()[b].count, lp.bins()[b].count) << b;
  const rfm::Histogram pp = rfm::read_histogram_raw(plain.dir / "run" / "hist_postcollision.csv");
  const rfm::Histogram ps = rfm::read_histogram_raw(sorted.dir / "run" / "hist_postcollision.csv");
  EXPECT_EQ(ps.total(), pp.total());
  // round-off (sums in another order) grows through the collisions: 2·10⁻⁹ after 12 000 steps
  EXPECT_NEAR(sorted.json("T_mean"), plain.json("T_mean"), 1e-6 * plain.json("T_mean"));
}

// quiet_steps lets a run skip the observer where it would do nothing: an observer called only
// after the steps it asks for (the simulation running the steps between at once, its kick
// predicting ahead) ends in the state, bit for bit, of one called after every step — through
// the transient, its end, the samples, the followed contacts and a sort every 37 steps
TEST(RfmObserver, QuietStepsLoseNothing) {
  std::string text = kTiny2D;
  text.replace(text.find("duration = 0.04"), 15, "duration = 0.012");
  text.replace(text.find("discard_time = 0.01"), 19, "discard_time = 0.0053");
  const SceneSpec s = parse_scene_string(text + "[integrator]\nsort_every = 37\n", "tiny.toml");
  const fs::path dir = fs::temp_directory_path() / ("gs_rfm_quiet_" + std::to_string(::getpid()));
  fs::create_directories(dir / "every");
  fs::create_directories(dir / "quiet");
  auto sim_of = [&] {
    World w = make_world(s);
    place_particles(w, s);
    return Simulation(std::move(w), SimSettings::from(s));
  };
  Simulation every = sim_of(), quiet = sim_of();
  RfmObserver obs_every(s, csv_records()), obs_quiet(s, csv_records());
  obs_every.start(every, (dir / "every").string());
  obs_quiet.start(quiet, (dir / "quiet").string());
  const std::int64_t steps = 12000;
  for (std::int64_t k = 0; k < steps; ++k) {
    every.step();
    obs_every.after_step(every);
  }
  std::int64_t calls = 0;
  while (quiet.world().s.step < steps) {
    // as the run loop: never past a sort (the observer follows one sort per call)
    const std::int64_t m = std::min(
        {1 + obs_quiet.quiet_steps(quiet), quiet.sort_every(), steps - quiet.world().s.step});
    quiet.run(m);
    obs_quiet.after_step(quiet);
    ++calls;
  }
  ByteWriter a, b;
  obs_every.save(a);
  obs_quiet.save(b);
  EXPECT_TRUE(a.out == b.out);
  EXPECT_EQ(every.world().s.x, quiet.world().s.x);
  EXPECT_EQ(every.world().s.vy, quiet.world().s.vy);
  // the transient (5300 steps) ran in batches; the steady part, whose contacts are followed,
  // step by step
  EXPECT_LT(calls, steps - 5000);
  EXPECT_GT(calls, steps - 5300);
  EXPECT_GT(StepInspector::steps_predicted_ahead(quiet), 4000u);
  obs_every.finish(every);
  obs_quiet.finish(quiet);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs
