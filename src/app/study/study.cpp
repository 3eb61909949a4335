#include "app/study/study.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/locations.hpp"
#include "app/run/run_info.hpp"
#include "app/study/study_problems.hpp"
#include "app/subprocess.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "output/run_dir.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

namespace fs = std::filesystem;

namespace {

// one row of study.csv: the combination, its outcome, and the error against its reference
struct StudyRow {
  StudyCase c;
  StudyOutcome o;
  double error = NAN;
  std::string error_kind;
  double reference = NAN;  ///< the value the error is taken against
  // the statistical problems: the spread (σ_φ, σ_T) against the reference's
  double sd_reference = NAN;
  double sd_error = NAN;       ///< |sd − sd_ref| (tapping), relative (rfm)
  double sd_stat_error = NAN;  ///< 95% half-widths of both spreads in quadrature, same units
};

// one bar of the stability map
struct StabilityRow {
  StudyProblem problem;
  IntegratorKind integrator;
  std::string switches;
  double max_stable = 0.0;      ///< largest stable Δt/t_c found (0: none)
  double first_unstable = 0.0;  ///< first unstable Δt/t_c (0: none up to stability_max)
  std::string message;
};

std::string num(double v) {
  if (!std::isfinite(v)) return "nan";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string csv_text(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"') o += '"';
    o += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return o + "\"";
}

std::string json_text(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  }
  return o + "\"";
}

std::string json_num(double v) { return std::isfinite(v) ? num(v) : "null"; }

std::string_view bp_name(BroadPhaseKind k) {
  return k == BroadPhaseKind::Box2DTree ? "box2d_tree" : "cell_grid";
}

// the switch sets that matter for a problem (others would only repeat the same run)
std::vector<StudySwitches> switch_sets(const StudySpec& s, StudyProblem p) {
  std::vector<StudySwitches> out;
  switch (p) {
    case StudyProblem::TwoDisk:
    case StudyProblem::Haff:
      for (bool c : s.clip) out.push_back({false, true, c});
      break;
    case StudyProblem::TwoDecagon:
    case StudyProblem::Pile:
      for (bool h : s.hdot_fd)
        for (bool r : s.rocking) out.push_back({h, r, false});
      break;
    case StudyProblem::GasEnergy:
      out.push_back({});
      break;
    // the statistical problems are costly: only their own switch varies, the others take the
    // matrix's first value
    case StudyProblem::Tapping:
      for (bool e : s.early_rest) out.push_back({s.hdot_fd.front(), s.rocking.front(), false, e});
      break;
    case StudyProblem::RfmTemperature:
      out.push_back({false, true, s.clip.front(), false});
      break;
  }
  return out;
}

// what the error measures, per problem
std::string_view error_kind(StudyProblem p) {
  switch (p) {
    case StudyProblem::TwoDisk:
      return "restitution_rel_error_vs_exact";
    case StudyProblem::TwoDecagon:
      return "restitution_rel_error_vs_reference";
    case StudyProblem::GasEnergy:
      return "energy_drift_per_s";
    case StudyProblem::Haff:
      return "haff_slope_rel_error_vs_enskog";
    case StudyProblem::Pile:
      return "phi_abs_error_vs_reference";
    case StudyProblem::Tapping:
      return "phi_mean_abs_error_vs_reference";
    case StudyProblem::RfmTemperature:
      return "temperature_rel_error_vs_reference";
  }
  return "";
}

// problems measured against a small-Δt Gear 6 run of the same model
bool needs_reference(StudyProblem p) {
  return p == StudyProblem::TwoDecagon || p == StudyProblem::Pile || p == StudyProblem::Tapping ||
         p == StudyProblem::RfmTemperature;
}

// problems whose value scatters from run to run: the reference's own error counts
bool statistical(StudyProblem p) {
  return p == StudyProblem::Tapping || p == StudyProblem::RfmTemperature;
}

// the switches of a problem's reference run: tapping is always compared with the
// paper-faithful protocol (full relaxations), so early rest's effect shows as an error
StudySwitches reference_switches(StudyProblem p, StudySwitches sw) {
  if (p == StudyProblem::Tapping) sw.early_rest = false;
  return sw;
}

// the reference Δt/t_c of a problem: tapping at an absolute Δt (paper check step 1e-5 s),
// rfm at its own value when given, the others at the study's
double reference_dt_over_tc(const StudySpec& s, StudyProblem p, double study_ref) {
  if (p == StudyProblem::Tapping) return s.sizes.tap_reference_dt / study_contact_time(s.sizes, p);
  if (p == StudyProblem::RfmTemperature && s.sizes.rfm_reference_dt_over_tc > 0)
    return s.sizes.rfm_reference_dt_over_tc;
  return study_ref;
}

// the Δt list of a problem: its own when its table gives one, else the matrix's
const std::vector<double>& dt_list(const StudySpec& s, StudyProblem p) {
  if (p == StudyProblem::Tapping && !s.tap_dt_over_tc.empty()) return s.tap_dt_over_tc;
  if (p == StudyProblem::RfmTemperature && !s.rfm_dt_over_tc.empty()) return s.rfm_dt_over_tc;
  return s.dt_over_tc;
}

void set_error(const StudySpec& s, StudyRow& r, const StudyOutcome& ref) {
  r.error_kind = std::string(error_kind(r.c.problem));
  const double v = r.o.value;
  switch (r.c.problem) {
    case StudyProblem::TwoDisk:
      r.reference = s.sizes.disk_eps;
      r.error = std::abs(v - r.reference) / r.reference;
      break;
    case StudyProblem::TwoDecagon:
      r.error = std::abs(v - r.reference) / r.reference;
      break;
    case StudyProblem::GasEnergy:
      r.error = v;
      break;
    case StudyProblem::Haff:
      r.reference = 1.0;
      r.error = std::abs(v - 1.0);
      break;
    case StudyProblem::Pile:
      r.error = std::abs(v - r.reference);
      break;
    case StudyProblem::Tapping:
    case StudyProblem::RfmTemperature: {
      // relative for T, absolute for φ̄; the band: both 95% half-widths in quadrature
      const double scale = r.c.problem == StudyProblem::Tapping ? 1.0 : r.reference;
      r.error = std::abs(v - r.reference) / scale;
      r.o.stat_error = std::hypot(r.o.stat_error, ref.stat_error) / scale;
      r.sd_reference = ref.sd;
      const double sd_scale = r.c.problem == StudyProblem::Tapping ? 1.0 : ref.sd;
      r.sd_error = std::abs(r.o.sd - ref.sd) / sd_scale;
      r.sd_stat_error = std::hypot(r.o.sd_stat, ref.sd_stat) / sd_scale;
      break;
    }
  }
  if (!r.o.stable) r.error = r.sd_error = NAN;
}

const char* kCsvHeader =
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
  std::ostringstream j;
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  j << "{\n  \"program\": \"gransim\",\n  \"version\": "
    << json_text(std::string(program_version()))
    << ",\n  \"kind\": \"study\",\n  \"name\": " << json_text(s.name)
    << ",\n  \"study_file\": " << json_text(s.file) << ",\n  \"threads\": " << threads
    << ",\n  \"wall_time_s\": " << json_num(wall) << ",\n  \"rows\": [";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const StudyRow& r = rows[k];
    const StudyOutcome& o = r.o;
    j << (k ? ",\n" : "\n") << "    {\"problem\": \"" << to_string(r.c.problem)
      << "\", \"integrator\": \"" << to_string(r.c.integrator) << "\", \"dt\": " << json_num(o.dt)
      << ", \"dt_over_tc\": " << json_num(r.c.dt_over_tc) << ", \"broad_phase\": \""
      << bp_name(r.c.broad_phase)
      << "\", \"switches\": " << json_text(study_switches_text(r.c.problem, r.c.switches))
      << ", \"wall_s\": " << json_num(o.wall_s) << ", \"sim_time_s\": " << json_num(o.sim_time)
      << ", \"particles\": " << o.particles << ", \"steps\": " << o.steps
      << ", \"value\": " << json_num(o.value) << ", \"reference\": " << json_num(r.reference)
      << ", \"error\": " << json_num(r.error) << ", \"error_kind\": \"" << r.error_kind
      << "\", \"stat_error\": " << json_num(o.stat_error)
      << ", \"final_ke\": " << json_num(o.final_ke)
      << ", \"wall_per_tap_s\": " << json_num(o.wall_per_tap) << ", \"sd\": " << json_num(o.sd)
      << ", \"sd_reference\": " << json_num(r.sd_reference)
      << ", \"sd_error\": " << json_num(r.sd_error)
      << ", \"sd_stat_error\": " << json_num(r.sd_stat_error)
      << ", \"tau_int\": " << json_num(o.tau_int) << ", \"samples\": " << o.samples
      << ", \"stable\": " << (o.stable ? "true" : "false") << ", \"note\": " << json_text(o.note)
      << "}";
  }
  j << "\n  ],\n  \"stability\": [";
  for (std::size_t k = 0; k < stab.size(); ++k) {
    const StabilityRow& r = stab[k];
    j << (k ? ",\n" : "\n") << "    {\"problem\": \"" << to_string(r.problem)
      << "\", \"integrator\": \"" << to_string(r.integrator)
      << "\", \"switches\": " << json_text(r.switches)
      << ", \"max_stable_dt_over_tc\": " << json_num(r.max_stable)
      << ", \"first_unstable_dt_over_tc\": " << json_num(r.first_unstable)
      << ", \"message\": " << json_text(r.message) << "}";
  }
  j << "\n  ]\n}\n";
  return j.str();
}

// run tools/charts_study.py on the study directory; "" on success, else what went wrong
std::string draw_charts(const std::string& out) {
  const std::string tools = find_tools_dir("charts_study.py");
  if (tools.empty()) return "tools/charts_study.py not found (set GS_TOOLS_DIR)";
  return run_python_script(tools + "/charts_study.py", {out});
}

// the largest stable Δt of one integrator and switch set: sweep up until blow-up
StabilityRow stability_sweep(const StudySpec& s, StudyProblem p, IntegratorKind integ,
                             const StudySwitches& sw, bool quiet) {
  StabilityRow r{p, integ, study_switches_text(p, sw), 0.0, 0.0, ""};
  for (double x = s.stability_start; x <= s.stability_max * (1 + 1e-12); x *= s.stability_factor) {
    StudyCase c{p, integ, x, BroadPhaseKind::CellGrid, sw};
    if (study_problem_walled(p)) c.broad_phase = BroadPhaseKind::Box2DTree;
    const StudyOutcome o = run_study_case(s.sizes, c);
    if (!o.stable) {
      r.first_unstable = x;
      r.message = o.note;
      break;
    }
    r.max_stable = x;
  }
  if (!quiet)
    std::fprintf(stderr, "  stability %-12s %-20s %-36s max stable dt/tc %s\n",
                 std::string(to_string(p)).c_str(), std::string(to_string(integ)).c_str(),
                 r.switches.c_str(), num(r.max_stable).c_str());
  return r;
}

}  // namespace

int study_command(const StudyOptions& opt) {
  const StudySpec s = parse_study_file(opt.file);
  const std::string out = opt.out.empty() ? "runs/study-" + s.name : opt.out;
  prepare_run_dir(out, opt.force);
  const auto t0 = std::chrono::steady_clock::now();

  double dt_min = s.dt_over_tc.front();
  for (double d : s.dt_over_tc) dt_min = std::min(dt_min, d);
  const double ref_dt = s.reference_dt_over_tc > 0 ? s.reference_dt_over_tc : dt_min / 2;

  // the matrix, one row at a time; study.csv is flushed after every row
  std::ofstream csv(out + "/study.csv");
  if (!csv) throw InputError(out, "", "cannot write study.csv");
  csv << kCsvHeader << std::flush;
  std::vector<StudyRow> rows;
  std::map<std::string, StudyOutcome> refs;  // (problem, reference switches) → reference run
  for (StudyProblem p : s.problems) {
    for (const StudySwitches& sw : switch_sets(s, p)) {
      const std::string sw_text = study_switches_text(p, sw);
      StudyOutcome ref;
      ref.value = NAN;
      if (needs_reference(p)) {
        const StudySwitches rsw = reference_switches(p, sw);
        const auto key = std::string(to_string(p)) + "|" + study_switches_text(p, rsw);
        if (!refs.count(key)) {
          const double rdt = reference_dt_over_tc(s, p, ref_dt);
          const BroadPhaseKind rbp =
              study_problem_walled(p) ? s.broad_phases.front() : BroadPhaseKind::CellGrid;
          StudyOutcome o = run_study_case(s.sizes, {p, IntegratorKind::Gear6, rdt, rbp, rsw});
          if (!o.stable) o.value = NAN;
          refs[key] = o;
          if (!opt.quiet)
            std::fprintf(stderr, "study: reference %s %s (gear6, dt/tc = %s): %s%s%s\n",
                         std::string(to_string(p)).c_str(), study_switches_text(p, rsw).c_str(),
                         num(rdt).c_str(), num(o.value).c_str(), statistical(p) ? " +- " : "",
                         statistical(p) ? num(o.stat_error).c_str() : "");
        }
        ref = refs[key];
      }
      // the broad phase varies only on the pile; tapping takes the first one
      std::vector<BroadPhaseKind> bps{BroadPhaseKind::CellGrid};
      if (p == StudyProblem::Pile)
        bps = s.broad_phases;
      else if (study_problem_walled(p))
        bps = {s.broad_phases.front()};
      for (BroadPhaseKind bp : bps)
        for (IntegratorKind integ : s.integrators)
          for (double x : dt_list(s, p)) {
            StudyRow r;
            r.c = {p, integ, x, bp, sw};
            r.o = run_study_case(s.sizes, r.c);
            r.reference = ref.value;
            set_error(s, r, ref);
            csv << csv_row(r) << std::flush;
            if (!opt.quiet)
              std::fprintf(stderr, "study: %-11s %-19s dt/tc %-7s %-10s %-34s error %-10s %s\n",
                           std::string(to_string(p)).c_str(), std::string(to_string(integ)).c_str(),
                           num(x).c_str(), std::string(bp_name(bp)).c_str(), sw_text.c_str(),
                           num(r.error).c_str(), r.o.stable ? "" : "UNSTABLE");
            rows.push_back(std::move(r));
          }
    }
  }

  // the stability map
  std::vector<StabilityRow> stab;
  if (s.stability) {
    for (StudyProblem p : s.stability_problems)
      for (const StudySwitches& sw : switch_sets(s, p))
        for (IntegratorKind integ : s.integrators)
          stab.push_back(stability_sweep(s, p, integ, sw, opt.quiet));
    write_file_atomic(out + "/stability.csv", stability_csv(stab));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_file_atomic(out + "/study.json", study_json(s, rows, stab, wall));
  std::fprintf(stderr, "gransim study: %zu combinations%s in %.1f s, results in %s\n", rows.size(),
               s.stability ? " and the stability map" : "", wall, out.c_str());

  // the charts; without python the CSV and JSON stand
  const std::string err = draw_charts(out);
  if (!err.empty())
    std::fprintf(stderr, "gransim study: charts skipped: %s. study.csv and study.json are in %s\n",
                 err.c_str(), out.c_str());
  return kExitOk;
}

}  // namespace gs
