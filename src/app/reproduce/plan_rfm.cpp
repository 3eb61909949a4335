// the Random Force Model study's plan: the thesis' systems (φ, ε, L, N) at each budget, every
// point from several seeds, and the conditions each sweep matches for the verdicts
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "app/reproduce/plan.hpp"

namespace gs {

namespace {

// core-seconds per particle-step (CPU time of `gransim run`, one thread, the RFM observer on,
// from a clustered steady state): the 2D reference fluid (φ = 0.353, ε = 0.6), the dense
// dissipative fluid (ε = 0.1, whose g(R) over all pairs and S(k) make a particle's share grow
// with N) and the ring on L′ = 1 m (as dear at N = 512 as at 4000: the noise costs as much as
// the contacts)
constexpr double kFluidCost = 2.3e-8;
constexpr double kDenseCostBase = 3.5e-8;
constexpr double kDenseCostPerParticle = 1.0e-12;
constexpr double kRingCost = 2.0e-8;

// core-seconds per realisation of the 8-level cascades, all seven kinds, and per walk of the
// Single Particle Model (P_l of the φ = 0.53 fluid, with as many walks in a disc of 1 mm)
constexpr double kCascadeCost = 0.17;
constexpr double kSpmCost = 2.5e-4;

constexpr double kDt = 1e-6;        // the scenes' time step
constexpr double kRadius = 0.0015;  // the scenes' bead

std::string rfm_text(double v) {
  std::ostringstream o;
  o.precision(12);
  o << v;
  return o.str();
}

template <class T>
std::string rfm_list(const std::vector<T>& v) {
  std::ostringstream o;
  o.precision(12);
  for (std::size_t i = 0; i < v.size(); ++i) o << (i ? "," : "") << v[i];
  return o.str();
}

std::vector<std::uint64_t> first_seeds(int n) {
  std::vector<std::uint64_t> s;
  for (int i = 1; i <= n; ++i) s.push_back(static_cast<std::uint64_t>(i));
  return s;
}

// the seeds as the last (fastest) parameter; one seed is a --set, so that a sweep of one seed
// keeps the run names of its other parameters (a sweep needs one parameter: then the seed)
void seed_param(PlannedSweep& s) {
  const auto& seeds = s.conditions.seeds;
  if (seeds.size() > 1 || s.params.empty())
    s.params.push_back("preparation.seed=" + rfm_list(seeds));
  else
    s.sets.push_back("preparation.seed=" + rfm_list(seeds));
}

// a 2D sweep of `scene` (a periodic square box): points at fixed L and ε over N, each run
// from every start and seed; `dense` picks the cost of a clustering fluid
PlannedSweep fluid_sweep(const std::string& name, const std::string& scene, double length,
                         double eps, const std::vector<int>& counts,
                         const std::vector<std::string>& starts, int seeds, double duration,
                         double discard, bool dense, std::vector<std::string> claims) {
  PlannedSweep s;
  s.name = name;
  s.scene = scene;
  PlannedConditions& c = s.conditions;
  c.dimension = 2;
  c.claims = std::move(claims);
  c.seeds = first_seeds(seeds);
  c.starts = starts;
  c.duration = duration;
  c.discard = discard;
  for (int n : counts)
    c.points.push_back(
        {n * std::numbers::pi * kRadius * kRadius / (length * length), eps, eps, length, n});
  if (counts.size() > 1) s.params.push_back("species[0].count=" + rfm_list(counts));
  if (starts.size() > 1) s.params.push_back("preparation.placement=" + rfm_list(starts));
  seed_param(s);
  s.sets.insert(s.sets.end(),
                {"scene.duration=" + rfm_text(duration), "rfm.discard_time=" + rfm_text(discard),
                 "material[0].eps_n=" + rfm_text(eps), "material[0].eps_t=" + rfm_text(eps),
                 "box.width=" + rfm_text(length), "box.height=" + rfm_text(length)});
  if (counts.size() == 1) s.sets.push_back("species[0].count=" + std::to_string(counts[0]));
  if (starts.size() == 1) s.sets.push_back("preparation.placement=" + starts[0]);
  // the pool's order: the first parameter slowest
  for (int n : counts)
    for (std::size_t k = 0; k < starts.size() * c.seeds.size(); ++k)
      s.run_seconds.push_back(n * duration / kDt * (dense ? rfm_cost_dense(n) : kFluidCost));
  return s;
}

// a ring sweep (L′ = 1 m): every ε and N from every seed, the first relax seconds discarded
PlannedSweep ring_sweep(const std::string& name, const std::vector<double>& eps,
                        const std::vector<int>& counts, int seeds, double duration, double discard,
                        std::vector<std::string> claims) {
  PlannedSweep s;
  s.name = name;
  s.scene = "rfm1d_reference.toml";
  PlannedConditions& c = s.conditions;
  c.dimension = 1;
  c.claims = std::move(claims);
  c.seeds = first_seeds(seeds);
  c.duration = duration;
  c.discard = discard;
  const double reduced = 1.0;
  for (double e : eps)
    for (int n : counts)
      c.points.push_back({n * 2 * kRadius / (reduced + n * 2 * kRadius), e, 1.0, reduced, n});
  if (eps.size() > 1) s.params.push_back("material[0].eps_n=" + rfm_list(eps));
  if (counts.size() > 1) s.params.push_back("species[0].count=" + rfm_list(counts));
  seed_param(s);
  s.sets.insert(s.sets.end(),
                {"scene.duration=" + rfm_text(duration), "rfm.discard_time=" + rfm_text(discard),
                 "box.reduced_length=" + rfm_text(reduced)});
  if (eps.size() == 1) s.sets.push_back("material[0].eps_n=" + rfm_text(eps[0]));
  if (counts.size() == 1) s.sets.push_back("species[0].count=" + std::to_string(counts[0]));
  for (std::size_t e = 0; e < eps.size(); ++e)
    for (int n : counts)
      for (std::size_t k = 0; k < c.seeds.size(); ++k)
        s.run_seconds.push_back(n * duration / kDt * rfm_cost_ring(n));
  return s;
}

// Table 6.2's multiplicative cascades: every kind at the thesis' 8 levels (§6.2.2)
PlannedModel cascade_model(int realisations) {
  return {"cascade",
          {"model", "cascade", "--kind", "all", "--levels", "8", "--realisations",
           std::to_string(realisations), "--quiet"},
          {"cascade"},
          realisations * kCascadeCost,
          ""};
}

// the Single Particle Model of §5.2.3 (Fig. 5.10) on the free paths of one run of a sweep (the
// L = 0.6 m fluid), once its analysis has written them
PlannedModel spm_model(const std::string& sweep, const std::string& run, int seed, int walks) {
  const std::string paths = "analysis/" + sweep + "/" + run + "/freepath.csv";
  return {"spm_seed" + std::to_string(seed),
          {"model", "walk", "--paths", "DIR/" + paths, "--walks", std::to_string(walks), "--radius",
           "0.001", "--v-max", "3", "--bins", "600", "--no-heating", "--quiet"},
          {"spm-pv"},
          walks * kSpmCost,
          paths};
}

}  // namespace

double rfm_cost_fluid() { return kFluidCost; }
double rfm_cost_dense(int particles) {
  return kDenseCostBase + kDenseCostPerParticle * std::max(particles, 0);
}
double rfm_cost_ring(int /*particles*/) { return kRingCost; }

namespace plan_detail {

ReproducePlan rfm_plan(Budget b, double scale) {
  ReproducePlan p;
  p.study = "rfm";
  p.budget = b;
  const std::vector<std::string> starts = {"square", "hexagonal", "uniform"};
  const std::vector<std::string> ref_claims = {"T-start", "transient", "T-mean-field",
                                               "alpha-reference"};
  const std::vector<std::string> sk_claims = {"Df-Sk", "g-R", "alpha-structure"};
  const std::vector<std::string> ring_claims = {"xi2", "xi-m", "zeta-m", "v-pdf"};
  switch (b) {
    case Budget::Smoke:
      // the ring's seeds prove the seed sweeps; three runs first keep the pool's overlap visible
      p.sweeps.push_back(fluid_sweep("reference", "rfm2d_reference.toml", 0.2, 0.6, {2000}, starts,
                                     1, 0.25, 0.1, false, ref_claims));
      p.sweeps.push_back(fluid_sweep("structure", "rfm2d_structure.toml", 0.2, 0.1, {3000},
                                     {"hexagonal"}, 1, 0.2, 0.1, true, sk_claims));
      p.sweeps.push_back(ring_sweep("ring", {0.1}, {100, 200}, 2, 1.0, 0.1, ring_claims));
      p.models.push_back(cascade_model(20));
      p.models.push_back(spm_model("structure", "seed=1", 1, 2000));  // proves the model step
      p.purpose = "proves the pipeline with runs of a fraction of a second; resolves no claim";
      p.resolves = false;
      break;
    case Budget::Quick:
      p.sweeps.push_back(fluid_sweep("reference", "rfm2d_reference.toml", 0.2, 0.6, {2000}, starts,
                                     1, 2.0, 1.0, false, ref_claims));
      p.sweeps.push_back(fluid_sweep("structure", "rfm2d_structure.toml", 0.2, 0.1, {3000},
                                     {"hexagonal"}, 1, 4.0, 1.0, true, sk_claims));
      p.sweeps.push_back(
          ring_sweep("ring", {0.1}, {400, 1000, 2500, 4000}, 1, 8.0, 1.0, ring_claims));
      p.models.push_back(cascade_model(200));
      p.purpose =
          "seconds of simulated time from one seed: the steady temperature and its start, the "
          "velocity tails, S(k) of a young clustered fluid, ξ₂ over N = 400…4000 after 1 s "
          "instead of the thesis' 20 s of relaxation";
      break;
    case Budget::Standard:
      // longest runs first, so that the two slots finish together
      p.sweeps.push_back(ring_sweep("ring_n512", {0.1}, {512}, 3, 220.0, 20.0,
                                    {"T-ring-settle", "G1-bisection", "v-pdf"}));
      // at L = 0.6 m the free paths' tail steepens until t ≈ 2 s (docs/reproduction, "Open
      // questions of the Random Force Model"), so this box discards two seconds, not one
      p.sweeps.push_back(fluid_sweep("freepath", "rfm2d_structure.toml", 0.6, 0.1, {27000},
                                     {"hexagonal"}, 3, 2.5, 2.0, true,
                                     {"Df-freepath", "alpha-structure"}));
      // Fig. 4.7's and Table 5.3's system: φ = 0.53 at L = 0.4 m
      p.sweeps.push_back(fluid_sweep("structure_l04", "rfm2d_structure.toml", 0.4, 0.1, {12000},
                                     {"hexagonal"}, 3, 3.0, 1.0, true, {"g-R", "crossover"}));
      p.sweeps.push_back(fluid_sweep("structure", "rfm2d_structure.toml", 0.2, 0.1, {3000},
                                     {"hexagonal"}, 3, 16.0, 1.0, true, sk_claims));
      // ξ₂ needs 200 s sampled at two sizes or more: over ε, or more sizes, do not fit a night
      p.sweeps.push_back(ring_sweep("ring", {0.1}, {398, 1000}, 3, 220.0, 20.0, ring_claims));
      p.sweeps.push_back(fluid_sweep("moments_phi", "rfm2d_structure.toml", 0.2, 0.1,
                                     {500, 1000, 2000, 4000}, {"hexagonal"}, 3, 5.0, 1.0, true,
                                     {"moments-phi", "alpha-phi"}));
      p.sweeps.push_back(fluid_sweep("reference", "rfm2d_reference.toml", 0.2, 0.6, {2000}, starts,
                                     3, 10.0, 1.0, false, ref_claims));
      p.models.push_back(cascade_model(500));
      for (int k = 1; k <= 3; ++k)
        p.models.push_back(spm_model("freepath", "seed=" + std::to_string(k), k, 50000));
      p.purpose =
          "the thesis' systems from three seeds each: the ring at N = 512 for 220 s (past the "
          "≈ 200 s the temperature takes to settle), ξ₂, ξ_m and the velocity PDFs at N = 398 "
          "and 1000, ε = 0.1, also 200 s after the thesis' 20 s relaxation (ξ_m and ζ_m need "
          "its 1000 s); S(k) at φ = 0.53 (L = 0.2 m); g(R) and "
          "the crossover fit on Fig. 4.7's and Table 5.3's system (φ = 0.53 at L = 0.4 m, 2 s "
          "sampled); free paths at L = 0.6 m over 0.5 s after 2 s, and the Single Particle Model "
          "on "
          "them; "
          "moments and tails against φ = 0.088…0.707 at L = 0.2 m; Table 6.2's cascades. Out of "
          "reach: ε other than 0.1 (ξ₂(ε), the collapse), N above 1000, φ = 0.177 at L ≥ L_Eff = "
          "0.48 m, S(k) at L = 0.4 and 0.8 m "
          "(Tables 4.1–4.3, 5.2)";
      break;
    case Budget::Full: {
      const std::vector<int> sizes = {100, 158, 251, 398, 631, 1000, 1585, 2512, 3981, 6310, 10000};
      p.sweeps.push_back(ring_sweep("ring", {0.1}, sizes, 3, 1020.0, 20.0, ring_claims));
      p.sweeps.push_back(ring_sweep("ring_eps", {0.21, 0.37, 0.5, 0.6, 0.75, 0.87, 0.97, 0.99},
                                    sizes, 3, 220.0, 20.0, {"xi2-eps", "collapse"}));
      p.sweeps.push_back(ring_sweep("ring_n512", {0.1}, {512, 1024, 2048, 4096}, 3, 1020.0, 20.0,
                                    {"T-ring-settle", "G1-bisection", "renormalisation"}));
      p.sweeps.push_back(fluid_sweep("freepath", "rfm2d_structure.toml", 0.6, 0.1, {18000, 27000},
                                     {"hexagonal"}, 3, 20.0, 2.0, true,
                                     {"Df-freepath", "alpha-structure"}));
      p.sweeps.push_back(fluid_sweep("structure_l08", "rfm2d_structure.toml", 0.8, 0.1,
                                     {16000, 32000, 48000}, {"hexagonal"}, 3, 20.0, 1.0, true,
                                     {"Df-Sk"}));
      p.sweeps.push_back(fluid_sweep("structure_l04", "rfm2d_structure.toml", 0.4, 0.1,
                                     {4000, 8000, 12000}, {"hexagonal"}, 3, 50.0, 1.0, true,
                                     {"Df-Sk"}));
      p.sweeps.push_back(fluid_sweep("structure", "rfm2d_structure.toml", 0.2, 0.1, {3000},
                                     {"hexagonal"}, 3, 100.0, 1.0, true, sk_claims));
      p.sweeps.push_back(fluid_sweep("moments_phi", "rfm2d_structure.toml", 0.2, 0.1,
                                     {100, 500, 1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500},
                                     {"hexagonal"}, 3, 20.0, 1.0, true,
                                     {"moments-phi", "alpha-phi"}));
      p.sweeps.push_back(fluid_sweep("reference", "rfm2d_reference.toml", 0.2, 0.6, {2000}, starts,
                                     3, 20.0, 1.0, false, ref_claims));
      p.models.push_back(cascade_model(2000));
      for (int k = 1; k <= 3; ++k)
        p.models.push_back(
            spm_model("freepath", "count=27000_seed=" + std::to_string(k), k, 200000));
      p.purpose =
          "the thesis' own run lengths from three seeds: the ring 1020 s per size up to "
          "N = 10⁴ and over ε, N = 512…4096 for the renormalisation, S(k) up to L = 0.8 m, "
          "free paths at L = 0.6 m (a cluster job)";
      break;
    }
  }
  // this machine against the one that measured the costs above
  for (PlannedSweep& sw : p.sweeps)
    for (double& t : sw.run_seconds) t *= scale;
  for (PlannedModel& m : p.models) m.core_seconds *= scale;
  return p;
}

}  // namespace plan_detail

}  // namespace gs
