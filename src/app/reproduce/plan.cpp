#include "app/reproduce/plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace gs {

namespace {

// core-seconds per particle-step, measured on a 2-vCPU Intel Xeon VM (one thread a run):
// the 1184-decagon pile, and the soft-disk fluids of the Random Force Model; they only
// scale the projections printed before a run
constexpr double kPolygonCost = 1.1e-6;
constexpr double kDisk2dCost = 4.0e-8;
constexpr double kRingCost = 2.0e-8;

std::string join(const std::vector<double>& v) {
  std::ostringstream o;
  for (std::size_t i = 0; i < v.size(); ++i) o << (i ? "," : "") << v[i];
  return o.str();
}

// simulated seconds of one tap with early rest and the quench: the excitation (pulse and
// flight, or the turn) and a relaxation that ends ≈ 1.4–1.5 s after it
double neg_tap_seconds(double g_p) { return 0.01 + 0.02 * g_p + 1.45; }  // flight 2g_p·t1
double rot_tap_seconds(double f) { return 1.0 / f + 1.5; }

// a tapping sweep of `scene` over `values` of `key`, each run `taps` taps after `settle` s
PlannedSweep tapping_sweep(const std::string& name, const std::string& scene,
                           const std::string& key, const std::vector<double>& values, int taps,
                           double settle, int grains, double dt,
                           std::vector<std::string> extra_sets = {}) {
  PlannedSweep s;
  s.name = name;
  s.scene = scene;
  s.params = {key + "=" + join(values)};
  s.sets = {"drive.taps=" + std::to_string(taps)};
  s.sets.insert(s.sets.end(), extra_sets.begin(), extra_sets.end());
  double seconds = 0.0, longest = 0.0;
  for (double v : values) {
    const double one =
        settle + taps * (key == "drive.g_p" ? neg_tap_seconds(v) : rot_tap_seconds(v));
    seconds += one;
    longest = std::max(longest, one);
  }
  s.particle_steps = seconds / dt * grains;
  s.longest_run = longest / dt * grains;
  s.runs = static_cast<int>(values.size());
  s.seconds_per_particle_step = kPolygonCost;
  return s;
}

// an RFM sweep: `runs` runs of `seconds` each of `particles` disks at Δt = 1e-6 s
PlannedSweep rfm_sweep(const std::string& name, const std::string& scene, const std::string& param,
                       std::vector<std::string> sets, double particle_seconds,
                       double longest_particle_seconds, int runs, double cost) {
  PlannedSweep s;
  s.longest_run = longest_particle_seconds / 1e-6;
  s.runs = runs;
  s.name = name;
  s.scene = scene;
  s.params = {param};
  s.sets = std::move(sets);
  s.particle_steps = particle_seconds / 1e-6;
  s.seconds_per_particle_step = cost;
  return s;
}

std::string secs(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// the paper's time-step check (section IV): Δt halved at two pulse strengths, as long as the
// study's own runs, beside them in the pool and analysed apart (analysis/timestep)
PlannedSweep timestep_sweep(const std::string& scene, int taps, double dt) {
  std::ostringstream half;
  half.precision(17);
  half << "integrator.dt=" << dt / 2;
  return tapping_sweep("timestep", scene, "drive.g_p", {6, 20}, taps, 3.0, 1184, dt / 2,
                       {half.str()});
}

ReproducePlan tapping_plan(Budget b) {
  ReproducePlan p;
  p.study = "tapping";
  p.budget = b;
  const double dt = 1.0 / 7500.0;
  const std::string neg = "paper_negative_g_fast.toml", rot = "paper_rotating_g_fast.toml";
  switch (b) {
    case Budget::Smoke: {
      // the 250-grain teaching pile at the fast scenes' step: proves the pipeline only
      const std::vector<std::string> fast = {
          "output.discard_taps=1", "integrator.dt=1.3333333333333333e-4", "drive.quench=true"};
      p.sweeps.push_back(tapping_sweep("negative_g", "tap_small_negative_g.toml", "drive.g_p",
                                       {2, 10, 20}, 21, 1.5, 250, dt, fast));
      p.sweeps.push_back(tapping_sweep("rotating_g", "tap_small_rotating_g.toml", "drive.f", {1, 2},
                                       21, 1.5, 250, dt, fast));
      p.purpose = "proves the pipeline on the 250-grain teaching pile; resolves no claim";
      p.resolves = false;
      break;
    }
    case Budget::Quick:
      p.sweeps.push_back(
          tapping_sweep("negative_g", neg, "drive.g_p", {2, 6, 12, 20, 30}, 60, 3.0, 1184, dt));
      p.sweeps.push_back(tapping_sweep("rotating_g", rot, "drive.f", {0.5, 2}, 50, 3.0, 1184, dt));
      p.purpose =
          "the paper's pile, 50–60 taps per value: the shape of φ̄(g_p) and φ̄(f), the "
          "transient, the test square's halves";
      break;
    case Budget::Standard:
      p.sweeps.push_back(tapping_sweep("negative_g", neg, "drive.g_p",
                                       {2, 4, 6, 9, 12, 16, 20, 25, 30}, 250, 3.0, 1184, dt));
      p.sweeps.push_back(
          tapping_sweep("rotating_g", rot, "drive.f", {0.5, 0.75, 1.25, 2}, 200, 3.0, 1184, dt));
      p.sweeps.push_back(timestep_sweep(neg, 250, dt));
      p.purpose =
          "the paper's pile, 200–250 taps per value: σ_φ, the overlapping histograms, "
          "the quadron fit and the time-step check";
      break;
    case Budget::Full:
      p.sweeps.push_back(tapping_sweep("negative_g", neg, "drive.g_p",
                                       {2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30},
                                       3000, 3.0, 1184, dt));
      p.sweeps.push_back(tapping_sweep("rotating_g", rot, "drive.f",
                                       {0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2}, 3000, 3.0, 1184,
                                       dt));
      p.sweeps.push_back(timestep_sweep(neg, 3000, dt));
      p.purpose = "the paper's own scale: 3000 taps per value (a cluster job)";
      break;
  }
  return p;
}

ReproducePlan rfm_plan(Budget b) {
  ReproducePlan p;
  p.study = "rfm";
  p.budget = b;
  // (seconds of the reference runs, of the structure run, of each ring; transient; ring sizes)
  double t_ref = 2, t_sk = 4, t_ring = 8, discard = 1;
  std::vector<double> sizes = {400, 1000, 2500, 4000};
  switch (b) {
    case Budget::Smoke:
      t_ref = 0.25, t_sk = 0.2, t_ring = 1.0, discard = 0.1, sizes = {100, 200};
      p.purpose = "proves the pipeline with runs of a fraction of a second; resolves no claim";
      p.resolves = false;
      break;
    case Budget::Quick:
      p.purpose =
          "seconds of simulated time: the steady temperature and its start, the "
          "velocity tails, S(k) of a young clustered fluid, ξ₂ over N = 400…4000";
      break;
    case Budget::Standard:
      t_ref = 5, t_sk = 20, t_ring = 40, sizes = {400, 630, 1000, 1580, 2500, 4000};
      p.purpose =
          "tens of seconds: S(k) and the free paths of a developed clustered fluid, "
          "ξ_m over N = 400…4000";
      break;
    case Budget::Full:
      t_ref = 20, t_sk = 100, t_ring = 1020,
      sizes = {100, 158, 251, 398, 631, 1000, 1585, 2512, 3981, 6310, 10000};
      p.purpose = "the thesis' own run lengths (1D: 1020 s per size up to N = 10⁴)";
      break;
  }
  const std::string d = "rfm.discard_time=" + secs(discard);
  p.sweeps.push_back(rfm_sweep(
      "reference", "rfm2d_reference.toml", "preparation.placement=square,hexagonal,uniform",
      {"scene.duration=" + secs(t_ref), d}, 3 * 2000 * t_ref, 2000 * t_ref, 3, kDisk2dCost));
  p.sweeps.push_back(rfm_sweep("structure", "rfm2d_structure.toml", "scene.duration=" + secs(t_sk),
                               {d}, 3000 * t_sk, 3000 * t_sk, 1, kDisk2dCost));
  double n_total = 0;
  for (double n : sizes) n_total += n;
  p.sweeps.push_back(rfm_sweep("ring", "rfm1d_reference.toml", "species[0].count=" + join(sizes),
                               {"scene.duration=" + secs(t_ring), d}, n_total * t_ring,
                               sizes.back() * t_ring, static_cast<int>(sizes.size()), kRingCost));
  return p;
}

}  // namespace

Budget parse_budget(const std::string& word) {
  if (word == "smoke") return Budget::Smoke;
  if (word == "quick") return Budget::Quick;
  if (word == "standard") return Budget::Standard;
  if (word == "full") return Budget::Full;
  throw InputError("", "--budget", "'" + word + "' is not a budget (smoke, quick, standard, full)");
}

const char* budget_name(Budget b) {
  switch (b) {
    case Budget::Smoke:
      return "smoke";
    case Budget::Quick:
      return "quick";
    case Budget::Standard:
      return "standard";
    case Budget::Full:
      return "full";
  }
  return "?";
}

double ReproducePlan::core_hours() const {
  double s = 0.0;
  for (const auto& w : sweeps) s += w.particle_steps * w.seconds_per_particle_step;
  return s / 3600.0;
}

double ReproducePlan::longest_run_hours() const {
  double h = 0.0;
  for (const auto& w : sweeps)
    h = std::max(h, w.longest_run * w.seconds_per_particle_step / 3600.0);
  return h;
}

int ReproducePlan::widest_sweep() const {
  int n = 1;
  for (const auto& w : sweeps) n = std::max(n, w.runs);
  return n;
}

ReproducePlan make_plan(const std::string& study, Budget budget) {
  if (study == "tapping") return tapping_plan(budget);
  if (study == "rfm") return rfm_plan(budget);
  throw InputError("", "STUDY", "'" + study + "' is not a study (tapping, rfm)");
}

}  // namespace gs
