#include "app/study/study_tables.hpp"

#include <cstdio>
#include <sstream>

#include "app/version.hpp"
#include "output/json_text.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs::study_detail {

namespace {

std::string csv_text(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"') o += '"';
    o += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return o + "\"";
}

}  // namespace

std::string num(double v) {
  if (!std::isfinite(v)) return "nan";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string_view bp_name(BroadPhaseKind k) {
  return k == BroadPhaseKind::Box2DTree ? "box2d_tree" : "cell_grid";
}

const char* const kCsvHeader =
    "problem,integrator,dt,dt_over_tc,broad_phase,switches,wall_s,particle_steps_per_s,error,"
    "error_kind,stable,note,wall_per_sim_s,sim_time_s,particles,steps,tc,value,reference,"
    "stat_error,final_ke,wall_per_tap_s,sd,sd_reference,sd_error,sd_stat_error,tau_int,samples\n";

std::string csv_row(const StudyRow& r) {
  const StudyOutcome& o = r.o;
  const double ps = o.wall_s > 0 ? o.particles * static_cast<double>(o.steps) / o.wall_s : NAN;
  const double per_sim = o.sim_time > 0 ? o.wall_s / o.sim_time : NAN;
  std::ostringstream l;
  l << to_string(r.c.problem) << ',' << to_string(r.c.integrator) << ',' << num(o.dt) << ','
    << num(r.c.dt_over_tc) << ',' << bp_name(r.c.broad_phase) << ','
    << study_switches_text(r.c.problem, r.c.switches) << ',' << num(o.wall_s) << ',' << num(ps)
    << ',' << num(r.error) << ',' << r.error_kind << ',' << (o.stable ? "true" : "false") << ','
    << csv_text(o.note) << ',' << num(per_sim) << ',' << num(o.sim_time) << ',' << o.particles
    << ',' << o.steps << ',' << num(o.tc) << ',' << num(o.value) << ',' << num(r.reference) << ','
    << num(o.stat_error) << ',' << num(o.final_ke) << ',' << num(o.wall_per_tap) << ',' << num(o.sd)
    << ',' << num(r.sd_reference) << ',' << num(r.sd_error) << ',' << num(r.sd_stat_error) << ','
    << num(o.tau_int) << ',' << o.samples << '\n';
  return l.str();
}

// stability.csv and the stability part of study.json
std::string stability_csv(const std::vector<StabilityRow>& rows) {
  std::ostringstream c;
  c << "problem,integrator,switches,max_stable_dt_over_tc,first_unstable_dt_over_tc,message\n";
  for (const auto& r : rows)
    c << to_string(r.problem) << ',' << to_string(r.integrator) << ',' << r.switches << ','
      << num(r.max_stable) << ',' << num(r.first_unstable) << ',' << csv_text(r.message) << '\n';
  return c.str();
}

std::string study_json(const StudySpec& s, const std::vector<StudyRow>& rows,
                       const std::vector<StabilityRow>& stab, double wall) {
  using ojson = nlohmann::ordered_json;
  // measured values carry six significant digits, as in the CSV tables
  auto n6 = [](double v) { return json_number(v, 6); };
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  ojson j;
  j["program"] = "gransim";
  j["version"] = program_version();
  j["kind"] = "study";
  j["name"] = s.name;
  j["study_file"] = s.file;
  j["threads"] = threads;
  j["wall_time_s"] = n6(wall);
  j["rows"] = ojson::array();
  for (const StudyRow& r : rows) {
    const StudyOutcome& o = r.o;
    j["rows"].push_back({{"problem", to_string(r.c.problem)},
                         {"integrator", to_string(r.c.integrator)},
                         {"dt", n6(o.dt)},
                         {"dt_over_tc", n6(r.c.dt_over_tc)},
                         {"broad_phase", bp_name(r.c.broad_phase)},
                         {"switches", study_switches_text(r.c.problem, r.c.switches)},
                         {"wall_s", n6(o.wall_s)},
                         {"sim_time_s", n6(o.sim_time)},
                         {"particles", o.particles},
                         {"steps", o.steps},
                         {"value", n6(o.value)},
                         {"reference", n6(r.reference)},
                         {"error", n6(r.error)},
                         {"error_kind", r.error_kind},
                         {"stat_error", n6(o.stat_error)},
                         {"final_ke", n6(o.final_ke)},
                         {"wall_per_tap_s", n6(o.wall_per_tap)},
                         {"sd", n6(o.sd)},
                         {"sd_reference", n6(r.sd_reference)},
                         {"sd_error", n6(r.sd_error)},
                         {"sd_stat_error", n6(r.sd_stat_error)},
                         {"tau_int", n6(o.tau_int)},
                         {"samples", o.samples},
                         {"stable", o.stable},
                         {"note", o.note}});
  }
  j["stability"] = ojson::array();
  for (const StabilityRow& r : stab)
    j["stability"].push_back({{"problem", to_string(r.problem)},
                              {"integrator", to_string(r.integrator)},
                              {"switches", r.switches},
                              {"max_stable_dt_over_tc", n6(r.max_stable)},
                              {"first_unstable_dt_over_tc", n6(r.first_unstable)},
                              {"message", r.message}});
  return json_text(j, {"rows", "stability"});
}

}  // namespace gs::study_detail
