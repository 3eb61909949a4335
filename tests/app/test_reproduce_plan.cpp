// the reproduction plans: what each RFM budget runs, its projected cost on the measured cost
// model, the seeds of every point, and the conditions plan.json gives the verdicts
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "app/reproduce/plan.hpp"
#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

const PlannedSweep* find_sweep(const ReproducePlan& p, const std::string& name) {
  for (const auto& s : p.sweeps)
    if (s.name == name) return &s;
  return nullptr;
}

bool has_size(const PlannedSweep& s, int n) {
  return std::any_of(s.conditions.points.begin(), s.conditions.points.end(),
                     [n](const PlannedPoint& q) { return q.particles == n; });
}

TEST(ReproducePlan, PoolWallTimeIsListScheduling) {
  // runs of 3, 1, 1, 1 h on two slots: the 3-hour run on one, the three short ones on the other
  ReproducePlan p;
  PlannedSweep a, b;
  a.run_seconds = {3 * 3600.0, 3600.0};
  b.run_seconds = {3600.0, 3600.0};
  p.sweeps = {a, b};
  EXPECT_DOUBLE_EQ(p.core_hours(), 6.0);
  EXPECT_DOUBLE_EQ(p.wall_hours(2), 3.0);
  EXPECT_DOUBLE_EQ(p.wall_hours(1), 6.0);
  EXPECT_DOUBLE_EQ(p.longest_run_hours(), 3.0);
  // sweep by sweep (under MPI): 3 h, then 1 h
  EXPECT_DOUBLE_EQ(p.sweep_by_sweep_wall_hours(2), 4.0);
  EXPECT_EQ(p.runs(), 4);
}

TEST(ReproducePlan, RunCostsFollowTheMeasuredCostModel) {
  // each run's projection is N × steps × the cost a particle-step of its scene
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  for (const auto& s : p.sweeps) {
    const auto& c = s.conditions;
    ASSERT_EQ(s.run_seconds.size(),
              c.points.size() * c.seeds.size() * std::max<std::size_t>(c.starts.size(), 1))
        << s.name;
    const PlannedPoint& q = c.points.front();
    const double steps = c.duration / 1e-6 * q.particles;
    const double cost = c.dimension == 1                    ? rfm_cost_ring(q.particles)
                        : s.scene == "rfm2d_reference.toml" ? rfm_cost_fluid()
                                                            : rfm_cost_dense(q.particles);
    EXPECT_NEAR(s.run_seconds.front(), steps * cost, 1e-9 * steps * cost) << s.name;
  }
  // the dense fluid's cost a particle-step grows with N (g(R) over all pairs, S(k)); the ring's
  // does not; all lie within the measured 1.8e-8 … 6.7e-8 core-seconds
  EXPECT_DOUBLE_EQ(rfm_cost_ring(512), rfm_cost_ring(3981));
  EXPECT_LT(rfm_cost_dense(3000), rfm_cost_dense(27000));
  for (double c : {rfm_cost_ring(512), rfm_cost_ring(3981), rfm_cost_fluid(), rfm_cost_dense(3000),
                   rfm_cost_dense(27000)}) {
    EXPECT_GT(c, 1.8e-8);
    EXPECT_LT(c, 6.7e-8);
  }
}

TEST(ReproducePlan, TheRingMeasuredHereScalesTheRfmProjections) {
  // a machine whose ring steps cost twice the reference projects twice the core-hours
  PileCost slow;
  slow.measured = true;
  slow.seconds = 2.0 * kRingCostReference;
  for (Budget b : {Budget::Quick, Budget::Standard}) {
    const ReproducePlan ref = make_plan("rfm", b), here = make_plan("rfm", b, slow);
    EXPECT_NEAR(here.core_hours(), 2.0 * ref.core_hours(), 1e-9 * ref.core_hours());
    EXPECT_NEAR(here.wall_hours(2), 2.0 * ref.wall_hours(2), 1e-9 * ref.wall_hours(2));
  }
}

TEST(ReproducePlan, StandardFitsOneNightOnTwoCores) {
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  EXPECT_TRUE(p.resolves);
  EXPECT_LE(p.wall_hours(2), 8.0) << p.core_hours() << " core-hours";
  EXPECT_GT(p.wall_hours(2), 0.5 * p.core_hours());  // two slots busy: no idle core
}

TEST(ReproducePlan, QuickFitsAnHourOnTwoCores) {
  const ReproducePlan p = make_plan("rfm", Budget::Quick);
  EXPECT_LE(p.wall_hours(2), 1.0) << p.core_hours() << " core-hours";
  const ReproducePlan smoke = make_plan("rfm", Budget::Smoke);
  EXPECT_FALSE(smoke.resolves);
  EXPECT_LE(smoke.wall_hours(2), 0.1);
}

TEST(ReproducePlan, EveryStandardPointFromThreeSeeds) {
  for (Budget b : {Budget::Standard, Budget::Full}) {
    const ReproducePlan p = make_plan("rfm", b);
    for (const auto& s : p.sweeps) {
      const auto& seeds = s.conditions.seeds;
      EXPECT_GE(seeds.size(), 3u) << s.name;
      EXPECT_EQ(std::set<std::uint64_t>(seeds.begin(), seeds.end()).size(), seeds.size());
      // the seeds are swept: each is its own run
      const bool swept = std::any_of(s.params.begin(), s.params.end(), [](const std::string& x) {
        return x.rfind("preparation.seed=", 0) == 0;
      });
      EXPECT_TRUE(swept) << s.name;
      EXPECT_FALSE(s.conditions.points.empty()) << s.name;
    }
  }
}

TEST(ReproducePlan, StandardRunsTheThesisSystems) {
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  // G₁ against the bisection at N = 2⁹, sampled past the ≈ 200 s the ring takes to settle
  const PlannedSweep* n512 = find_sweep(p, "ring_n512");
  ASSERT_NE(n512, nullptr);
  EXPECT_TRUE(has_size(*n512, 512));
  EXPECT_GE(n512->conditions.duration, 200.0);
  // ξ₂: two of the thesis' sizes (N ≥ 398 on L′ = 1 m) sampled its 200 s after its 20 s of
  // relaxation (the time its claims are judged on)
  const PlannedSweep* r = find_sweep(p, "ring");
  ASSERT_NE(r, nullptr);
  EXPECT_GE(r->conditions.discard, 20.0);
  EXPECT_GE(r->conditions.sampled(), 200.0);
  std::set<int> sizes;
  for (const auto& q : r->conditions.points) {
    EXPECT_GE(q.particles, 398);
    EXPECT_DOUBLE_EQ(q.length, 1.0);
    EXPECT_DOUBLE_EQ(q.eps_n, 0.1);
    sizes.insert(q.particles);
  }
  EXPECT_GE(sizes.size(), 2u);
  // free paths at the thesis' L = 0.6 m, φ = 0.53 (N = 27 000)
  const PlannedSweep* fp = find_sweep(p, "freepath");
  ASSERT_NE(fp, nullptr);
  EXPECT_DOUBLE_EQ(fp->conditions.points.front().length, 0.6);
  EXPECT_NEAR(fp->conditions.points.front().phi, 0.530, 0.001);
  // S(k): φ = 0.53 at L = 0.2 m (Table 4.1); g(R) and the crossover fit on φ = 0.53 at
  // L = 0.4 m (Fig. 4.7, Table 5.3's system)
  EXPECT_NEAR(find_sweep(p, "structure")->conditions.points.front().phi, 0.530, 0.001);
  const PlannedSweep* l04 = find_sweep(p, "structure_l04");
  ASSERT_NE(l04, nullptr);
  EXPECT_NEAR(l04->conditions.points.front().phi, 0.530, 0.001);
  EXPECT_DOUBLE_EQ(l04->conditions.points.front().length, 0.4);
  for (const char* claim : {"g-R", "crossover"})
    EXPECT_NE(std::find(l04->conditions.claims.begin(), l04->conditions.claims.end(), claim),
              l04->conditions.claims.end())
        << claim;
  // the reference fluid from its three starts
  EXPECT_EQ(find_sweep(p, "reference")->conditions.starts.size(), 3u);
}

TEST(ReproducePlan, PlanJsonCarriesTheConditions) {
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  const auto j = nlohmann::json::parse(plan_json(p, "gransim reproduce rfm --budget standard", 2));
  EXPECT_NEAR(j.at("projected_wall_hours").get<double>(), p.wall_hours(2), 1e-12);
  ASSERT_EQ(j.at("sweeps").size(), p.sweeps.size());
  for (const auto& s : j.at("sweeps")) {
    const auto& c = s.at("conditions");
    for (const char* k : {"dimension", "claims", "points", "seeds", "starts", "duration_s",
                          "discard_s", "sampled_s", "runs", "projected_core_hours"})
      EXPECT_TRUE(c.contains(k)) << s.at("name") << " " << k;
    EXPECT_DOUBLE_EQ(c.at("sampled_s").get<double>(),
                     c.at("duration_s").get<double>() - c.at("discard_s").get<double>());
    for (const auto& q : c.at("points")) {
      for (const char* k : {"phi", "eps_n", "eps_t", "N"}) EXPECT_TRUE(q.contains(k));
      EXPECT_TRUE(q.contains(c.at("dimension") == 1 ? "reduced_length" : "L"));
    }
  }
  // the reference fluid: φ = Nπr²/L² = 0.353
  const auto& ref = j.at("sweeps").back();
  ASSERT_EQ(ref.at("name"), "reference");
  EXPECT_NEAR(ref.at("conditions").at("points")[0].at("phi").get<double>(), 0.353, 0.001);
  EXPECT_EQ(ref.at("conditions").at("seeds"), nlohmann::json::array({1, 2, 3}));
  // the tapping plan carries none (its verdicts read the runs)
  const auto t = nlohmann::json::parse(plan_json(make_plan("tapping", Budget::Quick), "x", 2));
  EXPECT_FALSE(t.at("sweeps")[0].contains("conditions"));
}

TEST(ReproducePlan, ModelsRunAfterTheSweeps) {
  // Table 6.2's cascades at the thesis' 8 levels, at every RFM budget; none for tapping
  for (Budget b : {Budget::Smoke, Budget::Quick, Budget::Standard, Budget::Full}) {
    const ReproducePlan p = make_plan("rfm", b);
    ASSERT_GE(p.models.size(), 1u) << budget_name(b);
    const PlannedModel& m = p.models[0];
    EXPECT_EQ(m.name, "cascade");
    EXPECT_EQ(m.claims, std::vector<std::string>{"cascade"});
    const auto at = std::find(m.args.begin(), m.args.end(), "--levels");
    ASSERT_NE(at, m.args.end());
    EXPECT_EQ(*(at + 1), "8");
    EXPECT_GT(m.core_seconds, 0.0);
    EXPECT_LT(m.core_seconds, 600.0);  // minutes: no budget's projection changes by more
  }
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  double sweeps = 0.0, models = 0.0;
  for (const auto& s : p.sweeps) sweeps += s.core_seconds();
  for (const auto& m : p.models) models += m.core_seconds;
  EXPECT_NEAR(p.core_hours() * 3600.0, sweeps + models, 1e-6);
  EXPECT_LT(models, 600.0);
  const auto j = nlohmann::json::parse(plan_json(p, "gransim reproduce rfm --budget standard", 2));
  ASSERT_EQ(j.at("models").size(), 4u);
  EXPECT_EQ(j.at("models")[0].at("command"),
            "gransim model cascade --kind all --levels 8 --realisations 500 --quiet --out "
            "DIR/models/cascade");
  // the Single Particle Model on each seed's free paths of the L = 0.6 m fluid (Fig. 5.10)
  const PlannedSweep* fp = find_sweep(p, "freepath");
  ASSERT_NE(fp, nullptr);
  for (int k = 1; k <= 3; ++k) {
    const PlannedModel& m = p.models[static_cast<std::size_t>(k)];
    EXPECT_EQ(m.name, "spm_seed" + std::to_string(k));
    EXPECT_EQ(m.needs, "analysis/freepath/seed=" + std::to_string(k) + "/freepath.csv");
    EXPECT_EQ(m.args[3], "DIR/" + m.needs);
    EXPECT_EQ(fp->conditions.seeds[static_cast<std::size_t>(k - 1)], static_cast<unsigned>(k));
  }
  EXPECT_TRUE(make_plan("tapping", Budget::Standard).models.empty());
  const auto t = nlohmann::json::parse(plan_json(make_plan("tapping", Budget::Quick), "x", 2));
  EXPECT_FALSE(t.contains("models"));
}

TEST(ReproducePlan, RunsGetTheirPointFromTheSets) {
  // each run's scene keys give its point: φ, ε, L, N as the conditions say
  const ReproducePlan p = make_plan("rfm", Budget::Standard);
  const PlannedSweep* fp = find_sweep(p, "freepath");
  ASSERT_NE(fp, nullptr);
  auto has = [&](const std::string& x) {
    return std::find(fp->sets.begin(), fp->sets.end(), x) != fp->sets.end();
  };
  EXPECT_TRUE(has("box.width=0.6"));
  EXPECT_TRUE(has("box.height=0.6"));
  EXPECT_TRUE(has("species[0].count=27000"));
  EXPECT_TRUE(has("material[0].eps_n=0.1"));
  EXPECT_TRUE(has("material[0].eps_t=0.1"));
  EXPECT_TRUE(has("scene.duration=2.5"));
  EXPECT_TRUE(has("rfm.discard_time=2"));  // the tail's transient at L = 0.6 m
}

TEST(ReproducePlan, FullBudgetPrintsItsClusterCommands) {
  const fs::path dir = fs::temp_directory_path() / "gs_test_reproduce_full";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto o = testing::run_binary(
      {"reproduce", "rfm", "--budget", "full", "--out", (dir / "study").string()}, dir / "log");
  ASSERT_TRUE(o.exited) << o.output;
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("mpirun -np"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("sbatch -n"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("core-hours"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "study" / "sweeps"));  // nothing was started
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {

TEST(ReproducePlan, TappingProjectionScalesWithTheCostMeasuredHere) {
  // a clock that advances 0.6 s over the timed steps: cost = 0.6 s / (steps · grains)
  const std::string src = GS_SOURCE_DIR;
  int calls = 0;
  auto clock = [&calls] { return calls++ == 0 ? 10.0 : 10.6; };
  const PileCost c = measure_pile_cost(src + "/scenes/paper_negative_g_fast.toml",
                                       src + "/scenes/data/paper_pile_settled.csv", 3, clock);
  EXPECT_EQ(calls, 2);
  EXPECT_TRUE(c.measured);
  EXPECT_EQ(c.particles, 1184);
  EXPECT_DOUBLE_EQ(c.seconds, 0.6 / (3.0 * 1184));
  // every tapping run's projection is steps × grains × cost
  const ReproducePlan ref = make_plan("tapping", Budget::Standard);
  const ReproducePlan here = make_plan("tapping", Budget::Standard, c);
  EXPECT_FALSE(ref.cost.measured);
  EXPECT_NEAR(here.core_hours() / ref.core_hours(), c.seconds / kPileCostReference, 1e-12);
  // a 250-tap run at g_p = 6: its taps and the 3 s of settling, in steps of the fast scenes
  const double steps = (3.0 + 250 * neg_tap_seconds(6.0)) / kPaperDt;
  const auto& neg = here.sweeps.front();
  ASSERT_EQ(neg.params.front().rfind("drive.g_p=2,4,6", 0), 0u);
  EXPECT_NEAR(neg.run_seconds[2], steps * 1184 * c.seconds, 1e-9 * neg.run_seconds[2]);
  // plan.json says what the projection rests on
  const auto j = nlohmann::json::parse(plan_json(here, "x", 2));
  EXPECT_TRUE(j.at("cost").at("measured_here").get<bool>());
  EXPECT_DOUBLE_EQ(j.at("cost").at("core_seconds_per_particle_step").get<double>(), c.seconds);
  EXPECT_EQ(j.at("cost").at("steps_timed").get<int>(), 3);
  // a clock that does not advance measures nothing: the reference cost stays
  const PileCost none =
      measure_pile_cost(src + "/scenes/paper_negative_g_fast.toml",
                        src + "/scenes/data/paper_pile_settled.csv", 1, [] { return 5.0; });
  EXPECT_FALSE(none.measured);
  EXPECT_EQ(none.seconds, kPileCostReference);
}

TEST(ReproducePlan, PileCostNamesAnUnreadableState) {
  const std::string src = GS_SOURCE_DIR;
  try {
    measure_pile_cost(src + "/scenes/paper_negative_g_fast.toml", src + "/scenes/data/none.csv", 1);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("none.csv"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gs
