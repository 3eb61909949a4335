#include "app/reproduce/plan.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"

namespace gs {

// the excitation (pulse and flight 2g_p·t1) and a relaxation that ends ≈ 1.4–1.5 s after it
double neg_tap_seconds(double g_p) { return 0.01 + 0.02 * g_p + 1.45; }

namespace {

std::string join(const std::vector<double>& v) {
  std::ostringstream o;
  for (std::size_t i = 0; i < v.size(); ++i) o << (i ? "," : "") << v[i];
  return o.str();
}

// simulated seconds of a rotating-g tap with early rest and the quench: the turn and the
// relaxation after it
double rot_tap_seconds(double f) { return 1.0 / f + 1.5; }

// a tapping sweep of `scene` over `values` of `key`, each run `taps` taps after `settle` s
PlannedSweep tapping_sweep(const std::string& name, const std::string& scene,
                           const std::string& key, const std::vector<double>& values, int taps,
                           double settle, int grains, double dt, double cost,
                           std::vector<std::string> extra_sets = {}) {
  PlannedSweep s;
  s.name = name;
  s.scene = scene;
  s.params = {key + "=" + join(values)};
  s.sets = {"drive.taps=" + std::to_string(taps)};
  s.sets.insert(s.sets.end(), extra_sets.begin(), extra_sets.end());
  for (double v : values) {
    const double one =
        settle + taps * (key == "drive.g_p" ? neg_tap_seconds(v) : rot_tap_seconds(v));
    s.run_seconds.push_back(one / dt * grains * cost);
  }
  return s;
}

// the paper's time-step check (section IV): Δt halved at two pulse strengths, as long as the
// study's own runs, beside them in the pool and analysed apart (analysis/timestep)
PlannedSweep timestep_sweep(const std::string& scene, int taps, double dt, double cost) {
  std::ostringstream half;
  half.precision(17);
  half << "integrator.dt=" << dt / 2;
  return tapping_sweep("timestep", scene, "drive.g_p", {6, 20}, taps, 3.0, 1184, dt / 2, cost,
                       {half.str()});
}

ReproducePlan tapping_plan(Budget b, double cost) {
  ReproducePlan p;
  p.study = "tapping";
  p.budget = b;
  const double dt = kPaperDt;
  const std::string neg = "paper_negative_g_fast.toml", rot = "paper_rotating_g_fast.toml";
  switch (b) {
    case Budget::Smoke: {
      // the 250-grain teaching pile at the fast scenes' step: proves the pipeline only
      const std::vector<std::string> fast = {
          "output.discard_taps=1", "integrator.dt=1.3333333333333333e-4", "drive.quench=true"};
      p.sweeps.push_back(tapping_sweep("negative_g", "tap_small_negative_g.toml", "drive.g_p",
                                       {2, 10, 20}, 21, 1.5, 250, dt, cost, fast));
      p.sweeps.push_back(tapping_sweep("rotating_g", "tap_small_rotating_g.toml", "drive.f", {1, 2},
                                       21, 1.5, 250, dt, cost, fast));
      p.purpose = "proves the pipeline on the 250-grain teaching pile; resolves no claim";
      p.resolves = false;
      break;
    }
    case Budget::Quick:
      p.sweeps.push_back(tapping_sweep("negative_g", neg, "drive.g_p", {2, 6, 12, 20, 30}, 60, 3.0,
                                       1184, dt, cost));
      p.sweeps.push_back(
          tapping_sweep("rotating_g", rot, "drive.f", {0.5, 2}, 50, 3.0, 1184, dt, cost));
      p.purpose =
          "the paper's pile, 50–60 taps per value: the shape of φ̄(g_p) and φ̄(f), the "
          "transient, the test square's halves";
      break;
    case Budget::Standard:
      p.sweeps.push_back(tapping_sweep("negative_g", neg, "drive.g_p",
                                       {2, 4, 6, 9, 12, 16, 20, 25, 30}, 250, 3.0, 1184, dt, cost));
      p.sweeps.push_back(tapping_sweep("rotating_g", rot, "drive.f", {0.5, 0.75, 1.25, 2}, 200, 3.0,
                                       1184, dt, cost));
      p.sweeps.push_back(timestep_sweep(neg, 250, dt, cost));
      p.purpose =
          "the paper's pile, 200–250 taps per value: σ_φ, the overlapping histograms, "
          "the quadron fit and the time-step check";
      break;
    case Budget::Full:
      p.sweeps.push_back(tapping_sweep("negative_g", neg, "drive.g_p",
                                       {2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30},
                                       3000, 3.0, 1184, dt, cost));
      p.sweeps.push_back(tapping_sweep("rotating_g", rot, "drive.f",
                                       {0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2}, 3000, 3.0, 1184,
                                       dt, cost));
      p.sweeps.push_back(timestep_sweep(neg, 3000, dt, cost));
      p.purpose = "the paper's own scale: 3000 taps per value (a cluster job)";
      break;
  }
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

double PlannedSweep::core_seconds() const {
  double s = 0.0;
  for (double r : run_seconds) s += r;
  return s;
}

double ReproducePlan::core_hours() const {
  double s = 0.0;
  for (const auto& w : sweeps) s += w.core_seconds();
  for (const auto& m : models) s += m.core_seconds;
  return s / 3600.0;
}

double ReproducePlan::longest_run_hours() const {
  double h = 0.0;
  for (const auto& w : sweeps)
    for (double r : w.run_seconds) h = std::max(h, r / 3600.0);
  return h;
}

int ReproducePlan::widest_sweep() const {
  int n = 1;
  for (const auto& w : sweeps) n = std::max(n, static_cast<int>(w.run_seconds.size()));
  return n;
}

int ReproducePlan::runs() const {
  int n = 0;
  for (const auto& w : sweeps) n += static_cast<int>(w.run_seconds.size());
  return n;
}

namespace {

// each run goes to the slot that frees first, in the order the runs start
struct Slots {
  std::vector<double> free;
  explicit Slots(int n) : free(static_cast<std::size_t>(std::max(n, 1)), 0.0) {}
  void add(double seconds) { *std::min_element(free.begin(), free.end()) += seconds; }
  double end() const { return *std::max_element(free.begin(), free.end()); }
};

// a sweep's conditions as plan.json gives them
nlohmann::ordered_json conditions_json(const PlannedSweep& s) {
  const PlannedConditions& c = s.conditions;
  auto points = nlohmann::ordered_json::array();
  for (const auto& q : c.points)
    points.push_back({{"phi", q.phi},
                      {"eps_n", q.eps_n},
                      {"eps_t", q.eps_t},
                      {c.dimension == 1 ? "reduced_length" : "L", q.length},
                      {"N", q.particles}});
  return {{"dimension", c.dimension},
          {"claims", c.claims},
          {"points", points},
          {"seeds", c.seeds},
          {"starts", c.starts},
          {"duration_s", c.duration},
          {"discard_s", c.discard},
          {"sampled_s", c.sampled()},
          {"runs", s.run_seconds.size()},
          {"projected_core_hours", s.core_seconds() / 3600.0}};
}

}  // namespace

double ReproducePlan::wall_hours(int slots) const {
  Slots pool(slots);
  for (const auto& w : sweeps)
    for (double r : w.run_seconds) pool.add(r);
  double after = 0.0;  // the models run one after another once the pool is done
  for (const auto& m : models) after += m.core_seconds;
  return (pool.end() + after) / 3600.0;
}

double ReproducePlan::sweep_by_sweep_wall_hours(int slots) const {
  double h = 0.0;
  for (const auto& w : sweeps) {
    Slots pool(slots);
    for (double r : w.run_seconds) pool.add(r);
    h += pool.end() / 3600.0;
  }
  return h;
}

std::string plan_json(const ReproducePlan& p, const std::string& command, int slots) {
  nlohmann::ordered_json j;
  j["study"] = p.study;
  j["budget"] = budget_name(p.budget);
  j["purpose"] = p.purpose;
  j["resolves"] = p.resolves;  // false: the report gives no verdict
  j["command"] = command;
  j["projected_core_hours"] = p.core_hours();
  j["projected_wall_hours"] = p.wall_hours(slots);
  j["projected_slots"] = slots;
  // what a particle-step of the paper's pile (tapping) or of the ring (RFM) costs here
  j["cost"] = {{"core_seconds_per_particle_step", p.cost.seconds},
               {"measured_here", p.cost.measured},
               {"steps_timed", p.cost.steps},
               {"particles", p.cost.particles}};
  j["sweeps"] = nlohmann::ordered_json::array();
  for (const auto& s : p.sweeps) {
    nlohmann::ordered_json w = {
        {"name", s.name}, {"scene", s.scene}, {"params", s.params}, {"sets", s.sets}};
    if (p.study == "rfm") w["conditions"] = conditions_json(s);
    j["sweeps"].push_back(w);
  }
  if (!p.models.empty()) {
    j["models"] = nlohmann::ordered_json::array();
    for (const auto& m : p.models) {
      std::string cmd = "gransim";
      for (const auto& a : m.args) cmd += " " + a;
      j["models"].push_back({{"name", m.name},
                             {"command", cmd + " --out DIR/models/" + m.name},
                             {"claims", m.claims},
                             {"needs", m.needs},
                             {"projected_core_seconds", m.core_seconds}});
    }
  }
  return j.dump(2);
}

ReproducePlan make_plan(const std::string& study, Budget budget, const PileCost& pile_cost) {
  if (study == "tapping") {
    ReproducePlan p = tapping_plan(budget, pile_cost.seconds);
    p.cost = pile_cost;
    return p;
  }
  if (study == "rfm") {
    ReproducePlan p = plan_detail::rfm_plan(
        budget, pile_cost.measured ? pile_cost.seconds / kRingCostReference : 1.0);
    p.cost = pile_cost;
    return p;
  }
  throw InputError("", "STUDY", "'" + study + "' is not a study (tapping, rfm)");
}

}  // namespace gs
